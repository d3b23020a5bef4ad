// The cases axis of a sweep file (src/hexdyn/sweep/spec.*): paired keys set together, URDF
// paths from the sweep file, the scenes against `--set` overrides of the base, and one-line
// errors for malformed or invalid cases.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/model/urdf_robot.hpp"
#include "hexdyn/sweep/checkpoint.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/spec.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

namespace {

const std::string kCasesAxes =
    "set:\n  output.grid: uniform\n  motion.cycles: 1\n"
    "axes:\n"
    "  - cases:\n"
    "      - {label: tripod, gait.duty_factor: 1/2, motion.peak_speed: 0.1}\n"
    "      - {motion.peak_speed: 0.05, label: wave, gait.duty_factor: 5/6}\n"
    "  - key: terrain.riser_height\n    values: [0.03, 0.05]\n";

}  // namespace

TEST_CASE("sweep cases: an axis of labels whose cases set their keys together", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kCasesAxes));
  REQUIRE(spec.axes.size() == 2);
  CHECK(spec.scenario_count() == 4);
  const SweepAxis& cases = spec.axes[0];
  CHECK(cases.is_cases());
  CHECK(cases.key == "case");
  CHECK_FALSE(cases.numeric);
  CHECK(cases.values == std::vector<std::string>{"tripod", "wave"});
  CHECK(cases.labels == cases.values);
  // The keys in the order of the first case; each case's values in that order.
  CHECK(cases.case_keys == std::vector<std::string>{"gait.duty_factor", "motion.peak_speed"});
  REQUIRE(cases.case_values.size() == 2);
  CHECK(YAML::Load(cases.case_values[1][0]).as<double>() == 5.0 / 6.0);
  CHECK(cases.case_values[1][1] == "0.05");

  // Each scenario equals the base scene with its case's keys and the riser as --set.
  const ScenarioFactory factory(spec);
  for (std::size_t index = 0; index < spec.scenario_count(); ++index) {
    const auto p = grid_point(spec, index);
    std::vector<Override> overrides = spec.fixed;
    char five_sixths[32];  // p/q is the number p divided by q
    std::snprintf(five_sixths, sizeof five_sixths, "%.17g", 5.0 / 6.0);
    overrides.push_back({"gait.duty_factor", p[0] == 0 ? std::string("0.5") : five_sixths});
    overrides.push_back({"motion.peak_speed", p[0] == 0 ? "0.1" : "0.05"});
    overrides.push_back({"terrain.riser_height", p[1] == 0 ? "0.03" : "0.05"});
    const Scene expected = load_scene(kConfigs + "/sweeps/stairs_base.yaml", overrides);
    INFO("scenario " << index);
    const Scene from_input = load_scene_from_string(scenario_input(spec, index).yaml, "s");
    CHECK(from_input.resolved_yaml == expected.resolved_yaml);
    CHECK(factory.scene(index).resolved_yaml == expected.resolved_yaml);
  }
}

TEST_CASE("sweep cases: a case's URDF is relative to the sweep file and an input", "[sweep]") {
  TempDir dir;
  fs::create_directories(dir.path / "sweeps");
  fs::create_directories(dir.path / "robots");
  fs::copy_file(fs::path(HEXDYN_SOURCE_DIR) / "robots" / "kraby.urdf",
                dir.path / "robots" / "k.urdf");
  const std::string path =
      dir.write("sweeps/s.yaml",
                "base: " + kConfigs +
                    "/robots/phantomx_mark4_stairs.yaml\nset: {motion.cycles: 1}\n"
                    "axes:\n  - name: robot\n    cases:\n"
                    "      - {label: mark4, robot.urdf: " +
                    std::string(HEXDYN_SOURCE_DIR) +
                    "/robots/phantomx_mark4.urdf, robot.forward_axis: +x, gait.stroke: 0.0625}\n"
                    "      - {label: kraby, robot.urdf: ../robots/k.urdf, robot.forward_axis: +y, "
                    "gait.stroke: 0.025}\n");
  const SweepSpec spec = load_sweep(path);
  const SweepAxis& robot = spec.axes[0];
  CHECK(robot.key == "robot");
  REQUIRE(robot.case_keys[0] == "robot.urdf");
  CHECK(fs::equivalent(robot.case_values[1][0], dir.path / "robots" / "k.urdf"));
  CHECK(fs::path(robot.case_values[1][0]).is_absolute());
  bool listed = false;
  for (const InputFile& f : spec.inputs)
    listed = listed || (f.role == "URDF" && fs::equivalent(f.path, dir.path / "robots" / "k.urdf"));
  CHECK(listed);
  // The checkpoint's identity covers its content: an edited URDF is another sweep.
  const SweepIdentity before = sweep_identity(spec, false);
  std::ofstream(dir.path / "robots" / "k.urdf", std::ios::app) << "<!-- edited -->\n";
  const std::string why = sweep_identity(load_sweep(path), false).difference(before);
  INFO(why);
  CHECK(why.find("k.urdf changed") != std::string::npos);
  const ScenarioFactory factory(spec);
  const Scene kraby = factory.scene(1);
  REQUIRE(kraby.robot.urdf);
  CHECK(fs::equivalent(kraby.robot.urdf->source_path, dir.path / "robots" / "k.urdf"));
  CHECK(kraby.robot.urdf->forward_axis == "+y");
}

