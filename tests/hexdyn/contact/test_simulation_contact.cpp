// The contact law of forward simulation (contact/simulation_contact.hpp,
// docs/theory/replay.md#contact), each part against a second computation: a block sliding to
// rest against the closed-form distance v0²/(2 μ_d g) and the energy it dissipates; the
// linearisation against central differences in every regime; the dissipated powers against
// their definitions; the terrain contact against the distance to the staircase's boxes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "hexdyn/contact/impact.hpp"
#include "hexdyn/contact/simulation_contact.hpp"
#include "hexdyn/core/height_map.hpp"
#include "hexdyn/planning/terrain.hpp"
#include "hexdyn/sample_models.hpp"

using namespace hexdyn;

namespace {

/// The paper's compliant law as Table 1 reads in SI (K = 1e5 N/m^2.2, e = 2.2, C_max = 10 N s/m,
/// p = 1e-5 m; configs/variants/paper_contact_si_literal.yaml) with the tangential law's
/// parameters.
ContactParams contact_law(double mu_s, double mu_d, double v_s, double v_d) {
  ContactParams c = test::contact_params(1e5, 2.2, 10.0, 1e-5);
  c.static_friction = mu_s;
  c.dynamic_friction = mu_d;
  c.stiction_velocity_mps = v_s;
  c.friction_velocity_mps = v_d;
  return c;
}

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Vec3(n(rng), n(rng), n(rng)).normalized();
}

/// A unit vector perpendicular to n.
Vec3 tangent_of(const Vec3& n, std::mt19937& rng) {
  const Vec3 a = random_unit(rng);
  return (a - a.dot(n) * n).normalized();
}

// ---- a block sliding to rest ----

/// A point mass m on flat ground z = 0 (outward normal +z) under gravity: position, velocity
/// and the energy the contact has dissipated so far.
struct Block {
  Vec3 p = Vec3::Zero(), v = Vec3::Zero();
  double dissipated_J = 0.0;
};

struct BlockRate {
  Vec3 dp, dv;
  double dissipation_W;
};

BlockRate block_rate(const ContactParams& c, double m, const Block& b) {
  const FootContactForce f = foot_contact_force(c, -b.p.z(), Vec3::UnitZ(), b.v);
  return {b.v, f.force_W / m + Vec3(0.0, 0.0, -kGravity), f.damping_power_W + f.slip_power_W};
}

Block advanced(const Block& b, const BlockRate& r, double h) {
  Block out;
  out.p = b.p + h * r.dp;
  out.v = b.v + h * r.dv;
  out.dissipated_J = b.dissipated_J + h * r.dissipation_W;
  return out;
}

/// One classical Runge–Kutta step of length h.
Block rk4_step(const ContactParams& c, double m, const Block& b, double h) {
  const BlockRate k1 = block_rate(c, m, b);
  const BlockRate k2 = block_rate(c, m, advanced(b, k1, 0.5 * h));
  const BlockRate k3 = block_rate(c, m, advanced(b, k2, 0.5 * h));
  const BlockRate k4 = block_rate(c, m, advanced(b, k3, h));
  const BlockRate sum{
      k1.dp + 2.0 * k2.dp + 2.0 * k3.dp + k4.dp, k1.dv + 2.0 * k2.dv + 2.0 * k3.dv + k4.dv,
      k1.dissipation_W + 2.0 * k2.dissipation_W + 2.0 * k3.dissipation_W + k4.dissipation_W};
  return advanced(b, sum, h / 6.0);
}

/// Mechanical energy of the block: kinetic, gravity and the spring's K δ^(e+1)/(e+1) [J].
double block_energy(const ContactParams& c, double m, const Block& b) {
  const double delta = std::max(0.0, -b.p.z());
  return 0.5 * m * b.v.squaredNorm() + m * kGravity * b.p.z() +
         c.stiffness * std::pow(delta, c.exponent + 1.0) / (c.exponent + 1.0);
}

/// The block at its rest penetration under its weight, moving along +y at v0.
Block launched_block(const ContactParams& c, double m, double v0) {
  Block b;
  b.p = Vec3(0.0, 0.0, -static_penetration(c, m * kGravity));
  b.v = Vec3(0.0, v0, 0.0);
  return b;
}

