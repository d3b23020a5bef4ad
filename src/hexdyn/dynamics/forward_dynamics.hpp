#pragma once
/// \file forward_dynamics.hpp
/// Forward dynamics of the floating-base robot (docs/theory/replay.md#forward-dynamics): the
/// generalised acceleration ν̇ that a generalised force produces at a state,
///
///   M(q) ν̇ = τ_gen + Σ_l J_lᵀ F_l − h(q, ν),
///
/// by the composite-rigid-body algorithm (crba) for M, recursive Newton–Euler at ν̇ = 0
/// (rnea) for h − Σ J_lᵀ F_l, and a Cholesky factorisation of M. Coordinates, frames and the
/// model/data split are those of dynamics/rnea.hpp: ν = [v_W; ω_W; q̇] (6 + joints), τ_gen =
/// [f_base; n_base; τ_joints] (force and moment about P0 on the trunk in world axes, then the
/// joint torques), F_l the terrain's force on foot l at its contact point, world axes. The inverse
/// of rnea: rnea(q, ν, forward_dynamics(q, ν, τ)) = τ to rounding.
#include "hexdyn/dynamics/rnea.hpp"

namespace hexdyn {

/// Generalised acceleration ν̇ (6 + joints: a_W [m/s²], ω̇_W [rad/s²], q̈ [rad/s²], rnea.hpp) at the
/// pose and twist of `state` (its accelerations are ignored), joint angles q [rad] and rates
/// qd [rad/s], under the generalised force tau_gen (6 + joints) and the foot forces (nullptr: none)
/// at the contact points of normals_W. Gravity: model.gravity_W. With armature_kgm2 (one per
/// joint, joint side [kg m²]; nullptr: none) each joint's armature J_a adds to M's diagonal:
/// (M + diag(0, J_a)) ν̇ = τ_gen + Σ J_lᵀ F_l − h (docs/theory/replay.md#driven-by-the-actuators).
/// Fills data.M (crba, with the armature), data.M_llt, data.bias (h − Σ J_lᵀ F_l) and
/// data.nu_dot (the result); overwrites data.tau and the kinematics. Throws SolverError when M
/// is not positive definite (a model with a massless chain) or the result is not finite.
const DofVector& forward_dynamics(const RobotModel& model, RobotData& data, const BaseState& state,
                                  const JointVector& q, const JointVector& qd,
                                  const DofVector& tau_gen, LegVectors foot_forces_W = nullptr,
                                  LegVectors normals_W = nullptr,
                                  const JointVector* armature_kgm2 = nullptr);

/// The same with the joint torques alone (no force on the trunk other than gravity and the
/// feet): τ_gen = [0; 0; tau_joints].
const DofVector& forward_dynamics_joints(const RobotModel& model, RobotData& data,
                                         const BaseState& state, const JointVector& q,
                                         const JointVector& qd, const JointVector& tau_joints_Nm,
                                         LegVectors foot_forces_W = nullptr,
                                         LegVectors normals_W = nullptr,
                                         const JointVector* armature_kgm2 = nullptr);

/// Kinetic energy ½ νᵀ M ν [J] at the pose of `state` (fills data.M).
double kinetic_energy(const RobotModel& model, RobotData& data, const BaseState& state,
                      const JointVector& q, const JointVector& qd);

}  // namespace hexdyn
