#pragma once
/// \file joint_drive.hpp
/// The joints of a replay driven through its actuators
/// (docs/theory/replay.md#driven-by-the-actuators): each drive's torque bounded by its torque–speed
/// envelope, the joints' regularised Coulomb and viscous friction, their rows in the integrator's
/// step and what the drives spend. Internal to the replay stage (replay.cpp). Joint side
/// throughout: τ [N m], q̇ [rad/s]; vectors of model.joints() entries in flat joint order.
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/core/sizes.hpp"

namespace hexdyn {

/// The stiction speed ω_s of the replay's regularised Coulomb friction τ_c tanh(q̇ / ω_s)
/// [rad/s].
inline constexpr double kJointStictionSpeed_radps = 1e-3;

/// The friction torque of a joint at rate q̇ by the regularised law: τ_c tanh(q̇/ω_s) + b q̇.
double joint_friction_torque(const ActuatorParams& a, double qd_radps);

/// The same as a damper on the rate over a step: the secant τ_f(q̇)/q̇ at the step's start
/// rate (τ_c/ω_s + b at rest), so that the step never reverses a motion the law only slows
/// [N m s/rad].
double joint_friction_secant(const ActuatorParams& a, double qd_radps);

/// The drive torque of a command at rate q̇: the command, bounded by drive_torque_limit
/// (drive/drive.hpp) when `saturate`; `at_bound` tells whether the bound acted.
double bounded_drive_torque(const ActuatorParams& a, bool saturate, double command_Nm,
                            double qd_radps, bool& at_bound);

/// A driven step's joints: the drive torque u (the bound, or the command at the step's new
/// rates), the friction's secant c of the step (its torque at the new rates c q̇), whether at
/// the bound (1).
struct DrivenJoints {
  JointVector u, friction_secant, saturated;
};

/// Adds the joints' rows of a driven step of length h from rates qd and angles q towards the
/// plan point (q_plan, qd_plan, feedforward tau_plan, the planned drive torques) to the step's
/// force f and matrix A (6 + joints; replay.hpp's file comment): a joint whose command at the
/// start's rates lies beyond its envelope gives its bound over the step, the others the
/// feedforward and the PD of `gains` linearised; every joint adds its armature to A and its
/// friction secant as an implicit damper. Fills out.u with the bounds (others: the command
/// at the start's rates), out.friction_secant and out.saturated.
void add_driven_joint_rows(const DriveTrainParams& drive, const ReplayParams& gains,
                           const JointVector& q, const JointVector& qd, const JointVector& q_plan,
                           const JointVector& qd_plan, const JointVector& tau_plan, double h,
                           DofVector& f, DofMatrix& A, DrivenJoints& out);

/// Completes `out` at the step's new rates qd_new: each unbounded joint's u the command at
/// them.
void finish_driven_joints(const ReplayParams& gains, const JointVector& q,
                          const JointVector& q_plan, const JointVector& qd_plan,
                          const JointVector& tau_plan, const JointVector& qd_new, double h,
                          DrivenJoints& out);

/// What the drives spent, cumulative [J], and the time each joint was at its bound [s].
struct DriveSpending {
  double joint_friction_J = 0.0, copper_loss_J = 0.0, electrical_J = 0.0;
  std::vector<double> saturated_s;
};

/// Adds a step of length h with the joints `step` at rates qd_new: the friction's loss
/// c q̇², the copper loss and electrical power of each drive at (u, q̇)
/// (drive/drive.hpp), and h to each joint at its bound.
void account_driven_step(const DriveTrainParams& drive, const DrivenJoints& step,
                         const JointVector& qd_new, double h, DriveSpending& spent);

/// The armature J_a of each joint [kg m²] (forward_dynamics' armature_kgm2).
JointVector joint_armatures(const DriveTrainParams& drive);

/// Σ_joints electrical_power(u_j, q̇_j) [W]: the drives' electrical power at a state.
double electrical_power_total(const DriveTrainParams& drive, const JointVector& u,
                              const JointVector& qd);

}  // namespace hexdyn
