// A robot of 4-joint legs through the whole pipeline: a walking quadruped 4x4 written as URDF
// text (tests/hexdyn/urdf_writer.hpp) and a scene that points at it, in a temporary folder, run
// by the pipeline. (A hexapod 6x4 has 24 joints, more than the scene reader's per-joint arrays
// hold so far: config/robot_config.hpp's LoadedUrdfRobot is sized by kPaperJoints = 18.) The run
// completes, and its joint positions, put through a forward kinematics of the model's tree with the
// trunk pose of each sample, give the planned feet; at sampled instants of the plan, the kinematics
// stage's q̇ and q̈ equal central differences of its q.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/temp_dir.hpp"
#include "hexdyn/urdf_writer.hpp"

namespace hexdyn {
namespace {

const char* kScene = R"(name: walker_4x4
robot:
  urdf: walker.urdf
  forward_axis: +x
terrain: {type: flat, height: 0.0}
gait:
  duty_factor: 0.75
  stroke: 0.02
  foothold_margin: 0.01
  swing_clearance: 0.02
  touchdown_speed: 0.05
motion:
  posture: {height: auto, start_y: 0.0}
  peak_speed: 0.04
  cycles: 2
  ramp_duration: 1.0
allocation:
  friction: pyramid4
  torque_limit: 50
contact:
  model: compliant
  stiffness: 3.9810717055349725e11
  exponent: 2.2
  damping_max: 1.0e4
  full_damping_depth: 1.0e-5
  friction_coefficient: 0.6
output:
  sample_step: 0.05
  tolerance: 0
)";

/// The scene of a 4 × 4 walking robot in `dir`.
Scene walker_scene(const testing::TempDir& dir) {
  std::mt19937 rng(64u);
  dir.write("walker.urdf", test::urdf_text(test::walking_urdf_robot(rng, 4, 4)));
  return load_scene(dir.write("walker.yaml", kScene));
}

TEST_CASE("a quadruped of 4-joint legs runs end to end and its joints give the planned feet",
          "[any_leg][pipeline]") {
  const testing::TempDir dir("any_leg_run");
  const Scene scene = walker_scene(dir);
  const PreparedScene prep = prepare_scene(scene);
  const RobotModel& m = prep.model;
  REQUIRE(m.legs() == 4);
  for (int leg = 0; leg < m.legs(); ++leg) {
    REQUIRE(m.leg(leg).n_joints == 4);
    REQUIRE(m.leg_on_chain[leg]);
  }
  const RunResult r = run_prepared_scene(scene, prep, nullptr);
  const KinematicsResult& k = r.kin;
  REQUIRE(k.samples() > 50);
  REQUIRE(k.joint_position.cols() == 16);
  REQUIRE(static_cast<int>(r.dyn.joint_torque.rows()) == k.samples());
  double worst = 0.0;
  for (int i = 0; i < k.samples(); ++i) {
    // /base/* describe the description's root link frame (robot_model.hpp p_B_root, B_R_root):
    // the trunk frame B from it.
    const BaseState root = base_state_at(k, i);
    const Mat3 W_R_B = root.W_R_B * m.B_R_root.transpose();
    const Vec3 p_W = root.p_W - W_R_B * m.p_B_root;
    JointVector q = k.joint_position.row(i).transpose();
    BodyPoses poses;
    forward_kinematics_tree(m, q, poses);
    for (int leg = 0; leg < m.legs(); ++leg) {
      const Vec3 foot_W = p_W + W_R_B * tree_foot_position_B(m, poses, leg);
      const Vec3 planned = k.foot_position.row(i).segment<3>(3 * leg).transpose();  // point feet
      worst = std::max(worst, (foot_W - planned).norm());
    }
  }
  INFO("largest |FK(q) − planned foot| " << worst << " m");
  CHECK(worst < 1e-12);
  CHECK(r.dyn.joint_torque.allFinite());
}

TEST_CASE("a quadruped of 4-joint legs: the stage's q̇ and q̈ are differences of its q",
          "[any_leg][pipeline]") {
  const testing::TempDir dir("any_leg_rates");
  const Scene scene = walker_scene(dir);
  const PreparedScene prep = prepare_scene(scene);
  const double t_end = prep.grid.back();
  const double h1 = 1e-5;
  int checked = 0;
  for (double f : {0.23, 0.41, 0.57, 0.78}) {
    const double t = f * t_end;
    RobotKinematicState s, a, b;
    robot_state_at(prep.model, prep.plan, t, s);
    robot_state_at(prep.model, prep.plan, t - h1, a);
    robot_state_at(prep.model, prep.plan, t + h1, b);
    const JointVector qd_fd = (b.q - a.q) / (2.0 * h1);
    const JointVector qdd_fd = (b.qd - a.qd) / (2.0 * h1);
    INFO("t " << t << "\nqd " << s.qd.transpose() << "\nfd " << qd_fd.transpose());
    CHECK((s.qd - qd_fd).norm() <= 1e-6 * (1.0 + s.qd.norm()));
    CHECK((s.qdd - qdd_fd).norm() <= 1e-5 * (1.0 + s.qdd.norm()));
    ++checked;
  }
  CHECK(checked == 4);
}

}  // namespace
}  // namespace hexdyn
