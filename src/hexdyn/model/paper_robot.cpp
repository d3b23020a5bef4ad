#include "hexdyn/model/paper_robot.hpp"

#include <cmath>
#include <limits>

namespace hexdyn {
namespace {

RigidInertia to_inertia(const BodyParams& p) {
  RigidInertia r;
  r.mass_kg = p.mass_kg;
  r.com_m = p.com_m;
  r.inertia_com = p.inertia_kgm2.asDiagonal();
  return r;
}

Mat3 rot_z(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

/// The paper's leg numbering: L1, L3, L5 on the left.
bool paper_left(int leg) { return leg % 2 == 0; }

/// The trunk body and the trunk structure alone: with massless legs, each link's mass is a
/// point mass at its hip, added to both in leg and joint order.
struct PaperTrunk {
  RigidInertia body;  ///< trunk, payload and the massless legs' point masses
  RigidInertia only;  ///< trunk structure and the point masses, without the payload
};

PaperTrunk paper_trunk(const RobotParams& params) {
  PaperTrunk t;
  t.only = to_inertia(params.trunk);
  t.body = combine_inertias(t.only, to_inertia(params.payload));
  if (params.leg_inertia != LegInertia::kMassless) return t;
  for (int leg = 0; leg < params.legs; ++leg)
    for (int j = 0; j < kYamlRobotLegJoints; ++j) {
      if (!(params.link[j].mass_kg > 0.0)) continue;
      RigidInertia point;
      point.mass_kg = params.link[j].mass_kg;
      point.com_m = params.hip_position_m[leg];
      t.body = combine_inertias(t.body, point);
      t.only = combine_inertias(t.only, point);
    }
  return t;
}

}  // namespace

UrdfRobot paper_description(const RobotParams& params) {
  UrdfRobot r;
  r.name = "hexapod";
  r.source_path = "the scene's robot keys";
  r.trunk_link = "trunk";
  r.forward_axis = "+y";
  r.root_link = "trunk";
  r.trunk = paper_trunk(params).body;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const bool massless = params.leg_inertia == LegInertia::kMassless;
  const Vec3 minus_y(0.0, -1.0, 0.0);
  const double l1 = params.link_length_m[0], l2 = params.link_length_m[1];
  const double d1 = params.joint_offset_m[0];
  for (int leg = 0; leg < params.legs; ++leg) {
    const double side = paper_left(leg) ? -1.0 : 1.0;
    UrdfLeg l;
    l.joints.resize(kYamlRobotLegJoints);
    l.joints[0].p_parent_joint = params.hip_position_m[leg];
    l.joints[0].R_parent_joint = rot_z(params.hip_yaw_rad[leg]);
    l.joints[0].axis = Vec3::UnitZ();
    l.joints[1].p_parent_joint = Vec3(l1, side * params.joint_offset_m[1], -d1);
    l.joints[1].axis = minus_y;
    l.joints[2].p_parent_joint = Vec3(l2, side * params.joint_offset_m[2], 0.0);
    l.joints[2].axis = minus_y;
    for (int j = 0; j < kYamlRobotLegJoints; ++j) {
      UrdfJoint& joint = l.joints[j];
      joint.name = joint_name(leg, j);
      joint.link = joint.name + "_link";
      joint.type = UrdfJointType::kRevolute;
      joint.inertia =
          massless && params.link[j].mass_kg > 0.0 ? RigidInertia{} : to_inertia(params.link[j]);
      joint.lower_rad = params.joint_min_rad[j];
      joint.upper_rad = params.joint_max_rad[j];
      joint.effort_Nm = kNone;  // the scene's allocation.torque_limit applies
      joint.velocity_radps = kNone;
    }
    l.p_foot_last = Vec3(params.link_length_m[2], 0.0, 0.0);
    l.foot_radius_m = params.foot_radius_m;
    l.foot_kind = FootSource::kLinkOrigin;
    r.legs.push_back(std::move(l));
  }
  r.total_mass_kg = r.trunk.mass_kg;
  for (const UrdfLeg& l : r.legs)
    for (const UrdfJoint& j : l.joints) r.total_mass_kg += j.inertia.mass_kg;
  return r;
}

void use_paper_closed_forms(RobotModel& m, const RobotParams& params) {
  m.leg_geometry = LegGeometry::kPaperPlanar;
  for (std::size_t j = 0; j < m.link_length_m.size(); ++j)
    m.link_length_m[j] = params.link_length_m[j];
  m.d1_m = params.joint_offset_m[0];
  const PaperTrunk trunk = paper_trunk(params);
  m.trunk_only = trunk.only;
  m.payload = to_inertia(params.payload);
  for (int leg = 0; leg < params.legs; ++leg) {
    const double side = paper_left(leg) ? -1.0 : 1.0;
    // The outward direction from the right-side yaw ψ (hip_yaw = π − ψ on the left, mirrored
    // in x), so that legs straight out get exactly (±1, 0, 0).
    const double psi = paper_left(leg) ? M_PI - params.hip_yaw_rad[leg] : params.hip_yaw_rad[leg];
    m.hip_outward_B[leg] = Vec3(side * std::cos(psi), std::sin(psi), 0.0);
    m.d2_signed_m[leg] = side * params.joint_offset_m[1];
    m.d3_signed_m[leg] = side * params.joint_offset_m[2];
    m.lateral_m[leg] = m.d2_signed_m[leg] + m.d3_signed_m[leg];
  }
}

}  // namespace hexdyn
