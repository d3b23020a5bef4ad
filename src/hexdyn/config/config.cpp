#include "hexdyn/config/config.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/plausibility.hpp"
#include "hexdyn/config/run_limits.hpp"
#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/config/scene_readers.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/table_keys.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/stance.hpp"

namespace hexdyn {
namespace {

using namespace scene_keys;

/// `resolved` with its `auto:` record, if any, moved to the end (after the settings).
YAML::Node requests_last(YAML::Node resolved) {
  if (!resolved["auto"].IsDefined()) return resolved;
  const YAML::Node requests = YAML::Clone(resolved["auto"]);
  resolved.remove("auto");
  resolved["auto"] = requests;
  return resolved;
}

}  // namespace

std::vector<std::string> split_key_path(const std::string& path) {
  std::vector<std::string> keys;
  if (path.empty()) return keys;
  for (std::size_t begin = 0;;) {  // "a." names an empty key after a
    const std::size_t dot = path.find('.', begin);
    keys.push_back(path.substr(begin, dot == std::string::npos ? dot : dot - begin));
    if (dot == std::string::npos) return keys;
    begin = dot + 1;
  }
}

Override parse_override(const std::string& text) {
  // Bound for the result file's /meta, like a file's text (config/inputs.hpp).
  const std::size_t bad = first_non_utf8(text);
  if (bad != std::string::npos) require_utf8(text, "--set " + text.substr(0, bad) + "...");
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set " + text + ": expected key.path=value");
  // p/q as in sweep files: "--set gait.duty_factor=3/4".
  return {text.substr(0, eq), fraction_to_number_text(text.substr(eq + 1))};
}

void apply_override(YAML::Node& root, const Override& ov, const std::string& source_name) {
  const YAML::Node value = parse_yaml_checked(ov.value, "--set " + ov.key_path + "=" + ov.value);
  const auto keys = split_key_path(ov.key_path);
  for (const auto& k : keys)
    if (k.empty()) throw ConfigError("--set " + ov.key_path + ": empty key in the path");
  YAML::Node cur = root;
  std::string so_far;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    so_far += (so_far.empty() ? "" : ".") + keys[i];
    YAML::Node next = cur[keys[i]];
    if (!next.IsDefined() || next.IsNull()) {
      cur[keys[i]] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[keys[i]]);
    } else if (!next.IsMap()) {
      throw ConfigError(source_name + ": --set " + ov.key_path + ": " + so_far +
                        " is not a mapping");
    }
    cur.reset(next);
  }
  cur[keys.back()] = value;
}

Scene scene_from_yaml(const YAML::Node& root, const std::string& source_name, bool emit_resolved) {
  return scene_from_tree(SceneTree(root), source_name, emit_resolved);
}

Scene scene_from_tree(const SceneTree& tree, const std::string& source_name, bool emit_resolved) {
  Scene s;
  s.source_path = source_name;
  Reader r(tree, source_name, emit_resolved);
  s.name = r.string_or("name", s.name);
  read_auto_requests(r);
  LoadedUrdfRobot urdf;
  read_robot(r, s.robot, urdf);
  read_terrain(r, s.terrain);
  read_gait(r, s, urdf);
  if (urdf.robot && !r.given("gait.foot_lateral"))  // the stance sets the footholds
    s.warnings = stance_fallback_warnings(urdf.stance);
  read_motion(r, s.gait, s.terrain, s.motion);
  read_contact(r, s);
  read_replay(r, s);
  read_allocation(r, s, urdf);
  read_drive_train(r, s, urdf);
  read_output(r, s);
  read_robustness(r, s);
  r.check_unknown();
  check_physical_plausibility(s, source_name);  // timings that no physical motion has
  // Before anything is planned or allocated: the motion's duration and output samples.
  check_run_size_limits(s, source_name,
                        !s.motion.cycle_durations_s.empty() ? "motion.cycle_durations"
                        : r.given("motion.travel")          ? "motion.travel"
                                                            : "motion.cycles");
  if (!emit_resolved) return s;
  YAML::Emitter out;
  out << requests_last(in_table_order(r.resolved()));
  s.resolved_yaml = std::string(out.c_str()) + "\n";
  return s;
}

namespace {

/// A number as YAML text that reads back to the same double.
YAML::Node exact_number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return YAML::Node(std::string(buf));
}

/// `node[key]`, made a map when absent or not a map.
YAML::Node child_map(YAML::Node node, const std::string& key) {
  if (!node[key].IsMap()) node[key] = YAML::Node(YAML::NodeType::Map);
  return node[key];
}

}  // namespace

std::string with_chosen_posture(const std::string& resolved_yaml, double height_m,
                                double foot_lateral_m) {
  YAML::Node root = YAML::Load(resolved_yaml);
  YAML::Node posture = root["motion"]["posture"];
  if (!posture.IsMap()) return resolved_yaml;
  YAML::Node requests = child_map(child_map(child_map(root, "auto"), "motion"), "posture");
  for (const char* key :
       {"height", "height_range", "target_margin", "trunk_clearance", "foot_lateral"}) {
    if (!posture[key].IsDefined()) continue;
    requests[key] = YAML::Clone(posture[key]);
    posture.remove(key);
  }
  posture["height"] = exact_number(height_m);
  // gait.foot_lateral is a choice only when the search could vary it (a foot_lateral range).
  if (requests["foot_lateral"].IsDefined()) {
    YAML::Node gait = child_map(root, "gait");
    YAML::Node gait_requests = child_map(root["auto"], "gait");
    if (!gait_requests["foot_lateral"].IsDefined() && gait["foot_lateral"].IsDefined())
      gait_requests["foot_lateral"] = YAML::Clone(gait["foot_lateral"]);
    gait["foot_lateral"] = exact_number(foot_lateral_m);
  }
  YAML::Emitter out;
  out << requests_last(root);
  return std::string(out.c_str()) + "\n";
}

Scene load_scene_from_string(const std::string& yaml_text, const std::string& source_name,
                             const std::vector<Override>& overrides) {
  YAML::Node root = parse_yaml_text(yaml_text, source_name);
  for (const auto& ov : overrides) apply_override(root, ov, source_name);
  Scene s = scene_from_yaml(root, source_name);
  s.input_sha256 = input_sha256_text(scene_inputs({}, root));  // the URDF, if any
  return s;
}

Scene load_scene(const std::string& path, const std::vector<Override>& overrides,
                 std::vector<InputFile>* inputs) {
  // Each file read once: the digests are those of the bytes the scene was built from.
  const InputFreeze freeze;
  std::vector<std::string> files;
  YAML::Node root = load_scene_tree(path, &files);
  for (const auto& ov : overrides) apply_override(root, ov, path);
  std::vector<InputFile> read = scene_inputs(files, root);
  Scene s = scene_from_yaml(root, path);
  s.input_sha256 = input_sha256_text(read);
  if (inputs) *inputs = without_texts(std::move(read));
  return s;
}

}  // namespace hexdyn