/// The launched block integrated with RK4 steps of h until its speed is below 1e-12 m/s (in
/// the stiction zone the speed decays exponentially, at the rate 1.5 μ_s g / v_s: it never
/// stops exactly).
Block slide_to_rest(const ContactParams& c, double m, double v0, double h) {
  Block b = launched_block(c, m, v0);
  const double t_max = 2.0 * v0 / (c.dynamic_friction * kGravity) + 1.0;
  for (double t = 0.0; t < t_max && b.v.norm() > 1e-12; t += h) b = rk4_step(c, m, b, h);
  return b;
}

}  // namespace

TEST_CASE("the friction coefficient follows the ADAMS form", "[contact][friction]") {
  const ContactParams c = contact_law(0.5, 0.3, 1e-3, 1e-2);
  // The STEPs' end values and the odd cubic through zero: μ = μ_s (3x − x³)/2, x = s/v_s.
  CHECK(sliding_friction_coefficient(c, 0.0) == 0.0);
  CHECK(sliding_friction_coefficient(c, 1e-3) == Approx(0.5).epsilon(1e-15));
  CHECK(sliding_friction_coefficient(c, 1e-2) == Approx(0.3).epsilon(1e-15));
  CHECK(sliding_friction_coefficient(c, 7.0) == 0.3);
  for (double x : {0.1, 0.37, 0.8}) {
    CHECK(sliding_friction_coefficient(c, x * 1e-3) ==
          Approx(0.5 * (3.0 * x - x * x * x) / 2.0).epsilon(1e-13));
  }
  // Between v_s and v_d: μ_s + (μ_d − μ_s) Δ²(3 − 2Δ), Δ = (s − v_s)/(v_d − v_s).
  const double delta = 0.25;
  CHECK(sliding_friction_coefficient(c, 1e-3 + delta * 9e-3) ==
        Approx(0.5 - 0.2 * delta * delta * (3.0 - 2.0 * delta)).epsilon(1e-13));
  // The slope against central differences, in each part.
  for (double s : {0.0, 3e-4, 9e-4, 2e-3, 6e-3, 9.9e-3, 0.5}) {
    const double h = 1e-9;
    const double lo = sliding_friction_coefficient(c, std::max(0.0, s - h));
    const double fd =
        (sliding_friction_coefficient(c, s + h) - lo) / (s + h - std::max(0.0, s - h));
    CHECK(sliding_friction_slope(c, s) == Approx(fd).epsilon(1e-5).margin(1e-6));
  }
}

