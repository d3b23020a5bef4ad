// Configuration loading (config.hpp): the paper file gives the paper's numbers, every
// kind of bad input is refused with a one-line ConfigError naming the key, and the
// resolved YAML loads back to the same scene with the defaults spelt out.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/run_size.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

const std::string kPaperConfig = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";
const std::string kName = "case.yaml";

const std::string& paper_text() {
  static const std::string text = read_text_file(kPaperConfig);
  return text;
}

/// The text without every line that starts with `prefix`; requires at least one.
std::string without_lines(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line, out;
  int removed = 0;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) {
      ++removed;
      continue;
    }
    out += line + "\n";
  }
  REQUIRE(removed > 0);
  return out;
}

/// The text with the first line starting with `prefix` replaced; returns its 1-based number.
std::string replace_line(const std::string& text, const std::string& prefix,
                         const std::string& with, int* line_no) {
  std::istringstream in(text);
  std::string line, out;
  int n = 0;
  *line_no = 0;
  while (std::getline(in, line)) {
    ++n;
    if (*line_no == 0 && line.rfind(prefix, 0) == 0) {
      *line_no = n;
      line = with;
    }
    out += line + "\n";
  }
  REQUIRE(*line_no > 0);
  return out;
}

/// The message of the ConfigError that loading throws; fails when nothing is thrown.
std::string config_error(const std::string& text, const std::vector<Override>& overrides = {}) {
  try {
    load_scene_from_string(text, kName, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError was thrown");
  return "";
}

/// The message names the source and the key, and is one line.
void check_names(const std::string& msg, const std::string& key) {
  INFO("message: " << msg);
  CHECK(msg.rfind(kName + ": ", 0) == 0);
  CHECK(msg.find(key) != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
}

void check_override_refused(const std::string& key, const std::string& value) {
  INFO("--set " << key << "=" << value);
  check_names(config_error(paper_text(), {{key, value}}), key);
}

TEST_CASE("config: the paper file loads with the paper's numbers", "[config]") {
  const Scene s = load_scene(kPaperConfig);
  CHECK(s.name == "paper");
  CHECK(s.source_path == kPaperConfig);
  // Table 1 masses.
  CHECK(s.robot.trunk.mass_kg == 0.65);
  CHECK(s.robot.payload.mass_kg == 4.244);
  CHECK(s.robot.link[0].mass_kg == 0.150);
  CHECK(s.robot.link[1].mass_kg == 0.041);
  CHECK(s.robot.link[2].mass_kg == 0.110);
  CHECK(s.robot.leg_joints == 3);
  CHECK(s.robot.link_length_m == LegJointArray<double>{0.085, 0.120, 0.100});
  CHECK(s.robot.joint_offset_m == LegJointArray<double>{0.008, 0.018, 0.020});
  CHECK(s.robot.trunk.inertia_kgm2 == Vec3(1.66e-2, 2.52e-3, 1.69e-2));
  // Whole robot: 6.7 kg (65.7 N).
  const RobotModel model = build_robot_model(s.robot);
  CHECK(std::abs(model.total_mass_kg - 6.7) <= 1e-12);
  CHECK(std::abs(model.total_mass_kg * kGravity - 65.727) <= 1e-9);
  // Terrain, gait, motion, contact, allocation, output.
  CHECK(s.terrain.type == TerrainType::kStairs);
  CHECK(s.terrain.riser_height_m == 0.05);
  CHECK(s.terrain.tread_depth_m == 0.25);
  CHECK(s.gait.duty_factor == 0.5);
  CHECK(s.gait.stroke_m == 0.125);
  CHECK(s.gait.swing_clearance_m == 0.002);
  CHECK(s.motion.cycle_durations_s == std::vector<double>{3.0, 2.6, 3.0});
  CHECK(s.motion.cycles == 3);
  CHECK(std::abs(s.motion.ramp_duration_s - 0.8) <= 1e-12);
  CHECK(s.motion.initial_position_m == Vec3(0.0, 0.412, 0.235));
  CHECK(s.contact.exponent == 2.2);
  CHECK(s.contact.full_damping_depth_m == 1e-5);
  CHECK(s.contact.friction_coefficient == 0.3);
  CHECK(s.allocation.torque_limit_Nm == 6.0);
  CHECK(s.output.sample_step_s == 0.05);
  // The hip layout is the one the test robot factory assumes.
  const RobotParams expected = test::paper_robot_params();
  REQUIRE(s.robot.legs == expected.legs);
  for (int leg = 0; leg < s.robot.legs; ++leg) {
    INFO("leg " << leg);
    CHECK(s.robot.hip_position_m[leg] == expected.hip_position_m[leg]);
    CHECK(std::abs(s.robot.hip_yaw_rad[leg] - expected.hip_yaw_rad[leg]) <= 1e-15);
  }
  CHECK(s.robot.joint_min_rad == expected.joint_min_rad);
  CHECK(s.robot.joint_max_rad == expected.joint_max_rad);
}

TEST_CASE("config: a missing required key is named", "[config]") {
  check_names(config_error(without_lines(paper_text(), "  duty_factor:")), "gait.duty_factor");
  check_names(config_error(without_lines(paper_text(), "    mass: 0.150")), "robot.coxa.mass");
  check_names(config_error(without_lines(paper_text(), "  stiffness:")), "contact.stiffness");
  const std::string msg = config_error(without_lines(paper_text(), "  riser_height:"));
  check_names(msg, "terrain.riser_height");
  CHECK(msg.find("missing") != std::string::npos);
  // Removed from the tree rather than the text.
  YAML::Node root = YAML::Load(paper_text());
  REQUIRE(root["gait"].remove("stroke"));
  YAML::Emitter out;
  out << root;
  check_names(config_error(out.c_str()), "gait.stroke");
  // A key set to null counts as missing.
  check_override_refused("output.sample_step", "~");
}

// docs/user/configuration.md: a key set to null counts as absent, so an inheriting scene removes
// a key its own choices do not allow (flat ground's height on stairs), and a misspelt key set
// to null is nothing.
TEST_CASE("config: a null key is absent, even where it is not allowed", "[config]") {
  const std::string flat = std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/solo12_flat.yaml";
  const std::vector<Override> stairs = {
      {"terrain.type", "stairs"},       {"terrain.riser_height", "0.05"},
      {"terrain.tread_depth", "0.25"},  {"terrain.steps", "4"},
      {"terrain.first_riser_y", "0.3"}, {"terrain.ground_height", "0.0"}};
  auto with_null = stairs;
  with_null.push_back({"terrain.height", "~"});
  CHECK(load_scene(flat, with_null).terrain.type == TerrainType::kStairs);
  with_null.push_back({"gait.stroek", "~"});
  CHECK(load_scene(flat, with_null).terrain.riser_height_m == 0.05);
  try {
    (void)load_scene(flat, stairs);
    FAIL("flat ground's terrain.height was accepted on stairs");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("terrain.height: unknown key") != std::string::npos);
  }
}

TEST_CASE("config: a mistyped value is named with the value", "[config]") {
  const std::string msg = config_error(paper_text(), {{"contact.stiffness", "abc"}});
  check_names(msg, "contact.stiffness");
  CHECK(msg.find("abc") != std::string::npos);
  check_override_refused("terrain.steps", "2.5");
  check_override_refused("gait.duty_factor", "[0.5]");
  check_override_refused("robot.trunk.inertia", "[a, b, c]");
  check_override_refused("robot.trunk.inertia", "0.01");
  check_override_refused("output.grid", "coarse");
  check_override_refused("robot", "7");
}

TEST_CASE("config: non-finite numbers are refused", "[config]") {
  for (const char* v : {".nan", ".inf", "-.inf", ".NaN"}) {
    check_override_refused("contact.stiffness", v);
    check_override_refused("robot.trunk.mass", v);
    check_override_refused("motion.initial_position", std::string("[0.0, ") + v + ", 0.2]");
    check_override_refused("robot.payload.inertia", std::string("[") + v + ", 1e-3, 1e-3]");
  }
  const std::string msg = config_error(paper_text(), {{"contact.stiffness", ".nan"}});
  CHECK(msg.find("finite") != std::string::npos);
}

TEST_CASE("config: unknown keys are refused at every level", "[config]") {
  check_override_refused("bogus", "1");
  check_override_refused("gait.dutyfactor", "0.5");
  check_override_refused("robot.coxa.colour", "red");
  check_override_refused("robot.hips.w", "0.1");
  const std::string msg = config_error(paper_text() + "extra_section:\n  a: 1\n");
  check_names(msg, "extra_section");
  // The message lists what is allowed there.
  const std::string nested = config_error(paper_text(), {{"gait.dutyfactor", "0.5"}});
  CHECK(nested.find("allowed") != std::string::npos);
  CHECK(nested.find("duty_factor") != std::string::npos);
  CHECK(nested.find("stroke") != std::string::npos);
}

TEST_CASE("config: out-of-range values are refused", "[config]") {
  check_override_refused("gait.duty_factor", "0.4");
  check_override_refused("gait.duty_factor", "1.0");
  check_override_refused("gait.duty_factor", "1.5");
  check_override_refused("robot.femur.mass", "-0.041");
  check_override_refused("robot.femur.mass", "0");
  check_override_refused("robot.tibia.length", "-0.1");
  check_override_refused("contact.exponent", "7");
  check_override_refused("terrain.steps", "0");
  check_override_refused("robot.coxa.limits", "[1.0, -1.0]");
  check_override_refused("robot.hips.y", "[0.0, 0.2, -0.2]");
  // Principal moments of a physical body obey the triangle inequality.
  const std::string msg =
      config_error(paper_text(), {{"robot.trunk.inertia", "[1e-3, 1e-3, 5e-3]"}});
  check_names(msg, "robot.trunk.inertia");
  check_override_refused("robot.tibia.inertia", "[1e-5, 1e-4, 1e-5]");
  // The boundary case of the triangle inequality (a flat plate) is allowed.
  CHECK_NOTHROW(
      load_scene_from_string(paper_text(), kName, {{"robot.trunk.inertia", "[0.25, 0.5, 0.75]"}}));
  CHECK_NOTHROW(load_scene_from_string(paper_text(), kName, {{"gait.duty_factor", "0.5"}}));
}

TEST_CASE("config: gait.phases names every leg once, each phase from 0 up to 1", "[config]") {
  const std::string five = "L2: 0.5, L3: 0.5, L4: 0, L5: 0, L6: 0.5";
  const std::string six = "{L1: 0, " + five + "}";
  const Scene s = load_scene_from_string(paper_text(), kName, {{"gait.phases", six}});
  CHECK(s.gait.liftoff_phases == std::vector<double>{0.0, 0.5, 0.5, 0.0, 0.0, 0.5});
  CHECK(load_scene_from_string(paper_text(), kName, {}).gait.liftoff_phases.empty());
  // The resolved configuration records them, and reads back to the same phases.
  CHECK(load_scene_from_string(s.resolved_yaml, kName).gait.liftoff_phases ==
        s.gait.liftoff_phases);
  // p/q as for every number; the largest phase below 1.
  const Scene q = load_scene_from_string(
      paper_text(), kName,
      {{"gait.phases", "{L1: 1/3, L2: 0.99999999999999989, L3: 0.5, L4: 0, L5: 0, L6: 0.5}"}});
  CHECK(q.gait.liftoff_phases[0] == 1.0 / 3.0);
  CHECK(q.gait.liftoff_phases[1] == std::nextafter(1.0, 0.0));
  const auto refused = [&](const std::string& value, const std::string& key,
                           const std::string& part) {
    const std::string msg = config_error(paper_text(), {{"gait.phases", value}});
    check_names(msg, key);
    CHECK(msg.find(part) != std::string::npos);
  };
  refused("0.5", "gait.phases: got 0.5", "expected a map {L1: φ, …, L6: φ} naming every leg once");
  refused("[0, 0.5, 0.5, 0, 0, 0.5]", "gait.phases: got [0, 0.5", "naming every leg once");
  refused("{L1: 0, " + five + ", L7: 0}", "gait.phases: got the key L7",
          "expected leg names (L1, L2, L3, L4, L5, L6)");
  refused("{l1: 0, " + five + "}", "gait.phases: got the key l1", "expected leg names");
  refused("{" + five + "}", "gait.phases: got {L2: 0.5", ", L1 missing");
  refused("{}", "gait.phases: got {}", "every leg once (L1, L2, L3, L4, L5, L6), L1 missing");
  refused("{L1: 1, " + five + "}", "gait.phases.L1: got 1", "expected a number in [0, 1)");
  refused("{L1: -0.1, " + five + "}", "gait.phases.L1: got -0.1", "expected a number in [0, 1)");
  refused("{L1: .nan, " + five + "}", "gait.phases.L1", "finite");
  refused("{L1: [0], " + five + "}", "gait.phases.L1: got [0]", "expected a number in [0, 1)");
  // A leg named twice in a file: a duplicate key, with both lines.
  int line_no = 0;
  const std::string twice = replace_line(
      paper_text(), "  lower_fraction:", "  lower_fraction: 0.2\n  phases:\n    L1: 0\n    L1: 0.5",
      &line_no);
  const std::string msg = config_error(twice);
  check_names(msg, "gait.phases.L1: duplicate key");
  CHECK(msg.find("line " + std::to_string(line_no + 2)) != std::string::npos);
  CHECK(msg.find("line " + std::to_string(line_no + 3)) != std::string::npos);
}

TEST_CASE("config: lists of the wrong length are refused", "[config]") {
  check_override_refused("robot.trunk.inertia", "[1e-2, 1e-2]");
  check_override_refused("robot.trunk.inertia", "[1e-2, 1e-2, 1e-2, 1e-2]");
  check_override_refused("motion.initial_position", "[0.0, 0.4]");
  check_override_refused("robot.hips.y", "[0.2, 0.0, -0.2, -0.4]");
  check_override_refused("robot.coxa.limits", "[-1.0]");
  check_override_refused("motion.cycle_durations", "[3.0, 2.6]");
}

TEST_CASE("config: both motion forms at once are refused", "[config]") {
  for (const char* key : {"motion.peak_speed", "motion.cycles", "motion.ramp_duration"}) {
    const std::string msg = config_error(paper_text(), {{key, "1"}});
    INFO(msg);
    check_names(msg, "motion");
    CHECK(msg.find("cycle_durations") != std::string::npos);
  }
  // Either form alone is fine.
  const std::string by_speed = without_lines(paper_text(), "  cycle_durations:");
  const Scene s = load_scene_from_string(
      by_speed, kName,
      {{"motion.cycles", "4"}, {"motion.peak_speed", "0.1"}, {"motion.ramp_duration", "0.8"}});
  CHECK(s.motion.cycles == 4);
  CHECK(s.motion.peak_speed_mps == 0.1);
  CHECK(s.motion.cycle_durations_s.empty());
}

TEST_CASE("config: --set overrides", "[config]") {
  // An override of an unknown key is refused like an unknown key in the file.
  check_names(config_error(paper_text(), {{"gait.bogus", "1"}}), "gait.bogus");
  // An override through a value that is not a mapping.
  const std::string msg = config_error(paper_text(), {{"gait.duty_factor.x", "1"}});
  CHECK(msg.find("gait.duty_factor") != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
  // Malformed override text.
  CHECK_THROWS_AS(parse_override("gait.duty_factor"), ConfigError);
  CHECK_THROWS_AS(parse_override("=0.5"), ConfigError);
  const Override ov = parse_override("motion.cycle_durations=[3, 2.6, 3]");
  CHECK(ov.key_path == "motion.cycle_durations");
  CHECK(ov.value == "[3, 2.6, 3]");
  // A good override takes effect.
  const Scene s = load_scene_from_string(paper_text(), kName, {{"gait.duty_factor", "0.75"}});
  CHECK(s.gait.duty_factor == 0.75);
}

TEST_CASE("config: YAML syntax errors give file, line and column", "[config]") {
  int line_no = 0;
  const std::string bad = replace_line(paper_text(), "  stroke:", "  stroke: 0.125: 0.2", &line_no);
  const std::string msg = config_error(bad);
  INFO(msg << " (edited line " << line_no << ")");
  std::smatch m;
  REQUIRE(std::regex_search(msg, m, std::regex("^case\\.yaml:([0-9]+):([0-9]+): ")));
  const int line = std::stoi(m[1]);
  CHECK(line >= line_no);
  CHECK(line <= line_no + 1);
  CHECK(std::stoi(m[2]) >= 1);
  CHECK(msg.find('\n') == std::string::npos);

  // The same through a file: the message names the file's path.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("hexdyn_config_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "broken.yaml").string();
  { std::ofstream(path) << bad; }
  try {
    load_scene(path);
    FAIL("no ConfigError");
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.rfind(path + ":" + std::to_string(line) + ":", 0) == 0);
  }
  std::filesystem::remove_all(dir);
  // A document that is not a mapping.
  const std::string list_msg = config_error("- 1\n- 2\n");
  CHECK(list_msg.rfind(kName + ":", 0) == 0);
}

TEST_CASE("config: a missing file is named", "[config]") {
  const std::string path = "/nonexistent-hexdyn-dir/missing.yaml";
  CHECK_THROWS_AS(load_scene(path), ConfigError);
  CHECK_THROWS_WITH(load_scene(path), Catch::Contains(path));
  CHECK_THROWS_AS(read_text_file(path), ConfigError);
}

bool same_body(const BodyParams& a, const BodyParams& b) {
  return a.mass_kg == b.mass_kg && a.inertia_kgm2 == b.inertia_kgm2 && a.com_m == b.com_m;
}

/// Every typed field of two scenes is equal (the name aside).
void check_same_scene(const Scene& a, const Scene& b) {
  const RobotParams &ra = a.robot, &rb = b.robot;
  CHECK(same_body(ra.trunk, rb.trunk));
  CHECK(same_body(ra.payload, rb.payload));
  CHECK(ra.legs == rb.legs);
  CHECK(ra.leg_joints == rb.leg_joints);
  for (int j = 0; j < ra.leg_joints; ++j) CHECK(same_body(ra.link[j], rb.link[j]));
  CHECK(ra.link_length_m == rb.link_length_m);
  CHECK(ra.joint_offset_m == rb.joint_offset_m);
  CHECK(ra.hip_position_m == rb.hip_position_m);
  CHECK(ra.hip_yaw_rad == rb.hip_yaw_rad);
  CHECK(ra.joint_min_rad == rb.joint_min_rad);
  CHECK(ra.joint_max_rad == rb.joint_max_rad);
  CHECK(ra.ik_min_margin_m == rb.ik_min_margin_m);
  const TerrainParams &ta = a.terrain, &tb = b.terrain;
  CHECK(ta.type == tb.type);
  CHECK(ta.ground_height_m == tb.ground_height_m);
  CHECK(ta.slope_rad == tb.slope_rad);
  CHECK(ta.slope_origin_y_m == tb.slope_origin_y_m);
  CHECK(ta.riser_height_m == tb.riser_height_m);
  CHECK(ta.tread_depth_m == tb.tread_depth_m);
  CHECK(ta.steps == tb.steps);
  CHECK(ta.first_riser_y_m == tb.first_riser_y_m);
  const GaitParams &ga = a.gait, &gb = b.gait;
  CHECK(ga.duty_factor == gb.duty_factor);
  CHECK(ga.stroke_m == gb.stroke_m);
  CHECK(ga.foot_lateral_m == gb.foot_lateral_m);
  CHECK(ga.foothold_margin_m == gb.foothold_margin_m);
  CHECK(ga.swing_clearance_m == gb.swing_clearance_m);
  CHECK(ga.touchdown_speed_mps == gb.touchdown_speed_mps);
  CHECK(ga.lift_fraction == gb.lift_fraction);
  CHECK(ga.lower_fraction == gb.lower_fraction);
  const MotionParams &ma = a.motion, &mb = b.motion;
  CHECK(ma.cycle_durations_s == mb.cycle_durations_s);
  CHECK(ma.peak_speed_mps == mb.peak_speed_mps);
  CHECK(ma.ramp_duration_s == mb.ramp_duration_s);
  CHECK(ma.initial_position_m == mb.initial_position_m);
  CHECK(ma.cycles == mb.cycles);
  const ContactParams &ca = a.contact, &cb = b.contact;
  CHECK(ca.stiffness == cb.stiffness);
  CHECK(ca.exponent == cb.exponent);
  CHECK(ca.damping_max_Nspm == cb.damping_max_Nspm);
  CHECK(ca.full_damping_depth_m == cb.full_damping_depth_m);
  CHECK(ca.friction_coefficient == cb.friction_coefficient);
  const AllocationParams &aa = a.allocation, &ab = b.allocation;
  CHECK(aa.solver == ab.solver);
  CHECK(aa.friction == ab.friction);
  CHECK(aa.torque_limit_Nm == ab.torque_limit_Nm);
  CHECK(aa.min_normal_force_N == ab.min_normal_force_N);
  CHECK(aa.tolerance == ab.tolerance);
  CHECK(aa.slack_penalty == ab.slack_penalty);
  const OutputParams &oa = a.output, &ob = b.output;
  CHECK(oa.sample_step_s == ob.sample_step_s);
  CHECK(oa.grid == ob.grid);
  CHECK(oa.impact_samples == ob.impact_samples);
  CHECK(oa.event_step_s == ob.event_step_s);
}

TEST_CASE("config: the resolved YAML loads back to the same scene", "[config]") {
  const std::vector<std::vector<Override>> variants = {
      {},
      {{"gait.duty_factor", "0.6666666666666666"}, {"robot.payload.com", "[0.01, -0.02, 0.03]"}},
      {{"allocation.friction", "cone"},
       {"output.grid", "uniform"},
       {"robot.hips.yaw", "[0.1, 0.0, -0.1]"}},
  };
  for (const auto& ov : variants) {
    const Scene a = load_scene_from_string(paper_text(), kName, ov);
    const Scene b = load_scene_from_string(a.resolved_yaml, "resolved.yaml");
    check_same_scene(a, b);
    CHECK(b.name == a.name);
    CHECK(b.resolved_yaml == a.resolved_yaml);
  }
  // The speed form of the motion and a flat terrain.
  const Scene a = load_scene_from_string(
      without_lines(paper_text(), "  cycle_durations:"), kName,
      {{"motion.cycles", "4"}, {"motion.peak_speed", "0.09"}, {"motion.ramp_duration", "0.7"}});
  const Scene b = load_scene_from_string(a.resolved_yaml, "resolved.yaml");
  check_same_scene(a, b);
  CHECK(b.resolved_yaml == a.resolved_yaml);
}

TEST_CASE("config: the resolved YAML spells out defaults of absent optional keys", "[config]") {
  std::string text = paper_text();
  for (const char* prefix :
       {"name:", "  foothold_margin:", "  lift_fraction:", "  lower_fraction:", "  friction:",
        "  grid:", "  impact_samples:", "  event_step:", "  ik_min_margin:",
        "    com: [0.0, 0.0, 0.0]", "    com: [0.060", "    yaw:", "    z:", "  ground_height:",
        "  min_normal_force:", "  tolerance:", "  slack_penalty:"})
    text = without_lines(text, prefix);
  const Scene s = load_scene_from_string(text, kName);
  const YAML::Node r = YAML::Load(s.resolved_yaml);
  auto num = [&](const YAML::Node& n) {
    REQUIRE(n.IsDefined());
    return n.as<double>();
  };
  CHECK(r["name"].as<std::string>() == "scene");
  CHECK(num(r["gait"]["foothold_margin"]) == 0.02);
  CHECK(num(r["gait"]["lift_fraction"]) == 0.3);
  CHECK(num(r["gait"]["lower_fraction"]) == 0.2);
  CHECK(r["allocation"]["friction"].as<std::string>() == "pyramid4");
  CHECK(num(r["allocation"]["min_normal_force"]) == 0.0);
  CHECK(num(r["allocation"]["tolerance"]) == 1e-9);
  CHECK(num(r["allocation"]["slack_penalty"]) == 1e6);
  CHECK(r["output"]["grid"].as<std::string>() == "adaptive");
  CHECK(num(r["output"]["impact_samples"]) == 16);
  CHECK(num(r["output"]["event_step"]) == 1e-2);
  CHECK(num(r["robot"]["ik_min_margin"]) == 1e-4);
  CHECK(num(r["robot"]["hips"]["z"]) == 0.0);
  CHECK(num(r["terrain"]["ground_height"]) == 0.0);
  for (const char* body : {"trunk", "payload"})
    CHECK(r["robot"][body]["com"].as<std::vector<double>>() == std::vector<double>{0.0, 0.0, 0.0});
  CHECK(r["robot"]["hips"]["yaw"].as<std::vector<double>>() == std::vector<double>{0.0, 0.0, 0.0});
  // A link COM defaults to mid-length.
  CHECK(r["robot"]["femur"]["com"].as<std::vector<double>>() ==
        std::vector<double>{0.5 * 0.120, 0.0, 0.0});
  // The paper file states exactly these defaults, so the scenes agree.
  check_same_scene(s, load_scene(kPaperConfig));
  // And the resolved text loads back to the same scene.
  check_same_scene(s, load_scene_from_string(s.resolved_yaml, "resolved.yaml"));
}

}  // namespace
}  // namespace hexdyn

