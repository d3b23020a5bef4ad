#include "hexdyn/config/cases.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <system_error>

#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/paths.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

std::string joined(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}

/// The YAML text a case gives `key`: p/q evaluated, a robot.urdf path made absolute from
/// the study file.
std::string case_value(const YAML::Node& v, const std::string& key, const std::string& file) {
  std::string text = yaml_inline(v);
  if (!v.IsScalar() || is_quoted_number(v)) return text;  // a quoted number stays a string
  if (const auto q = parse_fraction(v.Scalar())) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", *q);
    return buf;
  }
  if (key == "robot.urdf" && !v.Scalar().empty()) {
    std::error_code ec;
    const fs::path beside = path_beside(file, v.Scalar());
    const fs::path abs = fs::absolute(beside, ec);
    return ec ? beside.string() : abs.lexically_normal().string();
  }
  return text;
}

}  // namespace

std::vector<Override> CaseList::overrides(std::size_t c) const {
  std::vector<Override> out;
  for (std::size_t k = 0; k < keys.size(); ++k) out.push_back({keys[k], values[c][k]});
  return out;
}

std::string CaseList::text(std::size_t c) const {
  std::string s;
  for (std::size_t k = 0; k < keys.size(); ++k) s += (k ? ", " : "") + keys[k] + "=" + values[c][k];
  return s;
}

CaseList read_case_list(const SpecReader& r, const YAML::Node& cases, const std::string& path,
                        const std::string& file) {
  if (!cases.IsSequence() || cases.size() == 0)
    r.fail_value(path, cases, "a non-empty list of maps {label: NAME, key: value, ...}");
  CaseList out;
  std::map<std::string, std::size_t> seen;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string here = path + "[" + std::to_string(k) + "]";
    const YAML::Node c = cases[k];
    if (!c.IsMap()) r.fail_value(here, c, "a map {label: NAME, key: value, ...}");
    const YAML::Node label = c["label"];
    if (!label.IsDefined() || label.IsNull())
      r.fail(here + ".label", "missing, this key is required (the case's name in the file)");
    if (!label.IsScalar() || label.Scalar().empty() ||
        label.Scalar().find_first_of("\n\r") != std::string::npos)
      r.fail_value(here + ".label", label, "a non-empty single-line name");
    const auto [it, inserted] = seen.emplace(label.Scalar(), k);
    if (!inserted)
      r.fail_value(
          here + ".label", label,
          "a label no other case has (cases[" + std::to_string(it->second) + "] has it too)");
    std::vector<std::string> keys, values;
    for (const auto& kv : c) {
      const std::string key = kv.first.Scalar();
      if (key == "label") continue;
      for (const auto& part : split_key_path(key))
        if (part.empty()) r.fail(here + "." + key, "empty key in the dotted path");
      const YAML::Node v = kv.second;
      bool list_of_values = v.IsSequence();
      for (std::size_t e = 0; list_of_values && e < v.size(); ++e) list_of_values = v[e].IsScalar();
      if (!v.IsScalar() && !list_of_values)
        r.fail_value(here + "." + key, v,
                     "a single value or a list of values (write nested keys as dotted paths)");
      keys.push_back(key);
      values.push_back(case_value(v, key, file));
    }
    if (keys.empty()) r.fail(here, "got only a label, expected at least one key the case sets");
    if (k == 0) {
      out.keys = keys;
    } else if (std::set<std::string>(keys.begin(), keys.end()) !=
               std::set<std::string>(out.keys.begin(), out.keys.end())) {
      r.fail(here, "got keys " + joined(keys) + ", expected the keys of cases[0] (" +
                       joined(out.keys) + "): every case sets the same keys");
    }
    std::vector<std::string> ordered;  // in the order of the first case
    for (const auto& key : out.keys)
      ordered.push_back(values[static_cast<std::size_t>(std::find(keys.begin(), keys.end(), key) -
                                                        keys.begin())]);
    out.values.push_back(std::move(ordered));
    out.labels.push_back(label.Scalar());
  }
  return out;
}

void check_cases_on(const SpecReader& r, const CaseList& cases, const YAML::Node& tree,
                    const std::string& path) {
  // Each case's keys set on the base's SceneTree, which shares every map they do not change
  // (no copy of the base per case); the YAML tree when a key runs through a non-map value.
  const SceneTree base(tree);
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const std::string source = "case " + cases.labels[c];
    try {
      SceneTree one = base;
      bool set = true;
      for (const Override& ov : cases.overrides(c)) {
        const YAML::Node value =
            parse_yaml_checked(ov.value, "--set " + ov.key_path + "=" + ov.value);
        set = set && one.set(split_key_path(ov.key_path), SceneTree::convert(value));
      }
      if (set) {
        (void)scene_from_tree(one, source, false);
      } else {
        YAML::Node copy = YAML::Clone(tree);
        for (const Override& ov : cases.overrides(c)) apply_override(copy, ov, source);
        (void)scene_from_yaml(copy, source, false);
      }
    } catch (const Error& e) {
      std::string why = e.what();
      if (why.rfind(source + ": ", 0) == 0) why = why.substr(source.size() + 2);
      r.fail(path + "[" + std::to_string(c) + "] (" + cases.labels[c] + ": " + cases.text(c) + ")",
             why);
    }
  }
}

void add_case_inputs(std::vector<InputFile>& inputs, const CaseList& cases) {
  for (std::size_t k = 0; k < cases.keys.size(); ++k)
    if (cases.keys[k] == "robot.urdf")
      for (const auto& values : cases.values)
        if (why_not_regular_file(values[k]) == std::nullopt) add_input(inputs, "URDF", values[k]);
}

}  // namespace hexdyn
