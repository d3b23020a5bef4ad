// A URDF robot's stance on the command line (model/stance.hpp): a leg whose default pose is out
// of reach is a warning on stderr from `hexdyn validate` and `hexdyn run`, `-v` prints every
// leg's pose and how it was obtained, the result's /meta config_yaml records it, and
// robot.nominal_pose for that leg removes the warning.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <regex>
#include <string>
#include <vector>

#include "hexdyn/cli/cli_harness.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/schema.hpp"

namespace hexdyn {
namespace {

using namespace cli_test;

/// The PhantomX (robots/phantomx_mark4.urdf) with its L3 tibia limited to [1.1, 2.18] rad: the
/// default pose's 1.057 rad is out, and the robot still walks on flat ground.
void write_robot(const Scratch& s) {
  std::string urdf = read_file(kSourceDir + "/robots/phantomx_mark4.urdf");
  const auto at = urdf.find("<joint name=\"left_middle_tibia\"");
  REQUIRE(at != std::string::npos);
  const auto from = urdf.find("<limit", at), to = urdf.find("/>", from);
  urdf.replace(from, to - from,
               std::regex_replace(urdf.substr(from, to - from), std::regex("lower=\"[^\"]*\""),
                                  "lower=\"1.1\""));
  write_file(s.work / "robot.urdf", urdf);
  write_file(s.work / "scene.yaml",
             "robot: {urdf: robot.urdf}\n"
             "terrain: {type: flat}\n"
             "gait: {duty_factor: 0.5, stroke: 0.0625, swing_clearance: 0.01,\n"
             "       touchdown_speed: 0.05}\n"
             "motion: {peak_speed: 0.05, cycles: 2, ramp_duration: 1,\n"
             "         posture: {height: auto, start_y: 0}}\n"
             "contact: {model: compliant, stiffness: 3.98e11, exponent: 2.2,\n"
             "          damping_max: 1.0e4, full_damping_depth: 1.0e-5,\n"
             "          friction_coefficient: 0.6}\n"
             "allocation: {friction: pyramid4}\n"
             "output: {sample_step: 0.5, grid: uniform}\n");
}

const std::string kFallback =
    "L3: fallback: mid-range joint angles (joint left_middle_tibia outside its limits), q [";
const std::string kWarning =
    "hexdyn: warning: L3: the nominal pose is out of reach, stance "
    "fallback: mid-range joint angles (joint left_middle_tibia outside "
    "its limits), radius ";

/// /meta config_yaml's auto.robot.nominal_pose of a result file.
YAML::Node stance_record(const fs::path& file) {
  const H5Reader in(file.string());
  const std::string yaml = in.string_attribute(schema::kMetaGroup, schema::kAttrConfigYaml);
  return YAML::Load(yaml)["auto"]["robot"]["nominal_pose"];
}

TEST_CASE("cli: a stance fallback is a warning, -v and /meta say how each leg stands",
          "[cli][stance]") {
  Scratch s;
  write_robot(s);
  const Outcome v = run_cli(s, {"validate", "scene.yaml", "-v"});
  INFO(v.err);
  REQUIRE(v.status == 0);
  CHECK(v.out.find("hexdyn: stance of each leg (robot.nominal_pose):\nL1: nominal pose, q [") !=
        std::string::npos);
  CHECK(v.out.find(kFallback) != std::string::npos);
  CHECK(v.out.find(" m: the mean over L1, L2, L4, L5, L6, the legs at their pose") !=
        std::string::npos);
  // One warning line, on stderr, with or without -v.
  CHECK(v.err.rfind(kWarning, 0) == 0);
  CHECK(v.err.find('\n') == v.err.size() - 1);
  const Outcome quiet = run_cli(s, {"validate", "scene.yaml"});
  CHECK(quiet.err == v.err);
  CHECK(quiet.out.find("stance") == std::string::npos);

  const Outcome r = run_cli(s, {"run", "scene.yaml", "-o", "out.h5", "-v"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find(kFallback) != std::string::npos);
  CHECK(r.err.find("\n" + kWarning) != std::string::npos);
  const YAML::Node rec = stance_record(s.work / "out.h5");
  REQUIRE(rec.IsMap());
  CHECK(rec["L1"]["source"].as<std::string>() == "nominal pose");
  CHECK(rec["L3"]["source"].as<std::string>() ==
        "fallback: mid-range joint angles (joint left_middle_tibia outside its limits)");
  // The radius the warning gives is the one recorded (printed to 6 digits).
  const auto at = r.err.find(kWarning) + kWarning.size();
  CHECK(std::stod(r.err.substr(at)) == Approx(rec["L3"]["radius"].as<double>()).epsilon(1e-5));

  // The fix: a pose for L3 inside its limits.
  const Outcome fixed = run_cli(
      s, {"run", "scene.yaml", "-o", "fixed.h5", "--set", "robot.nominal_pose={L3: [0, 0, 1.5]}"});
  INFO(fixed.err);
  REQUIRE(fixed.status == 0);
  CHECK(fixed.err.find("warning") == std::string::npos);
  const YAML::Node fixed_rec = stance_record(s.work / "fixed.h5");
  CHECK(fixed_rec["L3"]["source"].as<std::string>() == "robot.nominal_pose");
  CHECK(fixed_rec["L3"]["pose"][2].as<double>() == 1.5);
}

}  // namespace
}  // namespace hexdyn
