#pragma once
/// \file base_state.hpp
/// The trunk's pose, twist and their time derivatives at one instant: what the trunk
/// motion plans (planning/motion.hpp) and what the rigid-body algorithms take
/// (dynamics/rnea.hpp). One type for both, so that a planned state goes to the dynamics
/// as it is.
#include "hexdyn/core/common.hpp"

namespace hexdyn {

/// Trunk pose, twist and its time derivative, all in world frame G0.
struct BaseState {
  Mat3 W_R_B = Mat3::Identity();   ///< trunk (body) axes → world axes, orthonormal
  Vec3 p_W = Vec3::Zero();         ///< trunk origin P0 [m]
  Vec3 v_W = Vec3::Zero();         ///< velocity of P0 [m/s]
  Vec3 omega_W = Vec3::Zero();     ///< trunk angular velocity [rad/s]
  Vec3 a_W = Vec3::Zero();         ///< classical acceleration of P0, d v_W/dt [m/s²]
  Vec3 omegadot_W = Vec3::Zero();  ///< d omega_W/dt [rad/s²]
};

}  // namespace hexdyn
