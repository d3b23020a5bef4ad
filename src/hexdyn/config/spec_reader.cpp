#include "hexdyn/config/spec_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <set>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {

void SpecReader::fail(const std::string& path, const std::string& what) const {
  throw ConfigError(file_ + ": " + path + ": " + what);
}

void SpecReader::fail_value(const std::string& path, const YAML::Node& node,
                            const std::string& expected) const {
  if (!node.IsDefined()) fail(path, "missing, expected " + expected);
  fail(path, "got " + yaml_for_message(node) + ", expected " + expected);
}

void SpecReader::refuse_quoted_number(const std::string& path, const YAML::Node& node,
                                      const std::string& expected) const {
  if (is_quoted_number(node)) fail(path, quoted_number_message(node, expected));
}

void SpecReader::refuse_quoted_numbers(const std::string& path, const YAML::Node& node,
                                       const std::string& expected) const {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      refuse_quoted_numbers(path + "[" + std::to_string(i) + "]", node[i], expected);
  } else {
    refuse_quoted_number(path, node, expected);
  }
}

void SpecReader::fail_unknown(const std::string& path,
                              const std::vector<std::string>& allowed) const {
  const std::set<std::string> sorted(allowed.begin(), allowed.end());
  std::string list;
  for (const auto& a : sorted) list += (list.empty() ? "" : ", ") + a;
  fail(path, "unknown key, allowed here: " + list);
}

void SpecReader::fail_not_map(const std::string& path, const YAML::Node& node) const {
  fail_value(path.empty() ? "(top level)" : path, node, "a mapping of keys");
}

void SpecReader::check_keys(const YAML::Node& node, const std::string& path,
                            const std::vector<std::string>& allowed) const {
  if (!node.IsMap()) fail_not_map(path, node);
  for (const auto& kv : node) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : yaml_inline(kv.first);
    if (kv.second.IsNull()) continue;  // a key set to null counts as absent, wherever it is
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      fail_unknown(path.empty() ? key : path + "." + key, allowed);
  }
}

}  // namespace hexdyn
