#pragma once
/// \file scene_tree.hpp
/// Internal to config/ and sweep/scenario_factory.cpp: a scene's YAML tree as the
/// key reader (config/scene_key_reader.hpp) walks it, each map's entries held in file order
/// with their key text. A sweep converts its base tree once; a scenario's tree is the base
/// with its axis values set, sharing every map it does not change with the base (setting
/// a key copies only the maps on the key's path), so a scenario neither clones the base
/// tree nor searches yaml-cpp's maps, which compare keys by converting each one to a
/// string.
///
/// The YAML nodes a tree holds are shared with the tree it was made from and never
/// modified; a map changed by `set` is rebuilt as YAML only when asked for (`yaml`).
#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

class SceneTree {
 public:
  struct Node;
  using NodePtr = std::shared_ptr<const Node>;
  struct Entry {
    YAML::Node key;       ///< the key as read
    std::string text;     ///< its text; empty for a key that is not a scalar
    bool scalar = false;  ///< only a scalar key is found by name (as yaml-cpp's operator[])
    NodePtr value;
  };
  struct Node {
    YAML::Node yaml;  ///< the node; for a map changed by `set`, its type and style only
    YAML::NodeType::value type = YAML::NodeType::Undefined;  ///< yaml.Type()
    std::string scalar;                                      ///< a scalar's text (yaml.Scalar())
    std::vector<Entry> entries;  ///< a map's entries in order (empty for anything else)
    std::vector<NodePtr> items;  ///< a sequence's items in order (empty for anything else)
    bool changed = false;        ///< a map whose entries were set after it was read
    bool quoted_number = false;  ///< a string whose text is a number (is_quoted_number)
  };

  /// The tree of `root` (any node; the reader reports a top level that is not a map).
  explicit SceneTree(const YAML::Node& root);
  /// One node converted, to be set into trees (the value of a sweep axis).
  static NodePtr convert(const YAML::Node& node);

  const Node& root() const { return *root_; }

  /// Sets the key path `keys` to `value`, as `root[k1]…[kn] = value` on the YAML tree:
  /// an existing key keeps its place, a new one comes last in its map, and an intermediate
  /// key that is absent or null becomes a map. Returns false, leaving the tree as it was,
  /// when the path is empty or runs through a value that is neither a map nor absent nor
  /// null (the YAML tree's own rules apply there; the caller sets it on the YAML tree).
  bool set(const std::vector<std::string>& keys, const NodePtr& value);

  /// The value of the first entry of `map` whose key is the scalar `key`; null when absent.
  static const Node* find(const Node& map, std::string_view key);
  /// The node as a YAML tree: its own YAML node, or for a changed map, a new map built
  /// from its entries (with the original's style and tag).
  static YAML::Node yaml(const Node& node);

 private:
  NodePtr root_;
};

/// scene_from_yaml (config/config.hpp) of a tree already converted (defined in config/config.cpp).
Scene scene_from_tree(const SceneTree& tree, const std::string& source_name, bool emit_resolved);

}  // namespace hexdyn
