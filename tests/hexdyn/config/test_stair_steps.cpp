// terrain.steps as a list, terrain.nosing and the stairs' perturbations (config/stair_steps.hpp):
// a uniform list reads as the uniform stairs it spells out; entries take their defaults from
// the uniform keys; every bad step is named on a line of its own with its index, value and
// what is allowed; the perturbations change the risers they name.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/stairs.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";

Scene paper(const std::vector<Override>& sets) { return load_scene(kPaper, sets); }

/// The lines of the error that loading with `sets` throws (one per problem).
std::vector<std::string> error_lines(const std::vector<Override>& sets) {
  try {
    (void)paper(sets);
  } catch (const ConfigErrors& e) {
    return e.lines();
  } catch (const ConfigError& e) {
    return {e.what()};
  }
  FAIL("no ConfigError was thrown");
  return {};
}

/// `n` copies of the entry `entry` as a YAML flow list.
std::string repeated(const std::string& entry, int n) {
  std::string out = "[";
  for (int k = 0; k < n; ++k) out += (k ? ", " : "") + entry;
  return out + "]";
}

TEST_CASE("steps list: a uniform list is the uniform stairs", "[config][terrain]") {
  const Scene uniform = paper({});
  REQUIRE(uniform.terrain.step_list.empty());
  const Scene listed = paper({{"terrain.steps", repeated("{riser: 0.05, tread: 0.25}", 12)}});
  CHECK(listed.terrain.step_list.empty());
  CHECK(listed.terrain.steps == uniform.terrain.steps);
  CHECK(listed.terrain.riser_height_m == uniform.terrain.riser_height_m);
  CHECK(listed.terrain.tread_depth_m == uniform.terrain.tread_depth_m);
  // Entries without fields take terrain.riser_height and tread_depth (the paper's).
  const Scene defaulted = paper({{"terrain.steps", repeated("{}", 12)}});
  CHECK(defaulted.terrain.step_list.empty());
  CHECK(defaulted.terrain.steps == 12);
}

TEST_CASE("steps list: entries, landings and nosings are read as given", "[config][terrain]") {
  const Scene s = paper({{"terrain.steps",
                          "[{riser: 0.06}, {landing: 0.7}, {riser: -0.04, tread: 0.3, nosing: "
                          "0.02}, {tread: 1/4}]"},
                         {"terrain.nosing", "0.01"}});
  const auto& l = s.terrain.step_list;
  REQUIRE(l.size() == 4);
  CHECK(l[0].riser_m == 0.06);
  CHECK(l[0].tread_m == 0.25);   // terrain.tread_depth
  CHECK(l[0].nosing_m == 0.01);  // terrain.nosing
  CHECK(l[1].riser_m == 0.0);
  CHECK(l[1].tread_m == 0.7);
  CHECK(l[2].riser_m == -0.04);
  CHECK(l[2].nosing_m == 0.02);
  CHECK(l[3].riser_m == 0.05);  // terrain.riser_height
  CHECK(l[3].tread_m == 0.25);
  // The resolved configuration reads back to the same stairs.
  const Scene again = load_scene_from_string(s.resolved_yaml, "resolved.yaml");
  REQUIRE(again.terrain.step_list.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(again.terrain.step_list[k].riser_m == l[k].riser_m);
    CHECK(again.terrain.step_list[k].tread_m == l[k].tread_m);
    CHECK(again.terrain.step_list[k].nosing_m == l[k].nosing_m);
  }
}