TEST_CASE("a block slides to rest at v0^2/(2 mu_d g)", "[contact][friction]") {
  // Along the slide the block stays at its rest penetration (the normal force is its weight
  // m g: the normal law does not see the tangential motion on a flat face), so m dv/dt =
  // −μ(v) m g and the distance to rest is D = ∫₀^v0 v dv / (μ(v) g). With μ = μ_d beyond v_d,
  // μ ≤ μ_s everywhere, μ ≥ μ_d between v_s and v_d (μ_s ≥ μ_d) and μ(v) ≥ μ_s v / v_s below
  // v_s ((3x − x³)/2 ≥ x for x ≤ 1):
  //   (v0² − v_d²)/(2 μ_d g) + v_d²/(2 μ_s g)  ≤  D  ≤  (v0² − v_s²)/(2 μ_d g) + v_s²/(μ_s g).
  // With μ_s = μ_d = μ the bracket is [v0²/(2 μ g), v0²/(2 μ g) + v_s²/(2 μ g)]: relative width
  // (v_s/v0)² = 1e-6 here; with μ_s > μ_d its relative width is at most (v_d/v0)² = 1e-4.
  // The contact of configs/paper.yaml (K = 1e5 · 1000^2.2 N/m^2.2, C_max = 1e4 N s/m: the
  // block sinks 11 µm), the steps short enough for its normal modes (−100 and −2e4 1/s).
  const double m = 0.5, v0 = 1.0, h = 5e-5;
  struct Case {
    double mu_s, mu_d;
  };
  for (const Case k : {Case{0.3, 0.3}, Case{0.6, 0.3}}) {
    ContactParams c = contact_law(k.mu_s, k.mu_d, 1e-3, 1e-2);
    c.stiffness = 1e5 * std::pow(1000.0, 2.2);
    c.damping_max_Nspm = 1e4;
    const double vs = c.stiction_velocity_mps, vd = c.friction_velocity_mps, g = kGravity;
    const double closed_form = v0 * v0 / (2.0 * k.mu_d * g);
    const double lower = (v0 * v0 - vd * vd) / (2.0 * k.mu_d * g) + vd * vd / (2.0 * k.mu_s * g);
    const double upper = (v0 * v0 - vs * vs) / (2.0 * k.mu_d * g) + vs * vs / (k.mu_s * g);
    const Block start = launched_block(c, m, v0);
    const Block end = slide_to_rest(c, m, v0, h);
    const double distance = end.p.y();
    INFO("mu_s " << k.mu_s << " mu_d " << k.mu_d << ": distance " << distance << " m, closed form "
                 << closed_form << " m, bracket [" << lower << ", " << upper << "]");
    // The integration error (RK4 integrates the constant deceleration exactly; the C¹
    // transitions and the stiction zone's fast decay leave ~1e-9 relative) on top of the
    // bracket.
    CHECK(distance >= lower * (1.0 - 1e-8));
    CHECK(distance <= upper * (1.0 + 1e-8));
    CHECK(std::abs(distance / closed_form - 1.0) <= (k.mu_s == k.mu_d ? 2e-6 : 2e-4));
    // It stayed at its rest penetration and went straight.
    CHECK(end.p.z() == Approx(start.p.z()).epsilon(1e-9));
    CHECK(std::abs(end.p.x()) == 0.0);
    // Energy: the kinetic energy went into slip (∫ P_slip dt), the normal damper took none.
    CHECK(end.dissipated_J ==
          Approx(block_energy(c, m, start) - block_energy(c, m, end)).epsilon(1e-9));
    CHECK(end.dissipated_J == Approx(0.5 * m * v0 * v0).epsilon(1e-9));
  }
}

TEST_CASE("a block thrown onto the ground: what the contact dissipates is the energy lost",
          "[contact][friction]") {
  // Touchdown at 0.5 m/s down and 0.8 m/s along the ground: the normal damper (with its
  // clip on the rebound) and the slip dissipate; E(0) − E(T) = ∫ (P_damping + P_slip) dt.
  const ContactParams c = contact_law(0.6, 0.4, 1e-3, 1e-2);
  const double m = 0.2;
  auto run = [&](double h) {
    Block b;
    b.p = Vec3(0.0, 0.0, 1e-4);
    b.v = Vec3(0.3, 0.8, -0.5);
    const Block start = b;
    for (double t = 0.0; t < 0.1; t += h) b = rk4_step(c, m, b, h);
    return std::make_pair(start, b);
  };
  const auto [start, end] = run(1e-6);
  const double lost = block_energy(c, m, start) - block_energy(c, m, end);
  INFO("energy lost " << lost << " J, dissipated " << end.dissipated_J << " J");
  CHECK(lost > 0.01);
  CHECK(end.dissipated_J == Approx(lost).epsilon(1e-6));
}

TEST_CASE("foot_contact_force: dF/dv and dF/dp against central differences", "[contact]") {
  const ContactParams c = contact_law(0.5, 0.3, 1e-3, 1e-2);
  std::mt19937 rng(3301);
  // Slip speeds inside each regime: zero, stiction, transition, sliding.
  for (double s : {0.0, 0.4e-3, 5e-3, 0.2}) {
    // Penetrations inside the damping ramp and beyond it.
    for (double delta : {4e-6, 2e-4, 3e-3}) {
      for (int trial = 0; trial < 4; ++trial) {
        const Vec3 n = random_unit(rng);
        // Pressing in (δ̇ > 0): the force is not clipped.
        const double rate = uniform(rng, 0.1, 1.0) * 1e-2;
        const Vec3 v = s * tangent_of(n, rng) - rate * n;
        const FootContactForce f = foot_contact_force(c, delta, n, v);
        REQUIRE(f.normal_N > c.stiffness * std::pow(delta, c.exponent));
        const double hv = 1e-9, hp = 1e-4 * std::min(delta, c.full_damping_depth_m);
        Mat3 dv_fd, dp_fd;
        for (int j = 0; j < 3; ++j) {
          const Vec3 e = Vec3::Unit(j);
          dv_fd.col(j) = (foot_contact_force(c, delta, n, v + hv * e).force_W -
                          foot_contact_force(c, delta, n, v - hv * e).force_W) /
                         (2.0 * hv);
          // Moving the contact point by +h e changes the penetration by −h n·e.
          dp_fd.col(j) = (foot_contact_force(c, delta - hp * n[j], n, v).force_W -
                          foot_contact_force(c, delta + hp * n[j], n, v).force_W) /
                         (2.0 * hp);
        }
        INFO("slip " << s << " m/s, penetration " << delta << " m\ndF/dv\n"
                     << f.dF_dv << "\nFD\n"
                     << dv_fd << "\ndF/dp\n"
                     << f.dF_dp << "\nFD\n"
                     << dp_fd);
        CHECK((f.dF_dv - dv_fd).norm() <= 1e-6 * std::max(1.0, dv_fd.norm()));
        CHECK((f.dF_dp - dp_fd).norm() <= 1e-6 * dp_fd.norm());
      }
    }
  }
}

