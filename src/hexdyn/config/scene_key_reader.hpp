#pragma once
/// \file scene_key_reader.hpp
/// Internal to config/: the key-by-key reader of a scene tree. It reads keys by dotted path with
/// their allowed ranges (the rows of scene_key_table.hpp, through table_keys.hpp), records every
/// key asked for (so an unknown key is named with the allowed ones) and builds the resolved tree
/// with the defaults filled in. It is a SpecReader (spec_reader.hpp), whose one error format
/// sweep and envelope files share: every failure throws ConfigError "SOURCE: key.path: got
/// VALUE, expected WHAT". Messages are built only
/// when a key fails, and the resolved tree only when asked for: a sweep reads a scene per scenario.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/scene_key_table.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/spec_reader.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/spatial.hpp"

namespace hexdyn::scene_keys {

/// True when `text` is plain decimal notation: [-]digits[.digits][(e|E)[+|-]digits], or
/// for `integer`, [-]digits without a leading zero. yaml-cpp's stream conversion reads
/// such text as std::from_chars does (both round correctly), and other text (a sign +,
/// octal or hex integers, .inf, spaces) is left to yaml-cpp.
inline bool plain_decimal(std::string_view text, bool integer) {
  std::size_t i = (!text.empty() && text[0] == '-') ? 1 : 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return i - from;
  };
  const std::size_t lead = i;
  const std::size_t n = digits();
  if (n == 0) return false;
  if (integer) return i == text.size() && (n == 1 || text[lead] != '0');
  if (i < text.size() && text[i] == '.') {
    ++i;
    if (digits() == 0) return false;
  }
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == text.size();
}

