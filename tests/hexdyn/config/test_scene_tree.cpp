// The scene tree a sweep's scenarios share (config/scene_tree.hpp) against the YAML tree it
// stands for: a key set on the shared tree reads as the key set on a copy of the YAML tree
// (the sweep's former way), the base stays as it was, a scene read from either is the same
// with the same one-line errors, and numbers read without yaml-cpp's string stream are the
// numbers yaml-cpp reads.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

const std::string kStairsBase = std::string(HEXDYN_SOURCE_DIR) + "/configs/sweeps/stairs_base.yaml";

std::string emit(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return out.c_str();
}

/// `root[k1]…[kn] = value` on a deep copy, as the sweep set its values before.
YAML::Node set_on_copy(const YAML::Node& root, const std::string& path, const YAML::Node& value) {
  YAML::Node copy = YAML::Clone(root);
  const auto keys = split_key_path(path);
  YAML::Node cur = copy;
  for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
    YAML::Node next = cur[keys[k]];
    if (!next.IsDefined() || next.IsNull()) {
      cur[keys[k]] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[keys[k]]);
    }
    cur.reset(next);
  }
  cur[keys.back()] = YAML::Clone(value);
  return copy;
}

/// A key path and the YAML text of the value set there.
struct Case {
  const char* path;
  const char* value;
};

/// The message of the ConfigError `read` throws, or "" when it throws none.
template <class F>
std::string error_of(F read) {
  try {
    read();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("scene tree: a key set on the shared tree reads as on a copy of the YAML tree",
          "[config]") {
  const YAML::Node base =
      YAML::Load("a: {x: 1, y: [1, 2], n: ~}\nb:\n  c: {d: 2}\n  e: text\ns: 3\n? [k]\n: 4\n");
  const std::string base_text = emit(base);
  const SceneTree tree(base);
  for (const Case c :
       {Case{"a.x", "5"}, Case{"a.z", "6"}, Case{"a.n.m", "7"}, Case{"b.c.d", "[8, 9]"},
        Case{"b.f.g.h", "{p: 1}"}, Case{"b", "10"}, Case{"t", "{u: 11}"}, Case{"a.y", "~"}}) {
    INFO(c.path << " = " << c.value);
    const YAML::Node value = YAML::Load(c.value);
    SceneTree set = tree;
    REQUIRE(set.set(split_key_path(c.path), SceneTree::convert(value)));
    CHECK(emit(SceneTree::yaml(set.root())) == emit(set_on_copy(base, c.path, value)));
    CHECK(emit(SceneTree::yaml(tree.root())) == base_text);  // shared, never modified
  }
  // Through a value that is not a map the YAML tree's own rules apply: refused here.
  SceneTree set = tree;
  CHECK_FALSE(set.set(split_key_path("s.x"), SceneTree::convert(YAML::Node(1))));
  CHECK_FALSE(set.set(split_key_path("b.e.x"), SceneTree::convert(YAML::Node(1))));
  CHECK(emit(SceneTree::yaml(set.root())) == base_text);
  CHECK(emit(base) == base_text);
}

TEST_CASE("scene tree: a scene read from the shared tree is the scene of the YAML tree",
          "[config]") {
  const YAML::Node base = load_scene_tree(kStairsBase);
  const SceneTree tree(base);
  // Accepted values, including keys below maps read whole (motion.travel, auto), and
  // refused ones, whose messages quote the value (a changed map rebuilt as YAML).
  for (const Case c :
       {Case{"terrain.riser_height", "0.08"}, Case{"gait.duty_factor", "0.75"},
        Case{"motion.travel.distance", "0.6"}, Case{"motion.travel", "{treads: 2}"},
        Case{"auto.note", "x"}, Case{"name", "other"}, Case{"terrain.riser_height", "abc"},
        Case{"terrain.riser_height", "-1"}, Case{"terrain.steps", "0x10"},
        Case{"robot.hips.y", "[0.2, 0.3, 0.1]"}, Case{"robot.trunk.unknown", "1"},
        Case{"motion.posture.start_y", "{a: 1}"}, Case{"motion.travel.x", "1"},
        Case{"robot.coxa", "3"}, Case{"allocation.friction", "[cone]"}}) {
    INFO(c.path << " = " << c.value);
    const YAML::Node value = YAML::Load(c.value);
    const YAML::Node yaml = set_on_copy(base, c.path, value);
    SceneTree set = tree;
    REQUIRE(set.set(split_key_path(c.path), SceneTree::convert(value)));
    for (const bool resolved : {true, false}) {
      Scene from_yaml, from_tree;
      const std::string yaml_error =
          error_of([&] { from_yaml = scene_from_yaml(yaml, "s", resolved); });
      const std::string tree_error =
          error_of([&] { from_tree = scene_from_tree(set, "s", resolved); });
      CHECK(tree_error == yaml_error);
      if (!yaml_error.empty()) continue;
      CHECK(from_tree.resolved_yaml == from_yaml.resolved_yaml);
      CHECK(from_tree.terrain.riser_height_m == from_yaml.terrain.riser_height_m);
      CHECK(from_tree.gait.duty_factor == from_yaml.gait.duty_factor);
      CHECK(from_tree.motion.cycles == from_yaml.motion.cycles);
      CHECK(from_tree.gait.stroke_m == from_yaml.gait.stroke_m);
      CHECK(from_tree.name == from_yaml.name);
    }
  }
}

TEST_CASE("scene reader: numbers read as yaml-cpp reads them", "[config]") {
  for (const char* text : {"0.1",
                           "0.30000000000000004",
                           "-2.5e-3",
                           "1E5",
                           "1e+5",
                           "00.5",
                           "1e-400",
                           "1e400",
                           "-1e400",
                           "4.9406564584124654e-324",
                           "123456789012345678901234567890.5",
                           "-0",
                           "7",
                           "007",
                           "1.",
                           ".5",
                           "+1",
                           "0x10",
                           "010",
                           "1_000",
                           " 1",
                           "1 ",
                           "nan",
                           ".nan",
                           ".inf",
                           "-.inf",
                           "-",
                           "1e",
                           "e5",
                           "",
                           "9223372036854775807",
                           "9223372036854775808",
                           "-9223372036854775808",
                           "-9223372036854775809",
                           "12abc"}) {
    INFO("'" << text << "'");
    const YAML::Node node(std::string{text});
    const SceneTree::NodePtr read = SceneTree::convert(node);
    double d = 0.0, d_yaml = 0.0;
    const bool ok = scene_keys::decode_scalar(*read, d);
    REQUIRE(ok == YAML::convert<double>::decode(node, d_yaml));
    if (ok) CHECK(std::memcmp(&d, &d_yaml, sizeof d) == 0);  // bit for bit (NaN too)
    long long i = 0, i_yaml = 0;
    const bool ok_i = scene_keys::decode_scalar(*read, i);
    REQUIRE(ok_i == YAML::convert<long long>::decode(node, i_yaml));
    if (ok_i) CHECK(i == i_yaml);
  }
}

}  // namespace hexdyn
