// The dynamics driver (pipeline/solve_dynamics.hpp) on cheap scenes: one gait cycle of
// the paper's robot on the paper's stairs, sampled coarsely. Each result is checked against
// a second computation made here: energy against a trapezoid sum of Σ|τ ω| on a much finer
// grid, the cost of transport against the configured stride, the stored torques against
// the split recomputed from the stored forces; infeasible scenes against the promise that
// they finish flagged, finite and named.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// One gait cycle (the peak-speed form of `motion`) on the paper's uniform 0.1 s grid:
/// about 30 samples, none inside a touchdown transient.
std::vector<Override> cheap_overrides() {
  return {{"motion.cycle_durations", "null"}, {"motion.cycles", "1"},
          {"motion.peak_speed", "0.1"},       {"motion.ramp_duration", "0.5"},
          {"output.grid", "uniform"},         {"output.sample_step", "0.1"}};
}

Scene cheap_scene(std::vector<Override> extra = {}) {
  std::vector<Override> ov = cheap_overrides();
  ov.insert(ov.end(), extra.begin(), extra.end());
  return load_scene(kPaper, ov);
}

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

Vec3 foot_vec(const RowMatrix& m, int i, int l) { return m.row(i).segment<3>(3 * l).transpose(); }

/// Every number of a result is finite.
void check_finite(const RunResult& r) {
  CHECK(r.kin.joint_position.allFinite());
  CHECK(r.kin.joint_velocity.allFinite());
  CHECK(r.kin.joint_acceleration.allFinite());
  CHECK(r.dyn.joint_torque.allFinite());
  CHECK(r.dyn.contact_force.allFinite());
  CHECK(r.dyn.penetration.allFinite());
  CHECK(r.dyn.joint_power.allFinite());
  for (double p : r.dyn.total_power_W) CHECK(std::isfinite(p));
  for (double o : r.dyn.solver_objective) CHECK(std::isfinite(o));
  CHECK(std::isfinite(r.dyn.energy_total_J));
  CHECK(std::isfinite(r.dyn.cost_of_transport));
}

/// The stored torques are τ0 − Σ J_jᵀ F of the stored forces on every sample, relaxed
/// or not (the split recomputed from the sampled motion).
void check_torques_match_forces(const Scene& scene, const RunResult& r) {
  const RobotModel model = build_robot_model(scene.robot);
  RobotData data(model);
  for (int i = 0; i < r.kin.samples(); ++i) {
    const ContactSplit& s = contact_split(
        model, data, base_state_at(r.kin, i), r.kin.joint_position.row(i).transpose(),
        r.kin.joint_velocity.row(i).transpose(), r.kin.joint_acceleration.row(i).transpose());
    JointVector tau = s.tau0;
    double scale = 1.0 + s.tau0.cwiseAbs().maxCoeff();
    for (int l = 0; l < model.legs(); ++l) {
      tau -= s.JjT[l] * foot_vec(r.dyn.contact_force, i, l);
      scale =
          std::max(scale, (s.JjT[l] * foot_vec(r.dyn.contact_force, i, l)).cwiseAbs().maxCoeff());
    }
    INFO("sample " << i);
    CHECK((r.dyn.joint_torque.row(i).transpose() - tau).cwiseAbs().maxCoeff() <= 1e-9 * scale);
  }
}

}  // namespace

/// Trapezoid sum of Σ_k |τ_k ω_k| over a result's samples [J]; with `ordinary_only`, over
/// its ordinary samples alone (the left limits of the contact events left out, so that each
/// jump of the power is smeared over the step before it).
double trapezoid_energy(const RunResult& r, bool ordinary_only = false) {
  std::vector<double> t, P;
  for (int i = 0; i < r.kin.samples(); ++i)
    if (!ordinary_only || r.kin.sample_kind[i] == 0) {
      t.push_back(r.kin.time_s[i]);
      P.push_back(r.dyn.total_power_W[i]);
    }
  double E = 0.0;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) E += 0.5 * (t[i + 1] - t[i]) * (P[i] + P[i + 1]);
  return E;
}

