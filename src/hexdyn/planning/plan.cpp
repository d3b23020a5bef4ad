#include "hexdyn/planning/plan.hpp"

#include <cmath>

namespace hexdyn {

MotionPlan plan_motion_with(const Scene& scene, const RobotModel& model, const Vec3& p0_W,
                            double foot_lateral_m) {
  Terrain terrain(scene.terrain);
  MotionParams motion = scene.motion;
  motion.initial_position_m = p0_W;
  GaitParams gait_params = scene.gait;
  gait_params.foot_lateral_m = foot_lateral_m;
  TrunkMotion trunk(motion, gait_params, terrain);
  GaitPlan gait = plan_gait(model, gait_params, trunk, terrain);
  if (scene.motion.trunk == TrunkPath::kBalanced && !gait.legs.empty()) {
    const double h = p0_W.z() - mean_initial_foot_z(gait);
    if (h > 0.0)
      settle_swings(gait, trunk.duration_s(),
                    kSettlePeriods / std::sqrt(model.gravity_W.norm() / h));
  }
  return MotionPlan{terrain, trunk, gait, PostureChoice{}};
}

MotionPlan plan_motion(const Scene& scene, const RobotModel& model) {
  const PostureChoice posture = choose_posture(scene, model);
  MotionPlan plan = plan_motion_with(scene, model, posture.p0_W, posture.foot_lateral_m);
  plan.posture = posture;
  return plan;
}

}  // namespace hexdyn
