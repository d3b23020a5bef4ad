// The forward replay (replay/replay.hpp, docs/theory/replay.md) on the paper scene: it
// climbs, the balance of energy closes, and the integrator stays stable on contact much stiffer
// than its step resolves. That each stored sample is the forward dynamics of its own state is
// checked against DART's (tests/python/test_forward_dynamics_dart.py).
#include <catch2/catch.hpp>
#include <cmath>

#include "hexdyn/config/config.hpp"
#include "hexdyn/dynamics/forward_dynamics.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/run.hpp"
#include "hexdyn/replay/replay.hpp"
#include "paper_replay.hpp"

namespace {

using namespace hexdyn;

using test::replay_paper;
using test::Replayed;

double largest(const std::vector<Vec3>& v) {
  double m = 0.0;
  for (const Vec3& x : v) m = std::max(m, x.norm());
  return m;
}

}  // namespace

TEST_CASE("the paper's torques replayed climb the stairs, and the energy balance closes") {
  const Replayed r = replay_paper({});
  const ReplayResult& res = r.result;
  INFO(res.message);
  REQUIRE(res.message.empty());
  REQUIRE(res.t_s.size() == r.plan.t_s.size());
  CHECK(res.reached_top);
  // The trunk stays within millimetres of the plan at every cycle end (docs/validation/replay.md).
  REQUIRE(res.position_drift_m.size() == r.plan.cycle_start_s.size());
  CHECK(largest(res.position_drift_m) < 5e-3);
  CHECK(largest(res.orientation_drift_rad) < 5e-3);
  // The joints' signed work is what the robot gained plus what the contacts dissipated, to the
  // integrator's first-order error.
  CHECK(std::abs(res.energy_residual_J) < 1e-3 * res.actuator_work_J);
  // The potential energy gained is m g Δz of the centre of mass, which the trunk's rise bounds.
  const double gained = res.potential_J.back() - res.potential_J.front();
  const double rise = res.base.back().p_W.z() - res.base.front().p_W.z();
  CHECK(gained == Approx(r.model.total_mass_kg * kGravity * rise).epsilon(0.05));
  CHECK(res.actuator_work_J > gained);
  // Every dissipation is non-negative and cumulative.
  for (int l = 0; l < r.model.legs(); ++l) {
    CHECK(res.slip_energy_total_J[l] >= 0.0);
    CHECK(res.damping_total_J[l] >= -1e-9);
    for (std::size_t i = 1; i < res.t_s.size(); ++i)
      CHECK(res.slip_distance_m[i][l] >= res.slip_distance_m[i - 1][l]);
  }
  // The replay's energy is the inverse dynamics' to a few per cent.
  CHECK(res.energy_J == Approx(res.energy_plan_J).epsilon(0.05));
}

TEST_CASE("stable on contact far stiffer than the step resolves") {
  // The paper's law loads a foot at about 1.4e6 N/m (10 N), and the tibia is light: an
  // explicit step would need h < 2/ω ≈ 4e-4 s. At 4e-3 s, and with the contact ten times
  // stiffer, the replay stays finite and climbs.
  for (const char* step : {"4e-3", "1e-3"}) {
    const Replayed r = replay_paper({parse_override(std::string("replay.step=") + step),
                                     parse_override("contact.stiffness=3.98e12")});
    INFO("replay.step " << step << ": " << r.result.message);
    CHECK(r.result.message.empty());
    CHECK(r.result.reached_top);
    CHECK(std::abs(r.result.energy_residual_J) < 0.01 * r.result.actuator_work_J);
  }
}

/// Per foot, the slip over the replay's intervals at whose two ends the foot is loaded (F_n >
/// 1 N) below 0.9 μ_s F_n: the creep of a foot that friction should hold [m].
LegArray<double> creep(const ReplayResult& r, double mu_s, int legs) {
  LegArray<double> out{};
  for (std::size_t i = 1; i < r.t_s.size(); ++i)
    for (int l = 0; l < legs; ++l) {
      auto held = [&](std::size_t k) {
        const double fn = r.normal_N[k][l];
        const Vec3& F = r.force_W[k][l];
        // F = F_n n + F_t with F_t ⟂ n: |F_t|² = |F|² − F_n².
        return fn > 1.0 && std::sqrt(std::max(0.0, F.squaredNorm() - fn * fn)) < 0.9 * mu_s * fn;
      };
      if (held(i - 1) && held(i)) out[l] += r.slip_distance_m[i][l] - r.slip_distance_m[i - 1][l];
    }
  return out;
}