TEST_CASE("solve_dynamics: energy is the integral of the power series, and the cost of transport",
          "[solve_dynamics]") {
  // A non-uniform grid (refined at events) exercises the integration with varying steps;
  // 0.02 s between events, where the trapezoid is second order (at 0.1 s it is 2.3e-3 off).
  const Scene scene = cheap_scene({{"output.grid", "adaptive"},
                                   {"output.sample_step", "0.02"},
                                   {"output.event_step", "0.01"},
                                   {"output.impact_samples", "2"}});
  const RunResult r = run_scene(scene);
  const KinematicsResult& k = r.kin;
  const DynamicsResult& d = r.dyn;
  const int T = k.samples();
  REQUIRE(T > 30);
  check_finite(r);
  // Grid steps do vary.
  double h_min = 1e9, h_max = 0.0;
  for (int i = 0; i + 1 < T; ++i) {
    h_min = std::min(h_min, k.time_s[i + 1] - k.time_s[i]);
    h_max = std::max(h_max, k.time_s[i + 1] - k.time_s[i]);
  }
  REQUIRE(h_max > 10.0 * h_min);

  // Power per joint and in total, from the torques and the joint rates.
  const int joints = static_cast<int>(k.joint_velocity.cols());
  std::vector<double> P(T, 0.0);
  for (int i = 0; i < T; ++i) {
    for (int j = 0; j < joints; ++j) {
      const double p = d.joint_torque(i, j) * k.joint_velocity(i, j);
      CHECK(d.joint_power(i, j) == p);
      P[i] += std::abs(p);
    }
    CHECK(std::abs(d.total_power_W[i] - P[i]) <= 1e-14 * std::max(1.0, P[i]));
  }
  // Energy: the piecewise-cubic rule over the stored samples, against a second quadrature, the
  // trapezoid sum of Σ|τ ω| on a grid far finer everywhere (1 ms, 10 µs at events), which it
  // must match far better than the trapezoid over its ordinary samples alone (without the left
  // limits of the contact events: 8.6e-4) does; and within its own rule's difference to the
  // trapezoid over the same samples (the rules differ by less than the trapezoid's error).
  const RunResult fine = run_scene(cheap_scene({{"output.grid", "adaptive"},
                                                {"output.sample_step", "1e-3"},
                                                {"output.event_step", "1e-5"},
                                                {"output.impact_samples", "200"}}));
  const double E_fine = trapezoid_energy(fine);
  const double E = d.energy_total_J;
  REQUIRE(E > 0.0);
  CAPTURE(E, E_fine, trapezoid_energy(r, true));
  CHECK(std::abs(E - trapezoid_energy(r)) <= 1e-3 * E);
  CHECK(std::abs(E - E_fine) <= 1e-3 * E_fine);
  CHECK(std::abs(trapezoid_energy(r, true) - E_fine) > 5.0 * std::abs(E - E_fine));
  CHECK(std::abs(fine.dyn.energy_total_J - E_fine) <= 1e-4 * E_fine);
  REQUIRE(d.energy_joint_J.size() == static_cast<std::size_t>(joints));
  double sum_joint = 0.0;
  for (int j = 0; j < joints; ++j) {
    INFO("joint " << j);
    double E_joint_fine = 0.0;
    for (int i = 0; i + 1 < fine.kin.samples(); ++i)
      E_joint_fine +=
          0.5 * (fine.kin.time_s[i + 1] - fine.kin.time_s[i]) *
          (std::abs(fine.dyn.joint_power(i, j)) + std::abs(fine.dyn.joint_power(i + 1, j)));
    CHECK(std::abs(d.energy_joint_J[j] - E_joint_fine) <= 5e-3 * std::max(E_joint_fine, 1e-2 * E));
    sum_joint += d.energy_joint_J[j];
  }
  CHECK(std::abs(sum_joint - E) <= 1e-12 * E);

  // Cost of transport E / (m g d): mass summed from the configured bodies, d the trunk
  // travel along the slope, s0/β per cycle horizontally.
  const RobotParams& rp = scene.robot;
  const double m = rp.trunk.mass_kg + rp.payload.mass_kg +
                   rp.legs * (rp.link[0].mass_kg + rp.link[1].mass_kg + rp.link[2].mass_kg);
  const double slope = std::atan(scene.terrain.riser_height_m / scene.terrain.tread_depth_m);
  const double distance =
      scene.motion.cycles * (scene.gait.stroke_m / scene.gait.duty_factor) / std::cos(slope);
  CHECK(scene.motion.cycles == 1);
  CHECK(std::abs(r.total_mass_kg - m) <= 1e-12 * m);
  CHECK(std::abs(d.distance_m - distance) <= 1e-12 * distance);
  CHECK(std::abs(d.cost_of_transport - E / (m * kGravity * distance)) <=
        1e-12 * d.cost_of_transport);
  // The trunk did travel that far.
  const Vec3 travel = k.base_position.row(T - 1) - k.base_position.row(0);
  CHECK(std::abs(travel.norm() - distance) <= 1e-9);

  // One impact record per touchdown (every swing ends in one) at the swing's end.
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  std::vector<std::pair<int, double>> swing_ends;
  for (int l = 0; l < model.legs(); ++l)
    for (const Swing& sw : plan.gait.legs[l].swings) swing_ends.emplace_back(l, sw.t_touchdown_s);
  REQUIRE(d.impacts.size() == swing_ends.size());
  for (const ImpactRecord& rec : d.impacts) {
    const auto hit = std::count_if(swing_ends.begin(), swing_ends.end(), [&](const auto& e) {
      return e.first == rec.leg && e.second == rec.t_start_s;
    });
    CHECK(hit == 1);
  }
}

