#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/planning/margin_detail.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn::margin_detail {
namespace {

/// Angle of a joint to its nearer limit [rad], +inf for a continuous joint; negative when
/// outside. A revolute joint may be turned by ±2π into its limits (as the IK does).
double joint_clearance_rad(double q, double lo, double hi) {
  double best = -kInf;
  for (double shift : {0.0, 2.0 * M_PI, -2.0 * M_PI})
    best = std::max(best, std::min(q + shift - lo, hi - q - shift));
  return best;
}

/// Which of the reach boundaries limits a paper-geometry leg at target p_H; the other
/// geometries report the IK's margin without naming the boundary.
std::string reach_boundary(const RobotModel& m, int leg, const Vec3& p_H) {
  if (m.leg_geometry != LegGeometry::kPaperPlanar) return "reach: workspace boundary";
  const auto& L = m.link_length_m;
  const double w = m.lateral_m[leg];
  const double rho = std::sqrt(std::max(p_H.x() * p_H.x() + p_H.y() * p_H.y() - w * w, 0.0));
  const double dist = std::hypot(rho - L[0], p_H.z() + m.d1_m);
  return (L[1] + L[2]) - dist <= dist - std::abs(L[1] - L[2]) ? "reach: full extension"
                                                              : "reach: full fold";
}

/// Which constraint gives a sample's margin, kept as a code: the text is made only for the
/// sample that limits the whole motion (constraint_text), not on the per-sample path.
enum class Binding { kNone, kReachRefused, kReachBoundary, kJoint };

struct SampleMargin {
  double value_m = kInf;
  Binding binding = Binding::kNone;
  int joint = 0;       ///< kJoint: flat joint index
  bool lower = false;  ///< kJoint: the lower limit is the nearer
};

/// A paper-geometry leg's target p_H in its leg plane [m]: r from the coxa axis, ρ = √(r² − w²)
/// along the leg, (u, v) from the femur axis, and d = |(u, v)|, the IK's wrist distance.
struct LegPlane {
  double r2, r, rho, u, v, d;
};

LegPlane leg_plane(const RobotModel& m, int leg, const Vec3& p_H) {
  LegPlane g;
  const double w = m.lateral_m[leg];
  g.r2 = p_H.x() * p_H.x() + p_H.y() * p_H.y();
  g.r = std::sqrt(g.r2);
  g.rho = std::sqrt(std::max(g.r2 - w * w, 0.0));
  g.u = g.rho - m.link_length_m[0];
  g.v = p_H.z() + m.d1_m;
  g.d = std::sqrt(g.u * g.u + g.v * g.v);
  return g;
}

/// A lever arm as a lower bound of the Jacobian column norm it equals to rounding: 1e-6 of it
/// taken off, and 1e-12 m.
double lever_lower_bound(double lever_m) { return std::max(lever_m * (1.0 - 1e-6) - 1e-12, 0.0); }

/// Lower bounds of the joint margins of a paper-geometry leg at target p_H [m]: the angle to the
/// limit times a lower bound of the foot's lever arm, which for this geometry is a distance of
/// the target itself: from the coxa axis, r; from the femur axis, the wrist distance d of the
/// IK; about the tibia axis, the tibia's length (the norms of leg_jacobian_H's columns, to
/// rounding: lever_lower_bound). False for another geometry.
/// One value per joint of a leg (the first RobotModel::leg(l).n_joints are used).
using LegJointValues = std::array<double, kMaxLegJoints>;

bool joint_margin_bounds(const RobotModel& m, int leg, const Vec3& p_H,
                         const LegJointValues& clearance_rad, LegJointValues& bound_m) {
  if (m.leg_geometry != LegGeometry::kPaperPlanar) return false;
  const LegPlane g = leg_plane(m, leg, p_H);
  const Vec3 lever(g.r, g.d, m.link_length_m[2]);
  for (int j = 0; j < m.leg(leg).n_joints; ++j)
    bound_m[j] = clearance_rad[j] * lever_lower_bound(lever[j]);
  return true;
}

/// Margins of one leg at one instant from its IK, folded into `out` (file comment of
/// posture.hpp). The joint margins need the leg's Jacobian; when their lower bounds
/// (joint_margin_bounds) show that none can lower out.value_m or out.joint_m, it is not formed:
/// what is folded into `out` and what the caller does with the result are the same.
SampleMargin leg_margin(const RobotModel& m, int leg, const Vec3& p_H, const LegIkResult& ik,
                        KinematicMargin& out) {
  SampleMargin s;
  const bool joint_refusal = !ik.ok && ik.reason.rfind("joint ", 0) == 0;
  if (!ik.ok) out.admitted = false;
  if (!ik.ok && !joint_refusal) {
    // Out of reach: no joint angles; the IK's margin (negative or below the minimum).
    s.value_m = ik.margin_m;
    s.binding = Binding::kReachRefused;
    out.reach_m = std::min(out.reach_m, ik.margin_m);
    return s;
  }
  if (ik.ok) {
    out.reach_m = std::min(out.reach_m, ik.margin_m);
    s.value_m = ik.margin_m;
    s.binding = Binding::kReachBoundary;
  }
  const int n_joints = m.leg(leg).n_joints;
  LegJointValues clearance{};
  for (int j = 0; j < n_joints; ++j) {
    const int k = m.joint(leg, j);
    clearance[j] = joint_clearance_rad(ik.q[j], m.joint_lower_rad[k], m.joint_upper_rad[k]);
  }
  LegJointValues bound{};
  if (ik.ok && joint_margin_bounds(m, leg, p_H, clearance, bound)) {
    const double floor_m = std::max(out.value_m, out.joint_m);
    bool needed = false;
    for (int j = 0; j < n_joints; ++j) {
      if (!std::isfinite(clearance[j])) continue;
      out.joint_rad = std::min(out.joint_rad, clearance[j]);
      needed = needed || !(bound[j] >= floor_m);
    }
    if (!needed) return s;
  }
  const LegJacobian J = leg_jacobian(m, leg, ik.q);
  for (int j = 0; j < n_joints; ++j) {
    const int k = m.joint(leg, j);
    const double lo = m.joint_lower_rad[k], hi = m.joint_upper_rad[k];
    const double c = clearance[j];
    if (!std::isfinite(c)) continue;
    out.joint_rad = std::min(out.joint_rad, c);
    const double c_m = c * J.col(j).norm();
    out.joint_m = std::min(out.joint_m, c_m);
    if (c_m < s.value_m) {
      s.value_m = c_m;
      s.binding = Binding::kJoint;
      s.joint = k;
      s.lower = std::abs(ik.q[j] - lo) <= std::abs(hi - ik.q[j]);
    }
  }
  return s;
}

/// The limiting sample's constraint in words ("reach: full extension", "joint L3_tibia upper
/// limit", ...).
std::string constraint_text(const RobotModel& m, int leg, const Vec3& p_H, const LegIkResult& ik,
                            const SampleMargin& s) {
  switch (s.binding) {
    case Binding::kReachRefused:
      return ik.reason.find("extension") != std::string::npos ? "reach: full extension"
             : ik.reason.find("fold") != std::string::npos    ? "reach: full fold"
                                                              : "reach: " + ik.reason;
    case Binding::kReachBoundary:
      return reach_boundary(m, leg, p_H);
    case Binding::kJoint:
      return "joint " + m.joint_source_names[s.joint] + (s.lower ? " lower" : " upper") + " limit";
    case Binding::kNone:
      break;
  }
  return std::string();
}

Vec3 target_in_hip(const RobotModel& model, const BaseState& trunk, int leg, const Vec3& p_W) {
  const Vec3 r_B = trunk.W_R_B.transpose() * (p_W - trunk.p_W);
  return model.R_B_H[leg].transpose() * (r_B - model.p_hip_B[leg]);
}

}  // namespace

