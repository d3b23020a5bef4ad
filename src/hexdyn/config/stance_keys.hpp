#pragma once
/// \file stance_keys.hpp
/// Internal to config/: a URDF robot's robot.nominal_pose (config/robot_config.hpp) read and
/// checked, and the stance it gave recorded in the resolved configuration.
#include <array>
#include <optional>
#include <span>

#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

struct UrdfRobot;

/// robot.nominal_pose by leg (config/leg_keys.hpp: one for every leg, six in leg order, or
/// a map by leg name); none where it is not given.
std::array<std::optional<Vec3>, kLegs> read_nominal_pose(scene_keys::Reader& r);

/// Every given pose inside its leg's joint limits, else one line naming the leg, the joint,
/// the angle and the limits.
void check_nominal_pose(scene_keys::Reader& r, const std::array<std::optional<Vec3>, kLegs>& pose,
                        const UrdfRobot& robot);

/// auto.robot.nominal_pose of the resolved configuration: for each leg, the pose its stance
/// stood at, how it was obtained, its radius and depth (model/stance.hpp), written anew by
/// every read (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration).
void record_stance(scene_keys::Reader& r, std::span<const NominalStance> stance);

}  // namespace hexdyn
