#pragma once
/// \file leg_chain.hpp
/// Kinematics of a kChain leg (robot_model.hpp): any chain of three revolute joints,
/// evaluated from the model's tree (placements p_parent_joint / R_parent_joint, axes) and
/// the foot point p_foot_last. Every function works in the leg's hip frame H (the coxa
/// joint frame at zero coxa angle); q = (q_coxa, q_femur, q_tibia) [rad] in the
/// description's own signs and zero poses. The public entry points are the leg_* functions
/// of robot_model.hpp, which dispatch here for LegGeometry::kChain.
#include <cmath>

#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// Joints of the chains of this file: three revolute joints.
inline constexpr int kChainJoints3 = 3;

/// Joint origins o_k, joint axes w_k (unit) and the foot point, all in H, for angles q.
struct LegChainPose {
  std::array<Vec3, kChainJoints3> o_H;                 ///< joint origins [m]
  std::array<Vec3, kChainJoints3> w_H;                 ///< joint axes (unit)
  std::array<Mat3, kChainJoints3> R_H;                 ///< link frames → H
  Vec3 p_foot_H = Vec3::Zero();                        ///< foot point [m]
  std::array<double, kChainJoints3> cos_q{}, sin_q{};  ///< std::cos(q_k), std::sin(q_k)
};
LegChainPose chain_pose(const RobotModel& model, int leg, const Vec3& q);

/// Foot point in H: composition of the three joint transforms [m].
Vec3 chain_foot_position_H(const RobotModel& model, int leg, const Vec3& q);

/// ∂p_foot_H/∂q, columns w_k × (p_foot − o_k) [m/rad].
Mat3 chain_jacobian_H(const RobotModel& model, int leg, const Vec3& q);
/// The same from a pose chain_pose gave: a caller that needs J and J̇ at one q computes the
/// pose once (the same values, bit for bit).
Mat3 chain_jacobian_H(const LegChainPose& pose);

/// d/dt of chain_jacobian_H along joint rates qd, analytic: column k is
/// ẇ_k × (p − o_k) + w_k × (ṗ − ȯ_k) with ẇ_k = Ω_k × w_k, Ω_k = Σ_{i<k} w_i q̇_i.
Mat3 chain_jacobian_dot_H(const RobotModel& model, int leg, const Vec3& q, const Vec3& qd);
/// The same from a pose chain_pose gave.
Mat3 chain_jacobian_dot_H(const LegChainPose& pose, const Vec3& qd);

/// A hip that rolls (abducts) rather than yaws: its first axis nearer the trunk plane than the
/// trunk normal (a quadruped's HAA; a hexapod's coxa yaws).
inline bool rolling_hip(const LegIkData& d) {
  return std::abs(d.a0_H.normalized().dot(d.up_H)) < M_SQRT1_2;
}

/// IK of a kChain leg for a foot target p_H in H (LegIkMethod of model.leg_ik[leg]).
LegIkResult chain_inverse_kinematics(const RobotModel& model, int leg, const Vec3& p_H);

/// IK of a leg on its chain (RobotModel::leg_on_chain): the redundant resolution's q for a
/// foot at rest at p_H (model/leg_motion.cpp).
LegIkResult chain_leg_inverse_kinematics(const RobotModel& model, int leg, const Vec3& p_H);

}  // namespace hexdyn
