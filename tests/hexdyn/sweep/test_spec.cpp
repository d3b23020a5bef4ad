// Sweep files (src/hexdyn/sweep/spec.*): validation with one-line errors, the row-major
// grid against nested loops, scenario scenes against `--set` overrides of the base.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/spec.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

TEST_CASE("sweep: a sweep file gives axes, values and the row-major grid", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  CHECK(spec.name == "s");
  REQUIRE(spec.axes.size() == 3);
  CHECK(spec.scenario_count() == 4 * 3 * 2);

  const SweepAxis& riser = spec.axes[0];
  CHECK(riser.key == "terrain.riser_height");
  CHECK(riser.numeric);
  CHECK(riser.values == std::vector<std::string>{"0.03", "0.04", "0.05", "0.06"});
  CHECK(riser.numbers == std::vector<double>{0.03, 0.04, 0.05, 0.06});

  const SweepAxis& duty = spec.axes[1];
  CHECK(duty.labels == std::vector<std::string>{"1/2", "2/3", "0.75"});
  REQUIRE(duty.numbers.size() == 3);
  CHECK(duty.numbers[0] == 0.5);
  CHECK(duty.numbers[1] == 2.0 / 3.0);  // exactly the double nearest to 2/3
  CHECK(duty.numbers[2] == 0.75);

  const SweepAxis& friction = spec.axes[2];
  CHECK_FALSE(friction.numeric);
  CHECK(friction.numbers.empty());

  // Row-major, last axis fastest: the order of three nested loops.
  std::size_t index = 0;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 3; ++b)
      for (std::size_t c = 0; c < 2; ++c, ++index)
        CHECK(grid_point(spec, index) == std::vector<std::size_t>{a, b, c});
  CHECK(scenario_id(spec, 7) == "000007");
  CHECK(scenario_id(spec, 23) == "000023");
  CHECK(spec.fixed.size() == 2);
}

TEST_CASE("sweep: a scenario's scene is the base with --set overrides of its values", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  for (std::size_t index : {std::size_t{0}, std::size_t{5}, std::size_t{17}, std::size_t{23}}) {
    const ScenarioInput in = scenario_input(spec, index);
    CHECK(in.index == index);
    CHECK(in.id == scenario_id(spec, index));
    const auto p = grid_point(spec, index);
    std::vector<Override> overrides = spec.fixed;
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
      overrides.push_back({spec.axes[a].key, spec.axes[a].values[p[a]]});
    const Scene expected = load_scene(kConfigs + "/sweeps/stairs_base.yaml", overrides);
    const Scene got = load_scene_from_string(in.yaml, "scenario " + in.id);
    INFO("scenario " << in.id);
    CHECK(got.resolved_yaml == expected.resolved_yaml);
    const YAML::Node tree = YAML::Load(in.yaml);
    CHECK(at(tree, "allocation.friction").Scalar() == spec.axes[2].values[p[2]]);
    CHECK(at(tree, "terrain.riser_height").as<double>() == spec.axes[0].numbers[p[0]]);
  }
}

TEST_CASE("sweep: the stairs study and the smoke sweep are valid", "[sweep]") {
  const SweepSpec stairs = load_sweep(kConfigs + "/sweeps/stairs.yaml");
  CHECK(stairs.scenario_count() == 512);
  CHECK(stairs.axes[0].numbers ==
        std::vector<double>{0.0, 0.02, 0.04, 0.06, 0.08, 0.10, 0.12, 0.14});
  CHECK(stairs.axes[1].numbers == std::vector<double>{0.20, 0.25, 0.30, 0.35});
  CHECK(stairs.axes[2].numbers == std::vector<double>{0.05, 0.1, 0.15, 0.2});
  CHECK(stairs.axes[3].numbers == std::vector<double>{0.5, 2.0 / 3.0, 0.75, 5.0 / 6.0});
  // The base scene's motion is given by speed: the paper's cycle durations are removed.
  const YAML::Node base = YAML::Load(stairs.base_config_yaml);
  CHECK_FALSE(base["motion"]["cycle_durations"].IsDefined());
  CHECK(base["motion"]["peak_speed"].as<double>() == 0.1);
  const SweepSpec smoke = load_sweep(kConfigs + "/sweeps/smoke.yaml");
  CHECK(smoke.scenario_count() <= 8);
}