TEST_CASE("foot_contact_force: the dissipated powers are their definitions", "[contact]") {
  const ContactParams c = contact_law(0.5, 0.3, 1e-3, 1e-2);
  std::mt19937 rng(3303);
  int clipped = 0, in_contact = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double delta = uniform(rng, -1e-4, 1e-3) * std::pow(10.0, uniform(rng, -2.0, 0.0));
    const Vec3 n = random_unit(rng);
    const Vec3 v = std::pow(10.0, uniform(rng, -5.0, 0.0)) * random_unit(rng);
    const FootContactForce f = foot_contact_force(c, delta, n, v);
    CHECK(f.damping_power_W >= 0.0);
    CHECK(f.slip_power_W >= 0.0);
    if (!(delta > 0.0)) {
      CHECK(f.force_W.isZero(0.0));
      CHECK(f.damping_power_W == 0.0);
      continue;
    }
    ++in_contact;
    // Second computation: the normal law of eq. 7, the slip velocity and μ(s).
    const double rate = -n.dot(v);
    const double spring = c.stiffness * std::pow(delta, c.exponent);
    const double fn = impact_normal_force(c, delta, rate);
    if (fn == 0.0) ++clipped;
    const Vec3 vt = v - n.dot(v) * n;
    const double mu = sliding_friction_coefficient(c, vt.norm());
    CHECK(f.normal_N == Approx(fn).epsilon(1e-14));
    CHECK((f.slip_velocity_W - vt).norm() <= 1e-15 * v.norm());
    CHECK(f.slip_power_W == Approx(mu * fn * vt.norm()).epsilon(1e-12));
    CHECK(f.slip_power_W == Approx(-f.tangential_W.dot(vt)).epsilon(1e-12));
    CHECK(f.damping_power_W == Approx((fn - spring) * rate).epsilon(1e-12));
    CHECK(std::abs(f.tangential_W.dot(n)) <= 1e-14 * std::max(1.0, f.tangential_W.norm()));
    CHECK(f.tangential_W.norm() <= (c.static_friction * fn) * (1.0 + 1e-14));
    CHECK((f.force_W - (fn * n + f.tangential_W)).norm() <= 1e-14 * std::max(1.0, fn));
  }
  CHECK(in_contact > 500);
  CHECK(clipped > 50);  // the clip's branch was met
}

