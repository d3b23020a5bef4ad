#pragma once
/// \file stance.hpp
/// A leg's nominal standing pose and where it puts the foot, for footholds derived from
/// the robot's own geometry (planning/gait.hpp: footholds at `gait.foot_lateral` from the
/// hip along RobotModel::hip_outward_B; a URDF robot's default foot_lateral is the nominal
/// stance radius below).
///
/// Default nominal pose ("femur level, tibia plumb"): coxa at zero; the femur turned so
/// that the tibia joint is level with the femur joint; the tibia turned so that the foot
/// is straight below the tibia joint (the classic hexapod standing pose, mid-range for the
/// usual joint limits). Computed by IK of that foot point in the leg's plane; when it is
/// out of reach or outside the joint limits, the middle of the joint limits is used.
#include <optional>

#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

struct NominalStance {
  Vec3 q = Vec3::Zero();  ///< joint angles [rad], the description's signs and zero poses
  double radius_m = 0.0;  ///< horizontal distance of the foot from the coxa joint [m]
  double depth_m = 0.0;   ///< height of the coxa joint above the foot, along the trunk normal [m]
  bool from_pose = true;  ///< false: the default pose was out of reach, mid-range used
};

/// Stance of leg `leg` at joint angles q (FK in the hip frame).
NominalStance stance_at_pose(const RobotModel& model, int leg, const Vec3& q);

/// Stance of leg `leg` at the default nominal pose (file comment).
NominalStance default_nominal_stance(const RobotModel& model, int leg);

}  // namespace hexdyn
