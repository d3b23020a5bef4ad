#include "hexdyn/planning/gait.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

// Smootherstep and derivatives on [0, 1].
double S(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }
double dS(double u) { return 30.0 * u * u * (1.0 - u) * (1.0 - u); }
double ddS(double u) { return 60.0 * u * (1.0 - u) * (1.0 - 2.0 * u); }

/// Where on the stairs a leg wanted to stand: "step k of N" (the tread behind the riser of
/// step k), "step N of N (the last)" or "the ground before step 1".
std::string step_words(const Terrain& terrain, double y) {
  const int k = terrain.tread_index(y), n = terrain.edge_count();
  if (k == 0) return "the ground before step 1";
  const int last = terrain.edge_step(n);
  return "step " + std::to_string(terrain.edge_step(k)) + " of " + std::to_string(last) +
         (k == n ? " (the last)" : "");
}

/// Depth of the tread containing y between its edges (+inf for the ground and the last).
double tread_depth_at(const Terrain& terrain, double y) {
  const int k = terrain.tread_index(y), n = terrain.edge_count();
  if (k == 0 || k == n) return std::numeric_limits<double>::infinity();
  return terrain.edge_y(k + 1) - terrain.edge_y(k);
}

/// The one-line error of a foothold that cannot keep the margin
/// (docs/theory/stages.md#gait-planning).
std::string no_foothold_message(const Terrain& terrain, const GaitParams& gait, double radius_m,
                                int leg, double t_s, double y_nominal) {
  std::ostringstream s;
  s << "leg " << leg_name(leg) << ", stance from t = " << t_s << " s on "
    << step_words(terrain, y_nominal) << " (wanted y = " << y_nominal
    << " m): no foothold keeps gait.foothold_margin " << gait.foothold_margin_m << " m from the "
    << "edges of its tread";
  const double depth = tread_depth_at(terrain, y_nominal);
  if (radius_m > 0.0)
    s << " with its sphere foot of radius " << radius_m << " m: the tread depth " << depth
      << " m is less than 2 (margin + radius) = " << 2.0 * (gait.foothold_margin_m + radius_m)
      << " m";
  else
    s << ": the tread depth " << depth << " m is less than twice the margin";
  return s.str();
}

/// The one-line error of a foothold that no point of a height map near it can take.
std::string no_map_foothold_message(const GaitParams& gait, double radius_m, int leg, double t_s,
                                    double x, double y) {
  std::ostringstream s;
  s << "leg " << leg_name(leg) << ", stance from t = " << t_s << " s at (" << x << ", " << y
    << ") m on the height map: no point within " << kFootholdSearch_m
    << " m along y keeps gait.foothold_margin " << gait.foothold_margin_m;
  if (radius_m > 0.0) s << " + the foot's radius " << radius_m;
  s << " m from an edge or ground steeper than terrain.height_map.max_slope";
  return s.str();
}

/// A stance's foothold (gait.hpp). A sphere foot of radius r keeps the margin with its
/// horizontal extent [y − r, y + r]: its contact point keeps margin + r from nosing and riser.
Vec3 foothold(const RobotModel& model, const GaitParams& gait, const TrunkMotion& trunk,
              const Terrain& terrain, int leg, double tau_nominal) {
  const Vec3 hip_W = trunk.position_at_phase(tau_nominal) + trunk.W_R_B() * model.p_hip_B[leg];
  // The hip's outward direction, horizontal in the world (the paper robot: exactly ±x).
  Vec3 out_W = trunk.W_R_B() * model.hip_outward_B[leg];
  out_W.z() = 0.0;
  out_W.normalize();
  const double x = hip_W.x() + out_W.x() * gait.foot_lateral_m;
  const double y_nominal = hip_W.y() + out_W.y() * gait.foot_lateral_m;
  const double y_wanted = y_nominal + 0.5 * gait.stroke_m;
  const double radius = model.foot_radius_m[leg];
  const std::optional<double> y =
      terrain.valid_foothold_at(x, y_wanted, gait.foothold_margin_m + radius);
  if (!y && terrain.params().type == TerrainType::kHeightMap)
    throw PlanningError(
        no_map_foothold_message(gait, radius, leg, trunk.time_at_phase(tau_nominal), x, y_wanted));
  if (!y)
    throw PlanningError(no_foothold_message(terrain, gait, radius, leg,
                                            trunk.time_at_phase(tau_nominal), y_wanted));
  return Vec3(x, *y, terrain.height(x, *y));
}

