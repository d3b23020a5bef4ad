#include "hexdyn/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>

#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/urdf.hpp"
#include "hexdyn/pipeline/solve_dynamics.hpp"
#include "hexdyn/planning/grid.hpp"

namespace hexdyn {
namespace {

/// Touchdown transients are those of the physical legs, also when the dynamics treat the
/// legs as massless (robot.leg_inertia): a massless foot has no effective mass.
std::vector<Touchdown> physical_touchdowns(const Scene& scene, const RobotModel& model,
                                           const MotionPlan& plan) {
  RobotParams full_legs = scene.robot;
  full_legs.leg_inertia = LegInertia::kFull;
  const RobotModel touchdown_model =
      scene.robot.leg_inertia == LegInertia::kFull ? model : build_robot_model(full_legs);
  RobotData data(touchdown_model);
  return resolve_touchdowns(touchdown_model, data, plan, scene.contact);
}

}  // namespace

PreparedScene prepare_scene(const Scene& scene) {
  RobotModel model = build_robot_model(scene.robot);
  MotionPlan plan = plan_motion(scene, model);
  std::vector<Touchdown> touchdowns = physical_touchdowns(scene, model, plan);
  // The grid's events: every lift-off and every touchdown with its transient; the run lasts
  // until the motion and every transient have ended.
  std::vector<GridEvent> events;
  double t_end = plan.trunk.duration_s();
  for (const LegPlan& leg : plan.gait.legs)
    for (const Swing& sw : leg.swings) events.push_back({sw.t_liftoff_s, 0.0, 0.0});
  for (const Touchdown& td : touchdowns) {
    const double d = td.transient.occurred ? td.transient.duration_s : 0.0;
    events.push_back({td.t_s, d, td.transient.time_of_peak_s});
    t_end = std::max(t_end, td.t_s + d);
  }
  std::vector<double> grid = build_output_grid(scene.output, t_end, events);
  return PreparedScene{std::move(model), std::move(plan), std::move(touchdowns), std::move(grid)};
}

RunResult run_scene(const Scene& scene, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  RunResult result = run_prepared_scene(scene, prepare_scene(scene), log);
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

RunResult run_prepared_scene(const Scene& scene, const PreparedScene& prep, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  RunResult result;
  result.kin = sample_kinematics(prep.model, prep.plan, prep.grid);
  ContactSchedule contacts = schedule_contacts(result.kin, prep.plan.terrain, prep.touchdowns);
  result.dyn =
      solve_dynamics(scene, prep.model, prep.plan, result.kin, contacts, prep.touchdowns, log);
  result.kin.contact_phase = std::move(contacts.phase);
  result.config_yaml = scene.resolved_yaml;
  result.urdf = robot_urdf(prep.model, "hexdyn_hexapod");
  result.total_mass_kg = prep.model.total_mass_kg;
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace hexdyn
