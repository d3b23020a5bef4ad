#pragma once
/// \file urdf_robot.hpp
/// A legged robot read from a URDF (urdf_reader.hpp), in hexdyn's conventions, and the
/// RobotModel built from it. Nothing here depends on the URDF parser.
///
/// Trunk frame B (docs/theory/conventions.md#frames: x right, y forward, z up) has its origin at
/// the URDF trunk link's origin; its axes are the trunk link's rotated by B_R_U, which maps the
/// description's forward axis (UrdfReadOptions::forward_axis, default +x as in ROS
/// REP-103) to +y and its +z to +z. Every link joined to the trunk link by fixed joints is
/// part of the trunk body. Each leg is a chain of 3 to 6 revolute, continuous or prismatic
/// joints from the trunk; link k of the chain is the child link of its joint k together with
/// the links fixed to it. Link frames are the URDF child link frames; joint angles, axes,
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

/// The kind of a leg joint as the description gives it.
enum class UrdfJointType {
  kRevolute,    ///< limits [rad]
  kContinuous,  ///< a revolute joint without limits (±inf)
  kPrismatic,   ///< a sliding joint along its axis; limits [m], effort [N], velocity [m/s]
};

/// One moving joint of a leg and the body it moves: its child link with the links fixed to it.
struct UrdfJoint {
  std::string name;  ///< URDF joint name
  std::string link;  ///< its child link
  UrdfJointType type = UrdfJointType::kRevolute;
  /// Joint frame in the parent link frame (the leg's first joint: in the trunk frame B) [m].
  Vec3 p_parent_joint = Vec3::Zero();
  Mat3 R_parent_joint = Mat3::Identity();
  Vec3 axis = Vec3::UnitZ();  ///< unit, joint frame
  RigidInertia inertia;       ///< the merged body, child link frame
  /// The links fixed to `link` (not itself) whose <inertial> are merged into its body, as
  /// found walking down the fixed joints (`-v`).
  std::vector<std::string> merged_links;
  double lower_rad = 0.0, upper_rad = 0.0;  ///< ±inf: continuous (a prismatic joint: [m])
  double effort_Nm = 0.0;                   ///< +inf: none given (a prismatic joint: [N])
  double velocity_radps = 0.0;              ///< +inf: none given (a prismatic joint: [m/s])
  /// <dynamics damping friction>, 0 when not given: the defaults of an actuator's viscous
  /// (N m s/rad) and Coulomb (N m) friction (config/actuators.hpp).
  double damping_Nmsprad = 0.0, friction_Nm = 0.0;
};

/// One leg as read from the description, in hexdyn's leg order: a chain of 3 to 6 moving
/// joints (kMinLegJoints … kMaxLegJoints, core/sizes.hpp) from the trunk to the foot.
struct UrdfLeg {
  std::vector<UrdfJoint> joints;  ///< hip → foot
  int n_joints() const { return static_cast<int>(joints.size()); }
  const UrdfJoint& last() const { return joints.back(); }
  Vec3 p_foot_last = Vec3::Zero();  ///< foot point in the last link frame [m]
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

/// A robot read from a URDF: the trunk and 2 to 8 legs (kMinLegs … kMaxLegs) in hexdyn's leg
/// order (docs/theory/conventions.md#legs-and-joints), named L1 … Ln (leg_name).
struct UrdfRobot {
  std::string name;               ///< <robot name>
  std::string source_path;        ///< the file read
  std::string trunk_link;         ///< the URDF link whose frame is the trunk frame
  std::string forward_axis;       ///< "+x", "-x", "+y" or "-y" of the trunk link
  Mat3 B_R_U = Mat3::Identity();  ///< URDF trunk link axes → trunk frame B
  RigidInertia trunk;             ///< trunk body (links fixed to the trunk link), frame B
  /// The links fixed to the trunk link (not itself), merged into the trunk body, in name order
  /// (`-v`).
  std::vector<std::string> trunk_merged_links;
  std::vector<UrdfLeg> legs;         ///< L1 … Ln
  double total_mass_kg = 0.0;        ///< sum over every <inertial> of the file [kg]
  std::string root_link;             ///< the URDF's root link (the trunk link or fixed to it)
  Vec3 p_B_root = Vec3::Zero();      ///< root link origin in the trunk frame B [m]
  Mat3 B_R_root = Mat3::Identity();  ///< root link axes → B
  int n_legs() const { return static_cast<int>(legs.size()); }
  int n_joints() const;  ///< all legs' joints
};

/// The RobotModel of a URDF robot: LegGeometry::kChain, tree and inertias from `robot` (bodies
/// and joints leg by leg, hip to foot), no payload. ik_min_margin_m:
/// RobotParams::ik_min_margin_m. Throws ConfigError, one line naming the robot, for a robot
/// the model cannot hold (more bodies than its storage, a leg shape this build does not
/// simulate, a prismatic joint).
RobotModel build_robot_model(const UrdfRobot& robot, double ik_min_margin_m = 1e-4);

/// The part of build_robot_model the rigid-body dynamics (dynamics/rnea.hpp) reads: the tree,
/// inertias, joint kinds (revolute or prismatic), limits and names, the leg table, the feet
/// and the root link frame, without the legs' kinematics (leg_ik, p_hip_B, R_B_H and
/// hip_outward_B stay unset). Takes any joint kind the reader reads, prismatic too. Throws
/// ConfigError, one line naming the robot, for more bodies than the storage or a leg layout
/// this build does not hold.
RobotModel build_dynamics_model(const UrdfRobot& robot);

/// "L1 <- right_front_coxa / right_front_femur / right_front_tibia, hip (x, y, z) m in the
/// trunk frame, foot pxmark4/…" one line per leg: the mapping of the description's chains
/// to hexdyn's legs; a foot that is not a link's origin is given as a point of the last link
/// ("foot robot.foot_offset (x, y, z) m in LINK", "foot sphere r = R m of LINK's <collision>,
/// centre (x, y, z) m in LINK"), a sphere foot with its radius, and the foot check's finding;
/// then, for the trunk and each body that has them, the fixed links merged into it
/// ("  merged into LINK: A, B").
std::string leg_mapping_text(const UrdfRobot& robot);

/// The same mapping, one entry per leg L1 … Ln for /model/leg_mapping (io/schema.hpp):
/// "L1: JOINT1 JOINT2 JOINT3 foot FOOT" with the URDF's joint names, hip to foot, and the
/// foot's source: a link name (the foot point is that link's origin) or
/// "offset X Y Z LINK" (robot.foot_offset or a sphere's centre in the last link's frame) [m];
/// then " radius R" [m] for a sphere foot.
std::vector<std::string> leg_mapping_entries(const UrdfRobot& robot);

}  // namespace hexdyn
