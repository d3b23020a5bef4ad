// A URDF robot's stance (model/stance.hpp, config/stance_keys.hpp): a leg whose default pose
// is out of reach falls back to mid-range angles with a warning naming the leg, the reason
// and the radius; the default foot spread averages only the legs at their pose; the resolved
// configuration records every leg's stance; robot.nominal_pose per leg fixes a fallback, and
// a bad one is refused in one line. Radii and depths are checked against the tree's forward
// kinematics of the reported poses, mid-range angles against the limits written in the file.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

const std::string kMark4Urdf = std::string(HEXDYN_SOURCE_DIR) + "/robots/phantomx_mark4.urdf";
/// The PhantomX Mark IV: six legs of three joints.
constexpr int kMark4Legs = 6;
constexpr int kMark4LegJoints = 3;

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `urdf` with joint `joint`'s <limit lower upper> replaced.
std::string with_limits(std::string urdf, const std::string& joint, double lower, double upper) {
  const auto at = urdf.find("<joint name=\"" + joint + "\"");
  REQUIRE(at != std::string::npos);
  const auto from = urdf.find("<limit", at), to = urdf.find("/>", from);
  std::string limit = urdf.substr(from, to - from);
  limit = std::regex_replace(limit, std::regex("lower=\"[^\"]*\""),
                             "lower=\"" + std::to_string(lower) + "\"");
  limit = std::regex_replace(limit, std::regex("upper=\"[^\"]*\""),
                             "upper=\"" + std::to_string(upper) + "\"");
  return urdf.replace(from, to - from, limit);
}

