#pragma once
/// \file yaml_load.hpp
/// The one way hexdyn reads YAML (scene files, inherited files, sweep files, `--set`
/// values): size- and type-checked file reading, and a parse that refuses what yaml-cpp
/// would accept silently. Every refusal is a ConfigError with one line naming the file
/// (and line, and key path where there is one).
///
/// Beyond YAML syntax, the parse refuses
/// - a key given twice in one map ("FILE: a.b: duplicate key, first at line 12, again at
///   line 30"); yaml-cpp keeps both and lookups see the first, while Python's YAML keeps
///   the last, so a file with duplicates would mean different things to different readers;
/// - maps and lists nested deeper than kMaxYamlDepth levels;
/// - keys that are lists, maps or aliases (no hexdyn key is one);
/// - a second document ("---") in one file;
/// - more than kMaxYamlNodes nodes or kMaxYamlBytes bytes of values once aliases are
///   expanded, and an alias inside the node it names (counted on the event stream, before
///   any tree is built);
/// - a `--set` value (parse_yaml_checked) longer than kMaxConfigBytes.
/// The declarations of read_text_file, parse_yaml_text and load_scene_tree are in
/// config.hpp; they are implemented here with the checks above.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/process/paths.hpp"  // why_not_regular_file, for the readers of files

namespace YAML {
class Node;
}

namespace hexdyn {

/// Largest configuration or sweep file read [bytes] (1 MiB; configs/paper.yaml is 5 kB).
inline constexpr std::size_t kMaxConfigBytes = std::size_t{1} << 20;

/// Deepest nesting of maps and lists accepted (a scene needs 4: robot.femur.limits[0]).
inline constexpr int kMaxYamlDepth = 64;

/// Most YAML nodes (scalars, nulls, lists, maps; keys included) one text may stand for once
/// its aliases are expanded: an alias (*name) repeats its anchor's whole node, so nine
/// nested lists of ten aliases each (a 400-byte "billion laughs") would stand for 10^9 nodes
/// and gigabytes once copied. A text without aliases stays far below it (a 1 MiB file holds
/// at most about 530,000 nodes); the paper scene has about 200.
inline constexpr std::uint64_t kMaxYamlNodes = 1000000;

/// Most bytes of scalar text one YAML text may stand for once its aliases are expanded
/// (16 MiB: 16 times the largest file; one 1 MiB value repeated by aliases is refused).
inline constexpr std::uint64_t kMaxYamlBytes = std::uint64_t{16} << 20;

/// Parses YAML text with the checks above, any document shape (a `--set` value may be a
/// scalar or a list). `source_name` starts every message. Throws ConfigError.
YAML::Node parse_yaml_checked(const std::string& text, const std::string& source_name);

/// Whether `node` is a scalar that YAML (and Python's yaml) reads as a string although its
/// text is a number to hexdyn (a YAML int or float, or p/q): quoted ("1e-2", '0.05') or
/// tagged !!str (!!str 200). Where a number is expected it is refused, never read as one
/// (quoted_number_message). The parse above tags every quoted number !!str, so that it stays
/// a string when a tree is written out and read again (a sweep's base scene, a scenario):
/// yaml-cpp writes a quoted scalar without its quotes.
bool is_quoted_number(const YAML::Node& node);

/// "got the string \"1e-2\", expected EXPECTED (write it unquoted)": the refusal of a quoted
/// number (is_quoted_number) where a number is expected.
std::string quoted_number_message(const YAML::Node& node, const std::string& expected);

/// "p/q" with integers p and q ≠ 0 (spaces allowed around '/') → p divided by q;
/// nothing for any other text. Sweep axis values, `--set` values and the number keys of a
/// scene file (config/scene_key_reader.hpp) use it.
std::optional<double> parse_fraction(const std::string& text);

/// `text` with a p/q fraction replaced by its value, written with 17 significant digits
/// (so that it reads back to the same double); any other text unchanged.
std::string fraction_to_number_text(const std::string& text);

}  // namespace hexdyn
