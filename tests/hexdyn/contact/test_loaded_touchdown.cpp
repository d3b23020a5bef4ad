// Loaded touchdowns (contact.touchdown: loaded, docs/theory/contact.md#loaded-touchdowns):
// the transient m δ̈ = L − F_n against the analytic damped linear oscillator under a step
// load, its settling at L at the static penetration of the paper's law, and the load share
// against the barycentric weights of the centre of mass in a tripod, computed here.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/impact.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/sample_models.hpp"

using namespace hexdyn;

namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// The paper's contact in SI units (configs/paper.yaml).
ContactParams paper_si_contact() {
  return test::contact_params(1e5 * std::pow(1000.0, 2.2), 2.2, 1e4, 1e-5);
}

}  // namespace

TEST_CASE("loaded touchdown: the damped linear contact under a step load, in closed form",
          "[contact][loaded]") {
  // e = 1, p far below the penetration: m δ̈ + C δ̇ + K δ = L, δ(0) = 0, δ̇(0) = v:
  // δ = δ* + e^(−ζωt) (A cos ω_d t + B sin ω_d t), δ* = L/K, A = −δ*, B = (v + ζω A)/ω_d.
  const double K = 1e5, m = 0.1, C = 40.0, v = 0.1, L = 20.0, p = 1e-12;
  const double w = std::sqrt(K / m), zeta = C / (2.0 * std::sqrt(K * m));
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  const double d_star = L / K, A = -d_star, B = (v + zeta * w * A) / wd;
  auto delta = [&](double t) {
    return d_star + std::exp(-zeta * w * t) * (A * std::cos(wd * t) + B * std::sin(wd * t));
  };
  auto rate = [&](double t) {
    const double e = std::exp(-zeta * w * t);
    return e * ((B * wd - zeta * w * A) * std::cos(wd * t) -
                (A * wd + zeta * w * B) * std::sin(wd * t));
  };
  auto force = [&](double t) { return K * delta(t) + C * rate(t); };
  const ImpactTransient tr = simulate_touchdown(test::contact_params(K, 1.0, C, p), m, v, {}, L);
  REQUIRE(tr.occurred);
  REQUIRE_FALSE(tr.truncated);
  CHECK(tr.load_N == L);
  // Every sample on the closed form (the force stays positive: no clip), once the damping's
  // ramp over the first p = 1e-12 m is behind (it costs a momentum of order C p).
  double peak = 0.0;
  for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
    if (tr.penetration_m[i] < 1e3 * p) continue;
    INFO("t = " << tr.t_s[i]);
    CHECK(tr.force_N[i] == Approx(force(tr.t_s[i])).margin(1e-6 * L));
    CHECK(tr.penetration_m[i] == Approx(delta(tr.t_s[i])).margin(1e-6 * d_star));
    peak = std::max(peak, force(tr.t_s[i]));
  }
  CHECK(tr.peak_force_N == Approx(peak).epsilon(1e-6));
  CHECK(tr.peak_force_N > L);  // it overshoots: ζ = 0.2
  // The end: the force within 2 % of L, and before it the force was outside that band at
  // some instant of the last oscillation (it did not end early).
  const double t_end = tr.duration_s;
  CHECK(std::abs(force(t_end) - L) <= 0.02 * L * (1.0 + 1e-6));
  double worst_before = 0.0;
  for (double t = 0.5 * t_end; t < 0.95 * t_end; t += 1e-5)
    worst_before = std::max(worst_before, std::abs(force(t) - L));
  CHECK(worst_before > 0.02 * L);
  // The impulse: ∫F dt = L t − m (δ̇(t) − v) from the equation of motion.
  CHECK(tr.impulse_Ns == Approx(L * t_end - m * (rate(t_end) - v)).epsilon(1e-6));
}

TEST_CASE("loaded touchdown: the paper's contact settles at L, at its static penetration",
          "[contact][loaded]") {
  const ContactParams c = paper_si_contact();
  for (const double L : {5.0, 22.0, 40.0}) {
    const ImpactTransient tr = simulate_touchdown(c, 0.11, 0.05, {}, L);
    INFO("L = " << L << " N: " << tr.message);
    REQUIRE(tr.occurred);
    REQUIRE_FALSE(tr.truncated);
    CHECK(std::abs(tr.force_N.back() - L) <= 0.02 * L * (1.0 + 1e-6));
    // The damper dominates (damping ratio about 10): the force reaches L while the penetration
    // still creeps towards the static one, which it has not passed.
    CHECK(tr.penetration_m.back() > 0.0);
    CHECK(tr.penetration_m.back() < static_penetration(c, L));
    CHECK(tr.duration_s < 5e-3);
    // It rises through the impact and never falls back to zero after it began.
    for (std::size_t i = 1; i < tr.force_N.size(); ++i) CHECK(tr.force_N[i] > 0.0);
    // Its impulse is at least the approach momentum: the load adds to it.
    CHECK(tr.impulse_Ns > 0.11 * 0.05);
  }
  // No load: the paper's transient, which ends at zero force.
  const ImpactTransient paper = simulate_touchdown(c, 0.11, 0.05, {}, 0.0);
  CHECK(paper.force_N.back() == 0.0);
  CHECK_THROWS_AS(simulate_touchdown(c, 0.11, 0.05, {}, -1.0), SolverError);
  CHECK_THROWS_AS(simulate_touchdown(c, 0.11, 0.05, {}, std::nan("")), SolverError);
}

TEST_CASE(
    "loaded touchdown: the load share of a tripod is the centre of mass's barycentric "
    "weight",
    "[contact][loaded]") {
  // In the paper's tripod gait three feet stand after each touchdown: the shares that balance
  // the weight with no moment about the centre of mass are its barycentric coordinates in
  // their triangle, times m g.
  Scene scene = load_scene(kPaper);
  scene.contact.touchdown = TouchdownModel::kLoaded;
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const double mg = model.total_mass_kg * kGravity;
  int checked = 0;
  for (int leg = 0; leg < model.legs(); ++leg)
    for (const Swing& sw : plan.gait.legs[leg].swings) {
      const double t = sw.t_touchdown_s;
      RobotKinematicState s;
      // The instant touchdown_load_share looks at: just after t.
      robot_state_at(model, plan, t + 1e-9 * std::max(1.0, t), s);
      std::vector<int> standing;
      for (int l = 0; l < model.legs(); ++l)
        if (!s.feet[l].in_swing) standing.push_back(l);
      if (standing.size() != 3) continue;  // the last touchdowns: all six feet stand
      const Vec3 com = robot_momentum(model, data, s.trunk, s.q, s.qd).com_W;
      // Barycentric coordinates by areas of the sub-triangles (x, y).
      auto area = [](const Vec3& a, const Vec3& b, const Vec3& c) {
        return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y()));
      };
      const Vec3 &p0 = s.feet[standing[0]].p_W, &p1 = s.feet[standing[1]].p_W,
                 &p2 = s.feet[standing[2]].p_W;
      const double total = area(p0, p1, p2);
      const double weights[3] = {area(com, p1, p2) / total, area(p0, com, p2) / total,
                                 area(p0, p1, com) / total};
      for (int k = 0; k < 3; ++k)
        if (standing[k] == leg) {
          const double share = touchdown_load_share(model, data, plan, t, leg, Vec3::UnitZ());
          INFO("leg " << leg << " at t = " << t);
          CHECK(share == Approx(weights[k] * mg).epsilon(1e-6));
          ++checked;
        }
    }
  CHECK(checked >= 12);
}
