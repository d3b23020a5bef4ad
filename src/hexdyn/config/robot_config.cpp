#include "hexdyn/config/robot_config.hpp"

#include <yaml-cpp/yaml.h>

#include <deque>
#include <filesystem>
#include <mutex>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/stance.hpp"
#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/process/paths.hpp"

namespace hexdyn {

void resolve_file_relative_keys(YAML::Node& root, const std::string& file) {
  if (!root.IsMap()) return;
  YAML::Node terrain = root["terrain"];
  if (terrain.IsDefined() && terrain.IsMap() && terrain["height_map"].IsDefined() &&
      terrain["height_map"].IsMap()) {
    YAML::Node map_file = terrain["height_map"]["file"];
    if (map_file.IsDefined() && map_file.IsScalar() && !map_file.Scalar().empty()) {
      std::error_code ec;
      const std::string name = map_file.Scalar();
      const std::filesystem::path p = std::filesystem::absolute(path_beside(file, name), ec);
      terrain["height_map"]["file"] = ec ? path_beside(file, name) : p.lexically_normal().string();
    }
  }
  YAML::Node robot = root["robot"];
  if (!robot.IsDefined() || !robot.IsMap()) return;
  YAML::Node urdf = robot["urdf"];
  if (!urdf.IsDefined() || !urdf.IsScalar() || urdf.Scalar().empty())
    return;  // config.cpp reports it
  const std::string& name = urdf.Scalar();
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(path_beside(file, name), ec);
  robot["urdf"] = ec ? path_beside(file, name) : p.lexically_normal().string();
}

namespace {

/// The robots loaded last in this process, by their keys and their file's text.
struct LoadedEntry {
  UrdfRobotKeys keys;
  std::string text;
  LoadedUrdfRobot robot;
};
constexpr std::size_t kLoadedEntries = 8;
std::mutex loaded_mutex;
std::deque<LoadedEntry> loaded_entries;  ///< oldest first

bool same_keys(const UrdfRobotKeys& a, const UrdfRobotKeys& b) {
  return a.path == b.path && a.trunk_link == b.trunk_link && a.forward_axis == b.forward_axis &&
         a.foot_links == b.foot_links && a.foot_offset_m == b.foot_offset_m &&
         a.foot_radius_m == b.foot_radius_m && a.ik_min_margin_m == b.ik_min_margin_m;
}

}  // namespace

LoadedUrdfRobot load_urdf_robot(const UrdfRobotKeys& keys) {
  if (const auto why = why_not_input_file(keys.path))
    throw ConfigError("robot.urdf: got " + keys.path + ", which " + *why +
                      ", expected a URDF file");
  // Read as an input (config/inputs.hpp): while a command runs, the bytes it read first; outside
  // one, the file as it is now. A text and keys loaded before give the robot loaded then (a
  // sweep's scenarios share their robot).
  const InputFile file = read_input_text(keys.path, kMaxUrdfBytes, "a URDF file");
  const std::string& text = *file.text;
  {
    const std::lock_guard<std::mutex> lock(loaded_mutex);
    for (const LoadedEntry& e : loaded_entries)
      if (e.text == text && same_keys(e.keys, keys)) return e.robot;
  }
  UrdfReadOptions opt;
  opt.trunk_link = keys.trunk_link;
  opt.forward_axis = keys.forward_axis;
  opt.foot_links = keys.foot_links;
  opt.foot_offset = keys.foot_offset_m;
  opt.foot_radius = keys.foot_radius_m;
  LoadedUrdfRobot out;
  auto robot = std::make_shared<UrdfRobot>(read_urdf_robot_from_string(text, keys.path, opt));
  auto built = std::make_shared<const RobotModel>(build_robot_model(*robot, keys.ik_min_margin_m));
  const RobotModel& model = *built;
  out.stance.resize(model.legs());
  for (int leg = 0; leg < model.legs(); ++leg) {
    out.stance[leg] = default_nominal_stance(model, leg);
    for (int j = 0; j < model.leg(leg).n_joints; ++j) {
      const int k = model.joint(leg, j);
      const UrdfJoint& joint = robot->legs[leg].joints[j];
      out.effort_limit_Nm[k] = joint.effort_Nm;
      out.damping_Nmsprad[k] = joint.damping_Nmsprad;
      out.friction_Nm[k] = joint.friction_Nm;
      out.joint_names[k] = joint.name;
    }
  }
  const StanceMean mean = stance_mean(out.stance);
  out.stance_radius_m = mean.radius_m;
  out.stance_depth_m = mean.depth_m;
  out.robot = std::move(robot);
  out.model = std::move(built);
  const std::lock_guard<std::mutex> lock(loaded_mutex);
  if (loaded_entries.size() == kLoadedEntries) loaded_entries.pop_front();
  loaded_entries.push_back({keys, text, out});
  return out;
}

}  // namespace hexdyn