// ---- terrain contact against the staircase's boxes ----
namespace {

/// Distance from (y, z) to the closed box [y0, y1] × [z0, z1] (infinite bounds allowed) and
/// its nearest point.
double box_distance(double y, double z, double y0, double y1, double z0, double z1, double& cy,
                    double& cz) {
  cy = std::clamp(y, y0, y1);
  cz = std::clamp(z, z0, z1);
  return std::hypot(y - cy, z - cz);
}

/// The staircase as a union of boxes, independent of terrain_profile: the solid is {z ≤ g} ∪
/// ⋃_k {y ≥ Y_k, z ≤ g + k h}; the air is ⋃_k {Y_k ≤ y ≤ Y_k+1, z ≥ g + k h} (Y_0 = −∞,
/// Y_{N+1} = +∞). A point outside is at the distance of the nearest solid box, one inside at
/// that of the nearest air box; the outward normal points from the nearest solid point to
/// the point (from the point to the nearest air point).
struct BoxAnswer {
  double signed_distance = 0.0;
  Vec3 normal = Vec3::UnitZ();
};

BoxAnswer staircase_boxes(const TerrainParams& t, const Vec3& p) {
  const double inf = std::numeric_limits<double>::infinity();
  auto riser_y = [&](int k) {
    return k <= 0 ? -inf : k > t.steps ? inf : t.first_riser_y_m + (k - 1) * t.tread_depth_m;
  };
  const Terrain terrain(t);
  const bool inside = p.z() < terrain.height(0.0, p.y());
  double best = inf, by = 0.0, bz = 0.0;
  for (int k = 0; k <= t.steps; ++k) {
    const double zk = t.ground_height_m + k * t.riser_height_m;
    double cy = 0.0, cz = 0.0;
    const double d = inside
                         ? box_distance(p.y(), p.z(), riser_y(k), riser_y(k + 1), zk, inf, cy, cz)
                         : box_distance(p.y(), p.z(), riser_y(k), inf, -inf, zk, cy, cz);
    if (d < best) {
      best = d;
      by = cy;
      bz = cz;
    }
  }
  BoxAnswer a;
  a.signed_distance = inside ? -best : best;
  const Vec3 away(0.0, p.y() - by, p.z() - bz);
  if (away.norm() > 0.0) a.normal = (inside ? -away : away).normalized();
  return a;
}

TerrainParams test_stairs() {
  TerrainParams t;
  t.type = TerrainType::kStairs;
  t.ground_height_m = 0.013;
  t.riser_height_m = 0.05;
  t.tread_depth_m = 0.25;
  t.steps = 4;
  t.first_riser_y_m = 0.3;
  return t;
}

}  // namespace

TEST_CASE("terrain_contact on stairs against the distance to the staircase's boxes", "[contact]") {
  const TerrainParams t = test_stairs();
  // The profile over a window shorter than the stairs' own reach: every riser with one
  // tread of ground before and of top tread after, the ends continued as rays.
  const TerrainProfile prof = terrain_profile(t, 0.2, 1.0);
  const double Y2 = t.first_riser_y_m + t.tread_depth_m;  // the second riser
  const double z1 = t.ground_height_m + t.riser_height_m, z2 = z1 + t.riser_height_m;
  const double top = t.ground_height_m + t.steps * t.riser_height_m;
  const double y_end = t.first_riser_y_m + (t.steps - 1) * t.tread_depth_m;
  struct Region {
    const char* name;
    double y0, y1, z0, z1;
  };
  const Region regions[] = {
      {"tread", Y2 + 0.05, Y2 + 0.2, z2 - 0.01, z2 + 0.01},
      {"riser face, in front", Y2 - 0.01, Y2 - 1e-4, z1 + 0.005, z2 - 0.005},
      {"riser face, behind", Y2 + 1e-4, Y2 + 0.01, z1 + 0.005, z2 - 0.005},
      {"nosing, outside", Y2 - 0.01, Y2, z2, z2 + 0.01},
      {"nosing, around", Y2 - 0.01, Y2 + 0.01, z2 - 0.01, z2 + 0.01},
      {"riser corner", Y2 - 0.01, Y2 + 0.01, z1 - 0.01, z1 + 0.01},
      {"above the top tread", y_end + 0.5, y_end + 2.0, top - 0.01, top + 0.05},
      {"before the first riser", -1.0, t.first_riser_y_m - 0.01, t.ground_height_m - 0.01,
       t.ground_height_m + 0.05},
  };
  std::mt19937 rng(3307);
  for (const Region& r : regions) {
    for (double radius : {0.0, 0.004, 0.02}) {
      for (int trial = 0; trial < 60; ++trial) {
        const Vec3 p(uniform(rng, -0.1, 0.1), uniform(rng, r.y0, r.y1), uniform(rng, r.z0, r.z1));
        const TerrainContactPoint got = terrain_contact(prof.y_m, prof.z_m, p, radius);
        const BoxAnswer want = staircase_boxes(t, p);
        INFO(r.name << ", radius " << radius << ", p = (" << p.y() << ", " << p.z()
                    << "): penetration " << got.penetration_m << " vs "
                    << radius - want.signed_distance << ", normal " << got.normal_W.transpose()
                    << " vs " << want.normal.transpose());
        CHECK(got.penetration_m == Approx(radius - want.signed_distance).margin(1e-14));
        CHECK((got.normal_W - want.normal).norm() <= 1e-12);
        const Vec3 point = radius > 0.0 ? Vec3(p - radius * want.normal) : p;
        CHECK((got.point_W - point).norm() <= 1e-12);
      }
    }
  }
}

