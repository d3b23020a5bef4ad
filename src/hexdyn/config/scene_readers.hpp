#pragma once
/// \file scene_readers.hpp
/// Internal to config/: the readers of the scene's groups of keys, in the order
/// scene_from_tree (config.cpp) calls them. Each reads its keys by their rows of
/// scene_key_table.hpp (table_keys.hpp) and applies the rules of key_rules.hpp.
#include "hexdyn/config/robot_config.hpp"
#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn::scene_keys {

/// robot: the YAML robot, or the robot of `robot.urdf` (then `loaded` holds it).
void read_robot(Reader& r, RobotParams& p, LoadedUrdfRobot& loaded);  ///< scene_read_robot.cpp
void read_terrain(Reader& r, TerrainParams& t);                       ///< scene_read_motion.cpp
void read_gait(Reader& r, Scene& s, const LoadedUrdfRobot& urdf);     ///< scene_read_motion.cpp
void read_motion(Reader& r, GaitParams& g, const TerrainParams& t, MotionParams& m);
void read_contact(Reader& r, Scene& s);                                   ///< scene_read_run.cpp
void read_replay(Reader& r, Scene& s);                                    ///< scene_read_run.cpp
void read_allocation(Reader& r, Scene& s, const LoadedUrdfRobot& urdf);   ///< scene_read_run.cpp
void read_drive_train(Reader& r, Scene& s, const LoadedUrdfRobot& urdf);  ///< scene_read_run.cpp
/// The robot's legs: a URDF robot's (its legs read), else the six of the YAML keys
/// (scene_read_run.cpp).
int robot_leg_count(const LoadedUrdfRobot& urdf);
void read_auto_requests(Reader& r);     ///< scene_read_run.cpp
void read_output(Reader& r, Scene& s);  ///< scene_read_run.cpp
/// robustness: after the robot, terrain, contact and actuators it perturbs.
void read_robustness(Reader& r, Scene& s);  ///< scene_read_robustness.cpp

}  // namespace hexdyn::scene_keys
