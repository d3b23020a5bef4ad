#include "hexdyn/config/key_units.hpp"

#include "hexdyn/config/scene_key_table.hpp"

namespace hexdyn {

std::string scene_key_units(const std::string& key) {
  const SceneKey* row = find_scene_key(key);
  // A leg's entry of a per-leg list (robot.foot_offset.L3) has the list's unit.
  const std::size_t dot = key.rfind('.');
  if (!row && dot != std::string::npos) {
    row = find_scene_key(key.substr(0, dot));
    if (row && row->kind != KeyKind::kNumbers) row = nullptr;
  }
  if (!row || row->kind == KeyKind::kChoice || row->kind == KeyKind::kText) return "";
  return std::string(row->unit);
}

}  // namespace hexdyn