TEST_CASE("terrain_contact at a riser's exact y", "[contact]") {
  const TerrainParams t = test_stairs();
  const TerrainProfile prof = terrain_profile(t, 0.2, 1.0);
  const double Y = t.first_riser_y_m + t.tread_depth_m;
  const double z1 = t.ground_height_m + t.riser_height_m, z2 = z1 + t.riser_height_m;
  // Above the nosing: outside, the normal up (from the nosing to the point).
  TerrainContactPoint c = terrain_contact(prof.y_m, prof.z_m, Vec3(0.0, Y, z2 + 0.003), 0.0);
  CHECK(c.penetration_m == Approx(-0.003).epsilon(1e-12));
  CHECK((c.normal_W - Vec3::UnitZ()).norm() <= 1e-15);
  // A sphere resting there touches the tread by 1 mm.
  c = terrain_contact(prof.y_m, prof.z_m, Vec3(0.0, Y, z2 + 0.003), 0.004);
  CHECK(c.penetration_m == Approx(0.001).epsilon(1e-12));
  CHECK((c.point_W - Vec3(0.0, Y, z2 - 0.001)).norm() <= 1e-15);
  // Below the lower tread, under the riser's foot: inside, 2 mm deep, the way out is up.
  c = terrain_contact(prof.y_m, prof.z_m, Vec3(0.0, Y, z1 - 0.002), 0.0);
  CHECK(c.penetration_m == Approx(0.002).epsilon(1e-12));
  CHECK((c.normal_W - Vec3::UnitZ()).norm() <= 1e-15);
  // On the riser's face: on the surface.
  c = terrain_contact(prof.y_m, prof.z_m, Vec3(0.0, Y, 0.5 * (z1 + z2)), 0.0);
  CHECK(c.penetration_m == 0.0);
  CHECK((c.normal_W - Vec3(0.0, -1.0, 0.0)).norm() <= 1e-15);
  // On the nosing itself: the mean of the riser's and the tread's normals.
  c = terrain_contact(prof.y_m, prof.z_m, Vec3(0.0, Y, z2), 0.0);
  CHECK(c.penetration_m == 0.0);
  CHECK((c.normal_W - Vec3(0.0, -1.0, 1.0).normalized()).norm() <= 1e-15);
}

TEST_CASE("terrain_contact on a slope and flat ground: the distance to the plane", "[contact]") {
  for (double slope : {0.0, 0.3}) {
    TerrainParams t;
    t.type = slope == 0.0 ? TerrainType::kFlat : TerrainType::kSlope;
    t.ground_height_m = 0.02;
    t.slope_rad = slope;
    t.slope_origin_y_m = 0.1;
    const TerrainProfile prof = terrain_profile(t, -0.5, 0.5);
    const Terrain terrain(t);
    const Vec3 n = terrain.normal(0.0, 0.0);
    const Vec3 on_plane(0.0, t.slope_origin_y_m, t.ground_height_m);
    std::mt19937 rng(3311);
    for (int trial = 0; trial < 200; ++trial) {
      // Also beyond the profile's ends, where its end segments continue.
      const Vec3 p(uniform(rng, -1, 1), uniform(rng, -2.0, 2.0),
                   terrain.height(0.0, 0.0) + uniform(rng, -0.5, 0.5));
      const double r = uniform(rng, 0.0, 0.03);
      const TerrainContactPoint c = terrain_contact(prof.y_m, prof.z_m, p, r);
      CHECK(c.penetration_m == Approx(r - (p - on_plane).dot(n)).margin(1e-13));
      CHECK((c.normal_W - n).norm() <= 1e-14);
    }
  }
}

