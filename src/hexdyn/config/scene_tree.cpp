#include "hexdyn/config/scene_tree.hpp"

#include "hexdyn/config/yaml_load.hpp"

namespace hexdyn {
namespace {

using Node = SceneTree::Node;
using NodePtr = SceneTree::NodePtr;

SceneTree::Entry new_entry(const std::string& key, NodePtr value) {
  return {YAML::Node(key), key, true, std::move(value)};
}

/// `map` (a copy) with keys[i…] set to `value`; null when the path runs through a value
/// that is neither a map nor absent nor null.
NodePtr set_in(const Node& map, const std::vector<std::string>& keys, std::size_t i,
               const NodePtr& value) {
  if (map.type != YAML::NodeType::Map) return nullptr;
  auto copy = std::make_shared<Node>(map);  // the entries' values stay shared
  copy->changed = true;
  SceneTree::Entry* entry = nullptr;
  for (auto& e : copy->entries)
    if (e.scalar && e.text == keys[i]) {
      entry = &e;
      break;
    }
  NodePtr below = value;
  if (i + 1 < keys.size()) {
    if (entry && entry->value->type != YAML::NodeType::Undefined &&
        entry->value->type != YAML::NodeType::Null) {
      below = set_in(*entry->value, keys, i + 1, value);
    } else {  // an absent or null intermediate key becomes a new (empty) map
      Node empty;
      empty.yaml = YAML::Node(YAML::NodeType::Map);
      empty.type = YAML::NodeType::Map;
      below = set_in(empty, keys, i + 1, value);
    }
    if (!below) return nullptr;
  }
  if (entry)
    entry->value = std::move(below);
  else
    copy->entries.push_back(new_entry(keys[i], std::move(below)));
  return copy;
}

/// The node as a YAML tree of its own (shares nothing with the tree it was read from).
YAML::Node detached(const Node& node) {
  return node.changed ? SceneTree::yaml(node) : YAML::Clone(node.yaml);
}

}  // namespace

SceneTree::SceneTree(const YAML::Node& root) : root_(convert(root)) {}

NodePtr SceneTree::convert(const YAML::Node& node) {
  auto out = std::make_shared<Node>();
  out->yaml = node;
  out->type = node.Type();
  if (node.IsScalar()) {
    out->scalar = node.Scalar();
    out->quoted_number = is_quoted_number(node);
  }
  if (node.IsMap()) {
    out->entries.reserve(node.size());
    for (auto it = node.begin(); it != node.end(); ++it)
      out->entries.push_back(
          {it->first, it->first.Scalar(), it->first.IsScalar(), convert(it->second)});
  } else if (node.IsSequence()) {
    out->items.reserve(node.size());
    for (const YAML::Node& item : node) out->items.push_back(convert(item));
  }
  return out;
}

bool SceneTree::set(const std::vector<std::string>& keys, const NodePtr& value) {
  if (keys.empty()) return false;
  NodePtr root = set_in(*root_, keys, 0, value);
  if (!root) return false;
  root_ = std::move(root);
  return true;
}

const Node* SceneTree::find(const Node& map, std::string_view key) {
  for (const Entry& e : map.entries)
    if (e.scalar && e.text == key) return e.value.get();
  return nullptr;
}

YAML::Node SceneTree::yaml(const Node& node) {
  if (!node.changed) return node.yaml;
  YAML::Node map(YAML::NodeType::Map);
  map.SetStyle(node.yaml.Style());
  map.SetTag(node.yaml.Tag());
  for (const Entry& e : node.entries) map.force_insert(YAML::Clone(e.key), detached(*e.value));
  return map;
}

}  // namespace hexdyn
