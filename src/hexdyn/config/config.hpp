#pragma once
/// \file config.hpp
/// YAML scene files → validated `Scene`. Every key is checked before any work: a
/// missing, mistyped, non-finite, unknown or out-of-range value throws ConfigError
/// with one line "FILE: key.path: got VALUE, expected WHAT". YAML syntax errors name
/// file, line and column. The key reference is configs/paper.yaml.
#include <cstddef>
#include <string>
#include <vector>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/scene.hpp"

namespace YAML {
class Node;
}

namespace hexdyn {

/// One `--set key.path=value` override; value is parsed as YAML (scalar or [list]).
struct Override {
  std::string key_path;
  std::string value;
};

/// A YAML value on one line, as messages show it ("null" when absent): lists and maps in
/// flow style, aliases written out, a quoted number (is_quoted_number) in quotes, so that the
/// text parsed again (a sweep's or envelope's `set:`, a case's value) is again a string.
/// Defined in yaml_load.cpp.
std::string yaml_inline(const YAML::Node& node);

/// yaml_inline cut to kMaxMessageValueChars characters for a message, with the length of
/// the whole ("[1, 2, 3, ... (1234567 characters)]"): a value may be a 1 MiB list.
std::string yaml_for_message(const YAML::Node& node);

/// Longest value a message quotes [characters].
inline constexpr std::size_t kMaxMessageValueChars = 200;

/// "a.b.c" → {"a", "b", "c"}; empty keys are kept ("a..b", "a." name empty keys).
std::vector<std::string> split_key_path(const std::string& path);

/// Parses "key.path=value"; a value p/q (integers) becomes the number p divided by q, as
/// in sweep files. Throws ConfigError on a malformed string.
Override parse_override(const std::string& text);

/// Reads a scene file into a tree, resolving `inherit: OTHER.yaml` (a path relative to
/// the file): the file's keys are deep-merged over those of OTHER (maps merge key by
/// key; scalars and lists replace). Throws ConfigError on an unreadable file, an
/// `inherit:` that is not a regular file, or a cycle (files compared by canonical path,
/// so `./cfg.yaml` and `../dir/cfg.yaml` are found; the message shows the chain).
/// Every file goes through read_text_file and parse_yaml_text. When `files` is given, it
/// receives the files read: `path`, then each inherited file in inheritance order, as
/// named (relative paths joined to the inheriting file's folder).
YAML::Node load_scene_tree(const std::string& path, std::vector<std::string>* files = nullptr);

/// Reads (with inheritance), overrides and validates a scene file. Each input file is read
/// once (config/inputs.hpp InputFreeze), so Scene::input_sha256 is the digest of what was used.
/// When `inputs` is given, it receives the input files (scene, inherited files, URDF) with
/// their identities, without their texts: what the run's outputs are checked against
/// (io/output.hpp check_output_target).
Scene load_scene(const std::string& path, const std::vector<Override>& overrides = {},
                 std::vector<InputFile>* inputs = nullptr);

/// Same, from YAML text (`source_name` is used in messages, e.g. a sweep scenario id).
Scene load_scene_from_string(const std::string& yaml_text, const std::string& source_name,
                             const std::vector<Override>& overrides = {});

/// Validates an already-parsed YAML tree (used by the sweep, which builds scenario trees).
/// With `emit_resolved` false, Scene::resolved_yaml is left empty (writing it is a third
/// of the validation's cost; a sweep needs it only for the runs it keeps).
Scene scene_from_yaml(const YAML::Node& root, const std::string& source_name,
                      bool emit_resolved = true);

/// Parses YAML text into a tree, turning syntax errors into ConfigError with line/column;
/// refuses duplicate keys, nesting deeper than kMaxYamlDepth and a second document
/// (yaml_load.hpp), and a top level that is not a map ("FILE: top level: got a list,
/// expected a map of sections"). Scenes, inherited files and sweep files all come here.
YAML::Node parse_yaml_text(const std::string& text, const std::string& source_name);

/// Reads a whole configuration file; throws ConfigError naming the path if it cannot be
/// read, is not a regular file (directories, devices, FIFOs and sockets are refused by
/// their type before any open that could block) or is larger than kMaxConfigBytes (1 MiB).
std::string read_text_file(const std::string& path);

/// `resolved_yaml` (a Scene::resolved_yaml of a scene with motion.posture.height: auto)
/// with the automatic posture written in as the values used
/// (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration):
/// motion.posture.height becomes `height_m` and, when motion.posture.foot_lateral let the
/// search vary it, gait.foot_lateral becomes `foot_lateral_m`, both written with 17
/// significant digits (they read back to the same doubles); the search's keys (height:
/// auto, height_range, target_margin, trunk_clearance, foot_lateral) move to
/// auto.motion.posture, and gait.foot_lateral's value before the search to
/// auto.gait.foot_lateral unless that holds a request already. The result is a valid scene
/// that plans the same motion without searching.
std::string with_chosen_posture(const std::string& resolved_yaml, double height_m,
                                double foot_lateral_m);

/// Applies one override to a tree (creating intermediate maps); throws ConfigError when
/// the path runs through a non-map value.
void apply_override(YAML::Node& root, const Override& ov, const std::string& source_name);

}  // namespace hexdyn