namespace {

SampleBound bound_in_ball(const RobotModel& m, int leg, const Vec3& p, const LegIkResult& ik,
                          double radius_m) {
  const SampleBound none;
  if (m.leg_geometry != LegGeometry::kPaperPlanar || !ik.ok || !(radius_m > 0.0)) return none;
  const auto& L = m.link_length_m;
  const double D = radius_m, w = std::abs(m.lateral_m[leg]);
  const LegPlane g = leg_plane(m, leg, p);
  const double r_lo = g.r - D;
  // ρ > 0 in the ball (and above the IK's 1e-12 m² guard); atan2(y, x) continuous: the ball
  // keeps off its cut, the negative x axis.
  if (!(r_lo > w) || !(p.x() > D || std::abs(p.y()) > D)) return none;
  const double rho_lo = std::sqrt((r_lo - w) * (r_lo + w));
  if (!(rho_lo > 1e-5)) return none;
  const double k = r_lo / rho_lo;  // |Δ(u, v)| ≤ k |Δp|
  const double e = k * D;
  const double u = g.u, v = g.v, d_lo = g.d - e, d_hi = g.d + e;
  // Strictly inside the planar workspace (sin β3 > 0), and atan2(v, u) continuous.
  if (!(d_lo > std::abs(L[1] - L[2]) && d_hi < L[1] + L[2] && d_lo > 0.0)) return none;
  if (!(u > e || std::abs(v) > e)) return none;
  auto cos_knee = [&](double dist) {
    return (dist * dist - L[1] * L[1] - L[2] * L[2]) / (2.0 * L[1] * L[2]);
  };
  const double c_lo = cos_knee(d_lo), c_hi = cos_knee(d_hi);
  const double sin_lo = std::sqrt(std::max(1.0 - std::max(c_lo * c_lo, c_hi * c_hi), 0.0));
  if (!(sin_lo > 1e-9)) return none;
  SampleBound b;
  // β3 per metre of d; φ = atan2(l3 sin β3, l2 + l3 cos β3) per radian of β3,
  // l3 (l3 + l2 cos β3)/d², linear in cos β3: largest at an end.
  const double knee_d = d_hi / (L[1] * L[2] * sin_lo);
  const double phi_knee =
      L[2] * std::max(std::abs(L[2] + L[1] * c_lo), std::abs(L[2] + L[1] * c_hi)) / (d_lo * d_lo);
  b.slope[2] = k * knee_d;
  // β2 = atan2(v, u) − φ: the first moves across (u, v) (1/d), the second along it, so
  // their gradients are orthogonal.
  b.slope[1] = k * std::sqrt(1.0 / (d_lo * d_lo) + (phi_knee * knee_d) * (phi_knee * knee_d));
  b.slope[0] = 1.0 / rho_lo;
  // θ1 and β2 stay away from ±π, where the IK wraps them.
  for (int j = 0; j < 2; ++j)
    if (!(std::abs(ik.q[j]) + b.slope[j] * D < M_PI)) return none;
  const double lever[] = {r_lo, d_lo, L[2]};  // the paper geometry's three joints
  b.n_joints = m.leg(leg).n_joints;
  for (int j = 0; j < b.n_joints; ++j) {
    const int idx = m.joint(leg, j);
    const double lo = m.joint_lower_rad[idx], hi = m.joint_upper_rad[idx];
    b.clearance_rad[j] = joint_clearance_rad(ik.q[j], lo, hi);
    b.inside_rad[j] = std::min(ik.q[j] - lo, hi - ik.q[j]);
    b.lever_m[j] = lever_lower_bound(lever[j]);
  }
  b.reach_m = ik.margin_m;
  b.reach_slope = k;
  b.min_margin_m = m.ik_min_margin_m;
  b.radius_m = D;
  return b;
}

}  // namespace

