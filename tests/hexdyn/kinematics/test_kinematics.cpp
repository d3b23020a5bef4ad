// Whole-robot kinematics (kinematics.hpp) on the paper scene: analytic joint and foot
// rates against central finite differences of the sampled positions, with the O(h²)
// error order checked; the centre of mass against a sum over the bodies done in the
// test from the tree FK and the parameter masses; the trunk orientation against the
// stair slope.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"

namespace hexdyn {
namespace {

const std::string kPaperConfig = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";

struct Planned {
  Scene scene;
  RobotModel model;
  MotionPlan plan;
};

Planned plan_scene(const std::vector<Override>& overrides = {}) {
  Scene scene = load_scene(kPaperConfig, overrides);
  RobotModel model = build_robot_model(scene.robot);
  MotionPlan plan = plan_motion(scene, model);
  return Planned{std::move(scene), model, std::move(plan)};
}

/// Instants where the foot path is not smooth to third order: lift-offs, touchdowns
/// (velocity jump), and the ends of the lift and the start of the descent (jerk jump).
std::vector<double> kinks(const GaitPlan& gait) {
  std::vector<double> t;
  for (const LegPlan& leg : gait.legs)
    for (const Swing& sw : leg.swings) {
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      t.insert(t.end(), {sw.t_liftoff_s, sw.t_touchdown_s, sw.t_liftoff_s + sw.lift_end_u * D,
                         sw.t_liftoff_s + sw.lower_start_u * D});
    }
  return t;
}

/// Evenly spread instants at least `window` from every kink and from both ends.
std::vector<double> smooth_times(const Planned& p, int n, double window) {
  const double T = p.plan.trunk.duration_s();
  std::vector<double> k = kinks(p.plan.gait);
  k.push_back(0.0);
  k.push_back(T);
  std::vector<double> out;
  for (int i = 1; i < n; ++i) {
    const double t = T * i / n;
    bool near = false;
    for (double e : k) near = near || std::abs(t - e) < window;
    if (!near) out.push_back(t);
  }
  return out;
}

struct FdErrors {
  double qd = 0.0, qdd = 0.0, foot_v = 0.0;
};

FdErrors fd_errors(const Planned& p, const std::vector<double>& times, double h) {
  FdErrors e;
  RobotKinematicState s, sp, sm;
  for (double t : times) {
    robot_state_at(p.model, p.plan, t, s);
    robot_state_at(p.model, p.plan, t + h, sp);
    robot_state_at(p.model, p.plan, t - h, sm);
    e.qd = std::max(e.qd, (s.qd - (sp.q - sm.q) / (2 * h)).cwiseAbs().maxCoeff());
    e.qdd = std::max(e.qdd, (s.qdd - (sp.q - 2.0 * s.q + sm.q) / (h * h)).cwiseAbs().maxCoeff());
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const Vec3 v_fd = (sp.feet[leg].p_W - sm.feet[leg].p_W) / (2 * h);
      e.foot_v = std::max(e.foot_v, (s.feet[leg].v_W - v_fd).cwiseAbs().maxCoeff());
    }
  }
  return e;
}

TEST_CASE("kinematics: joint and foot rates match finite differences to O(h^2)", "[kinematics]") {
  const Planned p = plan_scene();
  const std::vector<double> times = smooth_times(p, 800, 0.01);
  REQUIRE(times.size() > 300);
  // Size of the quantities, for relative bounds.
  double qd_peak = 0.0, qdd_peak = 0.0, v_peak = 0.0;
  RobotKinematicState s;
  for (double t : times) {
    robot_state_at(p.model, p.plan, t, s);
    qd_peak = std::max(qd_peak, s.qd.cwiseAbs().maxCoeff());
    qdd_peak = std::max(qdd_peak, s.qdd.cwiseAbs().maxCoeff());
    for (const FootMotion& f : s.feet) v_peak = std::max(v_peak, f.v_W.cwiseAbs().maxCoeff());
  }
  REQUIRE(qd_peak > 0.0);
  REQUIRE(qdd_peak > 0.0);
  REQUIRE(v_peak > 0.0);
  const FdErrors e1 = fd_errors(p, times, 1e-3);
  const FdErrors e2 = fd_errors(p, times, 5e-4);
  INFO("qd " << e1.qd << " -> " << e2.qd << " (peak " << qd_peak << ")");
  INFO("qdd " << e1.qdd << " -> " << e2.qdd << " (peak " << qdd_peak << ")");
  INFO("foot v " << e1.foot_v << " -> " << e2.foot_v << " (peak " << v_peak << ")");
  // Halving the step quarters the error: the analytic rates are the derivatives.
  CHECK(e1.qd / e2.qd >= 3.0);
  CHECK(e1.qd / e2.qd <= 5.0);
  CHECK(e1.qdd / e2.qdd >= 3.0);
  CHECK(e1.qdd / e2.qdd <= 5.0);
  CHECK(e1.foot_v / e2.foot_v >= 3.0);
  CHECK(e1.foot_v / e2.foot_v <= 5.0);
  // And it is small.
  CHECK(e2.qd <= 1e-4 * qd_peak);
  CHECK(e2.qdd <= 1e-4 * qdd_peak);
  CHECK(e2.foot_v <= 1e-4 * v_peak);
}

TEST_CASE("kinematics: sampled joints put the feet where the gait plan wants them",
          "[kinematics]") {
  const Planned p = plan_scene();
  const double T = p.plan.trunk.duration_s();
  std::vector<double> times;
  for (int i = 0; i <= 300; ++i) times.push_back(T * i / 300.0);
  const KinematicsResult k = sample_kinematics(p.model, p.plan, times);
  BodyPoses poses;
  for (int i = 0; i < k.samples(); ++i) {
    const PaperJointVector q = k.joint_position.row(i).transpose();
    forward_kinematics_tree(p.model, q, poses);
    const BaseState trunk = p.plan.trunk.at(times[i]);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const Vec3 foot_W = trunk.p_W + trunk.W_R_B * tree_foot_position_B(p.model, poses, leg);
      const Vec3 planned = leg_foot_motion(p.plan.gait.legs[leg], times[i]).p_W;
      const Vec3 sampled = k.foot_position.row(i).segment<3>(3 * leg).transpose();
      INFO("t " << times[i] << " leg " << leg);
      CHECK((foot_W - planned).cwiseAbs().maxCoeff() <= 1e-12);
      CHECK((sampled - planned).cwiseAbs().maxCoeff() == 0.0);
      const int phase = k.contact_phase(i, leg);
      CHECK(phase == (leg_foot_motion(p.plan.gait.legs[leg], times[i]).in_swing ? 0 : 2));
    }
  }
}

