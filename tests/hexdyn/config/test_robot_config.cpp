// A scene's robot read from its URDF (config/robot_config.hpp): robot.urdf resolved relative
// to the file that names it (also through inherit:), the YAML robot's keys refused next to
// it, the URDF's effort limits as per-joint torque limits unless the scene gives one, the
// default foothold radius from the nominal stance, and broken descriptions refused in one
// line.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
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

const std::string kSource = HEXDYN_SOURCE_DIR;
const std::string kMark4Scene = kSource + "/configs/robots/phantomx_mark4_stairs.yaml";
const std::string kMark4Urdf = kSource + "/tests/data/urdf/robots/phantomx_mark4.urdf";
const std::string kHuma = kSource + "/tests/data/urdf/robots/phantomx_humarobotics.urdf";

/// A fresh directory under the system's temporary directory, removed at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("hexdyn_robot_config_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(counter()++));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  static int& counter() {
    static int n = 0;
    return n;
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
};

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The PhantomX scene with its robot: section replaced by `robot_section`.
std::string mark4_scene_with(const std::string& robot_section) {
  std::string text = file_text(kMark4Scene);
  const auto a = text.find("robot:\n"), b = text.find("\nterrain:");
  REQUIRE(a != std::string::npos);
  REQUIRE(b != std::string::npos);
  return text.substr(0, a) + robot_section + text.substr(b);
}

std::string config_error(const std::string& path, const std::vector<Override>& ov = {}) {
  try {
    (void)load_scene(path, ov);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError was thrown");
  return "";
}

}  // namespace

TEST_CASE("robot.urdf is relative to the file that names it, also when inherited",
          "[robot_config]") {
  TempDir dir;
  fs::create_directories(dir.path / "models");
  fs::copy_file(kMark4Urdf, dir.path / "models" / "robot.urdf");
  // models/base.yaml names robot.urdf beside itself; scenes/run.yaml inherits it from elsewhere.
  const std::string base = dir.write(
      "models/base.yaml", mark4_scene_with("robot:\n  urdf: robot.urdf\n  forward_axis: +x\n"));
  const std::string run =
      dir.write("scenes/run.yaml", "inherit: ../models/base.yaml\nname: inherited\n");
  const Scene a = load_scene(base);
  const Scene b = load_scene(run);
  REQUIRE(a.robot.urdf);
  REQUIRE(b.robot.urdf);
  CHECK(fs::equivalent(a.robot.urdf->source_path, dir.path / "models" / "robot.urdf"));
  CHECK(fs::equivalent(b.robot.urdf->source_path, dir.path / "models" / "robot.urdf"));
  CHECK(b.robot.urdf->name == "pxmark4");
  // The resolved configuration names the file by its absolute path, and loads back.
  CHECK(b.resolved_yaml.find((dir.path / "models" / "robot.urdf").string()) != std::string::npos);
  const Scene c = load_scene_from_string(b.resolved_yaml, "resolved");
  REQUIRE(c.robot.urdf);
  CHECK(c.gait.foot_lateral_m == b.gait.foot_lateral_m);
  // A missing file names the key and the path.
  const std::string bad =
      dir.write("scenes/bad.yaml", "inherit: ../models/base.yaml\nrobot:\n  urdf: nowhere.urdf\n");
  const std::string msg = config_error(bad);
  CHECK(msg.find("robot.urdf: got ") != std::string::npos);
  CHECK(msg.find("scenes/nowhere.urdf, which does not exist") != std::string::npos);
}

