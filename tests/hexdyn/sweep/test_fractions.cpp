// p/q fractions (config/yaml_load.hpp parse_fraction) are one parser for a number key in a
// scene file, a `--set` value and a sweep axis value: 2/3 is the double 2.0 / 3.0 in all
// three, and a bad fraction (1/0, a/b, or 3/2 for the duty factor) is refused with the same
// line after the source's name ("FILE: ", "scenario 000000: ").
#include <catch2/catch.hpp>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/spec.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;

namespace {

const std::string kBase = kConfigs + "/sweeps/stairs_base.yaml";

/// gait.duty_factor: `value` three ways: a scene file that inherits the stair base, `--set`
/// on the base, and the first scenario of a sweep over the base.
Scene from_scene_file(const TempDir& dir, const std::string& value) {
  return load_scene(
      dir.write("scene.yaml", "inherit: " + kBase + "\ngait:\n  duty_factor: " + value + "\n"));
}
Scene from_set(const std::string& value) {
  return load_scene(kBase, {parse_override("gait.duty_factor=" + value)});
}
Scene from_sweep(const TempDir& dir, const std::string& value) {
  const SweepSpec spec = load_sweep(
      sweep_file(dir, "axes:\n  - key: gait.duty_factor\n    values: [" + value + "]\n"));
  return ScenarioFactory(spec).scene(0);
}

/// The ConfigError's line from the key on ("gait.duty_factor: got ..."), or "(no error)".
template <class F>
std::string refusal(F&& read) {
  try {
    (void)read();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    CHECK(m.find('\n') == std::string::npos);
    const auto at = m.find("gait.duty_factor: ");
    return at == std::string::npos ? m : m.substr(at);
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("sweep: gait.duty_factor 2/3 is 2.0/3.0 in a scene file, --set and a sweep",
          "[sweep][config][fractions]") {
  TempDir dir;
  CHECK(from_scene_file(dir, "2/3").gait.duty_factor == 2.0 / 3.0);
  CHECK(from_set("2/3").gait.duty_factor == 2.0 / 3.0);
  CHECK(from_sweep(dir, "2/3").gait.duty_factor == 2.0 / 3.0);
  // Spaces around the slash, as in --set and sweeps.
  CHECK(from_scene_file(dir, "3 / 4").gait.duty_factor == 0.75);
  // The resolved configuration writes the number, which reads back to the same double.
  const Scene s = from_scene_file(dir, "2/3");
  CHECK(load_scene_from_string(s.resolved_yaml, "resolved").gait.duty_factor == 2.0 / 3.0);
}

TEST_CASE("sweep: a bad fraction is refused with the same line in a scene file, --set and a sweep",
          "[sweep][config][fractions]") {
  TempDir dir;
  const std::string range = ", expected a number in [0.5, 1)";
  for (const auto& [value, got] : {std::pair<std::string, std::string>{"1/0", "1/0"},
                                   {"3/2", "1.5"},
                                   {"a/b", "a/b"},
                                   {"-1/2", "-0.5"}}) {
    INFO("gait.duty_factor: " << value);
    const std::string expected = "gait.duty_factor: got " + got + range;
    CHECK(refusal([&] { return from_scene_file(dir, value); }) == expected);
    CHECK(refusal([&] { return from_set(value); }) == expected);
    CHECK(refusal([&] { return from_sweep(dir, value); }) == expected);
  }
}