SampleBound sample_bound(const RobotModel& m, int leg, const Vec3& p, const LegIkResult& ik,
                         double radius_m) {
  if (m.leg_geometry != LegGeometry::kPaperPlanar || !ik.ok) return SampleBound{};
  // The wrist moves about r/ρ times as far as the target, and must stay off full extension
  // and full fold: a ball of at most half the reach margin that way, then a quarter of that.
  const LegPlane g = leg_plane(m, leg, p);
  const double k = g.r / std::max(g.rho, 1e-150);
  const double D = std::min(radius_m, 0.5 * ik.margin_m / k);
  const SampleBound b = bound_in_ball(m, leg, p, ik, D);
  return b.radius_m > 0.0 ? b : bound_in_ball(m, leg, p, ik, 0.25 * D);
}

bool value_clears(const SampleBound& b, double delta_m, double floor_m) {
  if (!(b.radius_m > 0.0) || !(delta_m <= b.radius_m)) return false;
  if (!(b.reach_m - b.reach_slope * delta_m >= floor_m)) return false;
  for (int j = 0; j < b.n_joints; ++j) {
    if (!std::isfinite(b.clearance_rad[j])) continue;
    const double c = b.clearance_rad[j] - b.slope[j] * delta_m;
    if (!(c >= 0.0 && c * b.lever_m[j] >= floor_m)) return false;
  }
  return true;
}

