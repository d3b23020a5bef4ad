#pragma once
/// \file scene_key_rows.hpp
/// Internal to config/: the functions that append the rows of scene_key_table(), one per
/// file of rows, in the docs' order.
#include <deque>
#include <string_view>

#include "hexdyn/config/scene_key_table.hpp"

namespace hexdyn {

/// Appends rows to a table, each listed in the docs' table `section` (SceneKey::section);
/// a row pushed to the table directly is in none.
class SectionRows {
 public:
  SectionRows(std::deque<SceneKey>& table, std::string_view section)
      : table_(table), section_(section) {}
  void operator()(SceneKey row) const {
    row.section = section_;
    table_.push_back(row);
  }

 private:
  std::deque<SceneKey>& table_;
  std::string_view section_;
};

void add_robot_key_rows(std::deque<SceneKey>& table);            ///< scene_key_rows_robot.cpp
void add_terrain_gait_motion_rows(std::deque<SceneKey>& table);  ///< scene_key_rows.cpp
void add_run_key_rows(std::deque<SceneKey>& table);              ///< scene_key_rows_run.cpp
void add_robustness_key_rows(std::deque<SceneKey>& table);       ///< scene_key_rows_robustness.cpp

}  // namespace hexdyn
