#include "hexdyn/planning/plan.hpp"

#include <cmath>

namespace hexdyn {

double settle_time_s(const Scene& scene, const RobotModel& model) {
  if (scene.motion.trunk != TrunkPath::kBalanced) return 0.0;
  const double reach_m = longest_leg_reach_m(model);
  const double g = model.gravity_W.norm();
  return reach_m > 0.0 && g > 0.0 ? kSettlePeriods * std::sqrt(reach_m / g) : 0.0;
}

MotionPlan plan_motion_with(const Scene& scene, const RobotModel& model, const Vec3& p0_W,
                            double foot_lateral_m) {
  Terrain terrain(scene.terrain);
  MotionParams motion = scene.motion;
  motion.initial_position_m = p0_W;
  GaitParams gait_params = scene.gait;
  gait_params.foot_lateral_m = foot_lateral_m;
  TrunkMotion trunk(motion, gait_params, terrain, settle_time_s(scene, model));
  GaitPlan gait = plan_gait(model, gait_params, trunk, terrain);
  return MotionPlan{terrain, trunk, gait, PostureChoice{}};
}

MotionPlan plan_motion(const Scene& scene, const RobotModel& model) {
  const PostureChoice posture = choose_posture(scene, model);
  MotionPlan plan = plan_motion_with(scene, model, posture.p0_W, posture.foot_lateral_m);
  plan.posture = posture;
  return plan;
}

}  // namespace hexdyn