TEST_CASE("a loaded foot holds: creep on the paper scene at mu = 0.3") {
  // docs/validation/replay.md#creep. With the stick–slip law a foot loaded below μ_s F_n does
  // not move: its creep is 0. The regularised law creeps below v_s: the same replay with it
  // creeps millimetres. (A foot slides where the plan itself stands on the cone's edge, at
  // μ = 0.3 on some samples: that is slip, not creep.)
  const Replayed held = replay_paper({});
  const Replayed crept = replay_paper({parse_override("contact.friction_law=regularised")});
  REQUIRE(held.result.message.empty());
  REQUIRE(crept.result.message.empty());
  CHECK(held.result.reached_top);
  const double mu = held.scene.contact.static_friction;
  REQUIRE(mu == 0.3);
  const LegArray<double> held_creep = creep(held.result, mu, held.model.legs());
  const LegArray<double> crept_creep = creep(crept.result, mu, held.model.legs());
  double most_crept = 0.0;
  for (int l = 0; l < held.model.legs(); ++l) {
    INFO("leg " << l << ": creep with stick-slip " << held_creep[l] << " m (slip "
                << held.result.slip_distance_total_m[l] << " m), regularised " << crept_creep[l]
                << " m (slip " << crept.result.slip_distance_total_m[l] << " m)");
    CHECK(held_creep[l] < 1e-4);
    CHECK(held.result.slip_distance_total_m[l] < 2e-3);
    most_crept = std::max(most_crept, crept_creep[l]);
  }
  CHECK(most_crept > 1e-3);
}

TEST_CASE("a step applies the plan's feedforward of its start, with the terms it balances") {
  // docs/theory/replay.md#integrator. One step of h with the robot in the air (no contact) and
  // no PD: the linearly implicit Euler step is ν₁ = ν₀ + h M(q₀)⁻¹ ([0; τ_ff(t₀)] − h(q₀, ν₀)),
  // the forward dynamics at the start under the start's feedforward, computed here
  // independently of the replay's step system. The plan's torque at the step's end differs,
  // and the step must not apply it.
  const Scene scene = load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml", {});
  const RobotModel model = build_robot_model(scene.robot);
  const Eigen::Index n = model.joints();
  const double h = 1e-3;
  BaseState base;
  base.p_W = Vec3(0.0, 0.0, 2.0);  // far above the stairs
  base.v_W = Vec3(0.01, -0.02, 0.03);
  base.omega_W = Vec3(0.1, -0.05, 0.2);
  JointVector q(n), qd(n), tau_start(n), tau_end(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    q[j] = 0.2 + 0.05 * static_cast<double>(j % 3);
    qd[j] = 0.1 * std::sin(static_cast<double>(j));
    tau_start[j] = 0.5 * std::cos(static_cast<double>(j));
    tau_end[j] = tau_start[j] + 2.0;
  }
  ReplayPlan plan;
  plan.t_s = {0.0, h};
  plan.base = {base, base};
  plan.q_rad = {q, q};
  plan.qd_radps = {qd, qd};
  plan.tau_Nm = {tau_start, tau_end};
  plan.cycle_start_s = {0.0};
  plan.terrain_y_m = {-100.0, 100.0};
  plan.terrain_z_m = {0.0, 0.0};
  ReplayParams gains = scene.replay;
  gains.kp_Nmprad = 0.0;
  gains.kd_Nmsprad = 0.0;
  gains.step_s = h;
  const ReplayResult r = replay_plan(model, scene.contact, gains, scene.terrain, plan);
  REQUIRE(r.message.empty());
  REQUIRE(r.steps == 1);
  REQUIRE(r.qd.size() == 2);
  RobotData data(model);
  const auto rates_after = [&](const JointVector& tau) {
    const DofVector nu_dot = forward_dynamics_joints(model, data, base, q, qd, tau);
    return JointVector(qd + h * nu_dot.tail(n));
  };
  const JointVector expected = rates_after(tau_start);
  const JointVector if_end = rates_after(tau_end);
  const double error = (r.qd[1] - expected).cwiseAbs().maxCoeff();
  INFO("q̇ after the step against the start's feedforward "
       << error << " rad/s, against the end's " << (r.qd[1] - if_end).cwiseAbs().maxCoeff());
  CHECK(error < 1e-9);
  CHECK((r.qd[1] - if_end).cwiseAbs().maxCoeff() > 1e-4);
}

TEST_CASE("the default step's touchdown energy is a finer step's on the paper scene") {
  // docs/validation/replay.md#the-feedforwards-instant. The normal work of a step is taken
  // over its displacement to second order, so the contact damping at the default step (1 ms)
  // is within a few per cent of the same replay at a sixteenth of it, the independent
  // computation here (it was 9 % over before).
  const Replayed coarse = replay_paper({});
  const Replayed fine = replay_paper(
      {parse_override("replay.step=6.25e-5"), parse_override("replay.tolerance=0.01")});
  REQUIRE(coarse.result.message.empty());
  REQUIRE(fine.result.message.empty());
  double e_coarse = 0.0, e_fine = 0.0;
  for (int l = 0; l < coarse.model.legs(); ++l) {
    e_coarse += coarse.result.damping_total_J[l];
    e_fine += fine.result.damping_total_J[l];
  }
  INFO("contact damping at 1 ms " << e_coarse << " J, at 62.5 us " << e_fine << " J");
  CHECK(e_fine > 0.0);
  CHECK(e_coarse == Approx(e_fine).epsilon(0.05));
}