/// YAML::convert<T>::decode of a scalar node, without its string stream for plain decimal
/// text (the same value).
template <class T>
bool decode_scalar(const SceneTree::Node& n, T& v) {
  const std::string& text = n.scalar;
  if (plain_decimal(text, std::is_integral_v<T>)) {
    T x{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
    if (ec == std::errc() && end == text.data() + text.size()) {
      v = x;
      return true;
    }
  }
  return YAML::convert<T>::decode(n.yaml, v);
}

/// Reads keys by dotted path, records every key it was asked for (so unknown keys can
/// be reported with the allowed ones), and builds the resolved tree with defaults.
class Reader : public SpecReader {
 public:
  /// Reads `tree` (which must outlive the reader); with `keep_resolved` false, resolved()
  /// stays an empty map.
  Reader(const SceneTree& tree, std::string source, bool keep_resolved = true)
      : SpecReader(std::move(source)), tree_(tree), keep_resolved_(keep_resolved) {
    resolved_ = YAML::Node(YAML::NodeType::Map);
  }

  /// True when the key holds the scalar `word` (then recorded as resolved); the key
  /// counts as asked for either way.
  bool holds_word(const std::string& path, const std::string& word) {
    const SceneTree::Node* n = ask(path);
    if (!n || n->type != YAML::NodeType::Scalar || n->scalar != word) return false;
    set_resolved(path, word);
    return true;
  }

  /// True when the key is present and not null, without counting it as asked for (for a
  /// mapping whose own keys are then read and checked one by one).
  bool given(const std::string& path) const { return present(lookup(path)); }

  bool has(const std::string& path) { return present(ask(path)); }

  /// The node at `path` (undefined when absent), not counted as asked for: the keys below
  /// it are then read one by one, and an unknown one among them is reported.
  YAML::Node peek(const std::string& path) const {
    const SceneTree::Node* n = lookup(path);
    return present(n) ? SceneTree::yaml(*n) : YAML::Node(YAML::NodeType::Undefined);
  }

  double number(const std::string& path, Range r) { return number_impl(path, r, nullptr); }
  double number_or(const std::string& path, double def, Range r) {
    return number_impl(path, r, &def);
  }

  int integer(const std::string& path, int lo, int hi, const int* def = nullptr) {
    const SceneTree::Node* node = fetch(path, def != nullptr);
    if (!node) {
      set_resolved(path, *def);
      return *def;
    }
    long long v = 0;
    const std::string expected =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (node->quoted_number) fail(path, quoted_number_message(node->yaml, expected));
    if (node->type != YAML::NodeType::Scalar || !decode_scalar(*node, v) || v < lo || v > hi)
      fail_value(path, SceneTree::yaml(*node), expected);
    set_resolved(path, v);
    return static_cast<int>(v);
  }

  std::vector<double> numbers(const std::string& path, std::size_t min_n, std::size_t max_n,
                              Range r, const std::vector<double>* def = nullptr) {
    const SceneTree::Node* node = fetch(path, def != nullptr);
    const auto bad = [&] {
      fail_value(path, SceneTree::yaml(*node),
                 "a list of " +
                     (min_n == max_n ? std::to_string(min_n)
                                     : std::to_string(min_n) + " to " + std::to_string(max_n)) +
                     " numbers, each " + r.describe());
    };
    std::vector<double> out;
    if (!node) {
      out = *def;
    } else {
      const auto& items = node->items;
      if (node->type != YAML::NodeType::Sequence || items.size() < min_n || items.size() > max_n)
        bad();
      out.reserve(items.size());
      for (const auto& e : items) {
        if (e->quoted_number)
          fail(path + "[" + std::to_string(out.size()) + "]",
               quoted_number_message(e->yaml, r.describe()));
        double v = 0.0;
        if (e->type != YAML::NodeType::Scalar || !decode_scalar(*e, v) || !std::isfinite(v) ||
            !r.contains(v))
          bad();
        out.push_back(v);
      }
    }
    if (keep_resolved_) {
      YAML::Node seq(YAML::NodeType::Sequence);
      for (double v : out) seq.push_back(v);
      seq.SetStyle(YAML::EmitterStyle::Flow);
      set_resolved(path, seq);
    }
    return out;
  }

  Vec3 vec3(const std::string& path, Range r, const Vec3* def = nullptr) {
    std::vector<double> d;
    if (def) d = {def->x(), def->y(), def->z()};
    const auto v = numbers(path, 3, 3, r, def ? &d : nullptr);
    return Vec3(v[0], v[1], v[2]);
  }

  std::string choice(const std::string& path, const std::vector<std::string>& allowed,
                     const std::string* def = nullptr) {
    const SceneTree::Node* node = fetch(path, def != nullptr);
    std::string v;
    if (!node) {
      v = *def;
    } else {
      bool ok = node->type == YAML::NodeType::Scalar;
      if (ok) {
        v = node->scalar;
        ok = std::find(allowed.begin(), allowed.end(), v) != allowed.end();
      }
      if (!ok) {
        std::string expected = "one of";
        for (std::size_t i = 0; i < allowed.size(); ++i) expected += (i ? ", " : " ") + allowed[i];
        fail_value(path, SceneTree::yaml(*node), expected);
      }
    }
    set_resolved(path, v);
    return v;
  }

  std::string string_or(const std::string& path, const std::string& def) {
    const SceneTree::Node* node = fetch(path, true);
    std::string v = def;
    if (node) {
      if (node->type != YAML::NodeType::Scalar)
        fail_value(path, SceneTree::yaml(*node), "a string");
      v = node->scalar;
    }
    set_resolved(path, v);
    return v;
  }

  /// A list of `n` non-empty strings, or nothing when absent.
  std::vector<std::string> strings_or_none(const std::string& path, std::size_t n) {
    return strings_or_none(path, n, n);
  }
  /// A list of min_n to max_n non-empty names, or none.
  std::vector<std::string> strings_or_none(const std::string& path, std::size_t min_n,
                                           std::size_t max_n) {
    const SceneTree::Node* found = fetch(path, true);
    std::vector<std::string> out;
    if (!found) return out;
    const YAML::Node node = SceneTree::yaml(*found);
    const std::string expected = "a list of " + std::to_string(min_n) +
                                 (max_n == min_n ? std::string() : " to " + std::to_string(max_n)) +
                                 " names";
    if (!node.IsSequence() || node.size() < min_n || node.size() > max_n)
      fail_value(path, node, expected);
    YAML::Node seq(YAML::NodeType::Sequence);
    for (const auto& e : node) {
      if (!e.IsScalar() || e.Scalar().empty()) fail_value(path, node, expected);
      out.push_back(e.Scalar());
      seq.push_back(e.Scalar());
    }
    seq.SetStyle(YAML::EmitterStyle::Flow);
    set_resolved(path, seq);
    return out;
  }

  /// True when the key is absent or holds the word `word` (then recorded as `word` in the
  /// resolved tree); false when it holds anything else.
  bool absent_or_word(const std::string& path, const std::string& word) {
    const SceneTree::Node* n = fetch(path, true);
    if (n && (n->type != YAML::NodeType::Scalar || n->scalar != word)) return false;
    set_resolved(path, word);
    return true;
  }

  /// The node at `path` (undefined when absent), counted as asked for.
  YAML::Node node(const std::string& path) {
    const SceneTree::Node* n = ask(path);
    return n ? SceneTree::yaml(*n) : YAML::Node(YAML::NodeType::Undefined);
  }

  /// Writes `value` at `path` of the resolved tree (a value the file did not give as such).
  void record(const std::string& path, const YAML::Node& value) { set_resolved(path, value); }
  void record(const std::string& path, const char* word) { set_resolved(path, word); }

  /// Every key of the file must have been asked for; reports the first unknown one.
  void check_unknown() {
    std::sort(reached_.begin(), reached_.end(),
              [](const Reached& a, const Reached& b) { return std::less<>()(a.node, b.node); });
    walk(tree_.root(), "");
  }

  const YAML::Node& resolved() const { return resolved_; }

 private:
  double number_impl(const std::string& path, Range r, const double* def) {
    const SceneTree::Node* node = fetch(path, def != nullptr);
    if (!node) {
      set_resolved(path, *def);
      return *def;
    }
    if (node->quoted_number) fail(path, quoted_number_message(node->yaml, r.describe()));
    double v = 0.0;
    // A p/q fraction (parse_fraction) is its value, as in `--set` and sweep files: messages
    // show the number those write in its place (fraction_to_number_text), so that a scene
    // file, `--set` and a sweep refuse a value with the same line.
    YAML::Node shown = node->yaml;
    if (node->type == YAML::NodeType::Scalar && !decode_scalar(*node, v)) {
      if (const auto q = parse_fraction(node->scalar)) {
        v = *q;
        shown = YAML::Node(fraction_to_number_text(node->scalar));
      } else {
        fail_value(path, SceneTree::yaml(*node), r.describe());
      }
    }
    if (node->type != YAML::NodeType::Scalar)
      fail_value(path, SceneTree::yaml(*node), r.describe());
    if (!std::isfinite(v)) fail_value(path, shown, "a finite number (" + r.describe() + ")");
    if (!r.contains(v)) fail_value(path, shown, r.describe());
    set_resolved(path, v);
    return v;
  }

  static bool present(const SceneTree::Node* n) {
    return n && n->type != YAML::NodeType::Undefined && n->type != YAML::NodeType::Null;
  }

  /// The node at `path`; null when absent (or null) and optional; error when absent and
  /// required.
  const SceneTree::Node* fetch(const std::string& path, bool optional) {
    const SceneTree::Node* n = ask(path);
    if (present(n)) return n;
    if (!optional) fail(path, "missing, this key is required");
    return nullptr;
  }

  /// The node at `path`, counted as asked for.
  const SceneTree::Node* ask(const std::string& path) {
    asked_.push_back(path);
    return lookup(path, &reached_);
  }

  /// The node at `path`, null when absent; error when the path runs through a value that
  /// is not a map. Appends each node it reaches to `reached`.
  struct Reached {
    const SceneTree::Node* node;
    bool last;  ///< reached by the path's last key
  };
  const SceneTree::Node* lookup(const std::string& path,
                                std::vector<Reached>* reached = nullptr) const {
    const SceneTree::Node* cur = &tree_.root();
    if (path.empty()) return cur;
    for (std::size_t begin = 0;;) {
      const std::size_t dot = std::min(path.find('.', begin), path.size());
      if (!present(cur)) return nullptr;
      if (cur->type != YAML::NodeType::Map) {
        std::string so_far;  // the keys before this one, joined
        if (begin > 0)
          for (const auto& key : split_key_path(path.substr(0, begin - 1)))
            so_far += (so_far.empty() ? "" : ".") + key;
        fail_not_map(so_far, SceneTree::yaml(*cur));
      }
      cur = SceneTree::find(*cur, std::string_view(path).substr(begin, dot - begin));
      if (cur && reached) reached->push_back({cur, dot == path.size()});
      if (!cur || dot == path.size()) return cur;
      begin = dot + 1;
    }
  }

  /// Writes a value into the resolved tree when it is kept.
  template <class T>
  void set_resolved(const std::string& path, const T& value) {
    if (keep_resolved_) put_resolved(path, YAML::Node(value));
  }

  void put_resolved(const std::string& path, const YAML::Node& value) {
    const auto keys = split_key_path(path);
    YAML::Node cur = resolved_;
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      YAML::Node next = cur[keys[i]];
      if (!next.IsMap()) {
        cur[keys[i]] = YAML::Node(YAML::NodeType::Map);
        next.reset(cur[keys[i]]);
      }
      cur.reset(next);
    }
    cur[keys.back()] = value;
  }

  /// A key is known when it was asked for or a key below it was. The lookups of the keys
  /// asked for reached the entries they name (a key asked for, `last`, or one above it);
  /// an entry none reached (a key repeated in a map, for one) is judged by the paths asked.
  void walk(const SceneTree::Node& node, const std::string& prefix) {
    if (node.type != YAML::NodeType::Map) return;
    for (const SceneTree::Entry& kv : node.entries) {
      if (kv.value->type == YAML::NodeType::Null) continue;  // null counts as absent
      const auto [from, to] = std::equal_range(
          reached_.begin(), reached_.end(), Reached{kv.value.get(), false},
          [](const Reached& a, const Reached& b) { return std::less<>()(a.node, b.node); });
      bool asked = std::any_of(from, to, [](const Reached& r) { return r.last; });
      if (asked) continue;  // known, and nothing below it is read
      const std::string& key = kv.text;
      const std::string path = prefix.empty() ? key : prefix + "." + key;
      bool known = from != to;
      if (!known) {
        if (!asked_sorted_) {
          std::sort(asked_.begin(), asked_.end());
          asked_sorted_ = true;
        }
        asked = std::binary_search(asked_.begin(), asked_.end(), path);
        known = asked;
        if (!known) {  // a key asked for below this one: the first in order after "path."
          const std::string below = path + ".";
          const auto it = std::lower_bound(asked_.begin(), asked_.end(), below);
          known = it != asked_.end() && it->rfind(below, 0) == 0;
        }
      }
      if (!known) {
        std::vector<std::string> allowed;
        for (const auto& a : asked_) {
          if (prefix.empty() || a.rfind(prefix + ".", 0) == 0) {
            const std::string rest = prefix.empty() ? a : a.substr(prefix.size() + 1);
            allowed.push_back(rest.substr(0, rest.find('.')));
          }
        }
        fail_unknown(path, allowed);
      }
      if (!asked) walk(*kv.value, path);
    }
  }

  const SceneTree& tree_;
  bool keep_resolved_ = true;
  std::vector<std::string> asked_;  ///< the paths asked for (sorted when an entry needs them)
  bool asked_sorted_ = false;
  std::vector<Reached> reached_;  ///< by node once check_unknown starts
  YAML::Node resolved_;
};

}  // namespace hexdyn::scene_keys
