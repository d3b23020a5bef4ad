#include "hexdyn/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <optional>

#include "hexdyn/balance/balance.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/urdf.hpp"
#include "hexdyn/model/urdf_robot.hpp"
#include "hexdyn/pipeline/grid_refinement.hpp"
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

/// /base/* of a URDF robot describe its root link frame
/// (docs/theory/conventions.md#robots-from-urdf): the trunk frame's pose, velocities and
/// accelerations moved to the root link, a fixed frame at p_B_root with axes B_R_root. A YAML
/// robot's root link is the trunk frame: unchanged.
void describe_base_at_root_link(const RobotModel& model, KinematicsResult& kin) {
  if (model.p_B_root.isZero(0.0) && model.B_R_root == Mat3::Identity()) return;
  for (int i = 0; i < kin.samples(); ++i) {
    const Eigen::Vector4d q = kin.base_orientation_wxyz.row(i).transpose();
    const Mat3 W_R_B = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
    const Vec3 r_W = W_R_B * model.p_B_root;
    const Vec3 w = kin.base_angular_velocity.row(i).transpose();
    const Vec3 alpha = kin.base_angular_acceleration.row(i).transpose();
    kin.base_position.row(i) += r_W.transpose();
    kin.base_linear_velocity.row(i) += w.cross(r_W).transpose();
    kin.base_linear_acceleration.row(i) += (alpha.cross(r_W) + w.cross(w.cross(r_W))).transpose();
    Eigen::Quaterniond q_root(W_R_B * model.B_R_root);
    q_root.normalize();
    if (q_root.w() < 0.0) q_root.coeffs() *= -1.0;
    kin.base_orientation_wxyz.row(i) << q_root.w(), q_root.x(), q_root.y(), q_root.z();
  }
}

/// How far the stored terrain profile reaches beyond the run's feet and trunk along y [m]
/// (docs/theory/output-grid.md#the-terrain-in-the-file).
constexpr double kTerrainProfileMargin_m = 0.25;

/// /terrain: the height profile over the y-range of every foot and the trunk, with a margin.
void add_terrain_profile(const TerrainParams& terrain, const RobotModel& model, RunResult& result) {
  const KinematicsResult& k = result.kin;
  double y_min = k.base_position.col(1).minCoeff(), y_max = k.base_position.col(1).maxCoeff();
  for (int l = 0; l < model.legs(); ++l) {
    y_min = std::min(y_min, k.foot_position.col(3 * l + 1).minCoeff());
    y_max = std::max(y_max, k.foot_position.col(3 * l + 1).maxCoeff());
  }
  TerrainProfile profile =
      terrain_profile(terrain, y_min - kTerrainProfileMargin_m, y_max + kTerrainProfileMargin_m);
  result.terrain_y_m = std::move(profile.y_m);
  result.terrain_z_m = std::move(profile.z_m);
  result.terrain_type = terrain_type_name(terrain.type);
  result.terrain_map = terrain.map;
}

/// Rounds of posture search and balancing for an automatic posture (docs/theory/balance.md#reach).
constexpr int kReachRounds = 3;

/// Balances plan's trunk (balance/balance.hpp). With an automatic posture, a balanced path the
/// legs cannot follow sends the posture search again with the offset on every candidate's
/// trunk, and the trunk is balanced again at the new height, for up to kReachRounds rounds; a
/// plan still out of reach is left for the kinematics stage to report in one line.
BalanceReport balanced_plan(const Scene& scene, const RobotModel& model, MotionPlan& plan) {
  BalanceOptions options;
  options.margin_m = scene.motion.balance_margin_m;
  BalanceReport report = balance_trunk(model, plan, options);
  for (int round = 1; round < kReachRounds && plan.posture.mode == PostureMode::kAuto; ++round) {
    if (motion_kinematic_margin(model, plan).admitted) break;
    const std::shared_ptr<const TrunkOffset> offset = plan.trunk.shared_offset();
    const PostureChoice posture = choose_posture(scene, model, PostureCheck::kAdmission, offset);
    plan = plan_motion_with(scene, model, posture.p0_W, posture.foot_lateral_m);
    plan.posture = posture;
    report = balance_trunk(model, plan, options);
    report.posture_rounds = round + 1;
  }
  return report;
}

}  // namespace