/// How far the foot (its sphere) passes below the terrain on [ta, tb] of a swing, to within
/// kResolution_m of its path: a chord of the path whose lower end is above the highest
/// terrain under the sphere's shadow of the chord (Terrain::max_height_along) clears it; a
/// chord that does not is split in two until it is shorter than the resolution, so that only
/// the chords that cross a riser or a nosing are refined. Returns the depth and its time.
std::pair<double, double> depth_below_terrain(const Swing& sw, const Terrain& terrain,
                                              double radius_m, double ta, double tb, int level) {
  constexpr double kResolution_m = 1e-7;
  constexpr int kMaxLevel = 48;
  const Vec3 a = swing_foot_position(sw, ta), b = swing_foot_position(sw, tb);
  const double depth = terrain.max_height_along(a, b, radius_m) - std::min(a.z(), b.z());
  if (depth <= 0.0 || (b - a).norm() < kResolution_m || level >= kMaxLevel)
    return {depth, a.z() < b.z() ? ta : tb};
  const double tm = 0.5 * (ta + tb);
  const auto lo = depth_below_terrain(sw, terrain, radius_m, ta, tm, level + 1);
  const auto hi = depth_below_terrain(sw, terrain, radius_m, tm, tb, level + 1);
  return lo.first >= hi.first ? lo : hi;
}

/// PlanningError unless a blended swing's foot stays on or above the terrain
/// (depth_below_terrain over kChords chords of its path). A staged swing clears by
/// construction: it moves across only at the apex.
void check_blended_clearance(const Swing& sw, const Terrain& terrain, double radius_m, int leg) {
  constexpr int kChords = 64;
  constexpr double kTolerance_m = 1e-9;
  const double D = sw.t_touchdown_s - sw.t_liftoff_s;
  for (int i = 0; i < kChords; ++i) {
    const double ta = sw.t_liftoff_s + D * i / kChords;
    const auto [depth, t] =
        depth_below_terrain(sw, terrain, radius_m, ta, sw.t_liftoff_s + D * (i + 1) / kChords, 0);
    if (depth > kTolerance_m) {
      std::ostringstream m;
      m << "leg " << leg_name(leg) << ", swing at t = " << t << " s: the blended swing path passes "
        << depth
        << " m below the terrain under it (a riser or nosing in its way); use "
           "gait.swing_profile staged, a larger gait.swing_clearance or a shorter "
           "gait.lift_fraction";
      throw PlanningError(m.str());
    }
  }
}

}  // namespace

