#pragma once
/// \file urdf.hpp
/// The robot exactly as simulated, as URDF text (`/model/urdf`,
/// docs/theory/conventions.md#robots-from-urdf).
///
/// Links and joints (i = 1..6 is the leg number, leg index l = i − 1):
///   trunk               root; its frame is the body frame L0 at P0 (a URDF robot: its own
///                       root link frame, RobotModel::p_B_root / B_R_root, the frame of
///                       /base/*); trunk structure inertial
///   payload             on fixed joint `payload_mount` (identity origin); payload inertial
///   (joint names: RobotModel::joint_source_names, L{i}_coxa … for a YAML robot, a URDF
///   robot's own names otherwise)
///   L{i}_coxa_link      on revolute `L{i}_coxa`  (parent trunk)
///   L{i}_femur_link     on revolute `L{i}_femur` (parent L{i}_coxa_link)
///   L{i}_tibia_link     on revolute `L{i}_tibia` (parent L{i}_femur_link)
///   L{i}_foot           massless, on fixed joint `L{i}_foot_fixed` at the foot point
///                       (RobotModel::p_foot_last; the paper robot: (l3, 0, 0) of the tibia);
///                       a sphere foot's link holds a <collision> sphere of its radius
///                       centred on the link (RobotModel::foot_radius_m)
/// Each link frame is the simulation's body frame (RobotModel::body(l, j), moved by joint
/// RobotModel::joint(l, j)), so joint origins are RobotModel::p_parent_joint /
/// R_parent_joint (rpy fixed-axis, R = Rz(yaw) Ry(pitch) Rx(roll)), axes are
/// RobotModel::axis, zero angles and signs are the simulation's; joints with infinite
/// limits are `continuous`. Inertials: mass [kg], COM origin [m] and the full inertia
/// tensor about the COM in link axes [kg m²]; a massless body has no <inertial>.
/// Numbers are printed with 17 significant digits (round-trip exact).
#include <string>

#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {

/// `<limit effort>` of a joint whose model gives none (a YAML robot): the paper robot's
/// torque limit (docs/theory/allocation.md#torque-limits).
inline constexpr double kUrdfEffortLimitNm = 6.0;
/// `<limit velocity>` of a joint whose model gives none [rad/s].
inline constexpr double kUrdfVelocityLimitRadps = 10.0;

/// URDF document of `model` with `<robot name="robot_name">`.
std::string robot_urdf(const RobotModel& model, const std::string& robot_name);

/// URDF document of a description as read (urdf_robot.hpp), any number of legs and joints:
/// root link = the trunk link (frame U, its inertial the merged trunk body), each leg's
/// joints with their own names, types (revolute, continuous, prismatic), limits (+inf effort
/// or velocity written as 0: none), <dynamics> when nonzero, and child links with the merged
/// bodies, then a massless `L{i}_foot` on fixed joint `L{i}_foot_fixed` at the foot point (a
/// sphere foot: a <collision> sphere of its radius). Read back with the description's
/// forward axis (feet found by the default rules), it gives the same description
/// (placements through rpy to about 1e-15; links fixed to a body are merged, not listed).
std::string description_urdf(const UrdfRobot& robot);

/// Fixed-axis roll, pitch, yaw of a rotation matrix, R = Rz(yaw) Ry(pitch) Rx(roll) [rad];
/// pitch in [−π/2, π/2], roll = 0 at the gimbal lock.
Vec3 rotation_to_rpy(const Mat3& R);

}  // namespace hexdyn
