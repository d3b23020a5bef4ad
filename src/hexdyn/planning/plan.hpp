#pragma once
/// \file plan.hpp
/// The planning stage: a scene's terrain, trunk posture and motion, and gait, planned once.
/// Everything later (kinematics, touchdowns, dynamics) reads the plan and never changes it.
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/gait.hpp"
#include "hexdyn/planning/motion.hpp"
#include "hexdyn/planning/posture.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {

struct MotionPlan {
  Terrain terrain;
  TrunkMotion trunk;
  GaitPlan gait;
  PostureChoice posture;  ///< the start and foot spread the motion was planned with
};

/// Plans terrain, trunk posture (posture.hpp: absolute, relative or auto), trunk motion
/// and gait for a scene. Throws PlanningError, and ReachError when an automatic posture
/// finds no posture that admits the motion.
MotionPlan plan_motion(const Scene& scene, const RobotModel& model);

}  // namespace hexdyn