GaitPlan plan_gait(const RobotModel& model, const GaitParams& gait, const TrunkMotion& trunk,
                   const Terrain& terrain) {
  GaitPlan plan;
  const double beta = gait.duty_factor;
  plan.duty_factor = beta;
  plan.liftoff_phase = liftoff_phases(gait, gait_legs(model));
  if (std::ssize(plan.liftoff_phase) != model.legs())
    throw std::logic_error("gait: " + std::to_string(plan.liftoff_phase.size()) +
                           " lift-off phases for " + std::to_string(model.legs()) + " legs");
  plan.legs.resize(model.legs());
  const double n = trunk.cycles();
  constexpr double kMinSwingPhase = 1e-9;
  for (int leg = 0; leg < model.legs(); ++leg) {
    LegPlan& lp = plan.legs[leg];
    bool first = true;
    Vec3 p_current = Vec3::Zero();
    for (int k = -1; k <= trunk.cycles(); ++k) {
      const double a = k + plan.liftoff_phase[leg];
      const double b = a + (1.0 - beta);
      const double a_cut = std::max(a, 0.0), b_cut = std::min(b, n);
      if (b_cut - a_cut <= kMinSwingPhase) continue;
      if (first) {
        p_current = foothold(model, gait, trunk, terrain, leg, a - beta);
        lp.p_initial_W = p_current;
        first = false;
      }
      Swing sw;
      sw.t_liftoff_s = trunk.time_at_phase(a_cut);
      sw.t_touchdown_s = trunk.time_at_phase(b_cut);
      sw.p_liftoff_W = p_current;
      sw.p_touchdown_W = foothold(model, gait, trunk, terrain, leg, b_cut);
      // Over the sphere's shadow: the sphere, not only its contact point, clears by Δh.
      sw.apex_z_m =
          terrain.max_height_along(sw.p_liftoff_W, sw.p_touchdown_W, model.foot_radius_m[leg]) +
          gait.swing_clearance_m;
      sw.apex_z_m = std::max({sw.apex_z_m, sw.p_liftoff_W.z() + gait.swing_clearance_m,
                              sw.p_touchdown_W.z() + gait.swing_clearance_m});
      sw.touchdown_speed_mps = gait.touchdown_speed_mps;
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      double lower = gait.lower_fraction;
      // The quartic descent is monotone iff v_td · (lower · D) ≤ 4 (z_a − z_td).
      if (gait.touchdown_speed_mps > 0.0)
        lower = std::min(
            lower, 4.0 * (sw.apex_z_m - sw.p_touchdown_W.z()) / (gait.touchdown_speed_mps * D));
      sw.lift_end_u = gait.lift_fraction;
      sw.lower_start_u = 1.0 - lower;
      if (gait.swing_profile == SwingProfile::kBlended) {
        sw.transfer_start_u = 0.0;
        sw.transfer_end_u = 1.0;
        check_blended_clearance(sw, terrain, model.foot_radius_m[leg], leg);
      } else {
        sw.transfer_start_u = sw.lift_end_u;
        sw.transfer_end_u = sw.lower_start_u;
      }
      lp.swings.push_back(sw);
      p_current = sw.p_touchdown_W;
    }
    if (first)  // never swings (cannot happen for β < 1 and n ≥ 1, kept for safety)
      lp.p_initial_W = foothold(model, gait, trunk, terrain, leg, 0.0);
  }
  return plan;
}

double mean_initial_foot_z(const GaitPlan& gait) {
  double feet_z = 0.0;
  for (const LegPlan& leg : gait.legs) feet_z += leg.p_initial_W.z();
  return feet_z / static_cast<double>(gait.legs.size());
}

Vec3 swing_foot_position(const Swing& sw, double t) {
  Vec3 p;
  const double D = sw.t_touchdown_s - sw.t_liftoff_s;
  const double u = std::clamp((t - sw.t_liftoff_s) / D, 0.0, 1.0);
  const double ul = sw.lift_end_u, ud = sw.lower_start_u;
  const Vec3& p0 = sw.p_liftoff_W;
  const Vec3& p1 = sw.p_touchdown_W;
  // Horizontal transfer on [us, ue].
  const double us = sw.transfer_start_u, ue = sw.transfer_end_u;
  const double sigma = std::clamp((u - us) / (ue - us), 0.0, 1.0);
  const Eigen::Vector2d dxy = p1.head<2>() - p0.head<2>();
  p.head<2>() = p0.head<2>() + dxy * S(sigma);
  // Vertical: lift, hold, descend.
  const double za = sw.apex_z_m;
  if (u < ul) {
    const double w = u / ul, h = za - p0.z();
    p.z() = p0.z() + h * S(w);
  } else if (u <= ud) {
    p.z() = za;
  } else {
    const double Dd = (1.0 - ud) * D, w = (u - ud) / (1.0 - ud);
    const double delta = p1.z() - za, vD = sw.touchdown_speed_mps * Dd;
    const double b = -vD - 3.0 * delta, a = 4.0 * delta + vD;
    p.z() = za + w * w * w * (a + b * w);
  }
  return p;
}

