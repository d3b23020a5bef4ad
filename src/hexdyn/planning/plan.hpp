#pragma once
/// \file plan.hpp
/// The planning stage: a scene's terrain, trunk motion and gait, planned once. Everything
/// later (kinematics, touchdowns, dynamics) reads the plan and never changes it.
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/gait.hpp"
#include "hexdyn/planning/motion.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {

struct MotionPlan {
  Terrain terrain;
  TrunkMotion trunk;
  GaitPlan gait;
};

/// Plans terrain, trunk motion and gait for a scene. Throws PlanningError.
MotionPlan plan_motion(const Scene& scene, const RobotModel& model);

}  // namespace hexdyn
