#pragma once
// The robot model the dynamics functions of the Python module (dynamics.cpp) compute with: the
// robot `hexdyn run` builds from a scene, any robot the URDF reader takes (2 to 8 legs of 3 to
// 6 revolute or prismatic joints) or the YAML robot.
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn_python {

/// The model of the scene file `scene_path` with `overrides`: the scene loaded and validated as
/// `hexdyn run` loads it (config.hpp load_scene), its robot built (build_robot_model). Throws
/// hexdyn::ConfigError, one line naming the file and key, for a bad key or description.
hexdyn::RobotModel scene_dynamics_model(const std::string& scene_path,
                                        const std::vector<hexdyn::Override>& overrides);

}  // namespace hexdyn_python
