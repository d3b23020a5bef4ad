// Flags that mean what they say: a sample with status optimal meets every
// constraint of its allocation to the fixed threshold (allocation/qp.hpp
// kViolationThreshold), whatever the solver tolerance and back end. Checked here by a
// second computation on the stored result: the trunk rows from rnea with the stored foot
// forces (not the allocation problem's split), the torque limits on the stored torques,
// and the unilateral and exact-cone friction conditions on the stored forces.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// Largest violation of an optimal sample's constraints, each relative to the threshold
/// (≤ 1 means within it), and the number of optimal samples.
struct Worst {
  double ratio = 0.0;
  std::string where;
  int optimal = 0;
};

Worst worst_optimal_violation(const Scene& scene, const RunResult& r) {
  const RobotModel model = build_robot_model(scene.robot);
  RobotData data(model);
  const double tmax = scene.allocation.torque_limit_Nm, mu = scene.contact.friction_coefficient;
  const double thr = kViolationThreshold;
  Worst w;
  auto consider = [&](double excess, double bound, const std::string& what, int i) {
    const double ratio = excess / (thr * std::max(1.0, std::abs(bound)));
    if (ratio > w.ratio) {
      w.ratio = ratio;
      w.where = what + " at t = " + std::to_string(r.kin.time_s[i]) + " s, excess " +
                std::to_string(excess);
    }
  };
  for (int i = 0; i < r.kin.samples(); ++i) {
    if (r.dyn.solver_status[i] != SolverStatus::kOptimal) continue;
    ++w.optimal;
    const BaseState base = base_state_at(r.kin, i);
    const JointVector q = r.kin.joint_position.row(i).transpose();
    const JointVector qd = r.kin.joint_velocity.row(i).transpose();
    const JointVector qdd = r.kin.joint_acceleration.row(i).transpose();
    LegArray<Vec3> F;
    for (int l = 0; l < model.legs(); ++l)
      F[l] = r.dyn.contact_force.row(i).segment<3>(3 * l).transpose();
    const DofVector free = rnea(model, data, base, q, qd, qdd);  // the trunk rows' right side
    const DofVector residual = rnea(model, data, base, q, qd, qdd, &F);
    for (int k = 0; k < 6; ++k)
      consider(std::abs(residual[k]), free[k], "trunk row " + std::to_string(k), i);
    for (int l = 0; l < model.legs(); ++l)
      for (int j = 0; j < model.leg(l).n_joints; ++j) {
        const int k = model.joint(l, j);
        consider(std::abs(r.dyn.joint_torque(i, k)) - tmax, tmax,
                 "torque " + model.joint_source_names[k], i);
      }
    for (int l = 0; l < model.legs(); ++l) {
      const auto phase = static_cast<ContactPhase>(r.kin.contact_phase(i, l));
      if (phase == ContactPhase::kSwing) {
        consider(F[l].norm(), 0.0, "swing force " + leg_name(l), i);
        continue;
      }
      const double fn = F[l].z();  // stairs: every tread's normal is +z
      if (phase == ContactPhase::kSupport)
        consider(scene.allocation.min_normal_force_N - fn, scene.allocation.min_normal_force_N,
                 "normal " + leg_name(l), i);
      consider(F[l].head<2>().norm() - mu * fn, mu * fn, "friction cone " + leg_name(l), i);
    }
  }
  return w;
}

TEST_CASE("measured flags: optimal samples meet every constraint at the loosest tolerance",
          "[pipeline][flags]") {
  for (const char* solver : {"active-set", "ipopt"}) {
    for (const char* tol : {"1e-9", "1e-5"}) {
      INFO(solver << " at tolerance " << tol);
      const Scene scene =
          load_scene(kPaper, {{"allocation.solver", solver}, {"allocation.tolerance", tol}});
      const RunResult r = run_scene(scene);
      const Worst w = worst_optimal_violation(scene, r);
      INFO("worst: " << w.where << ", " << w.ratio << " x the threshold");
      CHECK(w.optimal > 100);  // the check is not vacuous
      CHECK(w.ratio <= 1.0);
      // Every flagged sample names what gave way.
      for (int i = 0; i < r.kin.samples(); ++i)
        if (r.dyn.solver_status[i] != SolverStatus::kOptimal)
          CHECK_FALSE(r.dyn.solver_messages[i].empty());
    }
  }
}

TEST_CASE("measured flags: a tolerance beyond what the solvers honour is refused",
          "[pipeline][flags]") {
  CHECK_THROWS_WITH(load_scene(kPaper, {{"allocation.tolerance", "1e-2"}}),
                    Catch::Contains("allocation.tolerance: got 0.01") && Catch::Contains("1e-05"));
  CHECK_NOTHROW(load_scene(kPaper, {{"allocation.tolerance", "1e-5"}}));
}

}  // namespace
}  // namespace hexdyn
