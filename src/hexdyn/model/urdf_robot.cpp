#include "hexdyn/model/urdf_robot.hpp"

#include <sstream>
#include <stdexcept>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

int UrdfRobot::n_joints() const {
  int n = 0;
  for (const UrdfLeg& l : legs) n += l.n_joints();
  return n;
}

namespace {

/// "4 legs of 3, 3, 3, 3 joints"
std::string shape_text(const UrdfRobot& robot) {
  std::string s = std::to_string(robot.n_legs()) + " legs of ";
  for (int leg = 0; leg < robot.n_legs(); ++leg)
    s += (leg ? ", " : "") + std::to_string(robot.legs[leg].n_joints());
  return s + " joints";
}

/// Refuses, in one line, a description the model cannot hold: more bodies than its storage.
void check_fits(const UrdfRobot& robot, std::size_t capacity) {
  const std::size_t bodies = 1 + static_cast<std::size_t>(robot.n_joints());
  if (bodies > capacity)
    throw ConfigError(robot.source_path + ": robot '" + robot.name + "' (" + shape_text(robot) +
                      "): " + std::to_string(bodies) + " bodies, expected at most " +
                      std::to_string(capacity) + " (the bodies a robot model of this build holds)");
}

}  // namespace

RobotModel build_dynamics_model(const UrdfRobot& robot) {
  RobotModel m;
  check_fits(robot, m.parent.size());
  m.leg_geometry = LegGeometry::kChain;
  m.parent[0] = -1;
  m.R_parent_joint[0].setIdentity();
  m.p_parent_joint[0].setZero();
  m.axis[0].setZero();
  m.inertia[0] = robot.trunk;
  m.trunk_only = robot.trunk;
  m.payload = RigidInertia{};
  m.link_length_m = {0.0, 0.0, 0.0};  // kPaperPlanar parameters: unused by a kChain model
  m.d1_m = 0.0;
  // The tree: each leg's chain in turn, body b moved by joint b − 1 (robot_model.hpp).
  int b = 1;
  for (const UrdfLeg& l : robot.legs) {
    for (int j = 0; j < l.n_joints(); ++j, ++b) {
      const UrdfJoint& joint = l.joints[j];
      m.parent[b] = j == 0 ? 0 : b - 1;
      m.p_parent_joint[b] = joint.p_parent_joint;
      m.R_parent_joint[b] = joint.R_parent_joint;
      m.axis[b] = joint.axis;
      m.inertia[b] = joint.inertia;
    }
  }
  // Storage beyond the robot's bodies: no parent, so that no leg starts there.
  for (std::size_t unused = b; unused < m.parent.size(); ++unused) m.parent[unused] = -1;
  try {
    fill_leg_table(m);
  } catch (const std::logic_error& e) {  // a leg layout this build does not simulate
    throw ConfigError(robot.source_path + ": robot '" + robot.name + "' (" + shape_text(robot) +
                      "): " + e.what());
  }
  for (int leg = 0; leg < m.legs(); ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    m.lateral_m[leg] = m.d2_signed_m[leg] = m.d3_signed_m[leg] = 0.0;
    for (int j = 0; j < m.leg(leg).n_joints; ++j) {
      const int k = m.joint(leg, j);
      const UrdfJoint& joint = l.joints[j];
      m.joint_lower_rad[k] = joint.lower_rad;
      m.joint_upper_rad[k] = joint.upper_rad;
      m.effort_limit_Nm[k] = joint.effort_Nm;
      m.velocity_limit_radps[k] = joint.velocity_radps;
      m.joint_source_names[k] = joint.name;
      m.joint_type[k] =
          joint.type == UrdfJointType::kPrismatic ? JointType::kPrismatic : JointType::kRevolute;
    }
    m.p_foot_last[leg] = l.p_foot_last;
    m.foot_radius_m[leg] = l.foot_radius_m;
  }
  m.total_mass_kg = 0.0;
  for (int body = 0; body < m.bodies(); ++body) m.total_mass_kg += m.inertia[body].mass_kg;
  m.p_B_root = robot.p_B_root;
  m.B_R_root = robot.B_R_root;
  return m;
}

RobotModel build_robot_model(const UrdfRobot& robot, double ik_min_margin_m) {
  RobotModel m = build_dynamics_model(robot);
  m.ik_min_margin_m = ik_min_margin_m;
  prepare_leg_chains(m);
  for (int leg = 0; leg < m.legs(); ++leg) {
    Vec3 out = m.R_B_H[leg] * m.leg_ik[leg].outward_H;
    out.z() = 0.0;
    m.hip_outward_B[leg] = out.normalized();
  }
  return m;
}

namespace {

/// The foot of leg l as leg_mapping_text describes it.
std::string foot_text(const UrdfLeg& l) {
  std::ostringstream point, s;
  const Vec3& p = l.p_foot_last;
  point << "(" << p.x() << ", " << p.y() << ", " << p.z() << ") m in " << l.last().link;
  switch (l.foot_kind) {
    case FootSource::kLinkOrigin:
      s << l.foot_source;
      break;
    case FootSource::kFootOffset:
      s << "robot.foot_offset " << point.str();
      break;
    case FootSource::kSphereCollision:
      s << "the sphere <collision> of " << l.foot_source << ", centre " << point.str();
      break;
  }
  if (l.foot_radius_m > 0.0) s << ", sphere foot of radius " << l.foot_radius_m << " m";
  if (!l.foot_check.empty()) s << "; foot check: " << l.foot_check;
  return s.str();
}

/// "  merged into LINK: A, B\n", or nothing when no link is fixed to `link`.
std::string merged_text(const std::string& link, const std::vector<std::string>& merged) {
  if (merged.empty()) return "";
  std::string s = "  merged into " + link + ":";
  for (std::size_t i = 0; i < merged.size(); ++i) s += (i ? ", " : " ") + merged[i];
  return s + "\n";
}

}  // namespace

std::string leg_mapping_text(const UrdfRobot& robot) {
  std::ostringstream s;
  s << merged_text(robot.trunk_link, robot.trunk_merged_links);
  for (int leg = 0; leg < robot.n_legs(); ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    const Vec3& h = l.joints.front().p_parent_joint;
    s << leg_name(leg) << " <- ";
    for (int j = 0; j < l.n_joints(); ++j) s << (j ? " / " : "") << l.joints[j].name;
    s << ", hip (" << h.x() << ", " << h.y() << ", " << h.z() << ") m in the trunk frame, foot "
      << foot_text(l) << "\n";
    for (const UrdfJoint& j : l.joints) s << merged_text(j.link, j.merged_links);
  }
  return s.str();
}

std::vector<std::string> leg_mapping_entries(const UrdfRobot& robot) {
  std::vector<std::string> out;
  for (int leg = 0; leg < robot.n_legs(); ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    std::ostringstream s;
    s.precision(17);
    s << leg_name(leg) << ":";
    for (const UrdfJoint& j : l.joints) s << " " << j.name;
    s << " foot ";
    if (l.foot_kind != FootSource::kLinkOrigin)
      s << "offset " << l.p_foot_last.x() << " " << l.p_foot_last.y() << " " << l.p_foot_last.z()
        << " " << l.last().link;
    else
      s << l.foot_source;
    if (l.foot_radius_m > 0.0) s << " radius " << l.foot_radius_m;
    out.push_back(s.str());
  }
  return out;
}

}  // namespace hexdyn
