// Quoted numbers (yaml_load.hpp's is_quoted_number): "1e-2", '0.05' and !!str 200 are strings
// to YAML and to Python's yaml, so every number key of a scene refuses them, naming the key
// (and the list item), the value and what is expected, while the same value unquoted loads. A
// quoted number stays a string once a tree is written out by yaml-cpp and read again (as a
// sweep's base scene and its scenarios are), and a value shown in a message is on one line.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

const std::string kSource = HEXDYN_SOURCE_DIR;
const std::string kPaper = kSource + "/configs/paper.yaml";

/// The message of loading `scene` with `key`=`value`, or "" when it loads.
std::string refusal(const std::string& scene, const std::string& key, const std::string& value) {
  try {
    (void)load_scene(scene, {{key, value}});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("yaml load: a quoted number is a string, also written out and read again",
          "[yaml][quoted]") {
  const std::string text =
      "a: \"1e-2\"\nb: '0.05'\nc: !!str 200\nd: \"3/4\"\ne: 1e-2\nf: \"abc\"\ng: !!float \"3\"\n"
      "h: [1, \"2\"]\ni: 3/4\n";
  const std::vector<std::pair<const char*, bool>> expected = {
      {"a", true},  {"b", true},  {"c", true},  {"d", true}, {"e", false},
      {"f", false}, {"g", false}, {"i", false}, {"h", false}};
  const YAML::Node read = parse_yaml_text(text, "q.yaml");
  YAML::Emitter out;
  out << read;
  // Read again as a sweep's scenarios read their base (parse_yaml_text) and as yaml-cpp alone.
  for (const YAML::Node& node :
       {read, parse_yaml_text(out.c_str(), "again"), YAML::Load(out.c_str())}) {
    for (const auto& [key, quoted] : expected) {
      INFO(key << " in " << out.c_str());
      CHECK(is_quoted_number(node[key]) == quoted);
    }
    CHECK(is_quoted_number(node["h"][1]));
    CHECK(yaml_inline(node["a"]) == "\"1e-2\"");
    CHECK(yaml_inline(node["h"]) == "[1, \"2\"]");
    CHECK(yaml_inline(node["f"]) == "abc");
  }
  // A list or map given in block style is shown on one line, aliases written out.
  const YAML::Node block = parse_yaml_text("x: &p\n  - 1\n  - {y: 2}\nz: [*p, *p]\n", "b.yaml");
  CHECK(yaml_inline(block["x"]) == "[1, {y: 2}]");
  CHECK(yaml_inline(block["z"]) == "[[1, {y: 2}], [1, {y: 2}]]");
  CHECK(quoted_number_message(read["a"], "a number") ==
        "got the string \"1e-2\", expected a number (write it unquoted)");
}

TEST_CASE("config: every number key refuses a quoted number, the same value unquoted loads",
          "[config][quoted]") {
  const std::string mark4 = kSource + "/configs/robots/phantomx_mark4_stairs.yaml";
  const std::string pexod = kSource + "/configs/robots/pexod_stairs.yaml";
  const std::string feet =
      "[0.0125, 0.1275, 0], [0.0125, -0.1275, 0], [0.0125, 0.1275, 0], "
      "[0.0125, -0.1275, 0], [0.0125, 0.1275, 0]";
  struct Case {
    std::string scene, key, quoted, plain, message;
  };
  const std::vector<Case> cases = {
      {kPaper, "output.tolerance", "\"1e-2\"", "1e-2",
       "output.tolerance: got the string \"1e-2\", expected a number in [0, 0.1] (write it "
       "unquoted)"},
      {kPaper, "output.tolerance", "'0.05'", "0.05", "output.tolerance: got the string \"0.05\""},
      {kPaper, "gait.duty_factor", "\"3/4\"", "3/4", "gait.duty_factor: got the string \"3/4\""},
      {kPaper, "output.impact_samples", "!!str 40", "40",
       "output.impact_samples: got the string \"40\", expected an integer in [1, "},
      {kPaper, "motion.cycle_durations", "[3.0, \"2.6\", 3.0]", "[3.0, 2.6, 3.0]",
       "motion.cycle_durations[1]: got the string \"2.6\""},
      {kPaper, "motion.initial_position", "[0, '0.412', 0.235]", "[0, 0.412, 0.235]",
       "motion.initial_position[1]: got the string \"0.412\""},
      {kPaper, "robot.hips.y", "[0.2, 0.0, \"-0.2\"]", "[0.2, 0.0, -0.2]",
       "robot.hips.y[2]: got the string \"-0.2\""},
      {pexod, "robot.foot_offset", "[" + feet + ", [\"0.0125\", -0.1275, 0]]",
       "[" + feet + ", [0.0125, -0.1275, 0]]",
       "robot.foot_offset[5][0]: got the string \"0.0125\""},
      {mark4, "robot.nominal_pose", "[0, !!str 0, 0]", "[0, 0, 0]",
       "robot.nominal_pose[1]: got the string \"0\""},
  };
  for (const Case& c : cases) {
    INFO(c.key << "=" << c.quoted);
    CHECK(refusal(c.scene, c.key, c.plain).empty());
    const std::string msg = refusal(c.scene, c.key, c.quoted);
    INFO(msg);
    CHECK(msg.find(c.message) != std::string::npos);
    CHECK(msg.size() > std::string("(write it unquoted)").size());
    CHECK(msg.substr(msg.size() - 19) == "(write it unquoted)");
    CHECK(msg.find('\n') == std::string::npos);
  }
  // A quoted value of a string key is its string, numbers and all.
  CHECK(load_scene(kPaper, {{"name", "\"2024\""}}).name == "2024");
  CHECK(refusal(kPaper, "terrain.type", "\"stairs\"").empty());
}

}  // namespace hexdyn