TEST_CASE("a URDF robot takes its effort limits per joint unless the scene gives one limit",
          "[robot_config]") {
  const Scene s = load_scene(kMark4Scene);
  REQUIRE(s.robot.urdf);
  REQUIRE(s.allocation.joint_torque_limit_Nm);
  const RobotModel m = build_robot_model(s.robot);
  REQUIRE(s.allocation.joint_torque_limit_Nm->size() == m.joints());
  for (int k = 0; k < m.joints(); ++k) {
    CHECK((*s.allocation.joint_torque_limit_Nm)[k] == m.effort_limit_Nm[k]);
    CHECK(m.effort_limit_Nm[k] == 3.0);  // every <limit effort="3"> of the file
  }
  CHECK(s.resolved_yaml.find("torque_limit: effort") != std::string::npos);
  const Scene t = load_scene(kMark4Scene, {{"allocation.torque_limit", "1.5"}});
  CHECK_FALSE(t.allocation.joint_torque_limit_Nm);
  CHECK(t.allocation.torque_limit_Nm == 1.5);
  // The YAML robot keeps its required scalar limit, for every joint.
  const Scene paper = load_scene(kSource + "/configs/paper.yaml");
  CHECK_FALSE(paper.allocation.joint_torque_limit_Nm);
  CHECK_FALSE(paper.robot.urdf);
}

TEST_CASE("a URDF robot's footholds default to its nominal stance radius", "[robot_config]") {
  TempDir dir;
  const std::string scene =
      dir.write("s.yaml", mark4_scene_with("robot:\n  urdf: " + kMark4Urdf + "\n"));
  const Scene s = load_scene(scene);
  const RobotModel m = build_robot_model(s.robot);
  // Default pose "femur level, tibia plumb": the foot below the tibia joint, which is level
  // with the femur joint: radius = horizontal distance of the tibia joint from the coxa axis.
  BodyPoses poses;
  const JointVector q = JointVector::Zero(m.joints());
  forward_kinematics_tree(m, q, poses);
  const Vec3 coxa = m.p_parent_joint[1];
  const Vec3 femur_B = poses.p_B[2], tibia_B = poses.p_B[3];  // at zero angles, leg L1
  // PhantomX: femur and tibia joints on the leg's outward line at zero coxa angle, the tibia
  // joint 0.015 m below the femur joint; level femur: the same horizontal reach l1 + l2.
  const double l1 = (femur_B - coxa).head<2>().norm();
  const double l2 = std::hypot((tibia_B - femur_B).head<2>().norm(), (tibia_B - femur_B).z());
  CHECK(s.gait.foot_lateral_m == Approx(l1 + l2).epsilon(1e-12));
  const Scene t = load_scene(scene, {{"gait.foot_lateral", "0.1"}});
  CHECK(t.gait.foot_lateral_m == 0.1);
  const Scene u = load_scene(scene, {{"robot.nominal_pose", "[0, 0, 0]"}});
  // Zero pose: femur and tibia straight out, foot at (0.095, 0, -0.09) of the tibia.
  const Vec3 foot0 = tree_foot_position_B(m, poses, 0);
  CHECK(u.gait.foot_lateral_m == Approx((foot0 - coxa).head<2>().norm()).epsilon(1e-12));
}

TEST_CASE("a URDF robot's scene refuses the YAML robot's keys and broken descriptions",
          "[robot_config]") {
  TempDir dir;
  const std::string extra = dir.write(
      "extra.yaml", mark4_scene_with("robot:\n  urdf: " + kMark4Urdf + "\n  hips:\n    x: 0.1\n"));
  CHECK(config_error(extra).find("robot.hips: unknown key, allowed here:") != std::string::npos);
  const std::string huma = config_error(kMark4Scene, {{"robot.urdf", kHuma}});
  CHECK(huma.find('\n') == std::string::npos);
  CHECK(huma.find("phantomx_humarobotics.urdf: link '") != std::string::npos);
  CHECK(huma.find("triangle inequality") != std::string::npos);
  CHECK(config_error(kMark4Scene, {{"robot.forward_axis", "+z"}})
            .find("robot.forward_axis: got +z, expected one of") != std::string::npos);
  CHECK(config_error(kMark4Scene, {{"robot.foot_links", "[a]"}})
            .find("robot.foot_links: got [a], expected a list of 2 to 8 names") !=
        std::string::npos);
  // Two names for the PhantomX's six legs: the reader, which knows the legs, refuses them.
  const std::string two = config_error(kMark4Scene, {{"robot.foot_links", "[a, b]"}});
  INFO(two);
  CHECK(two.find("robot.foot_links") != std::string::npos);
  CHECK(two.find('\n') == std::string::npos);
}

