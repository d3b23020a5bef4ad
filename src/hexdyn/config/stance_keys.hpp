#pragma once
/// \file stance_keys.hpp
/// Internal to config/: a URDF robot's robot.nominal_pose (config/robot_config.hpp) read and
/// checked against the robot's legs and joints, and the stance it gave recorded in the
/// resolved configuration.
#include <span>

#include "hexdyn/config/robot_config.hpp"
#include "hexdyn/config/scene_key_reader.hpp"

namespace hexdyn {

/// robot.nominal_pose by leg (config/leg_keys.hpp: one for every leg, one per leg of the
/// robot in leg order, or a map by leg name), each pose one angle per joint of its leg and
/// inside the joint limits, else one line naming the key, the value and what is allowed. The
/// legs it names stand at the pose given: their stances in `loaded` are replaced and the
/// stance radius and depth are taken anew.
void read_nominal_pose(scene_keys::Reader& r, LoadedUrdfRobot& loaded);

/// auto.robot.nominal_pose of the resolved configuration: for each leg, the pose its stance
/// stood at, how it was obtained, its radius and depth (model/stance.hpp), written anew by
/// every read (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration).
void record_stance(scene_keys::Reader& r, std::span<const NominalStance> stance);

}  // namespace hexdyn