TEST_CASE("kinematics: a sphere foot's centre stands r above the planned contact point",
          "[kinematics][sphere]") {
  // docs/theory/model.md#sphere-feet: the plan is the contact point, the IK places the centre.
  const double r = 0.012;
  const Planned p = plan_scene({{"robot.foot_radius", "0.012"}});
  REQUIRE(p.model.foot_radius_m[0] == r);
  const double T = p.plan.trunk.duration_s();
  std::vector<double> times;
  for (int i = 0; i <= 300; ++i) times.push_back(T * i / 300.0);
  const KinematicsResult k = sample_kinematics(p.model, p.plan, times);
  BodyPoses poses;
  for (int i = 0; i < k.samples(); ++i) {
    forward_kinematics_tree(p.model, k.joint_position.row(i).transpose(), poses);
    const BaseState trunk = p.plan.trunk.at(times[i]);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const Vec3 center_W = trunk.p_W + trunk.W_R_B * tree_foot_position_B(p.model, poses, leg);
      const Vec3 planned = leg_foot_motion(p.plan.gait.legs[leg], times[i]).p_W;
      const Vec3 contact = k.foot_position.row(i).segment<3>(3 * leg).transpose();
      const Vec3 center = k.foot_center.row(i).segment<3>(3 * leg).transpose();
      INFO("t " << times[i] << " leg " << leg);
      CHECK(contact == planned);
      CHECK((center - contact - r * Vec3::UnitZ()).norm() <= 1e-15);  // treads: n = +z
      CHECK((center_W - center).cwiseAbs().maxCoeff() <= 1e-12);
    }
  }
  // The joint rates move the centre as planned: J q̇ = ṗ (n constant on the stairs).
  RobotKinematicState s;
  for (double t : smooth_times(p, 200, 0.01)) {
    robot_state_at(p.model, p.plan, t, s);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const Vec3 q = s.q.segment<3>(paper_joint_index(leg, 0)),
                 qd = s.qd.segment<3>(paper_joint_index(leg, 0));
      const Vec3 v_W =
          s.trunk.v_W + s.trunk.W_R_B * p.model.R_B_H[leg] * leg_jacobian_H(p.model, leg, q) * qd;
      CHECK((v_W - s.feet[leg].v_W).norm() <= 1e-12);
    }
  }
}