bool admits(const SampleBound& b, double delta_m) {
  if (!(b.radius_m > 0.0) || !(delta_m <= b.radius_m)) return false;
  if (!(b.reach_m - b.reach_slope * delta_m >= b.min_margin_m + kSkipAllowance_m)) return false;
  for (int j = 0; j < b.n_joints; ++j)
    if (std::isfinite(b.clearance_rad[j]) &&
        !(b.inside_rad[j] - b.slope[j] * delta_m >= kSkipAllowance_m))
      return false;
  return true;
}

MarginBounds bounds_at(const SampleBound& b, double delta_m) {
  MarginBounds out;
  if (!(b.radius_m > 0.0) || !(delta_m <= b.radius_m)) return out;
  out.reach_m = b.reach_m - b.reach_slope * delta_m;
  out.admitted = out.reach_m >= b.min_margin_m + kSkipAllowance_m;
  double joint_m = kInf, joint_rad = kInf;
  for (int j = 0; j < b.n_joints; ++j) {
    if (!std::isfinite(b.clearance_rad[j])) continue;  // a continuous joint has no limit
    const double c = b.clearance_rad[j] - b.slope[j] * delta_m;
    joint_rad = std::min(joint_rad, c);
    joint_m = c >= 0.0 ? std::min(joint_m, c * b.lever_m[j]) : -kInf;
    out.admitted = out.admitted && b.inside_rad[j] - b.slope[j] * delta_m >= kSkipAllowance_m;
  }
  out.joint_m = joint_m;
  out.joint_rad = joint_rad;
  out.value_m = std::min(out.reach_m, joint_m);
  return out;
}

FootTrack foot_track(const RobotModel& model, const MotionPlan& plan, int uniform) {
  FootTrack f;
  f.t_s = margin_sample_times(plan, uniform);
  f.legs = model.legs();
  f.p_W.resize(f.t_s.size());
  // leg_foot_motion(leg, t).p_W, walking each leg's swings along the increasing times; a
  // sphere foot's centre, the IK's target, r n above it (kinematics/kinematics.hpp).
  for (int leg = 0; leg < model.legs(); ++leg) {
    const double radius = model.foot_radius_m[leg];
    const std::vector<Swing>& swings = plan.gait.legs[leg].swings;
    std::size_t k = 0;
    Vec3 foothold = plan.gait.legs[leg].p_initial_W;
    for (std::size_t i = 0; i < f.t_s.size(); ++i) {
      const double t = f.t_s[i];
      for (; k < swings.size() && t >= swings[k].t_touchdown_s; ++k)
        foothold = swings[k].p_touchdown_W;
      f.p_W[i][leg] = k < swings.size() && t >= swings[k].t_liftoff_s
                          ? swing_foot_position(swings[k], t)
                          : foothold;
      if (radius > 0.0)
        f.p_W[i][leg] += radius * leg_foot_normal(plan.gait.legs[leg], plan.terrain, t).n_W;
    }
  }
  return f;
}