namespace {

/// A height map of nx × ny nodes at spacing res from (0, 0), heights f(x, y).
HeightMap sampled_map(int nx, int ny, double res, double (*f)(double, double)) {
  HeightMap m;
  m.nx = nx;
  m.ny = ny;
  m.resolution_m = res;
  for (int i = 0; i < ny; ++i)
    for (int j = 0; j < nx; ++j) m.z_m.push_back(f(j * res, i * res));
  return m;
}

/// The distance from p to a surface z(x) that does not depend on y, the polyline through
/// (x_k, z_k) continued flat beyond its ends, in the x–z plane: the nearest of its segments.
double distance_to_profile(const std::vector<Eigen::Vector2d>& v, const Vec3& p) {
  const Eigen::Vector2d q(p.x(), p.z());
  std::vector<Eigen::Vector2d> pts = v;
  pts.insert(pts.begin(), Eigen::Vector2d(v.front().x() - 10.0, v.front().y()));
  pts.push_back(Eigen::Vector2d(v.back().x() + 10.0, v.back().y()));
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const Eigen::Vector2d a = pts[k], d = pts[k + 1] - pts[k];
    const double t = std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (q - (a + t * d)).norm());
  }
  return best;
}

double slab(double x, double) { return x >= 0.2 ? 0.1 : 0.0; }  // a 0.1 m slab from x = 0.2 m
double wall(double x, double) { return x >= 0.2 && x <= 0.21 + 1e-9 ? 0.1 : 0.0; }  // 1 cm thick
double tilted(double x, double y) { return 0.05 + 0.3 * x - 0.2 * y; }

}  // namespace

TEST_CASE("height_map_contact: no contact with a slab's or a wall's side from above or beside",
          "[contact]") {
  // The cell from x = 0.19 to 0.2 rises 0.1 m: its tangent plane (n_z about 0.1) passes close
  // to points far above it and beside it. The exact distance is that to the bilinear profile
  // over x; the check fails without the bound (a swing foot high above the cell "touches").
  struct Case {
    double (*f)(double, double);
    std::vector<Eigen::Vector2d> profile;
  };
  const Case cases[] = {{slab, {{0.19, 0.0}, {0.2, 0.1}}},
                        {wall, {{0.19, 0.0}, {0.2, 0.1}, {0.21, 0.1}, {0.22, 0.0}}}};
  std::mt19937 rng(4407);
  for (const Case& k : cases) {
    const HeightMap m = sampled_map(41, 11, 0.01, k.f);
    int clear = 0, touching = 0;
    for (int trial = 0; trial < 400; ++trial) {
      const double r = uniform(rng, 0.0, 0.03);
      const Vec3 p(uniform(rng, 0.15, 0.26), uniform(rng, 0.03, 0.07), uniform(rng, 0.0, 0.2));
      if (p.z() < m.height(p.x(), p.y())) continue;  // inside the solid
      const TerrainContactPoint c = height_map_contact(m, p, r);
      const double d = distance_to_profile(k.profile, p);
      // Within a cell the surface takes every height between its nodes' least and largest, so
      // each point of the cell's bounding box lies within a cell diagonal, √2 res, of it: a
      // sphere clearing the surface by more than that clears every box, and is not in contact.
      if (d > r + std::sqrt(2.0) * m.resolution_m) {
        ++clear;
        CHECK(c.penetration_m <= 0.0);
      } else if (d <= r) {
        ++touching;
      }
    }
    CHECK(clear > 100);
    CHECK(touching > 5);
  }
}

TEST_CASE("height_map_contact on a plane: the distance to the plane", "[contact]") {
  const HeightMap m = sampled_map(41, 41, 0.01, tilted);
  const Vec3 n = Vec3(-0.3, 0.2, 1.0).normalized();
  const Vec3 on_plane(0.0, 0.0, tilted(0.0, 0.0));
  std::mt19937 rng(4408);
  for (int trial = 0; trial < 200; ++trial) {
    const double r = uniform(rng, 0.0, 0.03);
    const double x = uniform(rng, 0.05, 0.35), y = uniform(rng, 0.05, 0.35);
    const Vec3 p(x, y, tilted(x, y) + uniform(rng, -0.01, 0.05));
    const TerrainContactPoint c = height_map_contact(m, p, r);
    CHECK(c.penetration_m == Approx(r - (p - on_plane).dot(n)).margin(1e-13));
    CHECK((c.normal_W - n).norm() <= 1e-12);
  }
}
