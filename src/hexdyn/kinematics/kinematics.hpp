#pragma once
/// \file kinematics.hpp
/// The kinematics stage: the whole robot's kinematics at given times, from a plan
/// (planning/plan.hpp), every leg through the model's leg_motion (robot_model.hpp). A leg of
/// three revolute joints: joint rates from the leg Jacobian, q̇ = J⁻¹ ṙ and
/// q̈ = J⁻¹ (r̈ − J̇ q̇), with r the foot point relative to the hip in the hip frame. A leg of
/// more joints or with a prismatic joint: the redundant resolution toward its nominal pose,
/// its q̇ and q̈ the derivatives of that resolution (docs/theory/model.md#redundant-legs).
/// Nothing is differentiated numerically. The planned foot path is where the foot touches: a sphere
/// foot's IK target, its centre, is that path + r n with n the normal under the foot and its
/// derivatives (planning/gait.hpp leg_foot_normal; docs/theory/model.md#sphere-feet).
#include <array>
#include <vector>

#include "hexdyn/core/base_state.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

/// The whole robot's kinematic state at one instant. The joint vectors have model.joints()
/// entries and the per-leg arrays model.legs() used entries: the constructor from a model sizes
/// them (robot_state_at sizes a default-constructed state on its first call).
struct RobotKinematicState {
  RobotKinematicState() = default;
  explicit RobotKinematicState(const RobotModel& model);
  BaseState trunk;            ///< world frame
  JointVector q, qd, qdd;     ///< flat joint order
  JointVector cos_q, sin_q;   ///< std::cos(q), std::sin(q)
  LegArray<FootMotion> feet;  ///< world frame
  /// The IK targets: the foot points (a sphere foot's centre), world frame [m].
  LegArray<Vec3> foot_center_W;
};

/// Fills `out` at time t. Throws ReachError naming the leg, the time and the margin
/// when a foot target cannot be reached.
void robot_state_at(const RobotModel& model, const MotionPlan& plan, double t_s,
                    RobotKinematicState& out);

/// Samples every kinematic dataset of the contract on `times` [s] (increasing);
/// contact_phase holds swing/support from the gait.
KinematicsResult sample_kinematics(const RobotModel& model, const MotionPlan& plan,
                                   const std::vector<double>& times);

/// The trunk state of sample i of a kinematics result (orientation re-normalised).
BaseState base_state_at(const KinematicsResult& kin, int i);

}  // namespace hexdyn
