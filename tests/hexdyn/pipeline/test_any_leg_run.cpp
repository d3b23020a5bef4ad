// A robot of 4-joint legs through the whole pipeline: a walking quadruped 4x4 written as URDF
// text (tests/hexdyn/urdf_writer.hpp) and a scene that points at it, in a temporary folder, run
// by the pipeline. The run completes, and its joint positions, put through a forward kinematics
// of the model's tree with the trunk pose of each sample, give the planned feet; at sampled
// instants of the plan, the kinematics stage's q̇ and q̈ equal central differences of its q. A pose
// given by robot.nominal_pose is the leg's stance and the pose its redundancy resolves toward.
#include <catch2/catch.hpp>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
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

/// Leg `leg`'s foot in its hip frame at its joints q and every other joint at zero, by the
/// tree's forward kinematics (not the leg's serial chain).
Vec3 tree_foot_H(const RobotModel& m, int leg, const LegVector& q) {
  JointVector all = JointVector::Zero(m.joints());
  all.segment(m.joint(leg, 0), q.size()) = q;
  BodyPoses poses;
  forward_kinematics_tree(m, all, poses);
  return m.R_B_H[leg].transpose() * (tree_foot_position_B(m, poses, leg) - m.p_hip_B[leg]);
}

TEST_CASE("robot.nominal_pose of a 4-joint leg: its stance and the pose it resolves toward",
          "[any_leg][stance]") {
  const testing::TempDir dir("any_leg_pose");
  const Scene plain = walker_scene(dir);
  const RobotModel m0 = build_robot_model(plain.robot);
  const int leg = 1;
  const int n = m0.leg(leg).n_joints;
  REQUIRE(n == 4);
  // A pose inside the limits, away from their middle (the default nominal pose), alternately
  // toward the upper and the lower limit.
  LegVector q(n);
  std::ostringstream pose;
  pose << std::setprecision(17) << "{L2: [";
  for (int j = 0; j < n; ++j) {
    const int k = m0.joint(leg, j);
    const double lo = m0.joint_lower_rad[k], hi = m0.joint_upper_rad[k];
    REQUIRE(std::isfinite(hi - lo));
    q[j] = 0.5 * (lo + hi) + (j % 2 ? 0.3 : -0.3) * (hi - lo);
    pose << (j ? ", " : "") << q[j];
  }
  pose << "]}";
  const Scene s = load_scene(dir.path / "walker.yaml", {{"robot.nominal_pose", pose.str()}});
  const NominalStance& st = s.robot.stance[leg];
  CHECK(st.source == "robot.nominal_pose");
  REQUIRE(st.q.size() == n);
  CHECK((st.q - q).norm() == 0.0);
  // Its radius and depth from the tree's foot at that pose.
  const Vec3 foot_H = tree_foot_H(m0, leg, q);
  const Vec3 up_H = m0.R_B_H[leg].transpose() * Vec3::UnitZ();
  CHECK(st.depth_m == Approx(-foot_H.dot(up_H)).epsilon(1e-12));
  CHECK(st.radius_m == Approx((foot_H - foot_H.dot(up_H) * up_H).norm()).epsilon(1e-12));
  // The scene's model resolves the leg toward the pose: its foot there gives the pose back, and
  // a foot moved off it a pose nearer the given one than the default model's.
  const RobotModel m = build_robot_model(s.robot);
  const LegIkResult at = leg_inverse_kinematics(m, leg, foot_H);
  REQUIRE(at.ok);
  CHECK((at.q - q).norm() < 1e-10);
  const Vec3 moved = foot_H + Vec3(0.004, -0.003, 0.005);
  const LegIkResult near = leg_inverse_kinematics(m, leg, moved);
  const LegIkResult mid = leg_inverse_kinematics(m0, leg, moved);
  REQUIRE(near.ok);
  REQUIRE(mid.ok);
  CHECK((tree_foot_H(m, leg, near.q) - moved).norm() < 1e-12);
  CHECK((near.q - q).norm() < (mid.q - q).norm());
  // The legs not named keep the middle of their limits.
  CHECK((m.leg_resolution[0].q_nominal - m0.leg_resolution[0].q_nominal).norm() == 0.0);
  // A pose of the wrong length is refused in one line naming the key and the count.
  std::string error;
  try {
    load_scene(dir.path / "walker.yaml", {{"robot.nominal_pose", "{L2: [0, 0, 0]}"}});
  } catch (const ConfigError& e) {
    error = e.what();
  }
  INFO(error);
  CHECK(error.find("robot.nominal_pose") != std::string::npos);
  CHECK(error.find("4") != std::string::npos);
  CHECK(error.find('\n') == std::string::npos);
}

}  // namespace
}  // namespace hexdyn