TEST_CASE("solve_dynamics: a touchdown at zero approach speed produces no impact",
          "[solve_dynamics]") {
  // Adaptive grid: had a transient occurred, samples would fall inside it.
  const Scene scene = cheap_scene({{"gait.touchdown_speed", "0"},
                                   {"output.grid", "adaptive"},
                                   {"output.event_step", "0.01"},
                                   {"output.impact_samples", "4"}});
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  REQUIRE(!tds.empty());
  for (const Touchdown& td : tds) {
    INFO("leg L" << td.leg + 1 << " at t = " << td.t_s << " s");
    CHECK(std::abs(td.approach_speed_mps) <= 1e-12);
    CHECK_FALSE(td.transient.occurred);
    CHECK(td.transient.peak_force_N == 0.0);
    CHECK(td.transient.impulse_Ns == 0.0);
    CHECK(transient_force_at(td.transient, 1e-5) == 0.0);
  }
  const RunResult r = run_scene(scene);
  check_finite(r);
  CHECK(r.dyn.impacts.empty());
  int touchdown_samples = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    INFO("sample " << i << " t = " << r.kin.time_s[i] << " s: " << r.dyn.solver_messages[i]);
    for (int l = 0; l < r.kin.contact_phase.cols(); ++l) CHECK(r.kin.contact_phase(i, l) != 1);
    CHECK_FALSE(contains(r.dyn.solver_messages[i], "impact"));
    CHECK(r.dyn.solver_status[i] == SolverStatus::kOptimal);
    for (const Touchdown& td : tds) touchdown_samples += r.kin.time_s[i] == td.t_s;
  }
  // The grid does hold the touchdown instants, where an impact would start.
  CHECK(touchdown_samples > 0);
}

/// Checks every sample of `r`: none failed, each relaxed one's message passes `named`;
/// with a torque limit > 0, each optimal one has no message and |τ| within the limit.
/// Returns the number of relaxed samples.
static int check_flagged_samples(const RunResult& r,
                                 const std::function<bool(const std::string&)>& named,
                                 double torque_limit_Nm = 0.0) {
  int relaxed = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    const SolverStatus st = r.dyn.solver_status[i];
    const std::string& msg = r.dyn.solver_messages[i];
    INFO("sample " << i << " t = " << r.kin.time_s[i] << " s, status " << st << ": " << msg);
    CHECK(st != SolverStatus::kFailed);
    if (st == SolverStatus::kRelaxed) {
      ++relaxed;
      CHECK(named(msg));
    }
    if (st == SolverStatus::kOptimal && torque_limit_Nm > 0.0) {
      CHECK(msg.empty());
      CHECK(r.dyn.joint_torque.row(i).cwiseAbs().maxCoeff() <= torque_limit_Nm + 1e-6);
    }
  }
  return relaxed;
}

TEST_CASE(
    "solve_dynamics: a torque limit that cannot hold gives flagged, finite samples naming torques",
    "[solve_dynamics]") {
  const Scene scene = cheap_scene({{"allocation.torque_limit", "0.5"}});
  RunResult r;
  REQUIRE_NOTHROW(r = run_scene(scene));
  check_finite(r);
  const int relaxed = check_flagged_samples(
      r, [](const std::string& msg) { return contains(msg, "torque"); }, 0.5);
  CHECK(relaxed > 0);
  check_torques_match_forces(scene, r);
}

TEST_CASE(
    "solve_dynamics: friction that cannot hold gives flagged, finite samples naming friction or "
    "trunk",
    "[solve_dynamics]") {
  const Scene scene = cheap_scene({{"contact.friction_coefficient", "0.01"}});
  RunResult r;
  REQUIRE_NOTHROW(r = run_scene(scene));
  check_finite(r);
  const int relaxed = check_flagged_samples(r, [](const std::string& msg) {
    return contains(msg, "friction") || contains(msg, "trunk");
  });
  CHECK(relaxed > 0);
  check_torques_match_forces(scene, r);
}

}  // namespace hexdyn
