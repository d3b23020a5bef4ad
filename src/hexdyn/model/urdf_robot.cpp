#include "hexdyn/model/urdf_robot.hpp"

#include <sstream>

namespace hexdyn {

RobotModel build_robot_model(const UrdfRobot& robot, double ik_min_margin_m) {
  RobotModel m;
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
  m.ik_min_margin_m = ik_min_margin_m;
  // The tree: each leg's chain in turn, body b moved by joint b − 1 (robot_model.hpp).
  int b = 1;
  for (const UrdfLeg& l : robot.legs) {
    for (int j = 0; j < kJointsPerLeg; ++j, ++b) {
      m.parent[b] = j == 0 ? 0 : b - 1;
      m.p_parent_joint[b] = l.p_parent_joint[j];
      m.R_parent_joint[b] = l.R_parent_joint[j];
      m.axis[b] = l.axis[j];
      m.inertia[b] = l.inertia[j];
    }
  }
  fill_leg_table(m);
  for (int leg = 0; leg < m.legs(); ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    m.lateral_m[leg] = m.d2_signed_m[leg] = m.d3_signed_m[leg] = 0.0;
    for (int j = 0; j < m.leg(leg).n_joints; ++j) {
      const int k = m.joint(leg, j);
      m.joint_lower_rad[k] = l.lower_rad[j];
      m.joint_upper_rad[k] = l.upper_rad[j];
      m.effort_limit_Nm[k] = l.effort_Nm[j];
      m.velocity_limit_radps[k] = l.velocity_radps[j];
      m.joint_source_names[k] = l.joint_names[j];
    }
    m.p_foot_last[leg] = l.p_foot_last;
    m.foot_radius_m[leg] = l.foot_radius_m;
  }
  m.total_mass_kg = 0.0;
  for (const auto& in : m.inertia) m.total_mass_kg += in.mass_kg;
  m.p_B_root = robot.p_B_root;
  m.B_R_root = robot.B_R_root;
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
  point << "(" << p.x() << ", " << p.y() << ", " << p.z() << ") m in " << l.link_names[2];
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

}  // namespace

std::string leg_mapping_text(const UrdfRobot& robot) {
  std::ostringstream s;
  for (int leg = 0; leg < kLegs; ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    const Vec3& h = l.p_parent_joint[0];
    s << leg_name(leg) << " <- " << l.joint_names[0] << " / " << l.joint_names[1] << " / "
      << l.joint_names[2] << ", hip (" << h.x() << ", " << h.y() << ", " << h.z()
      << ") m in the trunk frame, foot " << foot_text(l) << "\n";
  }
  return s.str();
}

std::array<std::string, kLegs> leg_mapping_entries(const UrdfRobot& robot) {
  std::array<std::string, kLegs> out;
  for (int leg = 0; leg < kLegs; ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    std::ostringstream s;
    s.precision(17);
    s << leg_name(leg) << ": " << l.joint_names[0] << " " << l.joint_names[1] << " "
      << l.joint_names[2] << " foot ";
    if (l.foot_kind != FootSource::kLinkOrigin)
      s << "offset " << l.p_foot_last.x() << " " << l.p_foot_last.y() << " " << l.p_foot_last.z()
        << " " << l.link_names[2];
    else
      s << l.foot_source;
    if (l.foot_radius_m > 0.0) s << " radius " << l.foot_radius_m;
    out[leg] = s.str();
  }
  return out;
}

}  // namespace hexdyn
