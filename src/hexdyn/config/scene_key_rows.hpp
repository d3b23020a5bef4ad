#pragma once
/// \file scene_key_rows.hpp
/// Internal to config/: the functions that append the rows of scene_key_table(), one per
/// file of rows, in the docs' order.
#include <deque>

#include "hexdyn/config/scene_key_table.hpp"

namespace hexdyn {

void add_robot_key_rows(std::deque<SceneKey>& table);            ///< scene_key_rows_robot.cpp
void add_terrain_gait_motion_rows(std::deque<SceneKey>& table);  ///< scene_key_rows.cpp
void add_run_key_rows(std::deque<SceneKey>& table);              ///< scene_key_rows_run.cpp

}  // namespace hexdyn
