#include "dynamics_model.hpp"

namespace hexdyn_python {

hexdyn::RobotModel scene_dynamics_model(const std::string& scene_path,
                                        const std::vector<hexdyn::Override>& overrides) {
  return hexdyn::build_robot_model(hexdyn::load_scene(scene_path, overrides).robot);
}

}  // namespace hexdyn_python