TEST_CASE("sweep cases: a bad cases axis is one ConfigError line naming it", "[sweep]") {
  TempDir dir;
  struct Case {
    std::string what, axes, names;
  };
  const std::string riser = "  - key: terrain.riser_height\n    values: [0.03]\n";
  const std::vector<Case> cases = {
      {"not a list", "  - cases: {label: a}\n",
       "axes[0].cases: got {label: a}, expected a non-empty list of maps"},
      {"empty", "  - cases: []\n", "axes[0].cases: got [], expected a non-empty list"},
      {"unknown key beside cases", "  - cases: [{label: a, gait.duty_factor: 0.5}]\n    key: x\n",
       "axes[0].key: unknown key, allowed here: cases, name"},
      {"a case not a map", "  - cases: [0.5]\n", "axes[0].cases[0]: got 0.5, expected a map"},
      {"no label", "  - cases: [{gait.duty_factor: 0.5}]\n", "axes[0].cases[0].label: missing"},
      {"empty label", "  - cases: [{label: '', gait.duty_factor: 0.5}]\n",
       "axes[0].cases[0].label: got , expected a non-empty single-line name"},
      {"labels twice",
       "  - cases: [{label: a, gait.duty_factor: 0.5}, {label: a, gait.duty_factor: 0.75}]\n",
       "axes[0].cases[1].label: got a, expected a label no other case has (cases[0] has it too)"},
      {"only a label", "  - cases: [{label: a}]\n",
       "axes[0].cases[0]: got only a label, expected at least one key"},
      {"other keys",
       "  - cases: [{label: a, gait.duty_factor: 0.5}, {label: b, motion.peak_speed: 0.1}]\n",
       "axes[0].cases[1]: got keys motion.peak_speed, expected the keys of cases[0] "
       "(gait.duty_factor): every case sets the same keys"},
      {"a nested map", "  - cases: [{label: a, gait: {duty_factor: 0.5}}]\n",
       "axes[0].cases[0].gait: got {duty_factor: 0.5}, expected a single value or a list"},
      {"key also on another axis", "  - cases: [{label: a, terrain.riser_height: 0.05}]\n" + riser,
       "axes[1].key: got terrain.riser_height, expected each key on one axis only"},
      {"key also fixed", "  - cases: [{label: a, output.grid: uniform}]\n",
       "axes[0].cases: got key output.grid, expected a key not also fixed by set:"},
      {"two unnamed cases axes",
       "  - cases: [{label: a, gait.duty_factor: 0.5}]\n"
       "  - cases: [{label: b, motion.peak_speed: 0.1}]\n",
       "axes[1].name: got case, expected a name no other axis has"},
      {"reserved name", "  - cases: [{label: a, gait.duty_factor: 0.5}]\n    name: scenario\n",
       "axes[0].name: got scenario, expected a word"},
      {"the name of a dataset of /axes/<i>, where the axis's coordinate goes",
       "  - cases: [{label: a, gait.duty_factor: 0.5}]\n    name: case_values\n",
       "axes[0].name: got case_values, expected a word"},
      {"unknown key in a case",
       "  - cases: [{label: a, gait.duty_factor: 0.5}, {label: b, gait.duty_factr: 0.5}]\n",
       "expected the keys of cases[0]"},
      {"unknown key in every case", "  - cases: [{label: a, gait.duty_factr: 0.5}]\n",
       "axes[0].cases[0] (a: gait.duty_factr=0.5): gait.duty_factr: unknown key, allowed here:"},
      {"a value out of range",
       "  - cases: [{label: ok, gait.duty_factor: 0.5}, {label: slow, gait.duty_factor: 0.2}]\n" +
           riser,
       "axes[0].cases[1] (slow: gait.duty_factor=0.2): gait.duty_factor: got 0.2, expected a "
       "number in [0.5, 1)"},
  };
  for (const Case& c : cases) {
    const std::string path = sweep_file(dir, "set:\n  output.grid: uniform\naxes:\n" + c.axes);
    const std::string msg = message_of(path);
    INFO(c.what << ": " << msg);
    CHECK(msg.find(c.names) != std::string::npos);
    CHECK(msg.rfind(path, 0) == 0);  // starts with the sweep file's path
    CHECK(msg.find('\n') == std::string::npos);
  }
}
