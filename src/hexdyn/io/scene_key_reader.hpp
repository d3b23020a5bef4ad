#pragma once
/// \file scene_key_reader.hpp
/// Internal to io/config.cpp: the key-by-key reader of a scene tree. It reads keys by
/// dotted path with their allowed ranges, records every key asked for (so an unknown key
/// is named with the allowed ones) and builds the resolved tree with the defaults filled
/// in. Every failure throws ConfigError "SOURCE: key.path: got VALUE, expected WHAT".
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/spatial.hpp"
#include "hexdyn/io/config.hpp"
#include "hexdyn/io/yaml_load.hpp"

namespace hexdyn::scene_keys {

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
inline Range closed(double lo, double hi) { return {lo, hi, false, false}; }
inline Range positive(double hi = kInf) { return {0.0, hi, true, false}; }
inline Range nonnegative(double hi = kInf) { return {0.0, hi, false, false}; }

/// Reads keys by dotted path, records every key it was asked for (so unknown keys can
/// be reported with the allowed ones), and builds the resolved tree with defaults.
class Reader {
 public:
  Reader(const YAML::Node& root, std::string source) : root_(root), source_(std::move(source)) {
    resolved_ = YAML::Node(YAML::NodeType::Map);
  }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw ConfigError(source_ + ": " + path + ": " + what);
  }
  [[noreturn]] void fail_value(const std::string& path, const YAML::Node& node,
                               const std::string& expected) const {
    fail(path, "got " + yaml_inline(node) + ", expected " + expected);
  }

  /// True when the key holds the scalar `word` (then recorded as resolved); the key
  /// counts as asked for either way.
  bool holds_word(const std::string& path, const std::string& word) {
    asked_.insert(path);
    const YAML::Node n = lookup(path);
    if (!n.IsDefined() || !n.IsScalar() || n.Scalar() != word) return false;
    set_resolved(path, YAML::Node(word));
    return true;
  }

  /// True when the key is present and not null, without counting it as asked for (for a
  /// mapping whose own keys are then read and checked one by one).
  bool given(const std::string& path) const {
    const YAML::Node n = lookup(path);
    return n.IsDefined() && !n.IsNull();
  }

  bool has(const std::string& path) {
    asked_.insert(path);
    const YAML::Node n = lookup(path);
    return n.IsDefined() && !n.IsNull();
  }

  double number(const std::string& path, Range r) { return number_impl(path, r, nullptr); }
  double number_or(const std::string& path, double def, Range r) {
    return number_impl(path, r, &def);
  }

