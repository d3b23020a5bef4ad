#pragma once
/// \file robot_config.hpp
/// A scene's robot read from its URDF: `robot: {urdf: PATH, ...}` (config.cpp reads the
/// keys, this module resolves the path and loads the description).
///
/// Keys (every one but urdf optional; the YAML robot's keys trunk, coxa, hips, ... are
/// not allowed next to urdf):
///   robot.urdf          the description; a relative path is relative to the file that
///                       names the key (resolved while reading the file, before `inherit:`
///                       merging, so an inherited robot.urdf keeps naming its file); given
///                       by `--set` or in text without a file, relative to the working
///                       directory. The resolved configuration holds the absolute path.
///   robot.trunk_link    the trunk link (default: the root link)
///   robot.forward_axis  "+x" (default, ROS REP-103), "-x", "+y", "-y" of the trunk link
///   robot.foot_links    one link name per leg, each fixed to the last link of a leg chain
///   robot.foot_offset   [x, y, z] m, the foot point in each chain's last link frame; or
///                       one per leg: a list of n [x, y, z] in the order L1 … Ln of the
///                       robot's n legs, or a map {L1: [x, y, z], …, Ln: [x, y, z]} naming
///                       every leg (config/leg_keys.hpp)
///   robot.foot_radius   m, every foot a sphere of this radius centred at its foot point
///                       (default: a sphere <collision> foot's own radius, else 0)
///   robot.nominal_pose  rad, in the description's signs, one position per joint of a leg
///                       ([coxa, femur, tibia] for a leg of three joints): the standing
///                       pose whose horizontal foot distance is gait.foot_lateral's default
///                       and toward which a leg of other than three revolute joints resolves
///                       its redundancy (default: model/stance.hpp "femur level, tibia
///                       plumb", "hanging" for a rolling hip, mid-range on a chain); one for
///                       every leg, a list of n in leg order L1 … Ln, or a map by leg
///                       name (legs not named keep the default); inside the joint limits
///   robot.ik_min_margin as for the YAML robot
/// and, outside robot:, gait.foot_lateral defaults to the stance radius (model/stance.hpp:
/// the mean over the legs at their pose, a fallback leg left out) and
/// allocation.torque_limit to `effort`: the URDF's per-joint effort limits.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"

namespace YAML {
class Node;
}

namespace hexdyn {

struct UrdfRobot;
struct RobotModel;

/// In a tree just read from `file`: a relative robot.urdf becomes an absolute path,
/// resolved beside `file`. Called by the YAML loader on each file of an `inherit:` chain.
void resolve_file_relative_keys(YAML::Node& root, const std::string& file);

/// The robot.* keys of a URDF robot (header comment).
struct UrdfRobotKeys {
  std::string path;
  std::string trunk_link;
  std::string forward_axis = "+x";
  std::vector<std::string> foot_links;
  /// One point for every leg, or one per leg L1 … Ln (UrdfReadOptions::foot_offset).
  std::optional<std::vector<Vec3>> foot_offset_m;
  std::optional<double> foot_radius_m;
  double ik_min_margin_m = 1e-4;
};

/// A loaded URDF robot with its default nominal stance (model/stance.hpp), legs L1 … Ln.
struct LoadedUrdfRobot {
  std::shared_ptr<const UrdfRobot> robot;
  std::shared_ptr<const RobotModel> model;  ///< built from `robot`
  std::vector<NominalStance> stance;        ///< each leg's pose and how it was obtained
  double stance_radius_m = 0.0;             ///< the stance radius, model/stance.hpp stance_mean [m]
  double stance_depth_m = 0.0;              ///< the same legs' mean hip height above the foot [m]
  JointArray<double> effort_limit_Nm{};     ///< +inf: none given
  /// <dynamics damping friction> by joint, 0 when not given [N m s/rad], [N m].
  JointArray<double> damping_Nmsprad{}, friction_Nm{};
  /// The URDF's joint names in flat joint order (/model/joint_names).
  JointArray<std::string> joint_names;
};

/// Reads and validates the description (ConfigError, one line naming the file and the
/// link, joint or chain) and computes every leg's default nominal stance (robot.nominal_pose
/// is read after it, config/stance_keys.hpp). The file is read as an input
/// (config/inputs.hpp read_input_text: the bytes kept while a command runs, else read now);
/// the last few robots loaded are kept by their keys and file text, and the same keys and
/// text give the robot loaded before (shared: a sweep's scenarios parse their URDF once).
LoadedUrdfRobot load_urdf_robot(const UrdfRobotKeys& keys);

}  // namespace hexdyn