FootMotion swing_foot_motion(const Swing& sw, double t) {
  FootMotion f;
  f.in_swing = true;
  f.p_W = swing_foot_position(sw, t);
  const double D = sw.t_touchdown_s - sw.t_liftoff_s;
  const double u = std::clamp((t - sw.t_liftoff_s) / D, 0.0, 1.0);
  const double ul = sw.lift_end_u, ud = sw.lower_start_u;
  const Vec3& p0 = sw.p_liftoff_W;
  const Vec3& p1 = sw.p_touchdown_W;
  const double us = sw.transfer_start_u, ue = sw.transfer_end_u;
  const double Dt = (ue - us) * D;
  const double sigma = std::clamp((u - us) / (ue - us), 0.0, 1.0);
  const Eigen::Vector2d dxy = p1.head<2>() - p0.head<2>();
  f.v_W.head<2>() = dxy * (dS(sigma) / Dt);
  f.a_W.head<2>() = dxy * (ddS(sigma) / (Dt * Dt));
  const double za = sw.apex_z_m;
  if (u < ul) {
    const double Dl = ul * D, w = u / ul, h = za - p0.z();
    f.v_W.z() = h * dS(w) / Dl;
    f.a_W.z() = h * ddS(w) / (Dl * Dl);
  } else if (u > ud) {
    const double Dd = (1.0 - ud) * D, w = (u - ud) / (1.0 - ud);
    const double delta = p1.z() - za, vD = sw.touchdown_speed_mps * Dd;
    const double b = -vD - 3.0 * delta, a = 4.0 * delta + vD;
    f.v_W.z() = w * w * (3.0 * a + 4.0 * b * w) / Dd;
    f.a_W.z() = w * (6.0 * a + 12.0 * b * w) / (Dd * Dd);
  }
  return f;
}

FootMotion leg_foot_motion(const LegPlan& leg, double t) {
  Vec3 p = leg.p_initial_W;
  for (const Swing& sw : leg.swings) {
    if (t < sw.t_liftoff_s) break;
    if (t < sw.t_touchdown_s) return swing_foot_motion(sw, t);
    p = sw.p_touchdown_W;
  }
  FootMotion f;
  f.p_W = p;
  return f;
}

FootNormal swing_foot_normal(const Swing& sw, const Vec3& n0, const Vec3& n1, double t) {
  FootNormal f;
  f.n_W = n0;
  if (n0 == n1) return f;
  const double D = sw.t_touchdown_s - sw.t_liftoff_s;
  const double u = std::clamp((t - sw.t_liftoff_s) / D, 0.0, 1.0);
  const double us = sw.transfer_start_u, ue = sw.transfer_end_u;
  const double Dt = (ue - us) * D;
  const double sigma = std::clamp((u - us) / (ue - us), 0.0, 1.0);
  const Vec3 dn = n1 - n0;
  const Vec3 m = n0 + S(sigma) * dn;
  const Vec3 md = dn * (dS(sigma) / Dt), mdd = dn * (ddS(sigma) / (Dt * Dt));
  // n = m/ρ, ρ = |m|: ṅ = (ṁ − ρ̇ n)/ρ with ρ̇ = n·ṁ; n̈ = (m̈ − ρ̈ n − 2 ρ̇ ṅ)/ρ with
  // ρ̈ = ṅ·ṁ + n·m̈.
  const double rho = m.norm();
  f.n_W = m / rho;
  const double rho_d = f.n_W.dot(md);
  f.nd_W = (md - rho_d * f.n_W) / rho;
  const double rho_dd = f.nd_W.dot(md) + f.n_W.dot(mdd);
  f.ndd_W = (mdd - rho_dd * f.n_W - 2.0 * rho_d * f.nd_W) / rho;
  return f;
}

FootNormal leg_foot_normal(const LegPlan& leg, const Terrain& terrain, double t) {
  Vec3 p = leg.p_initial_W;
  for (const Swing& sw : leg.swings) {
    if (t < sw.t_liftoff_s) break;
    if (t < sw.t_touchdown_s)
      return swing_foot_normal(sw, terrain.normal(sw.p_liftoff_W.x(), sw.p_liftoff_W.y()),
                               terrain.normal(sw.p_touchdown_W.x(), sw.p_touchdown_W.y()), t);
    p = sw.p_touchdown_W;
  }
  FootNormal f;
  f.n_W = terrain.normal(p.x(), p.y());
  return f;
}

}  // namespace hexdyn