namespace hexdyn {
namespace {

// docs/user/configuration.md#automatic-choices-in-the-resolved-configuration: the automatic
// posture written into the resolved configuration as the values used, the requests kept
// under auto:, and that configuration a valid scene with a relative posture at exactly those
// values; an auto: that is not a map is refused.
TEST_CASE("config: automatic choices in the resolved configuration", "[config]") {
  const std::string base = std::string(HEXDYN_SOURCE_DIR) + "/configs/sweeps/stairs_base.yaml";
  const Scene s = load_scene(base);
  REQUIRE(s.motion.posture.mode == PostureMode::kAuto);
  const YAML::Node first = YAML::Load(s.resolved_yaml);
  CHECK(first["allocation"]["solver"].Scalar() == "active-set");
  CHECK(first["auto"]["allocation"]["solver"].Scalar() == "auto");
  const double h = 0.1 + 1.0 / 3.0 * 1e-3, w = 0.2 - 1.0 / 7.0 * 1e-3;  // 17 digits needed
  const std::string resolved = with_chosen_posture(s.resolved_yaml, h, w);
  const YAML::Node r = YAML::Load(resolved);
  CHECK(r["auto"]["motion"]["posture"]["height"].Scalar() == "auto");
  CHECK(r["auto"]["motion"]["posture"]["foot_lateral"].size() == 2);
  CHECK(r["auto"]["gait"]["foot_lateral"].as<double>() == s.gait.foot_lateral_m);
  CHECK_FALSE(r["motion"]["posture"]["height_range"].IsDefined());
  const Scene again = load_scene_from_string(resolved, "resolved.yaml");
  CHECK(again.motion.posture.mode == PostureMode::kRelative);
  CHECK(again.motion.posture.height_m == h);  // bit for bit
  CHECK(again.gait.foot_lateral_m == w);
  CHECK(again.motion.posture.start_y_m == s.motion.posture.start_y_m);
  // The record is carried unchanged into the next resolved configuration.
  CHECK(YAML::Dump(YAML::Load(again.resolved_yaml)["auto"]) == YAML::Dump(r["auto"]));
  CHECK_THROWS_WITH(load_scene_from_string(paper_text() + "auto: 3\n", "a.yaml"),
                    Catch::Contains("a.yaml: auto: got 3"));
}

/// A number written to 17 digits.
std::string digits17(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// The number after `marker` in `msg` ("... at least 9.61e-06 s" → 9.61e-06).
double number_after(const std::string& msg, const std::string& marker) {
  const auto at = msg.find(marker);
  REQUIRE(at != std::string::npos);
  return std::stod(msg.substr(at + marker.size()));
}

// Every size that grows with the input is bounded before anything is planned
// (core/run_size.hpp, config/run_limits.hpp): each refusal names its key and the limit, and a
// value just inside is accepted. The boundaries are computed here from the scene: the paper
// scene's motion lasts 3 + 2.6 + 3 = 8.6 s, its grid spans 1 s more (the longest touchdown
// transient), and a uniform grid has floor(span / step) + 2 points at most.
TEST_CASE("config: cycles, duration and output samples are bounded before planning",
          "[config][sizes]") {
  const std::string by_speed = without_lines(paper_text(), "  cycle_durations:");
  const std::vector<Override> speed_form = {
      {"motion.peak_speed", "0.1"}, {"motion.ramp_duration", "0.8"}, {"motion.cycles", "3"}};
  auto with = [&](std::vector<Override> extra) {
    std::vector<Override> all = speed_form;
    all.insert(all.end(), extra.begin(), extra.end());
    return all;
  };
  const std::vector<Override> sparse = {{"output.grid", "uniform"}, {"output.sample_step", "100"}};
  // Cycles: at most kMaxCycles, whatever the grid.
  REQUIRE(kMaxCycles == 10000);
  auto sparse_with = [&](std::vector<Override> extra) {
    extra.insert(extra.end(), sparse.begin(), sparse.end());
    return with(extra);
  };
  CHECK(load_scene_from_string(by_speed, kName, sparse_with({{"motion.cycles", "10000"}}))
            .motion.cycles == 10000);
  std::string msg = config_error(by_speed, sparse_with({{"motion.cycles", "10001"}}));
  check_names(msg, "motion.cycles: got 10001");
  CHECK(msg.find("[1, 10000]") != std::string::npos);
  // motion.cycle_durations: at most kMaxCycles entries.
  auto durations = [&](int cruise) {
    std::string list = "[3";
    for (int i = 0; i < cruise; ++i) list += ", 2.6";
    std::vector<Override> ov = sparse;
    ov.push_back({"motion.cycle_durations", list + ", 3]"});
    return ov;
  };
  CHECK(load_scene_from_string(paper_text(), kName, durations(9998)).motion.cycles == 10000);
  msg = config_error(paper_text(), durations(9999));
  check_names(msg, "motion.cycle_durations: got [3, 2.6, 2.6");
  CHECK(msg.find("expected a list of 3 to 10000 numbers") != std::string::npos);
  CHECK(msg.size() < 500);  // the 10,001 values are not all quoted
  CHECK(msg.find("characters)") != std::string::npos);
  // Travel: the cycles its distance needs, at most kMaxCycles.
  const double stride = 0.125 / 0.5 / std::cos(std::atan2(0.05, 0.25));
  auto travel = [&](double distance) {
    std::vector<Override> ov = sparse;
    ov.push_back({"motion.peak_speed", "0.1"});
    ov.push_back({"motion.ramp_duration", "0.8"});
    ov.push_back({"motion.travel.distance", digits17(distance)});
    return ov;
  };
  CHECK(load_scene_from_string(by_speed, kName, travel(9999.5 * stride)).motion.cycles == 10000);
  msg = config_error(by_speed, travel(10000.5 * stride));
  check_names(msg, "motion.travel: got");
  CHECK(msg.find("10001 cycles of gait.stroke, expected at most 10000 cycles") !=
        std::string::npos);
  // Duration: at most kMaxRunDuration_s = 1e5 s; 10,000 cycles at speed v last
  // 10,000 stride / v + 0.8 s.
  REQUIRE(kMaxRunDuration_s == 1e5);
  const double v_limit = 10000.0 * stride / (1e5 - 0.8);
  auto slow = [&](double v) {
    return sparse_with({{"motion.cycles", "10000"}, {"motion.peak_speed", digits17(v)}});
  };
  CHECK_NOTHROW(load_scene_from_string(by_speed, kName, slow(v_limit * 1.0001)));
  msg = config_error(by_speed, slow(v_limit * 0.9999));
  check_names(msg, "motion.peak_speed: got");
  CHECK(msg.find("expected a motion of at most 1e+05 s") != std::string::npos);
  CHECK(number_after(msg, "a peak speed of at least ") >= v_limit);
  msg = config_error(by_speed, with({{"motion.peak_speed", "1e-300"}}));
  check_names(msg, "motion.peak_speed: got 1e-300 m/s, a motion of 7.6");
  // The paper run's 8.6 s: 9.6 s of uniform grid below 1,000,000 points; a step of 4e-9 s
  // (which overflowed an int) is refused in one line, as is any smaller one.
  REQUIRE(kMaxRunSamples == 1000000);
  auto uniform = [&](double step) {
    return std::vector<Override>{{"output.grid", "uniform"},
                                 {"output.sample_step", digits17(step)},
                                 {"output.event_step", digits17(step)}};
  };
  CHECK_NOTHROW(load_scene_from_string(paper_text(), kName, uniform(9.6 / 999997.5)));
  msg = config_error(paper_text(), uniform(9.6 / 999999.0));
  check_names(msg, "output.sample_step: got");
  CHECK(msg.find("expected at most 1000000 samples") != std::string::npos);
  CHECK(msg.find("--allow-large does not lift it") != std::string::npos);
  const double least = number_after(msg, "a sample step of at least ");
  CHECK_NOTHROW(load_scene_from_string(paper_text(), kName, uniform(least)));
  for (const char* step : {"4e-9", "1e-7", "1e-8", "1e-300"})
    check_names(config_error(paper_text(), uniform(std::stod(step))), "output.sample_step: got");
  // The adaptive grid's transients: output.impact_samples, with the most that fit.
  msg = config_error(paper_text(), {{"output.impact_samples", "100000"}});
  check_names(msg, "output.impact_samples: got 100000");
  const double most = number_after(msg, ": at most ");
  CHECK_NOTHROW(
      load_scene_from_string(paper_text(), kName, {{"output.impact_samples", digits17(most)}}));
  check_names(config_error(paper_text(), {{"output.impact_samples", digits17(most + 1)}}),
              "output.impact_samples");
  // Graded points of a tiny event step over many events: output.event_step.
  msg = config_error(by_speed, with({{"motion.cycles", "100"}, {"output.event_step", "1e-300"}}));
  check_names(msg, "output.event_step: got 1e-300");
  CHECK_NOTHROW(
      load_scene_from_string(by_speed, kName, with({{"motion.cycles", "100"}})).motion.cycles);
  // Many cycles on the adaptive grid: no output key alone can help, the cycles are named.
  msg = config_error(by_speed, with({{"motion.cycles", "10000"}}));
  check_names(msg, "motion.cycles: got 10000 cycles");
  const double cycles = number_after(msg, ": at most ");
  CHECK_NOTHROW(
      load_scene_from_string(by_speed, kName, with({{"motion.cycles", digits17(cycles)}})));
  // One more cycle is refused (naming whichever key can bring it back within the limit).
  check_names(config_error(by_speed, with({{"motion.cycles", digits17(cycles + 1)}})),
              "expected at most 1000000 samples");
}

}  // namespace
}  // namespace hexdyn
