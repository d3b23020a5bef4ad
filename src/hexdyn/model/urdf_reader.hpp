#pragma once
/// \file urdf_reader.hpp
/// Reads a legged robot from a URDF file with urdfdom (Debian liburdfdom-dev, the parser
/// Pinocchio and DART use) into a UrdfRobot (urdf_robot.hpp). Its own CMake target,
/// hexdyn_urdf_reader: only it links urdfdom.
///
/// What is read (URDF specification, and the choices hexdyn makes):
///  - Trunk: the root link, or options.trunk_link; every link joined to it by fixed
///    joints (in either direction) is merged into the trunk body.
///  - Fixed joints are merged: each link's <inertial> (mass, COM origin, rotated inertial
///    frame, full tensor with products of inertia) is moved into the body it is fixed to
///    (parallel-axis theorem). A link without <inertial> is massless.
///  - Legs: the moving joints leaving the trunk body, 2 to 8 (kMinLegs … kMaxLegs), each the
///    first of a chain of 3 to 6 (kMinLegJoints … kMaxLegJoints) revolute, continuous or
///    prismatic joints (each link of the chain carrying one moving joint, the last none).
///  - Foot: options.foot_links (one link name per leg, any order, each fixed to the last link
///    of a chain), else options.foot_offset (a point in each leg's last link frame [m]: one
///    for every leg, or one per leg L1 … Ln as mapped below), else a sphere <collision> of the
///    last link or of a link fixed to it (the sphere foot: its centre and radius; of several,
///    the one farthest from the last joint's origin), else the origin of the chain's last
///    link: the end of the chain of links fixed to the last joint's child (the child itself
///    when none is fixed to it). options.foot_radius, when given, is every foot's radius (a
///    sphere centred at the foot point; 0 a point foot). A foot on a revolute last joint's
///    axis is refused (the joint would not move it).
///  - Foot check: a robot.foot_offset point must lie inside (within kFootCheckTolerance_m)
///    one of the primitive <collision> geometries (sphere, box, cylinder, with their
///    origins) of the last link and the links fixed to it, else the leg is refused; mesh
///    geometry, whose files are not read, leaves the check undecided (UrdfLeg::foot_check
///    says so, and `-v` prints it), as does a last link without <collision>.
///  - Trunk axes: options.forward_axis of the trunk link ("+x" default, ROS REP-103;
///    "-x", "+y", "-y") becomes hexdyn's +y (forward), the link's +z stays up, x = y × z
///    (right). Legs map to L1 … Ln by their first joints in that frame
///    (docs/theory/conventions.md#legs-and-joints): x < 0 left, x > 0 right (|x| <= 1e-9 m,
///    a hip on the centre line, is refused; as many legs on each side, or one more on one
///    side for an odd count); ranked front to rear by decreasing y within a side; numbered
///    rank by rank, left before right.
///  - Limits: <limit lower upper> (continuous: ±inf), effort [N m], velocity [rad/s] (a
///    prismatic joint: [m], [N], [m/s]).
///
/// Validation: a broken description throws ConfigError (exit 2) with one line
/// "FILE: link|joint|chain 'NAME': RULE BROKEN" for: XML or URDF structure urdfdom refuses
/// (its message; duplicate link or joint names, a missing parent or child link, unknown
/// joint types, malformed numbers such as nan or inf); NaN or inf anywhere; a link with two
/// parent joints or not connected to the root (cycles); joint types other than fixed,
/// revolute, continuous, prismatic; a zero axis; lower > upper; negative effort or velocity; mass ≤
/// 0 in an <inertial>; an inertia that is not positive definite (an all-zero tensor is accepted as
/// a point mass, e.g. Kraby's end caps) or whose principal moments break the triangle inequality
/// (relative tolerance kInertiaTriangleTolerance); a sphere, box or cylinder in a <collision> or
/// <visual> with a size ≤ 0 (urdf_checks.hpp); fewer than 2 or more than 8 legs; a leg of fewer
/// than 3 or more than 6 moving joints; a chain that branches (a link with two moving children), or
/// two legs sharing a link (two branches long enough to be legs); a foot that cannot be found; a
/// hip on the centre line; a foot offset outside its last link's collision geometry (above). Values
/// are held to the scene's plausibility bounds (core/value_bounds.hpp): a mass above
/// kMaxBodyMass_kg, a principal moment above kMaxPrincipalInertia_kgm2, a joint or inertial origin
/// coordinate beyond ±kMaxRobotCoordinate_m, revolute limits outside ±kMaxJointAngle_rad, an effort
/// above kMaxJointEffort_Nm or a velocity above kMaxJointVelocity_radps is refused, naming the link
/// or joint and the value.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {

/// How far outside a collision geometry a robot.foot_offset point may lie [m]: the rounding
/// of numbers written to a few digits.
inline constexpr double kFootCheckTolerance_m = 1e-6;

struct UrdfReadOptions {
  std::string trunk_link;               ///< empty: the root link
  std::string forward_axis = "+x";      ///< "+x", "-x", "+y", "-y" of the trunk link
  std::vector<std::string> foot_links;  ///< empty, or one link name per leg (any order)
  /// The foot point in each leg's last link frame [m] (robot.foot_offset): one point for
  /// every leg, or one per leg L1 … Ln in leg order.
  std::optional<std::vector<Vec3>> foot_offset;
  std::optional<double> foot_radius;  ///< every foot's sphere radius [m] (robot.foot_radius)
};

/// Reads and validates `path`; throws ConfigError (message names `path`).
UrdfRobot read_urdf_robot(const std::string& path, const UrdfReadOptions& options = {});

/// The text of the URDF file `path`, as read_urdf_robot reads it (ConfigError naming `path`
/// when it cannot be read).
std::string read_urdf_text(const std::string& path);

/// Same, from URDF text; `source_name` is used in messages and as source_path.
UrdfRobot read_urdf_robot_from_string(const std::string& urdf_text, const std::string& source_name,
                                      const UrdfReadOptions& options = {});

}  // namespace hexdyn
