#include "hexdyn/config/stance_keys.hpp"

#include <cmath>

#include "hexdyn/config/leg_keys.hpp"
#include "hexdyn/model/stance.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {

using scene_keys::fmt;

namespace {

/// "[0, -0.07, 1]".
std::string angles_text(const LegVector& q) {
  std::string s = "[";
  for (int j = 0; j < q.size(); ++j) s += (j ? ", " : "") + fmt(q[j]);
  return s + "]";
}

/// The pose given for leg `leg` inside its joints' limits, else one line.
void check_limits(scene_keys::Reader& r, const LegVector& q, const UrdfLeg& l,
                  const std::string& leg) {
  for (int j = 0; j < q.size(); ++j) {
    if (q[j] >= l.joints[j].lower_rad && q[j] <= l.joints[j].upper_rad) continue;
    r.fail("robot.nominal_pose", "got " + angles_text(q) + " for " + leg + ", whose joint " +
                                     l.joints[j].name + " allows [" + fmt(l.joints[j].lower_rad) +
                                     ", " + fmt(l.joints[j].upper_rad) +
                                     "] rad, expected each angle inside its joint's limits");
  }
}

}  // namespace

void read_nominal_pose(scene_keys::Reader& r, LoadedUrdfRobot& loaded) {
  const RobotModel& model = *loaded.model;
  LegKeyShape shape;
  shape.legs = model.legs();
  shape.joints = true;
  for (int leg = 0; leg < model.legs(); ++leg) {
    shape.names[leg] = model.leg(leg).name;
    shape.sizes[leg] = model.leg(leg).n_joints;
  }
  const LegVectorKey key{"robot.nominal_pose", "rad", scene_keys::closed(-2 * M_PI, 2 * M_PI),
                         false};
  const LegKeyValues pose = read_leg_vectors(r, key, shape);
  if (!pose.given) return;
  for (int leg = 0; leg < model.legs(); ++leg) {
    if (!pose.by_leg[leg]) continue;
    const LegVector& q = *pose.by_leg[leg];
    check_limits(r, q, loaded.robot->legs[leg], shape.names[leg]);
    loaded.stance[leg] = stance_at_pose(model, leg, q, "robot.nominal_pose");
  }
  const StanceMean mean = stance_mean(loaded.stance);
  loaded.stance_radius_m = mean.radius_m;
  loaded.stance_depth_m = mean.depth_m;
}

void record_stance(scene_keys::Reader& r, std::span<const NominalStance> stance) {
  YAML::Node legs(YAML::NodeType::Map);
  for (int leg = 0; leg < static_cast<int>(stance.size()); ++leg) {
    const NominalStance& s = stance[leg];
    YAML::Node q(YAML::NodeType::Sequence);
    for (double x : s.q) q.push_back(x);
    q.SetStyle(YAML::EmitterStyle::Flow);
    YAML::Node entry(YAML::NodeType::Map);
    entry["source"] = s.source;
    entry["pose"] = q;
    entry["radius"] = s.radius_m;
    entry["depth"] = s.depth_m;
    entry.SetStyle(YAML::EmitterStyle::Flow);
    legs[leg_name(leg)] = entry;
  }
  r.record("auto.robot.nominal_pose", legs);
}

}  // namespace hexdyn