TEST_CASE("a URDF robot is read from its file as the file is now, parsed once per text",
          "[robot_config]") {
  TempDir dir;
  const std::string original = file_text(kMark4Urdf);
  const std::string urdf = dir.write("robot.urdf", original);
  const std::string scene = dir.write("s.yaml", mark4_scene_with("robot:\n  urdf: robot.urdf\n"));
  const Scene a = load_scene(scene);
  const Scene b = load_scene(scene);
  REQUIRE(a.robot.urdf);
  CHECK(b.robot.urdf == a.robot.urdf);  // the same text and keys: the robot loaded before
  // One link 1 kg heavier: the next scene has the edited robot.
  std::string edited = original;
  const std::string mass = "<mass value=\"1.522054\" />";
  const auto at = edited.find(mass);
  REQUIRE(at != std::string::npos);
  edited.replace(at, mass.size(), "<mass value=\"2.522054\" />");
  dir.write("robot.urdf", edited);
  const Scene c = load_scene(scene);
  REQUIRE(c.robot.urdf);
  CHECK(c.robot.urdf->total_mass_kg == Approx(a.robot.urdf->total_mass_kg + 1.0));
  CHECK(c.robot.urdf->total_mass_kg == read_urdf_robot(urdf).total_mass_kg);
  dir.write("robot.urdf", original);
  CHECK(load_scene(scene).robot.urdf->total_mass_kg == a.robot.urdf->total_mass_kg);
  // Other keys on the same file are another robot.
  const Scene d = load_scene(scene, {{"robot.ik_min_margin", "0.001"}});
  CHECK(d.robot.urdf != a.robot.urdf);
  CHECK(d.robot.ik_min_margin_m == 0.001);
}

// ---- feet (docs/user/robots.md#feet) ----
namespace {

const std::string kPexodScene = kSource + "/configs/robots/pexod_stairs.yaml";

/// pexod's sphere feet as its URDF gives them: centre (0.0125, ±0.1275, 0) m in the tibia
/// frame, + on the left legs (L1, L3, L5), − on the right; radius 0.025 m.
Vec3 pexod_foot(int leg) { return Vec3(0.0125, is_left(leg) ? 0.1275 : -0.1275, 0.0); }

}  // namespace

TEST_CASE("a URDF's sphere <collision> at a chain's end is its default foot, centre and radius",
          "[robot_config][feet]") {
  const Scene scene = load_scene(kPexodScene);
  REQUIRE(scene.robot.urdf);
  const RobotModel model = build_robot_model(scene.robot);
  REQUIRE(model.legs() == 6);
  for (int leg = 0; leg < model.legs(); ++leg) {
    const UrdfLeg& l = scene.robot.urdf->legs[leg];
    INFO(leg_name(leg) << ": " << l.joints[0].name);
    CHECK(l.foot_kind == FootSource::kSphereCollision);
    CHECK((model.p_foot_last[leg] - pexod_foot(leg)).norm() <= 1e-15);
    CHECK(model.foot_radius_m[leg] == 0.025);
  }
  CHECK(leg_mapping_text(*scene.robot.urdf).find("the sphere <collision> of leg_2_3") !=
        std::string::npos);
  CHECK(leg_mapping_entries(*scene.robot.urdf)[0].find(" radius 0.025") != std::string::npos);
  // robot.foot_radius replaces the sphere's radius; 0 makes the centre a point foot.
  const Scene point = load_scene(kPexodScene, {{"robot.foot_radius", "0"}});
  CHECK(build_robot_model(point.robot).foot_radius_m[3] == 0.0);
}