TEST_CASE("sweep: a bad sweep file is one ConfigError line naming file, key and value", "[sweep]") {
  TempDir dir;
  struct Case {
    std::string what, text, names;
  };
  const std::string base = "base: " + kConfigs + "/sweeps/stairs_base.yaml\n";
  const std::string axis = "axes:\n  - key: gait.duty_factor\n    values: [0.5, 0.75]\n";
  const std::vector<Case> cases = {
      {"YAML syntax", base + "axes: [\n", "s.yaml:"},
      {"unknown top-level key", base + axis + "axis: []\n",
       "axis: unknown key, allowed here: axes, base, name, set"},
      {"missing base", axis, "base: missing"},
      {"base not a file", "base: no-such.yaml\n" + axis,
       "base: got no-such.yaml, expected the path of a scene file"},
      {"missing axes", base, "axes: missing"},
      {"empty axes", base + "axes: []\n", "axes: got [], expected a non-empty list"},
      {"axis key unknown", base + "axes:\n  - key: gait.duty\n    values: [0.5]\n",
       "axes[0].key: got gait.duty, expected a key of the base scene"},
      {"axis key is a group", base + "axes:\n  - key: gait\n    values: [0.5]\n",
       "axes[0].key: got gait, expected a key holding a single value (it holds a group of keys)"},
      {"axis key holds a list", base + "axes:\n  - key: robot.hips.y\n    values: [0.5]\n",
       "axes[0].key: got robot.hips.y, expected a key holding a single value (it holds "
       "a list)"},
      {"axis key twice", base + axis + "  - key: gait.duty_factor\n    values: [0.6]\n",
       "axes[1].key: got gait.duty_factor, expected each key on one axis only"},
      {"axis key also fixed", base + "set:\n  gait.duty_factor: 0.5\n" + axis,
       "axes[0].key: got gait.duty_factor, expected a key not also fixed by set:"},
      {"unknown axis key", base + "axes:\n  - key: gait.duty_factor\n    vals: [0.5]\n",
       "axes[0].vals: unknown key, allowed here: key, range, values"},
      {"values and range",
       base + "axes:\n  - key: gait.duty_factor\n    values: [0.5]\n    range: {from: 0.5, to: "
              "0.6, count: 2}\n",
       "axes[0]: got both values and range, expected exactly one of them"},
      {"empty values", base + "axes:\n  - key: gait.duty_factor\n    values: []\n",
       "axes[0].values: got [], expected a non-empty list"},
      {"a list as a value", base + "axes:\n  - key: gait.duty_factor\n    values: [[0.5]]\n",
       "axes[0].values[0]: got [0.5], expected a single value"},
      {"duplicate values", base + "axes:\n  - key: gait.duty_factor\n    values: [0.5, 1/2]\n",
       "axes[0].values: got 1/2 twice (values 0 and 1), expected distinct values"},
      {"range count",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: 0.5, to: 0.6, count: 1}\n",
       "axes[0].range.count: got 1, expected an integer in [2, 100000]"},
      {"range without count",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: 0.5, to: 0.6}\n",
       "axes[0].range.count: missing, expected an integer in [2, 100000]"},
      {"range without from",
       base + "axes:\n  - key: gait.duty_factor\n    range: {to: 0.6, count: 3}\n",
       "axes[0].range.from: missing, expected a finite number"},
      {"range bound",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: .nan, to: 0.6, count: 3}\n",
       "axes[0].range.from: got .nan, expected a finite number"},
      {"range empty",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: 0.6, to: 0.6, count: 3}\n",
       "axes[0].range: got from = to = 0.6, expected from != to"},
      {"set makes the base invalid", base + "set:\n  output.grid: fine\n" + axis,
       "(base " + kConfigs +
           "/sweeps/stairs_base.yaml): output.grid: got fine, expected one of uniform, adaptive"},
      {"set of an unknown key", base + "set:\n  output.gird: uniform\n" + axis,
       "output.gird: unknown key"},
      {"set with a nested map", base + "set:\n  output: {grid: uniform}\n" + axis,
       "set.output: got {grid: uniform}, expected a value or a list"},
      {"too many scenarios",
       base +
           "axes:\n  - key: terrain.riser_height\n    range: {from: 0.01, to: 0.1, count: 100000}\n"
           "  - key: gait.duty_factor\n    range: {from: 0.5, to: 0.9, count: 100}\n",
       "axes: got more than 1000000 scenarios"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("s.yaml", c.text);
    const std::string msg = message_of(path);
    INFO(c.what << ": " << msg);
    CHECK(msg.find(c.names) != std::string::npos);
    CHECK(msg.rfind(path, 0) == 0);  // starts with the sweep file's path
    CHECK(msg.find('\n') == std::string::npos);
  }
}

// `hexdyn validate` of a sweep (check_sweep_scenarios: the scenario factory's trees, no YAML
// per scenario, values already refused on the base counted without being built again)
// against a second computation: each scenario's YAML text built and validated on its own
// (scenario_input, check_scenario). Out-of-range values (a speed above 10 m/s, a riser above
// 1 m), combinations of valid values (a ramp longer than the cruise at a high speed), and a
// value refused on the base scene alone that another axis's value makes valid.
TEST_CASE("sweep: validating every scenario from the factory agrees with one by one",
          "[sweep][sizes]") {
  TempDir dir;
  const SweepSpec spec =
      load_sweep(sweep_file(dir,
                            "axes:\n  - key: terrain.riser_height\n    values: [0.05, 2.0, 0.08]\n"
                            "  - key: motion.peak_speed\n    values: [0.05, 0.5, 50, 2]\n"
                            "  - key: motion.ramp_duration\n    values: [1.0, 10.0]\n"));
  // A ramp of 10 s is longer than the base scene's cruise (3 strides at 0.1 m/s, 7.6 s): not
  // valid on the base alone, valid at 0.05 m/s (15.3 s of cruise).
  REQUIRE(!spec.axes[2].errors[1].empty());
  REQUIRE(spec.scenario_count() == 24);
  CHECK_FALSE(check_scenario(scenario_input(spec, 1)));  // riser 0.05, 0.05 m/s, ramp 10 s
  std::size_t out_of_range = 0;
  std::string first;
  for (std::size_t i = 0; i < spec.scenario_count(); ++i)
    if (const auto row = check_scenario(scenario_input(spec, i)))
      if (out_of_range++ == 0) first = row->message;
  const SweepScenarioCheck check = check_sweep_scenarios(spec);
  CHECK(check.scenarios == 24);
  CHECK(out_of_range > 6);  // values and combinations both fail somewhere
  CHECK(out_of_range < 24);
  CHECK(check.out_of_range == out_of_range);
  CHECK(check.first == first);
  // A sweep whose scenarios are all valid.
  const SweepSpec smoke = load_sweep(kConfigs + "/sweeps/smoke.yaml");
  const SweepScenarioCheck none = check_sweep_scenarios(smoke);
  CHECK(none.out_of_range == 0);
  CHECK(none.first.empty());
}
