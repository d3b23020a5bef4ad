// Posture relative to the terrain and the automatic posture (planning/posture.hpp),
// checked against second computations: the reference line against the tread centres
// measured on the terrain; reachability by forward kinematics of the IK's joints through
// the generic tree (not the analytic FK the IK inverts), with the distance from full
// extension and fold measured on the tree's joint origins; swing and trunk clearance by
// scanning the terrain under the feet and under the trunk's axis.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"
#include "hexdyn/planning/posture.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {
namespace {

const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";

std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

TEST_CASE("posture: the paper's relative posture gives its absolute start to the last bit",
          "[posture]") {
  const Scene absolute = load_scene(kConfigs + "/paper.yaml");
  const Scene relative = load_scene(kConfigs + "/variants/paper_relative_posture.yaml");
  REQUIRE(absolute.motion.posture.mode == PostureMode::kAbsolute);
  REQUIRE(relative.motion.posture.mode == PostureMode::kRelative);
  const RobotModel model = build_robot_model(absolute.robot);
  const MotionPlan a = plan_motion(absolute, model), r = plan_motion(relative, model);
  CHECK(r.posture.p0_W.x() == 0.0);
  CHECK(r.posture.p0_W.y() == 0.412);
  CHECK(r.posture.p0_W.z() == 0.235);
  CHECK(a.posture.p0_W == r.posture.p0_W);
  // The whole plan is the same: trunk and every foot at many instants, bit for bit.
  const double T = a.trunk.duration_s();
  REQUIRE(r.trunk.duration_s() == T);
  for (int i = 0; i <= 997; ++i) {
    const double t = T * i / 997.0;
    CHECK(a.trunk.at(t).p_W == r.trunk.at(t).p_W);
    for (int leg = 0; leg < model.legs(); ++leg)
      CHECK(leg_foot_motion(a.gait.legs[leg], t).p_W == leg_foot_motion(r.gait.legs[leg], t).p_W);
  }
}

TEST_CASE("posture: the stairs' reference line passes through the tread centres", "[posture]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> riser(0.0, 0.2), tread(0.15, 0.4), y0(-1.0, 1.0),
      g(-0.5, 0.5);
  for (int n = 0; n < 50; ++n) {
    TerrainParams t;
    t.type = TerrainType::kStairs;
    t.riser_height_m = riser(rng);
    t.tread_depth_m = tread(rng);
    t.first_riser_y_m = y0(rng);
    t.ground_height_m = g(rng);
    t.steps = 8;
    const Terrain terrain(t);
    // Tread centres measured on the terrain: the midpoint between consecutive risers
    // found by scanning the height, k = 0 (ground) .. 7.
    for (int k = 0; k < 8; ++k) {
      const double y_c = t.first_riser_y_m + (k - 0.5) * t.tread_depth_m;
      const double z_c = terrain.height(0.0, y_c);
      CHECK(std::abs(reference_line_height(t, y_c) - z_c) <= 1e-12);
      // The rise above the line peaks just past each riser.
      const double y_back = t.first_riser_y_m + k * t.tread_depth_m + 1e-9;
      CHECK(terrain.height(0.0, y_back) - reference_line_height(t, y_back) <=
            terrain_rise_above_reference(t) + 1e-9);
      CHECK(terrain.height(0.0, y_back) - reference_line_height(t, y_back) >=
            terrain_rise_above_reference(t) - 1e-8);
    }
  }
}

/// A random stairs scene of the sweep base (automatic posture) inside the envelope.
Scene random_stairs(std::mt19937& rng) {
  std::uniform_real_distribution<double> riser(0.0, 0.08), tread(0.20, 0.35), speed(0.05, 0.20);
  const double betas[] = {0.5, 2.0 / 3.0, 0.75, 5.0 / 6.0};
  std::uniform_int_distribution<int> pick(0, 3);
  return load_scene(kConfigs + "/sweeps/stairs_base.yaml",
                    {{"terrain.riser_height", exact(riser(rng))},
                     {"terrain.tread_depth", exact(tread(rng))},
                     {"motion.peak_speed", exact(speed(rng))},
                     {"gait.duty_factor", exact(betas[pick(rng)])}});
}

TEST_CASE("posture: on random stairs inside the envelope every foot target is reachable (tree FK)",
          "[posture]") {
  std::mt19937 rng(2024);
  for (int n = 0; n < 8; ++n) {
    const Scene scene = random_stairs(rng);
    INFO("riser " << scene.terrain.riser_height_m << " tread " << scene.terrain.tread_depth_m
                  << " speed " << scene.motion.peak_speed_mps << " beta "
                  << scene.gait.duty_factor);
    const RobotModel model = build_robot_model(scene.robot);
    const MotionPlan plan = plan_motion(scene, model);
    REQUIRE(plan.posture.mode == PostureMode::kAuto);
    CHECK(plan.posture.margin.admitted);
    const Terrain& terrain = plan.terrain;
    const double T = plan.trunk.duration_s();
    const auto& L = model.link_length_m;
    double smallest_reach = 1.0, worst_fk = 0.0;
    BodyPoses poses;
    for (int i = 0; i <= 4000; ++i) {
      const double t = T * i / 4000.0;
      const BaseState trunk = plan.trunk.at(t);
      JointVector q = JointVector::Zero(model.joints());
      LegArray<Vec3> target_B;
      for (int leg = 0; leg < model.legs(); ++leg) {
        const Vec3 p_W = leg_foot_motion(plan.gait.legs[leg], t).p_W;
        target_B[leg] = trunk.W_R_B.transpose() * (p_W - trunk.p_W);
        const Vec3 p_H = model.R_B_H[leg].transpose() * (target_B[leg] - model.p_hip_B[leg]);
        const LegIkResult ik = leg_inverse_kinematics(model, leg, p_H);
        REQUIRE(ik.ok);
        q.segment<3>(model.joint(leg, 0)) = ik.q;  // the paper robot's legs of three joints
        for (int j = 0; j < model.leg(leg).n_joints; ++j) {
          CHECK(ik.q[j] >= scene.robot.joint_min_rad[j]);
          CHECK(ik.q[j] <= scene.robot.joint_max_rad[j]);
        }
      }
      forward_kinematics_tree(model, q, poses);
      for (int leg = 0; leg < model.legs(); ++leg) {
        worst_fk =
            std::max(worst_fk, (tree_foot_position_B(model, poses, leg) - target_B[leg]).norm());
        // Distance from full extension and fold: the foot relative to the femur joint,
        // projected on the plane normal to the femur axis (the lateral offsets d2, d3 lie
        // along that axis), from the tree's body poses.
        const int femur = model.body(leg, 1);
        const Vec3 a = poses.R_B[femur] * model.axis[femur];
        Vec3 r = tree_foot_position_B(model, poses, leg) - poses.p_B[femur];
        r -= r.dot(a) * a;
        const double d = r.norm();
        smallest_reach = std::min({smallest_reach, (L[1] + L[2]) - d, d - std::abs(L[1] - L[2])});
      }
    }
    CHECK(worst_fk <= 1e-9);
    CHECK(smallest_reach >= model.ik_min_margin_m - 1e-9);
    // The chosen height keeps the trunk clear of every nosing: P0 against the highest
    // terrain under the trunk's axis between rear and front hips, scanned every mm.
    double clearance = 1.0;
    for (int i = 0; i <= 200; ++i) {
      const double t = T * i / 200.0;
      const BaseState trunk = plan.trunk.at(t);
      for (double s = -0.25; s <= 0.25; s += 0.001) {
        const Vec3 p = trunk.p_W + trunk.W_R_B * Vec3(0.0, s, 0.0);
        clearance = std::min(clearance, p.z() - terrain.height(p.x(), p.y()));
      }
    }
    CHECK(clearance >= scene.motion.posture.trunk_clearance_m - 1e-9);
    // Every swing path clears the terrain: never below it, and swing_clearance above the
    // highest terrain under its path while it moves horizontally.
    for (int leg = 0; leg < model.legs(); ++leg)
      for (const Swing& sw : plan.gait.legs[leg].swings) {
        double highest = -1.0;
        for (int k = 0; k <= 400; ++k) {
          const Vec3 p = sw.p_liftoff_W + (sw.p_touchdown_W - sw.p_liftoff_W) * (k / 400.0);
          highest = std::max(highest, terrain.height(p.x(), p.y()));
        }
        for (int k = 0; k <= 400; ++k) {
          const double t = sw.t_liftoff_s + (sw.t_touchdown_s - sw.t_liftoff_s) * k / 400.0;
          const Vec3 p = swing_foot_motion(sw, t).p_W;
          CHECK(p.z() >= terrain.height(p.x(), p.y()) - 1e-12);
          const bool moving = (p.head<2>() - sw.p_liftoff_W.head<2>()).norm() > 1e-9 &&
                              (p.head<2>() - sw.p_touchdown_W.head<2>()).norm() > 1e-9;
          if (moving) CHECK(p.z() >= highest + scene.gait.swing_clearance_m - 1e-12);
        }
      }
  }
}

TEST_CASE("posture: the automatic height is a local maximum of the smallest margin", "[posture]") {
  std::mt19937 rng(7);
  for (int n = 0; n < 3; ++n) {
    const Scene scene = random_stairs(rng);
    const RobotModel model = build_robot_model(scene.robot);
    const PostureChoice c = choose_posture(scene, model);
    const double h_low = scene.terrain.riser_height_m / 2 + scene.motion.posture.trunk_clearance_m;
    auto margin_at = [&](double h) {
      const MotionPlan plan = plan_motion_with(
          scene, model, relative_start_position(scene.terrain, h, scene.motion.posture.start_y_m),
          c.foot_lateral_m);
      return motion_kinematic_margin(model, plan, 400).value_m;
    };
    const double m0 = margin_at(c.height_m);
    for (double dh : {-0.005, 0.005}) {
      if (c.height_m + dh < h_low) continue;
      INFO("height " << c.height_m << " + " << dh);
      CHECK(margin_at(c.height_m + dh) <= m0 + 1e-6);
    }
  }
}

TEST_CASE("posture: flat ground and slopes work with the automatic posture", "[posture]") {
  for (const std::vector<Override>& terrain :
       {std::vector<Override>{{"terrain", "{type: flat}"}},
        std::vector<Override>{{"terrain", "{type: slope, angle: 0.2}"}}}) {
    std::vector<Override> ov = terrain;
    ov.push_back({"gait.foothold_margin", "0"});
    const Scene scene = load_scene(kConfigs + "/sweeps/stairs_base.yaml", ov);
    const RobotModel model = build_robot_model(scene.robot);
    const MotionPlan plan = plan_motion(scene, model);
    CHECK(plan.posture.margin.admitted);
    CHECK(plan.posture.margin.value_m > 0.01);
  }
}

// A URDF robot's trunk frame may lie anywhere (Kraby's is at the bottom of its legs): the
// automatic posture places the hips. Moving the trunk frame by -d along the trunk normal
// (the coxa joints by +d in it) with the start moved so that the hips start where they
// did (start_y + d sin(pitch): the trunk is pitched) must move the chosen P0 height by
// -d / cos(pitch) and leave the foot spread and the margin as they were. Second
// computation: the same model with its coxa joints moved in the tree and its legs prepared
// again; the hips' clearance over the terrain measured on the plan.
TEST_CASE("posture: the automatic posture places the hips wherever the trunk frame is",
          "[posture][robots]") {
  const Scene scene = load_scene(kConfigs + "/robots/kraby_stairs.yaml");
  const RobotModel model = build_robot_model(scene.robot);
  const PostureChoice c0 = choose_posture(scene, model);
  REQUIRE(c0.margin.admitted);
  const double pitch = std::atan(scene.terrain.riser_height_m / scene.terrain.tread_depth_m);
  for (double d : {-0.15, 0.1}) {
    INFO("coxa joints moved by " << d << " m along the trunk normal");
    RobotModel moved = model;
    for (int leg = 0; leg < model.legs(); ++leg) moved.p_parent_joint[model.body(leg, 0)].z() += d;
    prepare_leg_chains(moved);
    Scene shifted = scene;
    shifted.motion.posture.start_y_m += d * std::sin(pitch);
    const PostureChoice c = choose_posture(shifted, moved);
    CHECK(c.margin.admitted);
    CHECK(c.height_m == Approx(c0.height_m - d / std::cos(pitch)).margin(1e-5));
    CHECK(c.margin.value_m == Approx(c0.margin.value_m).margin(1e-8));
    CHECK(c.foot_lateral_m == Approx(c0.foot_lateral_m).margin(1e-9));
  }
  // The trunk, taken as the segment of its hip plane from the rearmost to the foremost hip,
  // keeps the trunk clearance over the terrain straight beneath it along the whole motion.
  const MotionPlan plan = plan_motion(scene, model);
  const Terrain terrain(scene.terrain);
  double y_rear = 1e9, y_front = -1e9, z_hip = 1e9;
  for (int leg = 0; leg < model.legs(); ++leg) {
    y_rear = std::min(y_rear, model.p_hip_B[leg].y());
    y_front = std::max(y_front, model.p_hip_B[leg].y());
    z_hip = std::min(z_hip, model.p_hip_B[leg].z());
  }
  double lowest = 1e9;
  for (double t = 0.0; t <= plan.trunk.duration_s(); t += 0.01) {
    const BaseState b = plan.trunk.at(t);
    for (double y = y_rear; y <= y_front; y += 0.001) {
      const Vec3 p_W = b.p_W + b.W_R_B * Vec3(0.0, y, z_hip);
      lowest = std::min(lowest, p_W.z() - terrain.height(p_W.x(), p_W.y()));
    }
  }
  CHECK(lowest >= scene.motion.posture.trunk_clearance_m - 1e-9);
}

TEST_CASE("posture: beyond the robot's reach the error names leg, instant, constraint and margin",
          "[posture]") {
  const Scene scene =
      load_scene(kConfigs + "/sweeps/stairs_base.yaml", {{"terrain.riser_height", "0.25"}});
  const RobotModel model = build_robot_model(scene.robot);
  try {
    (void)plan_motion(scene, model);
    FAIL("a 0.25 m riser was planned");
  } catch (const ReachError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK(m.find("no trunk posture admits the motion") != std::string::npos);
    CHECK(m.find("leg L") != std::string::npos);
    CHECK(m.find(" at t = ") != std::string::npos);
    CHECK(m.find("margin") != std::string::npos);
  }
}

}  // namespace
}  // namespace hexdyn
