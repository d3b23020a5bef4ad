#include "hexdyn/config/table_keys.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace hexdyn::scene_keys {
namespace {

/// The row's default number, from the field of the default Scene.
double default_number(const SceneKey& k) {
  if (!k.field.number)
    throw std::logic_error("scene key " + std::string(k.path) + " has no default field");
  return *k.field.number(const_cast<Scene&>(default_scene()));
}

std::string default_word(const SceneKey& k) {
  const auto words = key_words(k.choices);
  return k.field.get_choice ? words.at(k.field.get_choice(default_scene())) : words.at(0);
}

int choice_index(const SceneKey& k, const std::string& word) {
  const auto words = key_words(k.choices);
  for (std::size_t i = 0; i < words.size(); ++i)
    if (words[i] == word) return static_cast<int>(i);
  return 0;  // choice() accepts only the row's words
}

}  // namespace

const Scene& default_scene() {
  static const Scene d;
  return d;
}

double number_key(Reader& r, const std::string& path) {
  const SceneKey& k = scene_key(path);
  return k.required ? r.number(path, k.range) : r.number_or(path, default_number(k), k.range);
}

double number_key_or(Reader& r, const std::string& path, double def) {
  return r.number_or(path, def, scene_key(path).range);
}

int integer_key(Reader& r, const std::string& path) {
  const SceneKey& k = scene_key(path);
  const int lo = static_cast<int>(k.range.lo), hi = static_cast<int>(k.range.hi);
  if (k.required) return r.integer(path, lo, hi);
  const int def = *k.field.integer(const_cast<Scene&>(default_scene()));
  return r.integer(path, lo, hi, &def);
}

std::vector<double> numbers_key(Reader& r, const std::string& path,
                                const std::vector<double>* def) {
  const SceneKey& k = scene_key(path);
  return r.numbers(path, k.min_count, k.max_count, k.range, def);
}

Vec3 vec3_key(Reader& r, const std::string& path, const Vec3* def) {
  return r.vec3(path, scene_key(path).range, def);
}

std::string choice_key(Reader& r, const std::string& path) {
  const SceneKey& k = scene_key(path);
  const auto words = key_words(k.choices);
  if (k.required) return r.choice(path, words);
  const std::string def = default_word(k);
  return r.choice(path, words, &def);
}

void read_table_keys(Reader& r, Scene& s, std::string_view section) {
  for (const SceneKey& k : scene_key_table()) {
    if (k.read != KeyRead::kTable || k.section != section) continue;
    const std::string path(k.path);
    switch (k.kind) {
      case KeyKind::kNumber:
        *k.field.number(s) = number_key(r, path);
        break;
      case KeyKind::kInteger:
        *k.field.integer(s) = integer_key(r, path);
        break;
      case KeyKind::kChoice:
        k.field.set_choice(s, choice_index(k, choice_key(r, path)));
        break;
      case KeyKind::kNumbers:
      case KeyKind::kText:
        throw std::logic_error("scene key " + path +
                               ": the table reads numbers, integers and "
                               "choices only");
    }
  }
}

YAML::Node in_table_order(const YAML::Node& resolved) {
  const auto& table = scene_key_table();
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& group : resolved) {
    const std::string name = group.first.Scalar();
    const bool read_by_table = std::any_of(table.begin(), table.end(), [&](const SceneKey& k) {
      return k.read == KeyRead::kTable && k.path.starts_with(name + ".");
    });
    if (!read_by_table || !group.second.IsMap()) {
      out[name] = group.second;
      continue;
    }
    std::vector<std::pair<std::size_t, std::string>> keys;  // (row, key), in the order read
    for (const auto& kv : group.second) {
      const SceneKey* row = find_scene_key(name + "." + kv.first.Scalar());
      std::size_t index = 0;  // the row's place in the table (a deque: counted, not subtracted)
      while (index < table.size() && &table[index] != row) ++index;
      keys.emplace_back(row ? index : std::numeric_limits<std::size_t>::max(), kv.first.Scalar());
    }
    std::stable_sort(keys.begin(), keys.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    YAML::Node ordered(YAML::NodeType::Map);
    for (const auto& [row, key] : keys) ordered[key] = group.second[key];
    out[name] = ordered;
  }
  return out;
}

}  // namespace hexdyn::scene_keys