TEST_CASE("steps list: one line per bad step, with its index, value and what is allowed",
          "[config][terrain]") {
  const auto lines = error_lines({{"terrain.steps",
                                   "[{riser: .nan}, {riser: 0.05}, {tread: -0.2}, 7, {landing: 0}, "
                                   "{riser: 0.05, height: 1}]"}});
  REQUIRE(lines.size() == 5);
  CHECK_THAT(lines[0], Catch::Contains("terrain.steps[1].riser: got .nan, expected a finite "
                                       "number in [-1, 1] m"));
  CHECK_THAT(lines[1], Catch::Contains("terrain.steps[3].tread: got -0.2, expected"));
  CHECK_THAT(lines[2], Catch::Contains("terrain.steps[4]: got 7, expected a map"));
  CHECK_THAT(lines[3], Catch::Contains("terrain.steps[5].landing: got 0, expected"));
  CHECK_THAT(lines[4], Catch::Contains("terrain.steps[6].height: unknown key"));
  for (const auto& l : lines) CHECK(l.find('\n') == std::string::npos);
  CHECK_THAT(error_lines({{"terrain.steps", "[{landing: 1, riser: 0.1}]"}})[0],
             Catch::Contains("terrain.steps[1]: got {landing: 1, riser: 0.1}, expected "
                             "{landing: L} alone"));
  // A nosing as deep as the tread it overhangs: going up, the tread before its riser.
  CHECK_THAT(error_lines({{"terrain.steps", "[{riser: 0.05}, {riser: 0.05, nosing: 0.25}]"}})[0],
             Catch::Contains("terrain.steps[2].nosing: got 0.25, expected less than the tread "
                             "it overhangs (0.25 m"));
  // Going down, the tread after it.
  CHECK_THAT(error_lines({{"terrain.steps",
                           "[{riser: -0.05, tread: 0.2, nosing: 0.21}, {riser: -0.05}]"}})[0],
             Catch::Contains("terrain.steps[1].nosing: got 0.21"));
  CHECK_THAT(error_lines({{"terrain.nosing", "0.25"}})[0],
             Catch::Contains("terrain.nosing: got 0.25, expected less than terrain.tread_depth"));
  CHECK_THAT(error_lines({{"terrain.steps", "[]"}})[0], Catch::Contains("terrain.steps: got []"));
  CHECK_THAT(error_lines({{"terrain.steps", "[{landing: 1}, {riser: 0, tread: 0.3}]"}})[0],
             Catch::Contains("expected at least one step with a riser"));
}

TEST_CASE("stairs perturbations: a scale on every riser, an offset on one", "[config][terrain]") {
  const Scene scaled = paper({{"terrain.riser_scale", "2"}});
  CHECK(scaled.terrain.step_list.empty());
  CHECK(scaled.terrain.riser_height_m == 0.1);
  const Scene one =
      paper({{"terrain.step_offset.step", "3"}, {"terrain.step_offset.riser", "0.01"}});
  REQUIRE(one.terrain.step_list.size() == 12);
  for (int k = 0; k < 12; ++k)
    CHECK(one.terrain.step_list[k].riser_m == (k == 2 ? 0.05 + 0.01 : 0.05));
  const Scene both = paper({{"terrain.steps", "[{riser: 0.04}, {riser: 0.06}]"},
                            {"terrain.riser_scale", "0.5"},
                            {"terrain.step_offset.step", "2"},
                            {"terrain.step_offset.riser", "-0.01"}});
  REQUIRE(both.terrain.step_list.size() == 2);
  CHECK(both.terrain.step_list[0].riser_m == 0.02);
  CHECK(both.terrain.step_list[1].riser_m == Approx(0.02).margin(1e-17));
  CHECK_THAT(error_lines({{"terrain.step_offset.step", "13"}})[0],
             Catch::Contains("terrain.step_offset.step: got 13, expected a step of the stairs, "
                             "1 to 12"));
}

TEST_CASE("stair edges: a nosing moves the edge towards the lower tread", "[terrain]") {
  TerrainParams t;
  t.first_riser_y_m = 1.0;
  t.step_list = {{0.1, 0.5, 0.03}, {-0.1, 0.5, 0.03}, {0.0, 2.0, 0.0}, {0.2, 0.5, 0.0}};
  const StairEdges e = stair_edges(t);
  REQUIRE(e.edge_y_m.size() == 3);  // the landing has none
  CHECK(e.edge_y_m[0] == 1.0 - 0.03);
  CHECK(e.edge_y_m[1] == 1.5 + 0.03);
  CHECK(e.edge_y_m[2] == 4.0);
  CHECK(e.edge_step == std::vector<int>{1, 2, 4});
  CHECK(e.tread_z_m == std::vector<double>{0.0, 0.1, 0.0, 0.2});
}

}  // namespace
}  // namespace hexdyn