namespace {

/// The limiting sample of a margin evaluation, kept as the complete evaluation in time order
/// keeps it: the smallest value, the first sample (i·legs + leg) of that value on ties.
struct Limit {
  int sample = -1;
  SampleMargin margin;
  Vec3 p_H = Vec3::Zero();
  std::string reason;

  bool take(KinematicMargin& out, const FootTrack& feet, int s, const SampleMargin& m,
            const Vec3& p, const LegIkResult& ik) {
    if (!(m.value_m < out.value_m || (m.value_m == out.value_m && s < sample))) return false;
    out.value_m = m.value_m;
    out.leg = s % feet.legs;
    out.t_s = feet.t_s[s / feet.legs];
    sample = s;
    margin = m;
    p_H = p;
    reason = m.binding == Binding::kReachRefused ? ik.reason : std::string();
    return true;
  }
};

KinematicMargin fresh_margin(const FootTrack& feet) {
  KinematicMargin out;
  out.value_m = out.reach_m = out.joint_m = out.joint_rad = kInf;
  out.admitted = true;
  out.samples = static_cast<int>(feet.t_s.size());
  return out;
}

void name_constraint(const RobotModel& model, const Limit& limit, KinematicMargin& out) {
  LegIkResult ik;
  ik.reason = limit.reason;
  out.constraint = constraint_text(model, out.leg, limit.p_H, ik, limit.margin);
}

/// A sample the bounds show to lower none of the minima of `out` nor to fail the IK.
bool cannot_matter(const MarginBounds& b, const KinematicMargin& out) {
  constexpr double eps = kSkipAllowance_m;
  return b.admitted && b.value_m >= out.value_m + eps && b.reach_m >= out.reach_m + eps &&
         b.joint_m >= out.joint_m + eps && b.joint_rad >= out.joint_rad + eps;
}

/// An admission's margin fields, not asked for: NaN.
void clear_unasked(KinematicMargin& out) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.value_m = out.reach_m = out.joint_m = out.joint_rad = out.t_s = nan;
}

/// refs for a new sample count: no sample evaluated yet, and the targets' path.
void reset_references(SampleReferences& refs, const TrunkMotion& trunk, const FootTrack& feet) {
  const int L = feet.legs;
  const int n = static_cast<int>(feet.t_s.size()), count = n * L;
  refs.slot.assign(count, -1);
  refs.entries.clear();
  refs.generation = 0;
  // The targets' path: the trunk keeps its attitude, so a target moves in its hip frame by
  // |Δp_W(foot) − Δp_W(trunk)| from one instant to the next, at every height.
  refs.path_m.assign(count, 0.0);
  Vec3 trunk_prev = trunk.at(feet.t_s[0]).p_W;
  for (int i = 1; i < n; ++i) {
    const Vec3 trunk_now = trunk.at(feet.t_s[i]).p_W;
    for (int leg = 0; leg < L; ++leg)
      refs.path_m[i * L + leg] =
          refs.path_m[(i - 1) * L + leg] +
          ((feet.p_W[i][leg] - feet.p_W[i - 1][leg]) - (trunk_now - trunk_prev)).norm();
    trunk_prev = trunk_now;
  }
}

