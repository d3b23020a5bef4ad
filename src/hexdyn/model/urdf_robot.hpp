#pragma once
/// \file urdf_robot.hpp
/// A hexapod read from a URDF (urdf_reader.hpp), in hexdyn's conventions, and the
/// RobotModel built from it. Nothing here depends on the URDF parser.
///
/// Trunk frame B (docs/theory/conventions.md#frames: x right, y forward, z up) has its origin at
/// the URDF trunk link's origin; its axes are the trunk link's rotated by B_R_U, which maps the
/// description's forward axis (UrdfReadOptions::forward_axis, default +x as in ROS
/// REP-103) to +y and its +z to +z. Every link joined to the trunk link by fixed joints is
/// part of the trunk body. Each leg is a chain of three revolute (or continuous) joints
/// from the trunk; link k of the chain is the child link of its joint k together with the
/// links fixed to it. Link frames are the URDF child link frames; joint angles, axes,
/// signs and zero poses are the URDF's.
#include <string>
#include <vector>

#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// One <collision> geometry of a leg's last link or of a link fixed to it, placed in the
/// last link's frame (urdf_reader.hpp: the default sphere foot and the foot check).
struct CollisionShape {
  enum class Kind { kSphere, kBox, kCylinder, kMesh };
  Kind kind = Kind::kMesh;
  std::string link;           ///< the link whose <collision> it is
  Vec3 p = Vec3::Zero();      ///< its origin in the last link frame [m]
  Mat3 R = Mat3::Identity();  ///< its axes → the last link's axes
  /// Box: the sides along its x, y, z; sphere: (radius, 0, 0); cylinder: (radius, length
  /// along its z, 0) [m]; mesh: unused (its file is not read).
  Vec3 size = Vec3::Zero();
};

/// Where a leg's foot point comes from (urdf_reader.hpp).
enum class FootSource {
  kLinkOrigin,       ///< a link's origin: robot.foot_links, or the end of the chain's links
  kFootOffset,       ///< robot.foot_offset, a point of the last link's frame
  kSphereCollision,  ///< the centre and radius of a sphere <collision> of the last link
};

/// One leg as read from the description, in hexdyn's leg order.
struct UrdfLeg {
  std::array<std::string, kJointsPerLeg> joint_names;  ///< URDF joint names, hip → foot
  std::array<std::string, kJointsPerLeg> link_names;   ///< their child links
  /// Joint frame in the parent link frame (joint 0: in the trunk frame B) [m].
  std::array<Vec3, kJointsPerLeg> p_parent_joint;
  std::array<Mat3, kJointsPerLeg> R_parent_joint;
  std::array<Vec3, kJointsPerLeg> axis;                        ///< unit, joint frame
  std::array<RigidInertia, kJointsPerLeg> inertia;             ///< merged link bodies, link frames
  std::array<double, kJointsPerLeg> lower_rad{}, upper_rad{};  ///< ±inf: continuous
  std::array<double, kJointsPerLeg> effort_Nm{};               ///< +inf: none given
  std::array<double, kJointsPerLeg> velocity_radps{};          ///< +inf: none given
  /// <dynamics damping friction>, 0 when not given: the defaults of an actuator's viscous
  /// (N m s/rad) and Coulomb (N m) friction (config/actuators.hpp).
  std::array<double, kJointsPerLeg> damping_Nmsprad{}, friction_Nm{};
  Vec3 p_foot_last = Vec3::Zero();  ///< foot point in the third link frame [m]
  /// Sphere foot radius [m] (RobotModel::foot_radius_m): p_foot_last is its centre; 0 a point.
  double foot_radius_m = 0.0;
  FootSource foot_kind = FootSource::kLinkOrigin;
  /// kLinkOrigin: the link whose origin is the foot; kFootOffset: "robot.foot_offset";
  /// kSphereCollision: the link whose <collision> the sphere is.
  std::string foot_source;
  /// The <collision> geometries of the last link and of the links fixed to it.
  std::vector<CollisionShape> collisions;
  /// What the foot check of a robot.foot_offset found, in words ("inside the box of
  /// LINK", "not checked: ..."); empty for the other feet.
  std::string foot_check;
};

struct UrdfRobot {
  std::string name;                  ///< <robot name>
  std::string source_path;           ///< the file read
  std::string trunk_link;            ///< the URDF link whose frame is the trunk frame
  std::string forward_axis;          ///< "+x", "-x", "+y" or "-y" of the trunk link
  Mat3 B_R_U = Mat3::Identity();     ///< URDF trunk link axes → trunk frame B
  RigidInertia trunk;                ///< trunk body (links fixed to the trunk link), frame B
  std::array<UrdfLeg, kLegs> legs;   ///< L1 … L6 (common.hpp)
  double total_mass_kg = 0.0;        ///< sum over every <inertial> of the file [kg]
  std::string root_link;             ///< the URDF's root link (the trunk link or fixed to it)
  Vec3 p_B_root = Vec3::Zero();      ///< root link origin in the trunk frame B [m]
  Mat3 B_R_root = Mat3::Identity();  ///< root link axes → B
};

/// The RobotModel of a URDF robot: LegGeometry::kChain, tree and inertias from `robot`,
/// no payload. ik_min_margin_m: RobotParams::ik_min_margin_m.
RobotModel build_robot_model(const UrdfRobot& robot, double ik_min_margin_m = 1e-4);

/// "L1 <- right_front_coxa / right_front_femur / right_front_tibia, hip (x, y, z) m in the
/// trunk frame, foot pxmark4/…" one line per leg: the mapping of the description's chains
/// to hexdyn's legs; a foot that is not a link's origin is given as a point of the last link
/// ("foot robot.foot_offset (x, y, z) m in LINK", "foot sphere r = R m of LINK's <collision>,
/// centre (x, y, z) m in LINK"), a sphere foot with its radius, and the foot check's finding.
std::string leg_mapping_text(const UrdfRobot& robot);

/// The same mapping, one entry per leg L1 … L6 for /model/leg_mapping (io/schema.hpp):
/// "L1: JOINT1 JOINT2 JOINT3 foot FOOT" with the URDF's joint names, hip to foot, and the
/// foot's source: a link name (the foot point is that link's origin) or
/// "offset X Y Z LINK" (robot.foot_offset or a sphere's centre in the third link's frame) [m];
/// then " radius R" [m] for a sphere foot.
std::array<std::string, kLegs> leg_mapping_entries(const UrdfRobot& robot);

}  // namespace hexdyn