/// A directory with the PhantomX URDF whose L3 tibia (default pose 1.057 rad) allows only
/// [0.2, 0.6] rad and whose L6 femur (default pose −0.245 rad) only [0.1, 0.5] rad, and a
/// flat-ground scene of it without gait.foot_lateral; removed at scope exit.
struct FallbackRobot {
  fs::path dir;
  std::string urdf, scene;
  explicit FallbackRobot(bool every_tibia = false) {
    static int n = 0;
    dir = fs::temp_directory_path() /
          ("hexdyn_stance_" + std::to_string(::getpid()) + "_" + std::to_string(n++));
    fs::create_directories(dir);
    std::string text = with_limits(file_text(kMark4Urdf), "left_middle_tibia", 0.2, 0.6);
    text = with_limits(text, "right_back_femur", 0.1, 0.5);
    if (every_tibia)
      for (const char* side : {"left", "right"})
        for (const char* row : {"front", "middle", "back"})
          text = with_limits(text, std::string(side) + "_" + row + "_tibia", 0.2, 0.6);
    urdf = (dir / "robot.urdf").string();
    std::ofstream(urdf) << text;
    scene = (dir / "scene.yaml").string();
    std::ofstream(scene) << "robot: {urdf: robot.urdf}\n"
                            "terrain: {type: flat}\n"
                            "gait: {duty_factor: 0.5, stroke: 0.0625, swing_clearance: 0.01,\n"
                            "       touchdown_speed: 0.05}\n"
                            "motion: {peak_speed: 0.05, cycles: 2, ramp_duration: 1,\n"
                            "         posture: {height: auto, start_y: 0}}\n"
                            "contact: {model: compliant, stiffness: 3.98e11, exponent: 2.2,\n"
                            "          damping_max: 1.0e4, full_damping_depth: 1.0e-5,\n"
                            "          friction_coefficient: 0.6}\n"
                            "allocation: {friction: pyramid4}\n"
                            "output: {sample_step: 0.5, grid: uniform}\n";
  }
  ~FallbackRobot() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

/// Horizontal distance and height of the coxa joint above the foot of leg `leg` at joint
/// angles q, by the tree's forward kinematics in the trunk frame (its z is the trunk normal).
std::pair<double, double> fk_radius_depth(const RobotModel& m, int leg, const Vec3& q) {
  JointVector q_all = JointVector::Zero(m.joints());
  for (int j = 0; j < m.leg(leg).n_joints; ++j) q_all[m.joint(leg, j)] = q[j];
  BodyPoses poses;
  forward_kinematics_tree(m, q_all, poses);
  const Vec3 hip = m.p_parent_joint[m.body(leg, 0)];
  const Vec3 foot = tree_foot_position_B(m, poses, leg);
  return {(foot - hip).head<2>().norm(), hip.z() - foot.z()};
}

/// The number after "radius " in a warning line.
double radius_in(const std::string& line) {
  const auto at = line.find("radius ");
  REQUIRE(at != std::string::npos);
  return std::stod(line.substr(at + 7));
}

std::string config_error(const std::string& path, const std::vector<Override>& ov) {
  try {
    (void)load_scene(path, ov);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError was thrown");
  return "";
}

}  // namespace

TEST_CASE(
    "a leg that cannot reach the default pose falls back, with a warning, and is left out "
    "of the default foot spread",
    "[stance]") {
  const FallbackRobot robot;
  const Scene s = load_scene(robot.scene);
  const RobotModel m = build_robot_model(s.robot);
  const UrdfRobot file = read_urdf_robot(robot.urdf);
  double mean = 0.0;
  for (int leg = 0; leg < kMark4Legs; ++leg) {
    INFO(leg_name(leg));
    const NominalStance& st = s.robot.stance[leg];
    const auto [radius, depth] = fk_radius_depth(m, leg, st.q);
    CHECK(st.radius_m == Approx(radius).epsilon(1e-12));
    CHECK(st.depth_m == Approx(depth).epsilon(1e-12));
    const bool fallback = leg == 2 || leg == 5;
    CHECK(st.from_pose == !fallback);
    if (!fallback) {
      CHECK(st.source == "nominal pose");
      mean += radius / 4.0;
      continue;
    }
    const UrdfLeg& l = file.legs[leg];
    for (int j = 0; j < kMark4LegJoints; ++j)
      CHECK(st.q[j] == Approx(0.5 * (l.joints[j].lower_rad + l.joints[j].upper_rad)).margin(1e-15));
  }
  CHECK(s.robot.stance[2].q[2] == Approx(0.4).margin(1e-15));  // [0.2, 0.6] as written
  CHECK(s.robot.stance[5].q[1] == Approx(0.3).margin(1e-15));  // [0.1, 0.5]
  CHECK(s.robot.stance[2].source ==
        "fallback: mid-range joint angles (joint left_middle_tibia outside its limits)");
  CHECK(s.robot.stance[5].source ==
        "fallback: mid-range joint angles (joint right_back_femur outside its limits)");
  // The default spread: the mean over L1, L2, L4, L5 only.
  CHECK(s.gait.foot_lateral_m == Approx(mean).epsilon(1e-12));
  // One warning per fallback leg, naming the leg, the reason and the radius it gives.
  REQUIRE(s.warnings.size() == 2);
  for (int i = 0; i < 2; ++i) {
    const int leg = i == 0 ? 2 : 5;
    const std::string& w = s.warnings[i];
    INFO(w);
    CHECK(w.find('\n') == std::string::npos);
    CHECK(w.rfind(leg_name(leg) + ": the nominal pose is out of reach", 0) == 0);
    CHECK(w.find(i == 0 ? "left_middle_tibia outside its limits" : "right_back_femur outside") !=
          std::string::npos);
    CHECK(radius_in(w) == Approx(fk_radius_depth(m, leg, s.robot.stance[leg].q).first)
                              .epsilon(1e-5));  // printed to 6 digits
    CHECK(w.find("left out of gait.foot_lateral's default") != std::string::npos);
    CHECK(w.find("the mean over L1, L2, L4, L5, the legs at their pose") != std::string::npos);
  }
  // The resolved configuration records each leg's stance.
  const YAML::Node rec = YAML::Load(s.resolved_yaml)["auto"]["robot"]["nominal_pose"];
  REQUIRE(rec.IsMap());
  for (int leg = 0; leg < kMark4Legs; ++leg) {
    const NominalStance& st = s.robot.stance[leg];
    const YAML::Node e = rec[leg_name(leg)];
    CHECK(e["source"].as<std::string>() == st.source);
    for (int j = 0; j < kMark4LegJoints; ++j) CHECK(e["pose"][j].as<double>() == st.q[j]);
    CHECK(e["radius"].as<double>() == st.radius_m);
    CHECK(e["depth"].as<double>() == st.depth_m);
  }
  // A given gait.foot_lateral: the stance sets nothing, no warning (the record stays).
  const Scene g = load_scene(robot.scene, {{"gait.foot_lateral", "0.1"}});
  CHECK(g.warnings.empty());
  CHECK(g.robot.stance[2].source == s.robot.stance[2].source);
}

TEST_CASE("when every leg falls back, the default spread is the mean of all six", "[stance]") {
  const FallbackRobot robot(true);
  const Scene s = load_scene(robot.scene);
  const RobotModel m = build_robot_model(s.robot);
  double mean = 0.0;
  for (int leg = 0; leg < kMark4Legs; ++leg) {
    CHECK_FALSE(s.robot.stance[leg].from_pose);
    mean += fk_radius_depth(m, leg, s.robot.stance[leg].q).first / kMark4Legs;
  }
  CHECK(s.gait.foot_lateral_m == Approx(mean).epsilon(1e-12));
  REQUIRE(s.warnings.size() == kMark4Legs);
  for (const std::string& w : s.warnings) {
    CHECK(w.find("averaged into gait.foot_lateral's default") != std::string::npos);
    CHECK(w.find("the mean over all 6 legs, none at its pose") != std::string::npos);
  }
}

TEST_CASE("robot.nominal_pose per leg fixes a fallback: a map by leg name, a list, one pose",
          "[stance]") {
  const FallbackRobot robot;
  const Scene s =
      load_scene(robot.scene, {{"robot.nominal_pose", "{L3: [0, -0.07, 0.5], L6: [0, 0.3, 1]}"}});
  CHECK(s.warnings.empty());
  const RobotModel m = build_robot_model(s.robot);
  double mean = 0.0;
  for (int leg = 0; leg < kMark4Legs; ++leg) {
    const NominalStance& st = s.robot.stance[leg];
    CHECK(st.from_pose);
    CHECK(st.source == (leg == 2 || leg == 5 ? "robot.nominal_pose" : "nominal pose"));
    const auto [radius, depth] = fk_radius_depth(m, leg, st.q);
    CHECK(st.radius_m == Approx(radius).epsilon(1e-12));
    CHECK(st.depth_m == Approx(depth).epsilon(1e-12));
    mean += radius / kMark4Legs;
  }
  CHECK(s.robot.stance[2].q == Vec3(0.0, -0.07, 0.5));
  CHECK(s.robot.stance[5].q == Vec3(0.0, 0.3, 1.0));
  CHECK(s.gait.foot_lateral_m == Approx(mean).epsilon(1e-12));
  // The resolved configuration reruns to the same stance and records nothing new.
  const Scene again = load_scene_from_string(s.resolved_yaml, "resolved");
  for (int leg = 0; leg < kMark4Legs; ++leg)
    CHECK(again.robot.stance[leg].q == s.robot.stance[leg].q);
  CHECK(again.gait.foot_lateral_m == s.gait.foot_lateral_m);
  CHECK(again.resolved_yaml == s.resolved_yaml);
  // One pose for every leg, six in a list and a map naming all six are the same stance.
  const std::string p = "[0, 0.3, 0.5]";
  const Scene one = load_scene(robot.scene, {{"robot.nominal_pose", p}});
  const Scene list = load_scene(
      robot.scene,
      {{"robot.nominal_pose", "[" + p + "," + p + "," + p + "," + p + "," + p + "," + p + "]"}});
  const Scene map = load_scene(
      robot.scene, {{"robot.nominal_pose", "{L1: " + p + ", L2: " + p + ", L3: " + p +
                                               ", L4: " + p + ", L5: " + p + ", L6: " + p + "}"}});
  for (const Scene* other : {&list, &map}) {
    for (int leg = 0; leg < kMark4Legs; ++leg) {
      CHECK(other->robot.stance[leg].q == Vec3(0.0, 0.3, 0.5));
      CHECK(other->robot.stance[leg].radius_m == one.robot.stance[leg].radius_m);
      CHECK(other->robot.stance[leg].source == "robot.nominal_pose");
    }
    CHECK(other->gait.foot_lateral_m == one.gait.foot_lateral_m);
  }
}

TEST_CASE(
    "a bad robot.nominal_pose is refused in one line with the key, value and what is "
    "allowed",
    "[stance]") {
  const FallbackRobot robot;
  const auto error = [&](const std::string& value) {
    const std::string e = config_error(robot.scene, {{"robot.nominal_pose", value}});
    CHECK(e.find('\n') == std::string::npos);
    return e;
  };
  const std::string forms =
      "expected [coxa, femur, tibia] rad, each a number in [-6.28319, 6.28319] (every leg); or "
      "6 of them: a list in leg order L1 … L6, or a map by leg name L1 … L6";
  CHECK(error("[1, 2]").find("robot.nominal_pose: got [1, 2], " + forms) != std::string::npos);
  CHECK(error("fold").find("robot.nominal_pose: got fold, " + forms) != std::string::npos);
  CHECK(error("{}").find("robot.nominal_pose: got {}, " + forms) != std::string::npos);
  CHECK(error("[[0, 0, 0], [0, 0, 0], [0, 0, 0]]").find("got [[0, 0, 0], ") != std::string::npos);
  CHECK(error("[[0,0,0],[0,0,0],[0,0,0],[0,0,0],[0,0,0],[0,0]]")
            .find("robot.nominal_pose: item 6 (L6): got [0, 0], expected [coxa, femur, tibia] "
                  "rad, each a number in [-6.28319, 6.28319]") != std::string::npos);
  CHECK(error("{L7: [0, 0, 0]}")
            .find("robot.nominal_pose: got the key L7, expected leg names (L1, L2, L3, L4, L5, "
                  "L6)") != std::string::npos);
  CHECK(error("{L2: [0, 0, 9]}")
            .find("robot.nominal_pose.L2: got [0, 0, 9], expected a list of 3 numbers, each a "
                  "number in [-6.28319, 6.28319]") != std::string::npos);
  CHECK(error("[0, 0, 7]").find("robot.nominal_pose: got [0, 0, 7], expected a list of 3") !=
        std::string::npos);
  // Inside the file's joint limits: L3's tibia allows [0.2, 0.6] rad here.
  CHECK(error("{L3: [0, -0.07, 1]}")
            .find("robot.nominal_pose: got [0, -0.07, 1] for L3, whose joint left_middle_tibia "
                  "allows [0.2, 0.6] rad, expected each angle inside its joint's limits") !=
        std::string::npos);
}

TEST_CASE("a quadruped's per-leg keys take its four legs, and refuse another count in one line",
          "[stance][quadruped]") {
  // Solo-12 (configs/robots/solo12_flat.yaml): four legs L1 … L4 of three joints.
  const std::string solo = std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/solo12_flat.yaml";
  const Scene plain = load_scene(solo);
  const RobotModel m0 = build_robot_model(plain.robot);
  REQUIRE(m0.legs() == 4);
  REQUIRE(plain.robot.legs == 4);
  REQUIRE(plain.robot.stance.size() == 4);
  // robot.nominal_pose: four poses in leg order, or a map by leg name.
  const std::string list = "[[0, 0.8, -1.6], [0, 0.7, -1.4], [0, -0.8, 1.6], [0, -0.7, 1.4]]";
  const std::string map =
      "{L1: [0, 0.8, -1.6], L2: [0, 0.7, -1.4], L3: [0, -0.8, 1.6], L4: [0, -0.7, 1.4]}";
  const Vec3 given[4] = {Vec3(0, 0.8, -1.6), Vec3(0, 0.7, -1.4), Vec3(0, -0.8, 1.6),
                         Vec3(0, -0.7, 1.4)};
  for (const std::string& value : {list, map}) {
    INFO(value);
    const Scene s = load_scene(solo, {{"robot.nominal_pose", value}});
    const RobotModel m = build_robot_model(s.robot);
    for (int leg = 0; leg < 4; ++leg) {
      const NominalStance& st = s.robot.stance[leg];
      CHECK(st.source == "robot.nominal_pose");
      CHECK(st.q == given[leg]);
      const auto [radius, depth] = fk_radius_depth(m, leg, st.q);
      CHECK(st.radius_m == Approx(radius).epsilon(1e-12));
      CHECK(st.depth_m == Approx(depth).epsilon(1e-12));
    }
    const Scene again = load_scene_from_string(s.resolved_yaml, "resolved");
    CHECK(again.resolved_yaml == s.resolved_yaml);
  }
  // robot.foot_offset: the feet the description gives, as four points in leg order or a map.
  std::string points = "[", named = "{";
  for (int leg = 0; leg < 4; ++leg) {
    const Vec3& p = m0.p_foot_last[leg];
    std::ostringstream xyz;
    xyz.precision(17);
    xyz << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
    points += (leg ? ", " : "") + xyz.str();
    named += (leg ? ", " : "") + leg_name(leg) + ": " + xyz.str();
  }
  points += "]";
  named += "}";
  for (const std::string& value : {points, named}) {
    INFO(value);
    const RobotModel m = build_robot_model(load_scene(solo, {{"robot.foot_offset", value}}).robot);
    for (int leg = 0; leg < 4; ++leg) CHECK(m.p_foot_last[leg] == m0.p_foot_last[leg]);
  }
  // Another count, or a leg the robot does not have: one line with the key, the value and what
  // is allowed.
  const auto error = [&](const std::string& key, const std::string& value) {
    const std::string e = config_error(solo, {{key, value}});
    CHECK(e.find('\n') == std::string::npos);
    return e;
  };
  const std::string six =
      "[[0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8, -1.6], "
      "[0, 0.8, -1.6], [0, 0.8, -1.6]]";
  CHECK(error("robot.nominal_pose", six)
            .find("robot.nominal_pose: got [[0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8, -1.6], "
                  "[0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8, -1.6]], expected [coxa, femur, tibia] "
                  "rad, each a number in [-6.28319, 6.28319] (every leg); or 4 of them: a list in "
                  "leg order L1 … L4, or a map by leg name L1 … L4") != std::string::npos);
  CHECK(error("robot.nominal_pose", "{L5: [0, 0.8, -1.6]}")
            .find("robot.nominal_pose: got the key L5, expected leg names (L1, L2, L3, L4)") !=
        std::string::npos);
  CHECK(error("robot.nominal_pose", "[[0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8, -1.6], [0, 0.8]]")
            .find("robot.nominal_pose: item 4 (L4): got [0, 0.8], expected [coxa, femur, tibia] "
                  "rad") != std::string::npos);
  CHECK(error("robot.foot_offset", "[[0, 0, -0.1], [0, 0, -0.1], [0, 0, -0.1]]")
            .find("robot.foot_offset: got 3 points [[0, 0, -0.1], [0, 0, -0.1], [0, 0, -0.1]], "
                  "expected one [x, y, z] for every leg or one per leg (4 legs, L1 … L4)") !=
        std::string::npos);
  CHECK(error("robot.foot_offset", "{L1: [0, 0, -0.1], L3: [0, 0, -0.1]}")
            .find("robot.foot_offset: got {L1: [0, 0, -0.1], L3: [0, 0, -0.1]}, expected a map "
                  "naming every leg (L1 … Ln of the robot's n legs), L2 missing") !=
        std::string::npos);
}

}  // namespace hexdyn