/// One bounded evaluation at trunk height height_m [m]: what evaluating a sample exactly
/// and bounding it from a reference read and update. Sample s is i·legs + leg.
struct BoundedScan {
  const RobotModel& model;
  const TrunkMotion& trunk;
  const FootTrack& feet;
  double height_m;
  const MarginRequest& req;
  SampleReferences& refs;
  KinematicMargin& out;  ///< the minima so far
  Limit& limit;          ///< the sample that gives out.value_m
  int stamp;             ///< this evaluation's generation in refs
  bool bounded;          ///< bounds exist (the paper geometry)

  /// Sample s has been evaluated by this evaluation.
  bool done(int s) const {
    return refs.slot[s] >= 0 && refs.entries[refs.slot[s]].evaluation == stamp;
  }
  bool evaluate(int s);
  bool harmless(int s, double delta_m) const;
  bool covers(int leg, int ref, int from, int to) const;
};

/// Sample s exactly, as motion_kinematic_margin evaluates it; it becomes s's reference. True
/// when the motion is known to be below req.below_m (or, for an admission, refused).
bool BoundedScan::evaluate(int s) {
  const int i = s / feet.legs, leg = s % feet.legs;
  const Vec3 p_H = target_in_hip(model, trunk.at(feet.t_s[i]), leg, feet.p_W[i][leg]);
  const LegIkResult ik = leg_inverse_kinematics(model, leg, p_H);
  limit.take(out, feet, s, leg_margin(model, leg, p_H, ik, out), p_H, ik);
  if (refs.slot[s] < 0) {
    refs.slot[s] = static_cast<int>(refs.entries.size());
    refs.entries.emplace_back();
  }
  SampleReferences::Entry& entry = refs.entries[refs.slot[s]];
  entry.height_m = height_m;
  entry.evaluation = stamp;
  if (bounded) entry.bound = sample_bound(model, leg, p_H, ik, kBoundRadius_m);
  return out.value_m < req.below_m || (req.kind == Evaluation::kAdmission && !out.admitted);
}

/// Bounds of any sample within delta_m of sample s's target at this height (from s's reference
/// at its own height: moving the trunk by Δh moves a target by |Δh|), and whether they show
/// it harmless: unable to lower the margin (and, for a check, any minimum or the IK).
bool BoundedScan::harmless(int s, double delta_m) const {
  if (refs.slot[s] < 0) return false;
  const SampleReferences::Entry& entry = refs.entries[refs.slot[s]];
  const SampleBound& b = entry.bound;
  const double delta = delta_m + std::abs(height_m - entry.height_m) + 1e-12;
  switch (req.kind) {
    case Evaluation::kCandidate:
      return value_clears(b, delta, out.value_m + kSkipAllowance_m);
    case Evaluation::kCheck:
      return cannot_matter(bounds_at(b, delta), out);
    case Evaluation::kAdmission:
      return admits(b, delta);
  }
  return false;
}

/// Instants [from, to) of `leg` from instant `ref`: their targets lie within the path from
/// ref's (the rounding of the sums allowed for), and ref's bounds show them harmless.
bool BoundedScan::covers(int leg, int ref, int from, int to) const {
  if (from >= to) return true;
  const int L = feet.legs;
  const double path_m =
      std::max(std::abs(refs.path_m[(to - 1) * L + leg] - refs.path_m[ref * L + leg]),
               std::abs(refs.path_m[from * L + leg] - refs.path_m[ref * L + leg]));
  return harmless(ref * L + leg, path_m * (1.0 + 1e-12) + 1e-12);
}

/// Every stride-th instant of n, and the last.
std::vector<int> coarse_instants(int n, int stride) {
  std::vector<int> top;
  for (int i = 0; i < n; i += stride) top.push_back(i);
  if (top.back() != n - 1) top.push_back(n - 1);
  return top;
}

