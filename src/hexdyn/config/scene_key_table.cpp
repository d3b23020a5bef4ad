#include "hexdyn/config/scene_key_table.hpp"

#include <stdexcept>

#include "hexdyn/config/scene_key_rows.hpp"

namespace hexdyn {
namespace {

std::deque<SceneKey>& table() {
  static std::deque<SceneKey> t = [] {
    std::deque<SceneKey> rows;
    add_robot_key_rows(rows);
    add_terrain_gait_motion_rows(rows);
    add_run_key_rows(rows);
    add_robustness_key_rows(rows);
    return rows;
  }();
  return t;
}

/// True when `path` is the row's path, or the row's path with `*` replaced by one of its
/// instances.
bool matches(const SceneKey& key, std::string_view path) {
  if (key.path == path) return true;
  const std::size_t star = key.path.find('*');
  if (star == std::string_view::npos) return false;
  const std::string_view head = key.path.substr(0, star), tail = key.path.substr(star + 1);
  if (path.size() <= head.size() + tail.size() || !path.starts_with(head) || !path.ends_with(tail))
    return false;
  const std::string_view word = path.substr(head.size(), path.size() - head.size() - tail.size());
  for (const auto& w : key_words(key.instances))
    if (w == word) return true;
  return false;
}

}  // namespace

const std::deque<SceneKey>& scene_key_table() { return table(); }

const SceneKey* find_scene_key(std::string_view path) {
  for (const SceneKey& key : table())
    if (matches(key, path)) return &key;
  return nullptr;
}

const SceneKey& scene_key(std::string_view path) {
  if (const SceneKey* key = find_scene_key(path)) return *key;
  throw std::logic_error("scene key " + std::string(path) +
                         " is not in config/scene_key_table.hpp's table");
}

std::string key_path(const SceneKey& key, std::string_view instance) {
  std::string path(key.path);
  const std::size_t star = path.find('*');
  if (star != std::string::npos) path.replace(star, 1, instance);
  return path;
}

std::vector<std::string> key_words(std::string_view list) {
  std::vector<std::string> words;
  for (std::size_t begin = 0; begin < list.size();) {
    const std::size_t end = std::min(list.find(' ', begin), list.size());
    if (end > begin) words.emplace_back(list.substr(begin, end - begin));
    begin = end + 1;
  }
  return words;
}

AddedSceneKey::AddedSceneKey(const SceneKey& key) { table().push_back(key); }

AddedSceneKey::~AddedSceneKey() { table().pop_back(); }

}  // namespace hexdyn
