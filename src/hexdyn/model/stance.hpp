#pragma once
/// \file stance.hpp
/// A leg's nominal standing pose and where it puts the foot, for footholds derived from
/// the robot's own geometry (planning/gait.hpp: footholds at `gait.foot_lateral` from the
/// hip along RobotModel::hip_outward_B; a URDF robot's default foot_lateral is the stance
/// radius below). NominalStance (core/scene.hpp) holds one leg's pose, radius, depth and
/// how the pose was obtained.
///
/// Default nominal pose ("femur level, tibia plumb"): coxa at zero; the femur turned so
/// that the tibia joint is level with the femur joint; the tibia turned so that the foot
/// is straight below the tibia joint (the classic hexapod standing pose, mid-range for the
/// usual joint limits). Computed by IK of that foot point in the leg's plane; when it is
/// out of reach or outside the joint limits, the leg falls back to the middle of its joint
/// limits (a "fallback", with the IK's reason), which `hexdyn run|validate` report.
///
/// A leg whose hip rolls (its first axis nearer the trunk plane than the trunk normal: a
/// quadruped's abduction joint) has no such plane across the trunk; its default pose
/// ("hanging") puts the foot straight below the foot's zero-pose point, at the depth
/// hypot(femur, tibia) at which the two links would stand square, the knee on the IK's
/// branch; the same fallback applies.
///
/// The stance radius (gait.foot_lateral's default) is the mean radius of the legs whose
/// stance is a pose, the default one reached or robot.nominal_pose: a fallback leg's
/// mid-range angles are no standing pose, and averaging them in would move every leg's
/// foothold. When every leg falls back, it is the mean of all legs.
#include <span>
#include <string>
#include <vector>

#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// Stance of leg `leg` at joint angles q (FK in the hip frame), obtained as `source` says.
/// q: one position per joint of the leg.
NominalStance stance_at_pose(const RobotModel& model, int leg, const LegVector& q,
                             std::string source);

/// Stance of leg `leg` at the default nominal pose, or its fallback (file comment). A leg solved
/// on its chain (RobotModel::leg_on_chain) stands at its resolution's nominal pose, the middle
/// of its joint limits; a pose given by robot.nominal_pose replaces it, and the leg's
/// redundancy then resolves toward that pose (set_leg_nominal_pose).
NominalStance default_nominal_stance(const RobotModel& model, int leg);

/// The stance radius and depth: the means over the legs whose stance is a pose, or over all
/// six when every leg fell back (file comment).
struct StanceMean {
  double radius_m = 0.0;  ///< gait.foot_lateral's default [m]
  double depth_m = 0.0;   ///< mean hip height above the foot [m]
  std::vector<int> legs;  ///< the legs averaged, in leg order
};
StanceMean stance_mean(std::span<const NominalStance> stance);

/// One line per leg, "L1: nominal pose, q [0, 0.43, -1.2] rad, radius 0.178 m, depth
/// 0.09 m", then "stance radius R m: the mean over L1, L2, ... (gait.foot_lateral's
/// default)"; newline-terminated.
std::string stance_text(std::span<const NominalStance> stance);

/// One warning line per fallback leg: the leg, why its default pose was out of reach, the
/// radius its mid-range angles give and what the default foot spread does with it.
std::vector<std::string> stance_fallback_warnings(std::span<const NominalStance> stance);

}  // namespace hexdyn
