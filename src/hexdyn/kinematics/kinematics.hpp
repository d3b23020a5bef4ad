#pragma once
/// \file kinematics.hpp
/// The kinematic half of the pipeline: plan (terrain, trunk motion, gait) and sample
/// the whole robot's kinematics at given times. Joint rates come from the leg
/// Jacobian, q̇ = J⁻¹ ṙ and q̈ = J⁻¹ (r̈ − J̇ q̇), with r the foot relative to the
/// hip in the hip frame; nothing is differentiated numerically.
#include <vector>

#include "hexdyn/planning/gait.hpp"
#include "hexdyn/planning/motion.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {

struct MotionPlan {
  Terrain terrain;
  TrunkMotion trunk;
  GaitPlan gait;
};

/// Plans terrain, trunk motion and gait for a scene. Throws PlanningError.
MotionPlan plan_motion(const Scene& scene, const RobotModel& model);

/// The whole robot's kinematic state at one instant.
struct RobotKinematicState {
  TrunkState trunk;
  VecJ q = VecJ::Zero(), qd = VecJ::Zero(), qdd = VecJ::Zero();  ///< 18, flat joint order
  std::array<FootMotion, kLegs> feet;                             ///< world frame
};

/// Fills `out` at time t. Throws ReachError naming the leg, the time and the margin
/// when a foot target cannot be reached.
void robot_state_at(const RobotModel& model, const MotionPlan& plan, double t_s,
                    RobotKinematicState& out);

/// Samples every kinematic dataset of the contract on `times` (increasing).
KinematicsResult sample_kinematics(const RobotModel& model, const MotionPlan& plan,
                                   const std::vector<double>& times);

/// An instant around which the output grid is refined: a touchdown (with its transient
/// of `duration_s`, whose force peak is at t_s + peak_offset_s) or a lift-off.
struct GridEvent {
  double t_s = 0.0;
  double duration_s = 0.0;
  double peak_offset_s = 0.0;
};

/// The output grid (README "Output grid"): uniform at sample_step from 0 to the end,
/// and for the adaptive grid, in addition, `impact_samples` points across each
/// transient, its peak instant, and points graded geometrically (factor 2) from the
/// finest step up to sample_step on both sides of every event.
std::vector<double> build_output_grid(const OutputParams& output, double duration_s,
                                      const std::vector<GridEvent>& events);

}  // namespace hexdyn
