// Footholds from the robot's own geometry (planning/gait.hpp): every foothold of a URDF
// robot lies at gait.foot_lateral from its hip along the direction the hip's leg points at
// zero angles (the URDF's hip yaw), made horizontal, moved only along y (s0/2 forward and
// the snap to the treads), for six legs as for four; the paper robot's rule is x = hip x ±
// foot_lateral.
#include <catch2/catch.hpp>
#include <cmath>

#include "hexdyn/config/config.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

TEST_CASE("footholds lie along each hip's direction at foot_lateral", "[gait][robots]") {
  const std::string src = HEXDYN_SOURCE_DIR;
  for (const std::string name : {"phantomx_mark4_stairs", "kraby_stairs", "paper", "solo12_flat",
                                 "anymal_c_crawl_stairs", "solo12_trot_flat"}) {
    INFO(name);
    const Scene s = load_scene(
        src + (name == "paper" ? "/configs/paper.yaml" : "/configs/robots/" + name + ".yaml"));
    const RobotModel m = build_robot_model(s.robot);
    const MotionPlan plan = plan_motion(s, m);
    // Each hip's direction from the legs' zero pose (generic tree FK), horizontal in the world.
    BodyPoses poses;
    forward_kinematics_tree(m, JointVector::Zero(m.joints()), poses);
    const double n = plan.trunk.cycles(), beta = s.gait.duty_factor;
    for (int leg = 0; leg < m.legs(); ++leg) {
      const Vec3 hip_B = m.p_parent_joint[m.body(leg, 0)];
      Vec3 d_B = tree_foot_position_B(m, poses, leg) - hip_B;
      d_B.z() = 0.0;
      if (name == "paper")
        d_B = Vec3(m.leg(leg).side == LegSide::kLeft ? -1.0 : 1.0, 0.0, 0.0);  // legs straight out
      Vec3 d_W = plan.trunk.W_R_B() * d_B.normalized();
      d_W.z() = 0.0;
      d_W.normalize();
      int checked = 0;
      for (const Swing& sw : plan.gait.legs[leg].swings) {
        // Touchdown at the end of the swing: the nominal phase of the stance it begins.
        double phase = 0.0;
        for (int k = -1; k <= plan.trunk.cycles(); ++k) {
          const double b = std::min(k + plan.gait.liftoff_phase[leg] + (1.0 - beta), n);
          if (std::abs(plan.trunk.time_at_phase(b) - sw.t_touchdown_s) < 1e-12) phase = b;
        }
        const Vec3 hip_W = plan.trunk.position_at_phase(phase) + plan.trunk.W_R_B() * hip_B;
        const double dx = sw.p_touchdown_W.x() - hip_W.x();
        CHECK(dx == Approx(plan.posture.foot_lateral_m * d_W.x()).margin(1e-12));
        if (name == "paper")
          CHECK(sw.p_touchdown_W.x() == hip_W.x() + d_B.x() * plan.posture.foot_lateral_m);
        ++checked;
      }
      CHECK(checked > 0);
    }
  }
}

}  // namespace hexdyn
