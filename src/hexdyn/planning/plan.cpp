#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

MotionPlan plan_motion(const Scene& scene, const RobotModel& model) {
  Terrain terrain(scene.terrain);
  TrunkMotion trunk(scene.motion, scene.gait, terrain);
  GaitPlan gait = plan_gait(model, scene.gait, trunk, terrain);
  return MotionPlan{terrain, trunk, gait};
}

}  // namespace hexdyn
