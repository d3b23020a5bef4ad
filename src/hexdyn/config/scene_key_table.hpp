#pragma once
/// \file scene_key_table.hpp
/// Every scene key declared once (after MuJoCo's mjxmacro.h): its path, kind, range or
/// choices, unit, default, the docs' table it is in and what it means. From this table come
/// the scene readers' ranges (config.cpp and the files it calls), the keys the table's own
/// loop reads into a Scene (read_table_keys), the unit of every numeric key
/// (key_units.hpp), the resolved configuration's defaults, `hexdyn validate`'s checks and the
/// key tables of docs/user/configuration.md (docs/gen_config_tables.py). A default is the
/// initial value of the key's field in core/scene.hpp, read from a default-constructed Scene.
/// Rules across keys stay code, in one place: key_rules.hpp.
#include <cstddef>
#include <deque>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {
namespace scene_keys {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string fmt(double x) {
  if (x == kInf) return "inf";
  if (x == -kInf) return "-inf";
  std::ostringstream s;
  s << x;
  return s.str();
}

/// Allowed interval of a number, with a readable description.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string describe() const {
    if (lo == -kInf && hi == kInf) return "a finite number";
    return std::string("a number in ") + (lo_open ? "(" : "[") + fmt(lo) + ", " + fmt(hi) +
           (hi_open ? ")" : "]");
  }
};
constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }
constexpr Range open_interval(double lo, double hi) { return {lo, hi, true, true}; }
constexpr Range positive(double hi = kInf) { return {0.0, hi, true, false}; }
constexpr Range nonnegative(double hi = kInf) { return {0.0, hi, false, false}; }

}  // namespace scene_keys

/// What a key's value is.
enum class KeyKind {
  kNumber,   ///< one number in `range`
  kInteger,  ///< one integer in `range`
  kNumbers,  ///< a list of min_count … max_count numbers, each in `range`
  kChoice,   ///< one of the words of `choices`
  kText,     ///< anything else (a string, a map, a number or a word): `allowed` says what
};

/// Who reads a key: the table's own loop (read_table_keys: the key is read, checked,
/// recorded and stored through `field` with no other code), or the scene reader's code, for
/// a key whose presence, default or meaning depends on other keys (still with the row's
/// path, range and default).
enum class KeyRead { kTable, kCode };

/// Where a key's value lives in a Scene: one accessor for its kind, or none. The default of
/// an optional key is the field of a default-constructed Scene.
struct KeyField {
  double* (*number)(Scene&) = nullptr;
  int* (*integer)(Scene&) = nullptr;
  int (*get_choice)(const Scene&) = nullptr;  ///< index of the value in the row's choices
  void (*set_choice)(Scene&, int) = nullptr;
  bool empty() const { return !number && !integer && !get_choice; }
};

struct SceneKey {
  /// Dotted path; a `*` stands for each word of `instances` ("robot.*.length").
  std::string_view path{};
  std::string_view instances{};  ///< the words `*` stands for, space-separated
  /// The table of docs/user/configuration.md the key is listed in (a region name of the
  /// generated tables: "gait", "motion-start", ...).
  std::string_view section{};
  KeyKind kind = KeyKind::kNumber;
  scene_keys::Range range{};                 ///< kNumber, kInteger, kNumbers: of each number
  std::size_t min_count = 0, max_count = 0;  ///< kNumbers
  std::string_view choices{};  ///< kChoice: the words, space-separated, in the field's order
  /// UDUNITS-2 unit of a number ("m", "1", "N s/m"); "" for words, or for a unit that cannot
  /// be written (contact.stiffness: N/m^e with the scene's exponent e).
  std::string_view unit{};
  bool required = false;  ///< no default: a scene must give the key
  /// The docs' default when neither `required` nor the field says it all ("`[0, 0, 0]`",
  /// "`contact.friction_coefficient`", "required without `cycle_durations`").
  std::string_view default_text{};
  /// The docs' allowed values when the kind and range do not say them all; `when` prefixes
  /// them with the condition under which the key applies ("stairs").
  std::string_view allowed_text{};
  std::string_view when{};
  /// The docs' meaning column (Markdown; links from the repository's root, docs/theory/...).
  std::string_view meaning{};
  KeyRead read = KeyRead::kCode;
  KeyField field{};
};

/// Every scene key, in the docs' order within each section; rows added by AddedSceneKey
/// come last. References stay valid while a row is added.
const std::deque<SceneKey>& scene_key_table();

/// The row of the dotted key `path` (a path with `*` as declared, or one instance of it:
/// "robot.coxa.length"); null when none.
const SceneKey* find_scene_key(std::string_view path);

/// The row of `path`, which the reader's code names: throws std::logic_error when it is not
/// in the table (a programming error, found by the first scene read).
const SceneKey& scene_key(std::string_view path);

/// The row's path with `*` replaced by `instance`.
std::string key_path(const SceneKey& key, std::string_view instance = {});

/// The words of a space-separated list (`choices`, `instances`).
std::vector<std::string> key_words(std::string_view list);

/// Adds a row to scene_key_table() for the life of the object: the table as a test extends
/// it (tests/hexdyn/config/test_scene_key_table.cpp adds a key and finds it in validate, the
/// resolved configuration and the generated docs). Not thread-safe; one at a time.
class AddedSceneKey {
 public:
  explicit AddedSceneKey(const SceneKey& key);
  ~AddedSceneKey();
  AddedSceneKey(const AddedSceneKey&) = delete;
  AddedSceneKey& operator=(const AddedSceneKey&) = delete;
};

/// Field accessors for the table's rows: the member reached from a Scene through the
/// pointers to members `M...` (&Scene::gait, &GaitParams::stroke_m).
namespace key_fields {

template <auto M, auto... Ms, class T>
constexpr auto& at(T& t) {
  if constexpr (sizeof...(Ms) == 0)
    return t.*M;
  else
    return at<Ms...>(t.*M);
}

template <auto... M>
KeyField number() {
  return {.number = [](Scene& s) -> double* { return &at<M...>(s); }};
}
template <auto... M>
KeyField integer() {
  return {.integer = [](Scene& s) -> int* { return &at<M...>(s); }};
}
/// An enum whose enumerators are in the order of the row's choices.
template <auto... M>
KeyField choice() {
  return {.get_choice = [](const Scene& s) { return static_cast<int>(at<M...>(s)); },
          .set_choice =
              [](Scene& s, int i) {
                auto& v = at<M...>(s);
                v = static_cast<std::remove_reference_t<decltype(v)>>(i);
              }};
}
/// A bool whose choices are written true-word first ("true false", "deflate none").
template <auto... M>
KeyField flag() {
  return {.get_choice = [](const Scene& s) { return at<M...>(s) ? 0 : 1; },
          .set_choice = [](Scene& s, int i) { at<M...>(s) = i == 0; }};
}

}  // namespace key_fields

}  // namespace hexdyn
