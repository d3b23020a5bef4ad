// The scene's actuators section (config/actuators.hpp, docs/user/configuration.md#actuators):
// each joint's values come field by field from joints.NAME over its type over default over
// the URDF's <dynamics> over the built-in defaults, an entry's model first and its own keys
// over it; rotor_inertia becomes the armature with the joint's final gear ratio; errors are
// one line naming the key path (and the joint, for a required value no entry gives); the
// resolved YAML holds every joint's values and reads back to the same drive train; a scene
// without the section has neither actuators nor allocation.objective in it.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/servo_table.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

const std::string kSource = HEXDYN_SOURCE_DIR;
const std::string kName = "case.yaml";
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string& paper_text() {
  static const std::string text = file_text(kSource + "/configs/paper.yaml");
  return text;
}

/// The paper scene with `section` (YAML text at the top level) appended.
Scene paper_with(const std::string& section, const std::vector<Override>& overrides = {}) {
  return load_scene_from_string(paper_text() + "\n" + section, kName, overrides);
}

/// The message of the ConfigError that loading throws; fails when nothing is thrown.
std::string config_error(const std::string& section, const std::vector<Override>& overrides = {}) {
  try {
    paper_with(section, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError was thrown for:\n" << section);
  return "";
}

/// The message names the source and the key path, says `what`, and is one line.
void check_error(const std::string& section, const std::string& key, const std::string& what) {
  const std::string msg = config_error(section);
  INFO("section:\n" << section << "message: " << msg);
  CHECK(msg.rfind(kName + ": " + key + ": ", 0) == 0);
  CHECK(msg.find(what) != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
}

/// A table value, +inf where the table gives none (an optional rating), or `fallback`.
double table(double value, double fallback) { return std::isnan(value) ? fallback : value; }

/// Every field of two joints' drives is equal (doubles bit for bit, +inf included).
void check_same(const ActuatorParams& a, const ActuatorParams& b) {
  CHECK(a.model == b.model);
  CHECK(a.gear_ratio == b.gear_ratio);
  CHECK(a.torque_constant_NmpA == b.torque_constant_NmpA);
  CHECK(a.resistance_ohm == b.resistance_ohm);
  CHECK(a.armature_kgm2 == b.armature_kgm2);
  CHECK(a.coulomb_friction_Nm == b.coulomb_friction_Nm);
  CHECK(a.viscous_friction_Nmsprad == b.viscous_friction_Nmsprad);
  CHECK(a.gear_efficiency == b.gear_efficiency);
  CHECK(a.voltage_V == b.voltage_V);
  CHECK(a.peak_torque_Nm == b.peak_torque_Nm);
  CHECK(a.continuous_torque_Nm == b.continuous_torque_Nm);
  CHECK(a.regeneration == b.regeneration);
  CHECK(a.thermal_window_s == b.thermal_window_s);
  CHECK(a.winding == b.winding);
  CHECK(a.voltage_utilization == b.voltage_utilization);
  const auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  CHECK(same(a.thermal_resistance_winding_KpW, b.thermal_resistance_winding_KpW));
  CHECK(same(a.thermal_capacity_winding_JpK, b.thermal_capacity_winding_JpK));
  CHECK(same(a.thermal_resistance_housing_KpW, b.thermal_resistance_housing_KpW));
  CHECK(same(a.thermal_capacity_housing_JpK, b.thermal_capacity_housing_JpK));
  CHECK(a.ambient_temperature_degC == b.ambient_temperature_degC);
  CHECK(a.winding_temperature_limit_degC == b.winding_temperature_limit_degC);
}

/// The drive a servo of the table gives a joint by itself (NaN: the built-in default).
ActuatorParams from_table(const ServoSpec& s) {
  ActuatorParams a;
  a.model = s.name;
  a.gear_ratio = s.gear_ratio;
  a.torque_constant_NmpA = s.torque_constant_NmpA;
  a.resistance_ohm = s.resistance_ohm;
  a.armature_kgm2 = table(s.armature_kgm2, 0.0);
  a.coulomb_friction_Nm = table(s.coulomb_friction_Nm, 0.0);
  a.viscous_friction_Nmsprad = table(s.viscous_friction_Nmsprad, 0.0);
  a.gear_efficiency = s.gear_efficiency;
  a.voltage_V = s.voltage_V;
  a.peak_torque_Nm = s.peak_torque_Nm;
  a.continuous_torque_Nm = table(s.continuous_torque_Nm, kInf);
  return a;
}

/// The resolved YAML reads back to the same drive train and objective.
void check_round_trip(const Scene& a) {
  const Scene b = load_scene_from_string(a.resolved_yaml, "resolved.yaml");
  CHECK(b.robot.drive.present == a.robot.drive.present);
  CHECK(b.allocation.objective == a.allocation.objective);
  REQUIRE(b.robot.drive.joints.size() == a.robot.drive.joints.size());
  for (int k = 0; k < a.robot.drive.joints.size(); ++k) {
    INFO("joint " << k);
    check_same(a.robot.drive.joints[k], b.robot.drive.joints[k]);
  }
}

/// One joint of a scene's robot: its flat index, its name in the files and its place in
/// its leg (0 at the hip).
struct JointAt {
  int k = 0, place = 0;
  std::string name;
};

/// Every joint of the scene's robot, in flat order, from the model's leg table.
std::vector<JointAt> joints_of(const Scene& s) {
  const RobotModel m = build_robot_model(s.robot);
  std::vector<JointAt> out;
  for (int l = 0; l < m.legs(); ++l)
    for (int j = 0; j < m.leg(l).n_joints; ++j)
      out.push_back({m.joint(l, j), j, m.joint_source_names[m.joint(l, j)]});
  return out;
}

const ServoSpec& servo(const char* name) {
  const ServoSpec* s = find_servo(name);
  REQUIRE(s != nullptr);
  return *s;
}

}  // namespace

TEST_CASE("actuators: joints over type over default over the model, field by field",
          "[config][actuators]") {
  const std::string section =
      "actuators:\n"
      "  default: {model: dynamixel_mx64, voltage: 11, regeneration: 0.5}\n"
      "  femur: {gear_ratio: 150, coulomb_friction: 0.2}\n"
      "  tibia: {model: dynamixel_xm430_w350, thermal_window: 2}\n"
      "  joints:\n"
      "    L2_femur: {resistance: 7, regeneration: 0.25}\n"
      "    L3_tibia: {model: dynamixel_mx64, peak_torque: 5}\n";
  const Scene s = paper_with(section);
  REQUIRE(s.robot.drive.present);
  const ServoSpec &mx = servo("dynamixel_mx64"), &xm = servo("dynamixel_xm430_w350");
  // Every joint starts from the default entry: the MX-64 with its voltage and regeneration.
  ActuatorParams base = from_table(mx);
  base.voltage_V = 11.0;
  base.regeneration = 0.5;
  ActuatorParams coxa = base;
  ActuatorParams femur = base;
  femur.gear_ratio = 150.0;
  femur.coulomb_friction_Nm = 0.2;
  ActuatorParams l2_femur = femur;
  l2_femur.resistance_ohm = 7.0;
  l2_femur.regeneration = 0.25;
  // The tibia entry's model replaces the servo: all the XM430 gives, its voltage over the
  // default's 11 V; the values it lacks (armature, friction) are the built-in defaults, not
  // the default entry's MX-64 values. Regeneration is not the servo's: the default's stays.
  ActuatorParams tibia = from_table(xm);
  tibia.regeneration = 0.5;
  tibia.thermal_window_s = 2.0;
  // L3_tibia's own model is more specific than both: the MX-64's 12 V, its own peak torque.
  ActuatorParams l3_tibia = from_table(mx);
  l3_tibia.peak_torque_Nm = 5.0;
  l3_tibia.regeneration = 0.5;
  l3_tibia.thermal_window_s = 2.0;
  REQUIRE(mx.voltage_V == 12.0);
  // The drive train is part of the robot: the model built from the scene carries it.
  const RobotModel model = build_robot_model(s.robot);
  REQUIRE(model.drive.present);
  REQUIRE(model.drive.joints.size() == model.joints());
  for (const JointAt& j : joints_of(s)) {
    INFO(j.name);
    const ActuatorParams& got = model.drive.joints[j.k];
    if (j.name == "L2_femur")
      check_same(got, l2_femur);
    else if (j.name == "L3_tibia")
      check_same(got, l3_tibia);
    else
      check_same(got, j.place == 0 ? coxa : j.place == 1 ? femur : tibia);
  }
  check_round_trip(s);
}

TEST_CASE("actuators: what no entry gives takes the built-in defaults", "[config][actuators]") {
  const Scene s = paper_with(
      "actuators:\n  default: {gear_ratio: 100, torque_constant: 0.01, resistance: 2}\n");
  ActuatorParams expected;  // core/scene.hpp: η 1, r 0, no armature, friction, ratings, window
  expected.gear_ratio = 100.0;
  expected.torque_constant_NmpA = 0.01;
  expected.resistance_ohm = 2.0;
  for (const JointAt& j : joints_of(s)) check_same(s.robot.drive.joints[j.k], expected);
  CHECK(expected.gear_efficiency == 1.0);
  CHECK(expected.voltage_V == kInf);
  CHECK(s.allocation.objective == AllocationObjective::kTorqueSquared);
  check_round_trip(s);
  // Also with the copper-loss objective, which the round trip keeps.
  const Scene c =
      paper_with("actuators:\n  default: {gear_ratio: 100, torque_constant: 0.01, resistance: 2}\n",
                 {{"allocation.objective", "copper_loss"}});
  CHECK(c.allocation.objective == AllocationObjective::kCopperLoss);
  check_round_trip(c);
}

TEST_CASE("actuators: rotor_inertia is the armature G² J_m with the joint's final gear ratio",
          "[config][actuators]") {
  const std::string section =
      "actuators:\n"
      "  default: {gear_ratio: 100, torque_constant: 0.01, resistance: 2, rotor_inertia: 1.0e-7}\n"
      "  femur: {gear_ratio: 200}\n"
      "  tibia: {armature: 0.02}\n"
      "  joints:\n"
      "    L1_tibia: {gear_ratio: 300, rotor_inertia: 2.0e-7}\n"
      "    L2_coxa: {gear_ratio: 50}\n"
      "    L4_femur: {armature: 0.05}\n";
  const Scene s = paper_with(section);
  for (const JointAt& at : joints_of(s)) {
    const int type = at.place;
    double expected = type == 0 ? 100.0 * 100.0 * 1e-7 : type == 1 ? 200.0 * 200.0 * 1e-7 : 0.02;
    if (at.name == "L1_tibia") expected = 300.0 * 300.0 * 2e-7;  // 0.018
    if (at.name == "L2_coxa") expected = 50.0 * 50.0 * 1e-7;     // gear ratio of the joint entry
    if (at.name == "L4_femur") expected = 0.05;                  // joint side, whatever G
    INFO(at.name);
    CHECK(s.robot.drive.joints[at.k].armature_kgm2 == Approx(expected).epsilon(1e-15));
  }
  // The resolved YAML states the joint side: armature, no rotor_inertia, for every joint.
  const YAML::Node joints = YAML::Load(s.resolved_yaml)["actuators"]["joints"];
  for (const JointAt& at : joints_of(s)) {
    const YAML::Node j = joints[at.name];
    REQUIRE(j.IsMap());
    CHECK(j["armature"].as<double>() == s.robot.drive.joints[at.k].armature_kgm2);
    CHECK_FALSE(j["rotor_inertia"].IsDefined());
  }
  check_round_trip(s);
  // One entry gives one of the two.
  check_error(
      "actuators:\n  default: {gear_ratio: 100, torque_constant: 0.01, resistance: 2}\n"
      "  femur: {rotor_inertia: 1.0e-7, armature: 0.01}\n",
      "actuators.femur", "rotor_inertia and armature");
}

TEST_CASE("actuators: a required value no entry gives is named with its joint",
          "[config][actuators]") {
  check_error("actuators:\n  default: {gear_ratio: 100, torque_constant: 0.01}\n",
              "actuators.joints.L1_coxa.resistance", "missing");
  check_error("actuators:\n  coxa: {gear_ratio: 100, torque_constant: 0.01, resistance: 2}\n",
              "actuators.joints.L1_femur.gear_ratio", "missing");
  // Every tibia but L4's gets its resistance by name.
  std::string section =
      "actuators:\n  default: {gear_ratio: 100, torque_constant: 0.01}\n"
      "  coxa: {resistance: 2}\n  femur: {resistance: 2}\n  joints:\n";
  for (const char* leg : {"L1", "L2", "L3", "L5", "L6"})
    section += std::string("    ") + leg + "_tibia: {resistance: 3}\n";
  check_error(section, "actuators.joints.L4_tibia.resistance", "missing");
  // Given by a joint's model alone: the others still miss it.
  check_error("actuators:\n  joints: {L1_coxa: {model: dynamixel_mx64}}\n",
              "actuators.joints.L1_femur.gear_ratio", "missing");
}

TEST_CASE("actuators: unknown joints, unknown keys and bad values are one line naming the key",
          "[config][actuators]") {
  const std::string full = "  default: {gear_ratio: 100, torque_constant: 0.01, resistance: 2}\n";
  check_error("actuators:\n" + full + "  joints: {L7_femur: {gear_ratio: 10}}\n",
              "actuators.joints.L7_femur", "unknown joint");
  CHECK(config_error("actuators:\n" + full + "  joints: {L7_femur: {gear_ratio: 10}}\n")
            .find("L6_tibia") != std::string::npos);
  check_error("actuators:\n" + full + "  hip: {gear_ratio: 10}\n", "actuators.hip", "unknown key");
  check_error("actuators:\n" + full + "  femur: {gear: 10}\n", "actuators.femur.gear", "unknown");
  check_error("actuators:\n" + full + "  joints: {L1_coxa: {colour: red}}\n",
              "actuators.joints.L1_coxa.colour", "unknown");
  const std::string model_msg = config_error("actuators:\n  default: {model: dynamixel_mx65}\n");
  for (const ServoSpec& s : servo_table()) CHECK(model_msg.find(s.name) != std::string::npos);
  check_error("actuators:\n  default: {model: dynamixel_mx65}\n", "actuators.default.model",
              "dynamixel_mx64");
  struct Bad {
    const char* key;
    const char* value;
  };
  for (const Bad& b :
       {Bad{"gear_ratio", "0"}, Bad{"torque_constant", "-0.01"}, Bad{"resistance", ".inf"},
        Bad{"gear_efficiency", "0"}, Bad{"gear_efficiency", "1.5"}, Bad{"regeneration", "1.5"},
        Bad{"voltage", "-12"}, Bad{"peak_torque", "0"}, Bad{"thermal_window", "0"},
        Bad{"coulomb_friction", "-1"}, Bad{"rotor_inertia", "2"}, Bad{"armature", "abc"}})
    check_error("actuators:\n" + full + "  tibia: {" + b.key + ": " + b.value + "}\n",
                std::string("actuators.tibia.") + b.key, std::string("got ") + b.value);
  check_error("actuators: 3\n", "actuators", "expected a mapping");
  check_error("actuators:\n  default: 5\n", "actuators.default", "expected a mapping");
  check_error("actuators:\n" + full + "  joints: [1, 2]\n", "actuators.joints",
              "expected a mapping");
  // The copper loss needs actuators.
  const std::string msg = config_error("", {{"allocation.objective", "copper_loss"}});
  CHECK(msg.rfind(kName + ": allocation.objective: ", 0) == 0);
  CHECK(msg.find('\n') == std::string::npos);
}

TEST_CASE("actuators: the resolved YAML holds every joint, and nothing without the section",
          "[config][actuators]") {
  const Scene s = paper_with("actuators:\n  default: {model: dynamixel_mx106}\n");
  const YAML::Node r = YAML::Load(s.resolved_yaml);
  REQUIRE(r["actuators"]["joints"].IsMap());
  const std::vector<JointAt> all = joints_of(s);
  CHECK(r["actuators"]["joints"].size() == all.size());
  for (const JointAt& at : all) {
    const YAML::Node j = r["actuators"]["joints"][at.name];
    REQUIRE(j.IsMap());
    const ActuatorParams& a = s.robot.drive.joints[at.k];
    CHECK(j["model"].as<std::string>() == "dynamixel_mx106");
    CHECK(j["gear_ratio"].as<double>() == a.gear_ratio);
    CHECK(j["torque_constant"].as<double>() == a.torque_constant_NmpA);
    CHECK(j["resistance"].as<double>() == a.resistance_ohm);
    CHECK(j["armature"].as<double>() == a.armature_kgm2);
    CHECK(j["voltage"].as<double>() == a.voltage_V);
    CHECK(j["regeneration"].as<double>() == 0.0);
    CHECK_FALSE(j["thermal_window"].IsDefined());  // absent: +inf, the whole run
  }
  CHECK(r["allocation"]["objective"].as<std::string>() == "torque_squared");
  check_round_trip(s);
  // The paper scene as it is: neither key.
  const Scene plain = load_scene_from_string(paper_text(), kName);
  CHECK_FALSE(plain.robot.drive.present);
  const YAML::Node p = YAML::Load(plain.resolved_yaml);
  CHECK_FALSE(p["actuators"].IsDefined());
  CHECK_FALSE(p["allocation"]["objective"].IsDefined());
  CHECK(plain.resolved_yaml.find("actuators") == std::string::npos);
  CHECK(plain.resolved_yaml.find("objective") == std::string::npos);
}

namespace {

/// A fresh directory under the system's temporary directory, removed at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("hexdyn_actuators_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

/// robots/phantomx_mark4.urdf (<dynamics friction="0.5"/> on every joint) with
/// right_front_femur's <dynamics damping="0.07" friction="0.3"/>, written into `dir`.
std::string mark4_urdf_with_damping(const TempDir& dir) {
  std::string text = file_text(kSource + "/robots/phantomx_mark4.urdf");
  const auto joint = text.find("<joint name=\"right_front_femur\" type=\"revolute\">");
  REQUIRE(joint != std::string::npos);
  const std::string old = "<dynamics friction=\"0.5\" />";
  const auto at = text.find(old, joint);
  REQUIRE(at != std::string::npos);
  text.replace(at, old.size(), "<dynamics damping=\"0.07\" friction=\"0.3\" />");
  const std::string path = (dir.path / "robot.urdf").string();
  std::ofstream(path) << text;
  return path;
}

/// The PhantomX stairs scene on the URDF at `urdf` with `section` appended.
Scene mark4_with(const std::string& urdf, const std::string& section) {
  const std::string scene = file_text(kSource + "/configs/robots/phantomx_mark4_stairs.yaml");
  return load_scene_from_string(scene + "\n" + section, kName, {{"robot.urdf", urdf}});
}

}  // namespace

TEST_CASE("actuators: a URDF's <dynamics> give the friction below every entry",
          "[config][actuators]") {
  TempDir dir;
  const std::string urdf = mark4_urdf_with_damping(dir);
  const std::string required =
      "actuators:\n  default: {gear_ratio: 100, torque_constant: 0.01, resistance: 2}\n";
  const Scene a = mark4_with(urdf, required);
  REQUIRE(a.robot.urdf);
  int damped = -1;
  const std::vector<JointAt> all = joints_of(a);
  for (const JointAt& at : all)
    if (at.name == "right_front_femur") {
      damped = at.k;
      REQUIRE(at.place == 1);
    }
  REQUIRE(damped >= 0);
  const int joints = static_cast<int>(all.size());
  for (int k = 0; k < joints; ++k) {
    INFO("joint " << k);
    CHECK(a.robot.drive.joints[k].coulomb_friction_Nm == (k == damped ? 0.3 : 0.5));
    CHECK(a.robot.drive.joints[k].viscous_friction_Nmsprad == (k == damped ? 0.07 : 0.0));
  }
  check_round_trip(a);
  // The type's Coulomb friction over the URDF's, its damping kept (field by field); the
  // joint's own entry, by its URDF name, over both.
  const Scene b = mark4_with(urdf, required +
                                       "  femur: {coulomb_friction: 0.1}\n"
                                       "  joints: {right_front_femur: {viscous_friction: 0.3}}\n");
  for (const JointAt& at : all) {
    const int k = at.k;
    INFO("joint " << k);
    const bool femur = at.place == 1;
    CHECK(b.robot.drive.joints[k].coulomb_friction_Nm == (femur ? 0.1 : 0.5));
    CHECK(b.robot.drive.joints[k].viscous_friction_Nmsprad == (k == damped ? 0.3 : 0.0));
  }
  check_round_trip(b);
  // A model in the default entry gives friction too, over the URDF's.
  const ServoSpec& mx = servo("dynamixel_mx64");
  REQUIRE(!std::isnan(mx.coulomb_friction_Nm));
  REQUIRE(!std::isnan(mx.viscous_friction_Nmsprad));
  const Scene c = mark4_with(urdf, "actuators:\n  default: {model: dynamixel_mx64}\n");
  for (int k = 0; k < joints; ++k) {
    CHECK(c.robot.drive.joints[k].coulomb_friction_Nm == mx.coulomb_friction_Nm);
    CHECK(c.robot.drive.joints[k].viscous_friction_Nmsprad == mx.viscous_friction_Nmsprad);
  }
  // A URDF robot's joints are named by the URDF: the paper's names are unknown there.
  try {
    mark4_with(urdf, required + "  joints: {L1_coxa: {resistance: 3}}\n");
    FAIL("no ConfigError was thrown");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    CHECK(msg.rfind(kName + ": actuators.joints.L1_coxa: unknown joint", 0) == 0);
    CHECK(msg.find("right_front_femur") != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
  }
  // Without the section the URDF's friction is not read: no drive train at all.
  const Scene none = mark4_with(urdf, "");
  CHECK_FALSE(none.robot.drive.present);
  const YAML::Node r = YAML::Load(none.resolved_yaml);
  CHECK_FALSE(r["actuators"].IsDefined());
  CHECK_FALSE(r["allocation"]["objective"].IsDefined());
}

namespace {

/// "N: 'line of a' / 'line of b'" for the first line where two texts differ, or "none".
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int n = 1;; ++n) {
    const bool ga = static_cast<bool>(std::getline(sa, la)),
               gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "none";
    if (!ga || !gb || la != lb)
      return std::to_string(n) + ": '" + (ga ? la : "<end>") + "' / '" + (gb ? lb : "<end>") + "'";
  }
}

}  // namespace

TEST_CASE("actuators: the resolved YAML resolves to itself", "[config][actuators]") {
  // A resolved configuration run again pins nothing new (tests/provenance/rerun_resolved.py:
  // the rerun's /meta config_yaml equals the first run's; test_config.cpp checks the same
  // text for scenes without actuators): with actuators, also when the scene leaves
  // allocation.objective to its default and the first resolution adds it.
  const std::string mx64 = "actuators:\n  default: {model: dynamixel_mx64}\n";
  TempDir dir;
  const std::string urdf = mark4_urdf_with_damping(dir);
  struct Case {
    const char* label;
    Scene scene;
  };
  const Case cases[] = {
      {"objective given", paper_with(mx64, {{"allocation.objective", "copper_loss"}})},
      {"objective by default", paper_with(mx64)},
      {"URDF robot, objective by default", mark4_with(urdf, mx64)},
  };
  for (const Case& c : cases) {
    const Scene again = load_scene_from_string(c.scene.resolved_yaml, "resolved.yaml");
    INFO(c.label << ": first differing line "
                 << first_difference(c.scene.resolved_yaml, again.resolved_yaml));
    CHECK((again.resolved_yaml == c.scene.resolved_yaml));
  }
}

TEST_CASE("actuators: entries by place j1 … jm, for legs of any length", "[config][actuators]") {
  // Solo-12: four legs of three joints HAA, HFE, KFE, named by its URDF.
  const std::string solo = kSource + "/configs/robots/solo12_flat.yaml";
  const std::string base =
      "{default: {gear_ratio: 9, torque_constant: 0.025, resistance: 0.349}, j2: {gear_ratio: "
      "12}, joints: {FL_KFE: {gear_ratio: 7}}}";
  const Scene s = load_scene(solo, {{"actuators", base}});
  const std::vector<JointAt> all = joints_of(s);
  REQUIRE(all.size() == 12);
  for (const JointAt& at : all) {
    INFO(at.name);
    const double expected = at.name == "FL_KFE" ? 7.0 : at.place == 1 ? 12.0 : 9.0;
    CHECK(s.robot.drive.joints[at.k].gear_ratio == expected);
  }
  // j2 of a leg of three joints is its femur: the two entries are the same joints.
  const Scene femur =
      load_scene(solo, {{"actuators",
                         "{default: {gear_ratio: 9, torque_constant: 0.025, resistance: 0.349}, "
                         "femur: {gear_ratio: 12}, joints: {FL_KFE: {gear_ratio: 7}}}"}});
  for (const JointAt& at : all)
    CHECK(femur.robot.drive.joints[at.k].gear_ratio == s.robot.drive.joints[at.k].gear_ratio);
  const Scene again = load_scene_from_string(s.resolved_yaml, "resolved.yaml");
  for (const JointAt& at : all)
    check_same(again.robot.drive.joints[at.k], s.robot.drive.joints[at.k]);
  // Both forms of one place, or a place beyond the robot's legs: one line each.
  const auto error = [&](const std::string& value) {
    try {
      (void)load_scene(solo, {{"actuators", value}});
    } catch (const ConfigError& e) {
      const std::string msg = e.what();
      CHECK(msg.find('\n') == std::string::npos);
      return msg;
    }
    FAIL("no ConfigError was thrown for " << value);
    return std::string();
  };
  CHECK(error("{default: {gear_ratio: 9, torque_constant: 0.025, resistance: 0.349}, j1: "
              "{gear_ratio: 2}, coxa: {gear_ratio: 3}}")
            .find("actuators.j1: got both actuators.coxa and actuators.j1, expected one of them") !=
        std::string::npos);
  const std::string j4 =
      error("{default: {gear_ratio: 9, torque_constant: 0.025, resistance: 0.349}, j4: {}}");
  CHECK(j4.find("actuators.j4") != std::string::npos);
  CHECK(j4.find("j1, j2, j3") != std::string::npos);
  CHECK(j4.find("j5") == std::string::npos);
  // A required value no entry gives names the place among the entries that could.
  CHECK(error("{default: {torque_constant: 0.025, resistance: 0.349}}")
            .find("actuators.joints.FL_HAA.gear_ratio: missing, expected it from "
                  "actuators.default, actuators.coxa, actuators.j1, actuators.joints.FL_HAA or "
                  "their model") != std::string::npos);
}

TEST_CASE("actuators: three-phase, gear-stage and thermal keys, and their bad values",
          "[config][actuators]") {
  const std::string full = "  default: {gear_ratio: 9, torque_constant: 0.025, resistance: 0.2}\n";
  struct Bad {
    const char* key;
    const char* value;
    const char* what;
  };
  for (const Bad& b :
       {Bad{"winding", "ac", "three_phase_amplitude"}, Bad{"voltage_utilization", "0", "(0, 1]"},
        Bad{"voltage_utilization", "1.2", "(0, 1]"},
        Bad{"thermal_resistance_winding", "-1", "(0, 10000]"},
        Bad{"thermal_capacity_housing", "0", "(0, 1e+07]"},
        Bad{"ambient_temperature", "2000", "[-100, 1000]"},
        Bad{"winding_temperature_limit", "hot", "[-100, 1000]"}}) {
    const std::string msg =
        config_error("actuators:\n" + full + "  tibia: {" + b.key + ": " + b.value + "}\n");
    INFO(msg);
    CHECK(msg.rfind(kName + ": actuators.tibia." + b.key + ": got " + b.value, 0) == 0);
    CHECK(msg.find(b.what) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
  }
  check_error("actuators:\n" + full + "  femur: {gear_stages: []}\n", "actuators.femur.gear_stages",
              "a list of 1 to 8 stages");
  check_error("actuators:\n" + full + "  femur: {gear_stages: [{ratio: 0}]}\n",
              "actuators.femur.gear_stages[0].ratio", "got 0");
  check_error("actuators:\n" + full + "  femur: {gear_stages: [{ratio: 3}, {ratio: 3, mass: 1}]}\n",
              "actuators.femur.gear_stages[1].mass", "unknown key");
  check_error("actuators:\n" + full + "  femur: {gear_stages: [{inertia: 1.0e-6}]}\n",
              "actuators.femur.gear_stages[0].ratio", "missing");
  check_error("actuators:\n" + full + "  femur: {gear_ratio: 9, gear_stages: [{ratio: 9}]}\n",
              "actuators.femur", "gear_ratio and gear_stages");
  // Three of the thermal model's four values: the fourth is named, with the joint.
  check_error("actuators:\n" + full +
                  "  coxa: {thermal_resistance_winding: 2, thermal_capacity_winding: 8,"
                  " thermal_resistance_housing: 6}\n",
              "actuators.joints.L1_coxa.thermal_capacity_housing", "four values");
}

TEST_CASE("actuators: gear stages multiply their ratios and reflect their inertia",
          "[config][actuators]") {
  // Motor 3:1 then 4:1: G = 12; the rotor 2e-6 seen through 12, the first stage's output
  // 1e-5 through the second stage's 4, the last stage's output 3e-4 as it is.
  const Scene s = paper_with(
      "actuators:\n"
      "  default: {torque_constant: 0.025, resistance: 0.2, rotor_inertia: 2.0e-6,\n"
      "            gear_stages: [{ratio: 3, inertia: 1.0e-5}, {ratio: 4, inertia: 3.0e-4}]}\n"
      "  joints: {L1_coxa: {gear_ratio: 5}}\n");
  for (const JointAt& at : joints_of(s)) {
    const ActuatorParams& a = s.robot.drive.joints[at.k];
    INFO(at.name);
    if (at.name == "L1_coxa") {  // its own ratio: no stages, the rotor through 5
      CHECK(a.gear_ratio == 5.0);
      CHECK(a.armature_kgm2 == Approx(25.0 * 2e-6).epsilon(1e-15));
      continue;
    }
    CHECK(a.gear_ratio == 12.0);
    CHECK(a.armature_kgm2 == Approx(144.0 * 2e-6 + 16.0 * 1e-5 + 3e-4).epsilon(1e-15));
  }
  check_round_trip(s);
}

TEST_CASE("actuators: a brushless module of the table is three-phase with its thermal model",
          "[config][actuators]") {
  const Scene s = paper_with(
      "actuators:\n"
      "  default: {model: odri_actuator}\n"
      "  tibia: {model: mini_cheetah_knee, ambient_temperature: 35}\n"
      "  joints: {L1_coxa: {winding: three_phase_power, voltage_utilization: 0.57}}\n");
  const ServoSpec& odri = servo("odri_actuator");
  const ServoSpec& knee = servo("mini_cheetah_knee");
  for (const JointAt& at : joints_of(s)) {
    const ActuatorParams& a = s.robot.drive.joints[at.k];
    const ServoSpec& m = at.place == 2 ? knee : odri;
    INFO(at.name);
    CHECK(a.model == m.name);
    CHECK(a.gear_ratio == m.gear_ratio);
    CHECK(a.armature_kgm2 == m.armature_kgm2);
    CHECK(a.thermal_capacity_winding_JpK == m.thermal_capacity_winding_JpK);
    CHECK(a.winding_temperature_limit_degC == m.winding_temperature_limit_degC);
    CHECK(thermal_params(a).present);
    CHECK(a.ambient_temperature_degC == (at.place == 2 ? 35.0 : 25.0));
    CHECK(a.winding ==
          (at.name == "L1_coxa" ? Winding::kThreePhasePower : Winding::kThreePhaseAmplitude));
    CHECK(a.voltage_utilization == (at.name == "L1_coxa" ? 0.57 : 0.5));
  }
  // The resolved YAML states the winding and the thermal values, and reads back the same.
  const YAML::Node j = YAML::Load(s.resolved_yaml)["actuators"]["joints"]["L2_tibia"];
  CHECK(j["winding"].as<std::string>() == "three_phase_amplitude");
  CHECK(j["thermal_resistance_housing"].as<double>() == knee.thermal_resistance_housing_KpW);
  CHECK(j["ambient_temperature"].as<double>() == 35.0);
  check_round_trip(s);
  // A DC scene's record has none of the new keys.
  const Scene dc = paper_with("actuators:\n  default: {model: dynamixel_mx64}\n");
  const YAML::Node d = YAML::Load(dc.resolved_yaml)["actuators"]["joints"]["L1_coxa"];
  for (const char* key : {"winding", "voltage_utilization", "ambient_temperature",
                          "thermal_resistance_winding", "winding_temperature_limit"})
    CHECK_FALSE(d[key].IsDefined());
}

}  // namespace hexdyn