TEST_CASE("kinematics: /com/position equals the mass-weighted mean of the bodies", "[kinematics]") {
  // Off-centre trunk, payload and link COMs so that every term counts.
  const Planned p = plan_scene({{"robot.payload.com", "[0.01, -0.02, 0.03]"},
                                {"robot.trunk.com", "[-0.005, 0.01, 0.0]"},
                                {"robot.femur.com", "[0.05, 0.004, -0.003]"},
                                {"robot.tibia.com", "[0.04, -0.002, 0.005]"}});
  const RobotParams& rp = p.scene.robot;
  const double T = p.plan.trunk.duration_s();
  std::vector<double> times;
  for (int i = 0; i <= 200; ++i) times.push_back(T * i / 200.0);
  const KinematicsResult k = sample_kinematics(p.model, p.plan, times);
  double total = rp.trunk.mass_kg + rp.payload.mass_kg;
  for (int j = 0; j < kPaperLegJoints; ++j) total += kPaperLegs * rp.link[j].mass_kg;
  BodyPoses poses;
  double moved = 0.0;
  for (int i = 0; i < k.samples(); ++i) {
    const PaperJointVector q = k.joint_position.row(i).transpose();
    forward_kinematics_tree(p.model, q, poses);
    Vec3 first_moment = rp.trunk.mass_kg * rp.trunk.com_m + rp.payload.mass_kg * rp.payload.com_m;
    for (int leg = 0; leg < kPaperLegs; ++leg)
      for (int j = 0; j < kPaperLegJoints; ++j) {
        const int b = p.model.body(leg, j);
        first_moment += rp.link[j].mass_kg * (poses.p_B[b] + poses.R_B[b] * rp.link[j].com_m);
      }
    const BaseState trunk = p.plan.trunk.at(times[i]);
    const Vec3 com_W = trunk.p_W + trunk.W_R_B * (first_moment / total);
    const Vec3 sampled = k.com_position.row(i).transpose();
    INFO("t " << times[i] << " expected " << com_W.transpose() << " sampled "
              << sampled.transpose());
    CHECK((sampled - com_W).cwiseAbs().maxCoeff() <= 1e-12);
    moved = std::max(moved, (com_W - trunk.p_W).norm());
  }
  CHECK(moved > 1e-3);  // the COM is not simply P0
}

TEST_CASE("kinematics: base orientation is the stair slope pitch", "[kinematics]") {
  const Planned p = plan_scene();
  const double alpha = std::atan(p.scene.terrain.riser_height_m / p.scene.terrain.tread_depth_m);
  const Mat3 R = bryant_to_rotation(Vec3(alpha, 0.0, 0.0));
  const double T = p.plan.trunk.duration_s();
  std::vector<double> times;
  for (int i = 0; i <= 50; ++i) times.push_back(T * i / 50.0);
  const KinematicsResult k = sample_kinematics(p.model, p.plan, times);
  for (int i = 0; i < k.samples(); ++i) {
    const Quat q(k.base_orientation_wxyz(i, 0), k.base_orientation_wxyz(i, 1),
                 k.base_orientation_wxyz(i, 2), k.base_orientation_wxyz(i, 3));
    CHECK(std::abs(q.norm() - 1.0) <= 1e-14);
    CHECK((q.toRotationMatrix() - R).cwiseAbs().maxCoeff() <= 1e-14);
    // A pitch about x by α: (cos α/2, sin α/2, 0, 0), up to sign.
    const double sign = q.w() < 0 ? -1.0 : 1.0;
    CHECK(std::abs(sign * q.w() - std::cos(alpha / 2)) <= 1e-14);
    CHECK(std::abs(sign * q.x() - std::sin(alpha / 2)) <= 1e-14);
    CHECK(std::abs(q.y()) <= 1e-14);
    CHECK(std::abs(q.z()) <= 1e-14);
    CHECK(k.base_angular_velocity.row(i).norm() == 0.0);
  }
}

TEST_CASE("kinematics: the shared sines and cosines give the tree FK's poses bit for bit",
          "[kinematics]") {
  // robot_state_at hands the tree FK the sines and cosines its Jacobians used: they must be
  // those the tree FK computes from q, so that /com/position is that of the tree FK from q.
  // The paper robot (closed-form legs) and a URDF robot (chain legs).
  const std::string urdf_scene =
      std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/phantomx_mark4_stairs.yaml";
  for (const std::string& config : {kPaperConfig, urdf_scene}) {
    INFO(config);
    const Scene scene = load_scene(config, {});
    const RobotModel model = build_robot_model(scene.robot);
    const MotionPlan plan = plan_motion(scene, model);
    const double T = plan.trunk.duration_s();
    std::vector<double> times;
    for (int i = 0; i <= 100; ++i) times.push_back(T * i / 100.0);
    const KinematicsResult k = sample_kinematics(model, plan, times);
    RobotKinematicState s;
    BodyPoses from_q, from_trig;
    for (int i = 0; i < k.samples(); ++i) {
      robot_state_at(model, plan, times[i], s);
      INFO("t " << times[i]);
      forward_kinematics_tree(model, s.q, from_q);
      forward_kinematics_tree(model, s.cos_q, s.sin_q, from_trig);
      for (int b = 0; b < kPaperBodies; ++b) {
        CHECK((from_q.R_B[b].array() == from_trig.R_B[b].array()).all());
        CHECK((from_q.p_B[b].array() == from_trig.p_B[b].array()).all());
      }
      const Vec3 com_W = s.trunk.p_W + s.trunk.W_R_B * center_of_mass_B(model, from_q);
      CHECK((k.com_position.row(i).transpose().array() == com_W.array()).all());
    }
  }
}

}  // namespace
}  // namespace hexdyn