  int integer(const std::string& path, int lo, int hi, const int* def = nullptr) {
    const YAML::Node n = fetch(path, def != nullptr);
    const std::string expected =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!n.IsDefined()) {
      set_resolved(path, YAML::Node(*def));
      return *def;
    }
    long long v = 0;
    if (!n.IsScalar() || !YAML::convert<long long>::decode(n, v) || v < lo || v > hi)
      fail_value(path, n, expected);
    set_resolved(path, YAML::Node(v));
    return static_cast<int>(v);
  }

  std::vector<double> numbers(const std::string& path, std::size_t min_n, std::size_t max_n,
                              Range r, const std::vector<double>* def = nullptr) {
    const YAML::Node n = fetch(path, def != nullptr);
    std::string expected =
        "a list of " +
        (min_n == max_n ? std::to_string(min_n)
                        : std::to_string(min_n) + " to " + std::to_string(max_n)) +
        " numbers, each " + r.describe();
    std::vector<double> out;
    if (!n.IsDefined()) {
      out = *def;
    } else {
      if (!n.IsSequence() || n.size() < min_n || n.size() > max_n) fail_value(path, n, expected);
      for (const auto& e : n) {
        double v = 0.0;
        if (!e.IsScalar() || !YAML::convert<double>::decode(e, v) || !std::isfinite(v) ||
            !r.contains(v))
          fail_value(path, n, expected);
        out.push_back(v);
      }
    }
    YAML::Node seq(YAML::NodeType::Sequence);
    for (double v : out) seq.push_back(v);
    seq.SetStyle(YAML::EmitterStyle::Flow);
    set_resolved(path, seq);
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
    const YAML::Node n = fetch(path, def != nullptr);
    std::string expected = "one of";
    for (std::size_t i = 0; i < allowed.size(); ++i) expected += (i ? ", " : " ") + allowed[i];
    std::string v;
    if (!n.IsDefined()) {
      v = *def;
    } else {
      if (!n.IsScalar()) fail_value(path, n, expected);
      v = n.Scalar();
      bool ok = false;
      for (const auto& a : allowed) ok = ok || a == v;
      if (!ok) fail_value(path, n, expected);
    }
    set_resolved(path, YAML::Node(v));
    return v;
  }

  std::string string_or(const std::string& path, const std::string& def) {
    const YAML::Node n = fetch(path, true);
    std::string v = def;
    if (n.IsDefined()) {
      if (!n.IsScalar()) fail_value(path, n, "a string");
      v = n.Scalar();
    }
    set_resolved(path, YAML::Node(v));
    return v;
  }

  /// A list of `n` non-empty strings, or nothing when absent.
  std::vector<std::string> strings_or_none(const std::string& path, std::size_t n) {
    const YAML::Node node = fetch(path, true);
    std::vector<std::string> out;
    if (!node.IsDefined()) return out;
    const std::string expected = "a list of " + std::to_string(n) + " names";
    if (!node.IsSequence() || node.size() != n) fail_value(path, node, expected);
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
    const YAML::Node n = fetch(path, true);
    if (n.IsDefined() && (!n.IsScalar() || n.Scalar() != word)) return false;
    set_resolved(path, YAML::Node(word));
    return true;
  }

  /// The node at `path` (undefined when absent), counted as asked for.
  YAML::Node node(const std::string& path) {
    asked_.insert(path);
    return lookup(path);
  }

  /// Writes `value` at `path` of the resolved tree (a value the file did not give as such).
  void record(const std::string& path, const YAML::Node& value) { set_resolved(path, value); }
  void record(const std::string& path, const char* word) { set_resolved(path, YAML::Node(word)); }

  /// Every key of the file must have been asked for; reports the first unknown one.
  void check_unknown() const { walk(root_, ""); }

  const YAML::Node& resolved() const { return resolved_; }
  const std::string& source() const { return source_; }

 private:
  double number_impl(const std::string& path, Range r, const double* def) {
    const YAML::Node n = fetch(path, def != nullptr);
    if (!n.IsDefined()) {
      set_resolved(path, YAML::Node(*def));
      return *def;
    }
    double v = 0.0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, v)) fail_value(path, n, r.describe());
    if (!std::isfinite(v)) fail_value(path, n, "a finite number (" + r.describe() + ")");
    if (!r.contains(v)) fail_value(path, n, r.describe());
    set_resolved(path, YAML::Node(v));
    return v;
  }

  /// The node at `path`; undefined when absent and optional; error when absent and required.
  YAML::Node fetch(const std::string& path, bool optional) {
    asked_.insert(path);
    YAML::Node n = lookup(path);
    if (!n.IsDefined() || n.IsNull()) {
      if (!optional) fail(path, "missing, this key is required");
      return YAML::Node(YAML::NodeType::Undefined);
    }
    return n;
  }

  YAML::Node lookup(const std::string& path) const {
    // Walks with const access only: a const node's operator[] never inserts the key, so
    // the tree needs no copy (a copy per key cost ~10 ms per scene, most of a sweep
    // scenario's time).
    YAML::Node cur = root_;
    std::string so_far;
    for (const auto& key : split_key_path(path)) {
      if (!cur.IsDefined() || cur.IsNull()) return YAML::Node(YAML::NodeType::Undefined);
      if (!cur.IsMap())
        fail_value(so_far.empty() ? "(top level)" : so_far, cur, "a mapping of keys");
      const YAML::Node& here = cur;
      YAML::Node next = here[key];
      if (!next.IsDefined()) return YAML::Node(YAML::NodeType::Undefined);
      cur.reset(next);
      so_far += (so_far.empty() ? "" : ".") + key;
    }
    return cur;
  }

  void set_resolved(const std::string& path, const YAML::Node& value) {
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

  void walk(const YAML::Node& node, const std::string& prefix) const {
    if (!node.IsMap()) return;
    for (const auto& kv : node) {
      const std::string key = kv.first.Scalar();
      const std::string path = prefix.empty() ? key : prefix + "." + key;
      bool known = asked_.count(path) > 0;
      if (!known) {
        for (const auto& a : asked_)
          if (a.rfind(path + ".", 0) == 0) known = true;
      }
      if (!known) {
        std::set<std::string> allowed;
        for (const auto& a : asked_) {
          if (prefix.empty() || a.rfind(prefix + ".", 0) == 0) {
            const std::string rest = prefix.empty() ? a : a.substr(prefix.size() + 1);
            allowed.insert(rest.substr(0, rest.find('.')));
          }
        }
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(path, "unknown key, allowed here: " + list);
      }
      if (asked_.count(path) == 0) walk(kv.second, path);
    }
  }

  YAML::Node root_;
  std::string source_;
  std::set<std::string> asked_;
  YAML::Node resolved_;
};

}  // namespace hexdyn::scene_keys
