#pragma once
/// \file robot_model.hpp
/// The immutable robot description (Pinocchio's `Model` role): kinematic tree,
/// joint placements, inertias, and the per-leg analytic kinematics (FK, IK,
/// Jacobian and its time derivative).
///
/// Tree: body 0 is the trunk (trunk + payload, floating); body b = 1 + k is moved by
/// joint k (flat index, DESIGN.md §2), its parent is the trunk for a coxa and the
/// previous link otherwise.
///
/// Leg frame H_l ("hip frame"): origin at the coxa joint, z along the trunk normal,
/// x the leg's outward direction at zero coxa angle. Link frames at zero angles are
/// parallel to H_l with x along the link. Positive femur/tibia angles raise the
/// link (rotation about −y of the link frame). Foot point: tibia frame (l3, 0, 0).
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// One rigid body's spatial inertia parameters in its own frame.
struct RigidInertia {
  double mass_kg = 0.0;
  Vec3 com_m = Vec3::Zero();           ///< centre of mass in the body frame
  Mat3 inertia_com = Mat3::Zero();     ///< rotational inertia about the COM, body axes [kg m²]
};

struct RobotModel {
  // --- tree (bodies 0..18) ---
  std::array<int, kBodies> parent{};           ///< parent[0] = -1
  std::array<Mat3, kBodies> R_parent_joint;    ///< joint frame orientation in parent frame
  std::array<Vec3, kBodies> p_parent_joint;    ///< joint frame origin in parent frame [m]
  std::array<Vec3, kBodies> axis;              ///< revolute axis in the joint frame (unit)
  std::array<RigidInertia, kBodies> inertia;   ///< body 0: trunk and payload combined
  // --- separate parts kept for the URDF ---
  RigidInertia trunk_only;    ///< trunk structure alone, trunk frame
  RigidInertia payload;       ///< payload alone, trunk frame
  // --- analytic leg parameters ---
  std::array<double, 3> link_length_m{};  ///< l1, l2, l3
  double d1_m = 0.0;                      ///< femur axis below the coxa link [m]
  std::array<double, kLegs> lateral_m{};  ///< signed lateral foot offset side·(d2+d3) [m]
  std::array<double, kLegs> d2_signed_m{}, d3_signed_m{};
  std::array<Vec3, kLegs> p_hip_B;        ///< coxa joint in the trunk frame [m]
  std::array<Mat3, kLegs> R_B_H;          ///< hip frame → trunk frame
  std::array<double, kJointsPerLeg> joint_min_rad{}, joint_max_rad{};
  double ik_min_margin_m = 1e-4;
  double total_mass_kg = 0.0;
};

/// Builds the model from validated parameters (no checks beyond those of load_scene).
RobotModel build_robot_model(const RobotParams& params);

/// Foot position of leg `leg` in its hip frame for joint angles q = (θ1, β2, β3) [m].
Vec3 leg_foot_position_H(const RobotModel& model, int leg, const Vec3& q);

/// Foot Jacobian ∂p_H/∂q (3×3), hip frame.
Mat3 leg_jacobian_H(const RobotModel& model, int leg, const Vec3& q);

/// Time derivative of the foot Jacobian for joint rates qd (3×3), hip frame.
Mat3 leg_jacobian_dot_H(const RobotModel& model, int leg, const Vec3& q, const Vec3& qd);

/// Closed-form IK (knee-up branch, foot outside the coxa axis).
struct LegIkResult {
  Vec3 q = Vec3::Zero();
  double margin_m = 0.0;  ///< distance to the nearest workspace boundary (≥ ik_min_margin)
  bool ok = false;
  std::string reason;     ///< why not ok: "beyond full extension", "joint limit", ...
};
/// p_H: foot target in the hip frame. Never throws; callers turn !ok into ReachError.
LegIkResult leg_inverse_kinematics(const RobotModel& model, int leg, const Vec3& p_H);

/// Poses of every body in the trunk frame for joint angles q (18).
struct BodyPoses {
  std::array<Mat3, kBodies> R_B;  ///< body → trunk rotation
  std::array<Vec3, kBodies> p_B;  ///< body origin in the trunk frame [m]
};
void forward_kinematics_tree(const RobotModel& model, const VecJ& q, BodyPoses& out);

/// Foot point of leg `leg` in the trunk frame computed through the generic tree
/// (a second computation of the analytic FK).
Vec3 tree_foot_position_B(const RobotModel& model, const BodyPoses& poses, int leg);

/// Whole-robot centre of mass in the trunk frame [m].
Vec3 center_of_mass_B(const RobotModel& model, const BodyPoses& poses);

}  // namespace hexdyn