TEST_CASE("robot.foot_offset: one point, one per leg in leg order, or a map by leg name",
          "[robot_config][feet]") {
  constexpr int kPexodLegs = 6;
  std::string list = "[", map = "{";
  for (int leg = 0; leg < kPexodLegs; ++leg) {
    const Vec3 p = pexod_foot(leg);
    std::ostringstream xyz;
    xyz << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
    list += (leg ? ", " : "") + xyz.str();
    map += (leg ? ", " : "") + leg_name(leg) + ": " + xyz.str();
  }
  list += "]";
  map += "}";
  for (const std::string& value : {list, map}) {
    INFO(value);
    const Scene scene = load_scene(kPexodScene, {{"robot.foot_offset", value}});
    const RobotModel model = build_robot_model(scene.robot);
    REQUIRE(model.legs() == kPexodLegs);
    for (int leg = 0; leg < kPexodLegs; ++leg) {
      CHECK(model.p_foot_last[leg] == pexod_foot(leg));
      CHECK(model.foot_radius_m[leg] == 0.0);  // a point, unless robot.foot_radius says
      // Inside the tibia's <collision> box (it reaches the sphere's centre).
      CHECK(scene.robot.urdf->legs[leg].foot_check ==
            "inside the box <collision> of " + scene.robot.urdf->legs[leg].joints[2].link);
    }
    // The resolved configuration reruns to the same feet.
    const Scene again = load_scene_from_string(scene.resolved_yaml, kPexodScene);
    const RobotModel again_model = build_robot_model(again.robot);
    for (int leg = 0; leg < kPexodLegs; ++leg)
      CHECK(again_model.p_foot_last[leg] == model.p_foot_last[leg]);
    const Scene sphere =
        load_scene(kPexodScene, {{"robot.foot_offset", value}, {"robot.foot_radius", "0.025"}});
    CHECK(build_robot_model(sphere.robot).foot_radius_m[5] == 0.025);
  }
  // One point for every leg: the left feet's point lies outside the right tibias.
  const std::string one = config_error(kPexodScene, {{"robot.foot_offset", "[0.0125, 0.1275, 0]"}});
  CHECK(one.find('\n') == std::string::npos);
  CHECK(one.find("leg L2 (chain 'body_leg_3'): robot.foot_offset (0.0125, 0.1275, 0) m lies "
                 "outside the <collision> geometry of its last link 'leg_3_3' (box, sphere; ") !=
        std::string::npos);
  // Malformed values: one line with the key, the value and what is allowed.
  struct Bad {
    std::string value, expected;
  };
  const std::vector<Bad> bad = {
      // Another count than the robot's six legs: the URDF reader, which counts them.
      {"[[0, 0, 0], [0, 0, 0]]",
       "robot.foot_offset: got 2 points [[0, 0, 0], [0, 0, 0]], expected one [x, y, z] for "
       "every leg or one per leg (6 legs, L1 … L6)"},
      {"{L1: [0, 0, 0]}",
       "robot.foot_offset: got {L1: [0, 0, 0]}, expected a map naming every leg (L1 … Ln of the "
       "robot's n legs), L2 missing"},
      {"{L9: [0, 0, 0]}",
       "robot.foot_offset: got the key L9, expected leg names (L1 … Ln of the robot's n legs)"},
      {"[0, 0]",
       "robot.foot_offset: got [0, 0], expected [x, y, z] m, each a number in [-10, 10] (every "
       "leg); or one per leg: a list in leg order L1 … Ln, or a map naming every leg L1 … Ln"},
      {"[0, 0, 11]",
       "robot.foot_offset: got [0, 0, 11], expected a list of 3 numbers, each a "
       "number in [-10, 10]"},
      {"[[0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, x]]",
       "robot.foot_offset: item 6 (L6): got [0, 0, x], expected [x, y, z] m, each a number in "
       "[-10, 10]"},
      {"7", "robot.foot_offset: got 7, expected [x, y, z]"},
  };
  for (const Bad& b : bad) {
    const std::string e = config_error(kPexodScene, {{"robot.foot_offset", b.value}});
    INFO(e);
    CHECK(e.find('\n') == std::string::npos);
    CHECK(e.find(b.expected) != std::string::npos);
  }
  CHECK(config_error(kPexodScene, {{"robot.foot_radius", "-0.01"}})
            .find("robot.foot_radius: got -0.01, expected a number in [0, 1]") !=
        std::string::npos);
}

}  // namespace hexdyn
