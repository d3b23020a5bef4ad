// Fidelity choices of a scene (robot.leg_inertia, contact.model), each checked against a
// second computation that does not use the option's own code path:
//  - massless legs: the joint torques are exactly the statics of the foot forces,
//    τ = −J_jᵀ F (foot Jacobians from foot_jacobians, independent of the RNEA that produced
//    τ), swing legs carry no torque, and the lumped trunk keeps mass and centre of mass;
//  - rigid touchdowns: no transient, no impact phase, zero penetration, and the forces at
//    every sample balance the trunk exactly (optimal allocation throughout).
#include <catch2/catch.hpp>
#include <cmath>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace hexdyn {
namespace {

const char* const kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

}  // namespace

TEST_CASE("fidelity: massless legs keep the robot's mass and its centre of mass at the hips",
          "[fidelity]") {
  const Scene full = load_scene(kPaper);
  const Scene light = load_scene(kPaper, {{"robot.leg_inertia", "massless"}});
  REQUIRE(light.robot.leg_inertia == LegInertia::kMassless);
  const RobotModel a = build_robot_model(full.robot);
  const RobotModel b = build_robot_model(light.robot);
  CHECK(b.total_mass_kg == Approx(a.total_mass_kg).epsilon(1e-14));
  for (int k = 1; k < kPaperBodies; ++k) CHECK(b.inertia[k].mass_kg == 0.0);
  // Trunk COM: trunk, payload and every link mass placed at its hip, summed by hand.
  Vec3 moment = full.robot.trunk.mass_kg * full.robot.trunk.com_m +
                full.robot.payload.mass_kg * full.robot.payload.com_m;
  double mass = full.robot.trunk.mass_kg + full.robot.payload.mass_kg;
  for (int l = 0; l < kPaperLegs; ++l)
    for (int j = 0; j < kPaperLegJoints; ++j) {
      moment += full.robot.link[j].mass_kg * full.robot.hip_position_m[l];
      mass += full.robot.link[j].mass_kg;
    }
  CHECK((b.inertia[0].com_m - moment / mass).norm() < 1e-14);
}

TEST_CASE("fidelity: with massless legs the torques are the statics of the foot forces",
          "[fidelity]") {
  const Scene scene = load_scene(kPaper, {{"robot.leg_inertia", "massless"}});
  const RunResult r = run_scene(scene);
  const RobotModel model = build_robot_model(scene.robot);
  RobotData data(model);
  double worst = 0.0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    const BaseState base = base_state_at(r.kin, i);
    const PaperJointVector q = r.kin.joint_position.row(i).transpose();
    foot_jacobians(model, data, base, q);
    PaperJointVector tau_static = PaperJointVector::Zero();
    for (int l = 0; l < kPaperLegs; ++l) {
      const Vec3 F = r.dyn.contact_force.row(i).segment<3>(3 * l).transpose();
      tau_static -= data.J_foot_W[l].middleCols<kPaperJoints>(6).transpose() * F;
    }
    worst =
        std::max(worst, (r.dyn.joint_torque.row(i).transpose() - tau_static).cwiseAbs().maxCoeff());
  }
  INFO("worst |τ + J_jᵀF| " << worst << " N m");
  CHECK(worst < 1e-10);
  // The touchdown transients are those of the physical (full-inertia) legs.
  const RunResult ref = run_scene(load_scene(kPaper));
  REQUIRE(r.dyn.impacts.size() == ref.dyn.impacts.size());
  for (std::size_t k = 0; k < r.dyn.impacts.size(); ++k)
    CHECK(r.dyn.impacts[k].peak_force_N == ref.dyn.impacts[k].peak_force_N);
  // Leg dynamics are not negligible here: the energy differs by more than 5 %.
  CHECK(std::abs(r.dyn.energy_total_J - ref.dyn.energy_total_J) > 0.05 * ref.dyn.energy_total_J);
}

TEST_CASE("fidelity: rigid touchdowns have no transient and balance the trunk at every sample",
          "[fidelity]") {
  const Scene scene = load_scene(kPaper, {{"contact.model", "rigid"}});
  REQUIRE(scene.contact.model == ContactModel::kRigid);
  const RunResult r = run_scene(scene);
  CHECK(r.dyn.impacts.empty());
  const RobotModel model = build_robot_model(scene.robot);
  RobotData data(model);
  double worst_trunk = 0.0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    INFO("t = " << r.kin.time_s[i]);
    CHECK(r.dyn.solver_status[i] == SolverStatus::kOptimal);
    for (int l = 0; l < kPaperLegs; ++l) {
      CHECK(r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kImpact));
      CHECK(r.dyn.penetration(i, l) == 0.0);
    }
    // Trunk rows from the split of the prescribed motion with the stored forces.
    const ContactSplit& split = contact_split(
        model, data, base_state_at(r.kin, i), r.kin.joint_position.row(i).transpose(),
        r.kin.joint_velocity.row(i).transpose(), r.kin.joint_acceleration.row(i).transpose());
    Vec6 residual = split.trunk_rhs;
    for (int l = 0; l < kPaperLegs; ++l)
      residual -= split.JbT[l] * r.dyn.contact_force.row(i).segment<3>(3 * l).transpose();
    worst_trunk = std::max(worst_trunk, residual.cwiseAbs().maxCoeff());
  }
  CHECK(worst_trunk < 1e-6);
}

TEST_CASE("fidelity: unknown fidelity choices are configuration errors naming the key",
          "[fidelity]") {
  CHECK_THROWS_WITH(load_scene(kPaper, {{"robot.leg_inertia", "light"}}),
                    Catch::Contains("robot.leg_inertia") && Catch::Contains("massless"));
  CHECK_THROWS_WITH(load_scene(kPaper, {{"contact.model", "stiff"}}),
                    Catch::Contains("contact.model") && Catch::Contains("rigid"));
  CHECK_THROWS_WITH(load_scene(kPaper, {{"allocation.solver", "cone"}}),
                    Catch::Contains("allocation.solver") && Catch::Contains("ipopt"));
  // The exact cone on the active-set back end is the outer approximation
  // (allocation/cone_backend.hpp).
  CHECK(load_scene(kPaper, {{"allocation.solver", "active-set"}, {"allocation.friction", "cone"}})
            .allocation.solver == AllocationSolver::kActiveSet);
}

}  // namespace hexdyn
