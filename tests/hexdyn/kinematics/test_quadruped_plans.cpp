// Stance, footholds, swings and posture of the quadrupeds (configs/robots/solo12_*.yaml,
// anymal_c_*.yaml), crawling (β = 3/4) and trotting (β = 0.6) on flat ground and on stairs,
// against computations made here from the terrain's keys and the model's tree:
//   - every foothold stands on the tread the stairs' keys put under it (height counted from the
//     risers' positions) and keeps gait.foothold_margin + the foot's radius from every riser
//     line (nosing behind and riser ahead alike);
//   - along every swing, sampled densely, the foot's contact point stays above the terrain
//     under its sphere's shadow, and on the horizontal transfer at least gait.swing_clearance
//     above it; lift and descent are vertical over the footholds;
//   - the automatic posture holds: at sampled instants every joint lies inside its limits, and
//     the tree's forward kinematics of the joint angles puts each foot point where the plan
//     wants it (the IK reached every target).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {
namespace {

struct QuadCase {
  std::string scene;
  std::vector<Override> overrides;
};

const std::vector<Override> kTrot{{"gait.pattern", "trot"}, {"gait.duty_factor", "0.6"}};

std::vector<QuadCase> quad_cases() {
  std::vector<QuadCase> c;
  for (const std::string robot : {"solo12", "anymal_c"}) {
    c.push_back({robot + "_flat", {}});             // crawl
    c.push_back({robot + "_stairs", {}});           // crawl, low risers
    c.push_back({robot + "_crawl_stairs", {}});     // crawl, risers ≥ 40 % of the hip height
    c.push_back({robot + "_crawl_stairs", kTrot});  // trot on the same stairs
    c.push_back({robot + "_trot_flat", {}});        // trot
  }
  return c;
}

/// The terrain's height under y, from the keys: the ground plus one riser for every riser at
/// or behind y (the stairs rise along +y; a riser's own y belongs to the tread above it).
double stairs_height(const TerrainParams& t, double y) {
  if (t.type == TerrainType::kFlat) return t.ground_height_m;
  double z = t.ground_height_m;
  for (int k = 0; k < t.steps; ++k)
    if (t.first_riser_y_m + k * t.tread_depth_m <= y) z += t.riser_height_m;
  return z;
}

/// Distance from y to the nearest riser line (every nosing is one) [m]; +inf on flat ground.
double riser_distance(const TerrainParams& t, double y) {
  double d = std::numeric_limits<double>::infinity();
  if (t.type != TerrainType::kStairs) return d;
  for (int k = 0; k < t.steps; ++k)
    d = std::min(d, std::abs(y - (t.first_riser_y_m + k * t.tread_depth_m)));
  return d;
}

/// The highest terrain under a sphere's shadow [y − r, y + r] (the stairs never fall along +y).
double shadow_height(const TerrainParams& t, double y, double r) { return stairs_height(t, y + r); }

void check_footholds(const Scene& s, const RobotModel& m, const MotionPlan& plan) {
  const TerrainParams& t = s.terrain;
  int checked = 0;
  for (int leg = 0; leg < m.legs(); ++leg) {
    const double r = m.foot_radius_m[leg];
    std::vector<Vec3> holds{plan.gait.legs[leg].p_initial_W};
    for (const Swing& sw : plan.gait.legs[leg].swings) holds.push_back(sw.p_touchdown_W);
    for (const Vec3& p : holds) {
      INFO("leg " << leg_name(leg) << " foothold y " << p.y());
      CHECK(p.z() == Approx(stairs_height(t, p.y())).margin(1e-12));
      CHECK(riser_distance(t, p.y()) >= s.gait.foothold_margin_m + r - 1e-12);
      ++checked;
    }
  }
  CHECK(checked > 2 * m.legs());
}

void check_swings(const Scene& s, const RobotModel& m, const MotionPlan& plan) {
  const TerrainParams& t = s.terrain;
  const double clearance = s.gait.swing_clearance_m;
  int transfer = 0;
  for (int leg = 0; leg < m.legs(); ++leg) {
    const double r = m.foot_radius_m[leg];
    for (const Swing& sw : plan.gait.legs[leg].swings) {
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      for (int i = 0; i <= 400; ++i) {
        const double u = i / 400.0, time = sw.t_liftoff_s + u * D;
        const Vec3 p = swing_foot_position(sw, time);
        INFO("leg " << leg_name(leg) << " swing from " << sw.t_liftoff_s << " s, u " << u);
        CHECK(p.z() - shadow_height(t, p.y(), r) >= -1e-12);
        if (u <= sw.lift_end_u) CHECK((p.head<2>() - sw.p_liftoff_W.head<2>()).norm() < 1e-12);
        if (u >= sw.lower_start_u) CHECK((p.head<2>() - sw.p_touchdown_W.head<2>()).norm() < 1e-12);
        if (u >= sw.lift_end_u && u <= sw.lower_start_u) {
          CHECK(p.z() - shadow_height(t, p.y(), r) >= clearance - 1e-12);
          ++transfer;
        }
      }
    }
  }
  CHECK(transfer > 0);
}

void check_posture(const RobotModel& m, const MotionPlan& plan) {
  RobotKinematicState state(m);
  BodyPoses poses;
  const double T = plan.trunk.duration_s();
  for (int i = 0; i <= 300; ++i) {
    const double time = T * i / 300.0;
    robot_state_at(m, plan, time, state);
    forward_kinematics_tree(m, state.q, poses);
    for (int leg = 0; leg < m.legs(); ++leg) {
      INFO("leg " << leg_name(leg) << " t " << time);
      const Vec3 foot_W = state.trunk.p_W + state.trunk.W_R_B * tree_foot_position_B(m, poses, leg);
      CHECK((foot_W - state.foot_center_W[leg]).norm() < 1e-9);
      for (int j = 0; j < m.leg(leg).n_joints; ++j) {
        const int k = m.joint(leg, j);
        CHECK(state.q[k] >= m.joint_lower_rad[k]);
        CHECK(state.q[k] <= m.joint_upper_rad[k]);
      }
    }
  }
}

TEST_CASE("quadrupeds: the stairs' risers are at least 40 % of the standing hip height",
          "[quadruped][stance]") {
  // The hip height above the ground of each scene's comment, and the riser measured against it.
  for (const auto& [name, hip_height_m] :
       {std::pair<std::string, double>{"solo12_crawl_stairs", 0.2263},
        std::pair<std::string, double>{"anymal_c_crawl_stairs", 0.4641}}) {
    INFO(name);
    const Scene s =
        load_scene(std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/" + name + ".yaml");
    const RobotModel m = build_robot_model(s.robot);
    REQUIRE(static_cast<int>(s.robot.stance.size()) == m.legs());
    // Every leg at its stance, the trunk level: the hip joint's height above the foot point
    // from the tree's forward kinematics (the stance's depth), and above the ground the
    // sphere's radius more (the foot stands on the sphere's lowest point).
    JointVector q = JointVector::Zero(m.joints());
    for (int leg = 0; leg < m.legs(); ++leg)
      for (int j = 0; j < m.leg(leg).n_joints; ++j) q[m.joint(leg, j)] = s.robot.stance[leg].q[j];
    BodyPoses poses;
    forward_kinematics_tree(m, q, poses);
    for (int leg = 0; leg < m.legs(); ++leg) {
      const double depth =
          m.p_parent_joint[m.body(leg, 0)].z() - tree_foot_position_B(m, poses, leg).z();
      CHECK(depth == Approx(s.robot.stance[leg].depth_m).margin(1e-12));
      CHECK(depth + m.foot_radius_m[leg] == Approx(hip_height_m).margin(1e-4));
    }
    CHECK(s.terrain.riser_height_m >= 0.4 * hip_height_m);
  }
}

TEST_CASE("quadrupeds: footholds, swings and posture from the model's hips and chains",
          "[quadruped][gait][posture]") {
  for (const QuadCase& c : quad_cases()) {
    INFO(c.scene << (c.overrides.empty() ? "" : " (trot 0.6)"));
    const Scene s = load_scene(
        std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/" + c.scene + ".yaml", c.overrides);
    const RobotModel m = build_robot_model(s.robot);
    REQUIRE(m.legs() == 4);
    const MotionPlan plan = plan_motion(s, m);
    CHECK(plan.posture.margin.admitted);
    check_footholds(s, m, plan);
    check_swings(s, m, plan);
    check_posture(m, plan);
  }
}

}  // namespace
}  // namespace hexdyn
