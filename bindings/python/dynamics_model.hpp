#pragma once
// The robot model the dynamics functions of the Python module (dynamics.cpp) compute with: the
// robot `hexdyn run` builds from a scene, or, for a URDF robot whose legs the other stages of
// this build do not take yet (legs of other than three revolute joints, more than six legs),
// the part of it the rigid-body dynamics reads (model/urdf_robot.hpp build_dynamics_model),
// from the scene's robot.* keys alone.
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn_python {

/// The model of the scene file `scene_path` with `overrides`:
///  - a YAML robot, or a URDF robot of at most six legs of three revolute joints each: the
///    scene is loaded and validated as `hexdyn run` loads it (config.hpp load_scene) and its
///    robot built (build_robot_model);
///  - another URDF robot: the scene's tree is read (inheritance and overrides applied), its
///    keys robot.urdf, trunk_link, forward_axis, foot_links, foot_offset and foot_radius read
///    as load_scene reads them, the description read and validated by the URDF reader, and
///    the dynamics model built (build_dynamics_model); the scene's other keys are not read.
/// Throws hexdyn::ConfigError, one line naming the file and key, for a bad key or description.
hexdyn::RobotModel scene_dynamics_model(const std::string& scene_path,
                                        const std::vector<hexdyn::Override>& overrides);

}  // namespace hexdyn_python
