// motion.travel (config/config.cpp read_travel): the cycles follow from a distance or a number of
// treads, the stride shrinks so that the trunk travels exactly that distance at any duty
// factor, the resolved scene loads back to the same motion, and conflicts are one line.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

const std::string kStairs = std::string(HEXDYN_SOURCE_DIR) + "/configs/sweeps/stairs_base.yaml";

/// The stairs base scene with its cycles removed, plus `overrides`.
Scene stairs_with(std::vector<Override> overrides) {
  overrides.insert(overrides.begin(), {"motion.cycles", "null"});
  return load_scene(kStairs, overrides);
}

/// Trunk travel along the slope: cycles × stride, the stride s0/β across the treads.
double travel_of(const Scene& s) {
  const double slope = std::atan2(s.terrain.riser_height_m, s.terrain.tread_depth_m);
  return s.motion.cycles * (s.gait.stroke_m / s.gait.duty_factor) / std::cos(slope);
}

std::string error_of(const std::vector<Override>& overrides) {
  try {
    load_scene(kStairs, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError was thrown");
  return "";
}

}  // namespace

TEST_CASE("travel: every duty factor covers the distance, in the fewest cycles", "[config]") {
  const double stroke = 0.125;  // stairs_base.yaml's gait.stroke (the paper's s0)
  for (const char* duty : {"0.5", "0.6", "0.75", "0.8333333333333333", "0.9"}) {
    for (const double d : {0.3, 0.7, 1.0}) {
      const Scene s = stairs_with({{"gait.duty_factor", duty},
                                   {"motion.travel.distance", std::to_string(d)},
                                   {"terrain.riser_height", "0.08"}});
      INFO("duty " << duty << ", distance " << d);
      CHECK(std::abs(travel_of(s) - d) < 1e-12);
      CHECK(s.gait.stroke_m <= stroke);
      // Fewest: one cycle less at the given stroke would not cover d.
      const double slope = std::atan2(0.08, 0.25);
      const double stride = stroke / std::stod(duty) / std::cos(slope);
      CHECK((s.motion.cycles - 1) * stride < d);
      CHECK(s.motion.cycles * stride >= d - 1e-12);
    }
  }
}

TEST_CASE("travel: treads are treads across and risers up", "[config]") {
  const Scene s = stairs_with({{"motion.travel.treads", "3"},
                               {"terrain.tread_depth", "0.3"},
                               {"terrain.riser_height", "0.1"},
                               {"gait.duty_factor", "0.75"}});
  CHECK(std::abs(travel_of(s) - 3.0 * std::hypot(0.3, 0.1)) < 1e-12);
  // Strides that cover the treads exactly keep the stroke as given: the paper's three
  // treads at β = 1/2 are its three cycles of s0 = 0.125 m.
  const Scene paper = stairs_with({{"motion.travel.treads", "3"}});
  CHECK(paper.motion.cycles == 3);
  CHECK(paper.gait.stroke_m == 0.125);
}

TEST_CASE("travel: the resolved scene loads back to the same motion", "[config]") {
  const Scene s = stairs_with({{"motion.travel.distance", "0.7"}, {"gait.duty_factor", "0.75"}});
  REQUIRE(s.gait.stroke_m < 0.125);  // adapted
  const Scene again = load_scene_from_string(s.resolved_yaml, "resolved.yaml");
  CHECK(again.gait.stroke_m == s.gait.stroke_m);
  CHECK(again.motion.cycles == s.motion.cycles);
  CHECK(again.resolved_yaml == s.resolved_yaml);
  CHECK(s.resolved_yaml.find("auto:") != std::string::npos);  // the stroke asked, recorded
}

TEST_CASE("travel: conflicts and malformed travel are one line naming the key", "[config]") {
  struct Case {
    std::vector<Override> overrides;
    std::string names;
  };
  const std::vector<Case> cases = {
      {{{"motion.travel.treads", "3"}},
       "motion.travel: got {treads: 3} and motion.cycles 3, expected one of them"},
      {{{"motion.cycles", "null"}, {"motion.travel.treads", "3"}, {"motion.travel.distance", "1"}},
       "motion.travel: got {treads: 3, distance: 1}, expected exactly one of distance"},
      {{{"motion.cycles", "null"}, {"motion.travel", "{}"}},
       "motion.travel: got {}, expected exactly one of distance"},
      {{{"motion.cycles", "null"}, {"motion.travel", "2"}},
       "motion.travel: got 2, expected a map {distance: D} (m) or {treads: N}"},
      {{{"motion.cycles", "null"}, {"motion.travel.tread", "2"}},
       "motion.travel.tread: unknown key, allowed here: distance, treads"},
      {{{"motion.cycles", "null"}, {"motion.travel.treads", "0"}},
       "motion.travel.treads: got 0, expected an integer in [1, 100000]"},
      {{{"motion.cycles", "null"}, {"motion.travel.distance", "-1"}},
       "motion.travel.distance: got -1, expected a number in (0, 10000]"},
      {{{"motion.cycles", "null"},
        {"terrain", "{type: flat, height: 0.0}"},
        {"motion.travel.treads", "2"}},
       "motion.travel.treads: got 2 on terrain without treads, expected terrain.type stairs"},
      {{{"motion.cycles", "null"},
        {"motion.peak_speed", "null"},
        {"motion.ramp_duration", "null"},
        {"motion.cycle_durations", "[3.0, 2.6, 3.0]"},
        {"motion.travel.treads", "2"}},
       "motion: got both cycle_durations and peak_speed/cycles/ramp_duration/travel"},
  };
  for (const Case& c : cases) {
    const std::string msg = error_of(c.overrides);
    INFO(msg);
    CHECK(msg.rfind(kStairs + ": ", 0) == 0);
    CHECK(msg.find(c.names) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
  }
}

}  // namespace hexdyn