/// Per leg, the instants between two of `top` bounded from the nearer (its farthest target's
/// distance); where that cannot show them harmless the middle instant is taken (evaluated
/// unless harmless) and both halves bounded again. True when the motion is known below.
bool refine_between(BoundedScan& scan, const std::vector<int>& top, int leg) {
  std::vector<std::pair<int, int>> pending;
  for (std::size_t k = 0; k + 1 < top.size(); ++k) pending.emplace_back(top[k], top[k + 1]);
  while (!pending.empty()) {
    const auto [a, b] = pending.back();
    pending.pop_back();
    if (b - a < 2) continue;
    const int mid = (a + b) / 2;
    if (scan.covers(leg, a, a + 1, mid + 1) && scan.covers(leg, b, mid + 1, b)) continue;
    const int s = mid * scan.feet.legs + leg;
    if (!scan.done(s) && !scan.harmless(s, 0.0) && scan.evaluate(s)) return true;
    pending.emplace_back(a, mid);
    pending.emplace_back(mid, b);
  }
  return false;
}

/// Evaluates the samples that can matter, req.hot first; true as soon as the motion is
/// known to be below req.below_m (the evaluation stops there).
bool scan_samples(BoundedScan& scan) {
  const int L = scan.feet.legs;
  const int n = static_cast<int>(scan.feet.t_s.size()), count = n * L;
  if (scan.req.hot)
    for (int s : *scan.req.hot)
      if (!scan.done(s) && scan.evaluate(s)) return true;
  if (!scan.bounded) {
    for (int s = 0; s < count; ++s)
      if (!scan.done(s) && scan.evaluate(s)) return true;
    return false;
  }
  // Every req.stride-th instant and the last, each skipped when its own reference shows it
  // harmless; then the instants between them (refine_between). Skipping with the minima
  // found so far is safe: they only decrease.
  const std::vector<int> top = coarse_instants(n, scan.req.stride);
  for (int i : top)
    for (int leg = 0; leg < L; ++leg) {
      const int s = i * L + leg;
      if (!scan.done(s) && !scan.harmless(s, 0.0) && scan.evaluate(s)) return true;
    }
  for (int leg = 0; leg < L; ++leg)
    if (refine_between(scan, top, leg)) return true;
  return false;
}

}  // namespace

MarginEvaluation bounded_margin(const RobotModel& model, const TrunkMotion& trunk,
                                const FootTrack& feet, double height_m, const MarginRequest& req,
                                SampleReferences& refs) {
  MarginEvaluation e;
  KinematicMargin& out = e.margin;
  out = fresh_margin(feet);
  Limit limit;
  const int count = static_cast<int>(feet.t_s.size()) * feet.legs;
  if (static_cast<int>(refs.slot.size()) != count) reset_references(refs, trunk, feet);
  const int stamp = ++refs.generation;
  const bool bounded = model.leg_geometry == LegGeometry::kPaperPlanar;
  BoundedScan scan{model, trunk, feet, height_m, req, refs, out, limit, stamp, bounded};
  const bool below = scan_samples(scan);
  e.limiting_sample = limit.sample;
  if (below) {
    e.complete = false;
  } else if (req.kind == Evaluation::kCheck) {
    name_constraint(model, limit, out);
  }
  if (req.kind == Evaluation::kAdmission) clear_unasked(out);
  return e;
}

KinematicMargin full_margin(const RobotModel& model, const TrunkMotion& trunk,
                            const FootTrack& feet) {
  KinematicMargin out = fresh_margin(feet);
  Limit limit;
  for (std::size_t i = 0; i < feet.t_s.size(); ++i) {
    const BaseState state = trunk.at(feet.t_s[i]);
    for (int leg = 0; leg < feet.legs; ++leg) {
      const Vec3 p_H = target_in_hip(model, state, leg, feet.p_W[i][leg]);
      const LegIkResult ik = leg_inverse_kinematics(model, leg, p_H);
      limit.take(out, feet, static_cast<int>(i) * feet.legs + leg,
                 leg_margin(model, leg, p_H, ik, out), p_H, ik);
    }
  }
  name_constraint(model, limit, out);
  return out;
}

}  // namespace hexdyn::margin_detail