PreparedScene prepare_scene(const Scene& scene, StageTimes* times) {
  std::optional<StageTimer> clock(std::in_place, times, Stage::kModel);
  RobotModel model = build_robot_model(scene.robot);
  clock.emplace(times, Stage::kPosture);
  // A run reports the posture, not its margin: the dense check only proves it admitted.
  const PostureChoice posture = choose_posture(scene, model, PostureCheck::kAdmission);
  clock.emplace(times, Stage::kPlanning);  // plan_motion, with the posture timed on its own
  MotionPlan plan = plan_motion_with(scene, model, posture.p0_W, posture.foot_lateral_m);
  plan.posture = posture;
  std::optional<BalanceReport> balance;
  if (scene.motion.trunk == TrunkPath::kBalanced) balance = balanced_plan(scene, model, plan);
  clock.emplace(times, Stage::kTouchdowns);
  std::vector<Touchdown> touchdowns = physical_touchdowns(scene, model, plan);
  clock.emplace(times, Stage::kGrid);
  // The grid's events: every lift-off and every touchdown with its transient; the run lasts
  // until the motion and every transient have ended.
  std::vector<GridEvent> events;
  double t_end = plan.trunk.duration_s();
  for (const LegPlan& leg : plan.gait.legs)
    for (const Swing& sw : leg.swings) events.push_back({sw.t_liftoff_s, 0.0, 0.0});
  for (const Touchdown& td : touchdowns) {
    // From the plan's touchdown on (a loaded foot's first contact came contact_lead_s() sooner).
    const double d = td.transient.occurred ? td.after_touchdown_s() : 0.0;
    events.push_back({td.t_s, d, std::max(0.0, td.transient.time_of_peak_s - td.contact_lead_s())});
    t_end = std::max(t_end, td.t_s + d);
  }
  std::vector<std::int8_t> kind;
  std::vector<double> grid = build_output_grid(scene.output, t_end, events, &kind);
  return PreparedScene{std::move(model), std::move(plan), std::move(touchdowns),
                       std::move(grid),  std::move(kind), balance};
}

SampleProblem sample_problem(const Scene& scene, const PreparedScene& prep, double t_s) {
  ContactSchedule contacts;
  const KinematicsResult kin = sample_with_contacts(prep, {t_s}, contacts, nullptr);
  return solve_sample_problem(scene, prep.model, kin, 0, contacts.samples.front());
}

RunResult run_scene(const Scene& scene, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  RunResult result = run_prepared_scene(scene, prepare_scene(scene), log);
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

RunResult run_prepared_scene(const Scene& scene, const PreparedScene& prep, std::ostream* log,
                             StageTimes* times) {
  const auto start = std::chrono::steady_clock::now();
  if (log && prep.balance) {
    const BalanceReport& b = *prep.balance;
    *log << "hexdyn: balanced trunk: " << b.pieces << " pieces, " << b.iterations
         << " passes, ZMP within " << b.zmp_error_m << " m of its path at the nodes, least margin "
         << b.smallest_margin_m << " m, largest offset " << b.largest_offset_m << " m, omega "
         << b.omega_radps << " rad/s, standing " << prep.plan.trunk.hold_s() << " s at each end";
    if (b.stalled)
      *log << ", stalled at " << b.iterations << " passes short of its tolerance by a moment of "
           << b.stall_moment_Nm << " N m";
    if (b.posture_rounds > 1)
      *log << ", posture searched " << b.posture_rounds << " times with the offset (height "
           << prep.plan.posture.height_m << " m)";
    *log << "\n";
  }
  RunResult result;
  ContactSchedule contacts;
  result.kin = sample_with_contacts(prep, prep.grid, contacts, times);
  if (prep.sample_kind.size() == prep.grid.size()) result.kin.sample_kind = prep.sample_kind;
  // The solver, the refinement and the assembly time their own stages.
  DynamicsSolver solver(scene, prep.model);
  result.dyn = solver.solve(result.kin, contacts, times);
  CubicEstimates estimates;
  result.grid =
      refine_output_grid(scene, prep, solver, result.kin, result.dyn, log, times, &estimates);
  finish_dynamics(scene, prep.model, prep.plan, result.kin, prep.touchdowns, result.dyn, log, times,
                  &estimates);
  const StageTimer clock(times, Stage::kAssembly);
  describe_base_at_root_link(prep.model,
                             result.kin);  // after the dynamics, which use the trunk frame
  result.config_yaml = scene.resolved_yaml;
  result.compress = scene.output.compress;
  result.summary_only = scene.output.summary_only;
  result.input_sha256 = scene.input_sha256;
  result.posture.automatic = prep.plan.posture.mode == PostureMode::kAuto;
  result.posture.height_m = prep.plan.posture.height_m;
  result.posture.foot_lateral_m = prep.plan.posture.foot_lateral_m;
  result.urdf =
      robot_urdf(prep.model, scene.robot.urdf ? scene.robot.urdf->name : "hexdyn_hexapod");
  result.joint_names.assign(prep.model.joint_source_names.begin(),
                            prep.model.joint_source_names.begin() + prep.model.joints());
  for (int l = 0; l < prep.model.legs(); ++l)
    result.leg_joint_counts.push_back(prep.model.leg(l).n_joints);
  if (scene.robot.urdf) {
    const auto mapping = leg_mapping_entries(*scene.robot.urdf);
    result.leg_mapping.assign(mapping.begin(), mapping.begin() + prep.model.legs());
  }
  result.sphere_feet = has_sphere_feet(prep.model);
  result.total_mass_kg = prep.model.total_mass_kg;
  result.cycle_start_s = prep.plan.trunk.cycle_start_times();
  add_terrain_profile(prep.plan.terrain.params(), prep.model, result);
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace hexdyn
