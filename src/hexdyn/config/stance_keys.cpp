#include "hexdyn/config/stance_keys.hpp"

#include <cmath>

#include "hexdyn/config/leg_keys.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {

using scene_keys::fmt;

std::array<std::optional<Vec3>, kLegs> read_nominal_pose(scene_keys::Reader& r) {
  return read_leg_vectors(r, {"robot.nominal_pose", "[coxa, femur, tibia] rad",
                              scene_keys::closed(-2 * M_PI, 2 * M_PI), false});
}

void check_nominal_pose(scene_keys::Reader& r, const std::array<std::optional<Vec3>, kLegs>& pose,
                        const UrdfRobot& robot) {
  for (int leg = 0; leg < static_cast<int>(robot.legs.size()) && leg < kLegs; ++leg) {
    if (!pose[leg]) continue;
    const UrdfLeg& l = robot.legs[leg];
    const Vec3& q = *pose[leg];
    for (int j = 0; j < kJointsPerLeg; ++j) {
      if (q[j] >= l.joints[j].lower_rad && q[j] <= l.joints[j].upper_rad) continue;
      r.fail("robot.nominal_pose", "got [" + fmt(q.x()) + ", " + fmt(q.y()) + ", " + fmt(q.z()) +
                                       "] for " + leg_name(leg) + ", whose joint " +
                                       l.joints[j].name + " allows [" + fmt(l.joints[j].lower_rad) +
                                       ", " + fmt(l.joints[j].upper_rad) +
                                       "] rad, expected each angle inside its joint's limits");
    }
  }
}

void record_stance(scene_keys::Reader& r, std::span<const NominalStance> stance) {
  YAML::Node legs(YAML::NodeType::Map);
  for (int leg = 0; leg < static_cast<int>(stance.size()); ++leg) {
    const NominalStance& s = stance[leg];
    YAML::Node q(YAML::NodeType::Sequence);
    for (int j = 0; j < kJointsPerLeg; ++j) q.push_back(s.q[j]);
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
