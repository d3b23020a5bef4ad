// The replay's plan: read from a run, checked before any work (plan_checks.hpp), and the
// tolerance of its arrival.
#include "hexdyn/replay/plan_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/root_link.hpp"
#include "hexdyn/replay/replay.hpp"

namespace hexdyn {

void check_plan(const RobotModel& model, const ReplayPlan& p) {
  const std::size_t T = p.t_s.size();
  if (T < 2) throw ConfigError("replay: the plan has " + std::to_string(T) + " samples, needs 2");
  if (p.base.size() != T || p.q_rad.size() != T || p.qd_radps.size() != T || p.tau_Nm.size() != T)
    throw ConfigError("replay: the plan's series differ in length from its time");
  if (model.drive.present != !p.tau_drive_Nm.empty())
    throw ConfigError(model.drive.present
                          ? "replay: the robot has actuators but the plan has no drive torques "
                            "(/joints/drive_torque of a run with the same actuators:)"
                          : "replay: the plan has drive torques but the robot no actuators "
                            "(the scene's actuators: key)");
  if (!p.tau_drive_Nm.empty() && p.tau_drive_Nm.size() != T)
    throw ConfigError("replay: the plan's drive torques differ in length from its time");
  if (p.terrain_y_m.size() < 2 || p.terrain_y_m.size() != p.terrain_z_m.size())
    throw ConfigError("replay: the terrain profile needs at least 2 vertices of y and z");
  for (std::size_t k = 1; k < T; ++k)
    if (!(p.t_s[k] > p.t_s[k - 1]))
      throw ConfigError("replay: the plan's time is not strictly increasing at sample " +
                        std::to_string(k));
}

void check_replay_work(const ReplayPlan& p, const ReplayParams& replay) {
  const double span_s = p.t_s.back() - p.t_s.front();
  const double steps = span_s / replay.step_s;
  if (!(steps <= kMaxReplaySteps))
    throw ConfigError(
        "replay.step: got " + format_number(replay.step_s, 6) + " s, which takes " +
        format_number(steps, 3) + " steps over the plan's " + format_number(span_s, 6) +
        " s, expected at most " + format_number(kMaxReplaySteps, 6) +
        " steps: replay.step >= " + format_number(span_s / kMaxReplaySteps, 3) + " s");
  const RowMatrixI8& phase = p.contact_phase;
  if (replay.early_contact == EarlyContact::kHold &&
      static_cast<std::size_t>(phase.rows()) != p.t_s.size())
    throw ConfigError(
        "replay.early_contact: hold needs the plan's contact phases, one row per "
        "instant (/contacts/phase), got " +
        std::to_string(phase.rows()) + " rows for " + std::to_string(p.t_s.size()) + " instants");
}

void check_mass_matrix(const RobotModel& model, RobotData& data, const ReplayPlan& p) {
  crba(model, data, p.base.front(), p.q_rad.front());
  data.M_llt.compute(data.M);
  if (data.M_llt.info() == Eigen::Success) return;
  for (int l = 0; l < model.legs(); ++l)
    for (int j = 0; j < model.leg(l).n_joints; ++j) {
      if (model.inertia[model.body(l, j)].mass_kg > 0.0) continue;
      throw ConfigError("robot.leg_inertia: the body of joint " +
                        joint_name(l, j, model.leg(l).n_joints) +
                        " has no mass, so the forward dynamics have no mass matrix to integrate; "
                        "a replay needs legs with mass (robot.leg_inertia: full, or links with "
                        "<inertial> in the URDF)");
    }
  throw ConfigError(
      "robot: the mass matrix at the plan's first state is not positive definite "
      "(a body's inertia: robot.*.inertia or the URDF's <inertial>)");
}

BaseState trunk_state_from_row(const RobotModel& model, const Vec3& position_m,
                               const Eigen::Vector4d& wxyz, const Vec3& velocity_mps,
                               const Vec3& omega_radps) {
  BaseState root;
  root.W_R_B =
      Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized().toRotationMatrix();
  root.p_W = position_m;
  root.v_W = velocity_mps;
  root.omega_W = omega_radps;
  return trunk_state_from_root_link(model, root);
}

ReplayPlan plan_from_result(const RobotModel& model, const RunResult& r) {
  const KinematicsResult& k = r.kin;
  if (!r.dyn.present) throw ConfigError("replay: the run has no dynamics to replay");
  ReplayPlan p;
  p.t_s = k.time_s;
  for (int i = 0; i < k.samples(); ++i) {
    p.base.push_back(trunk_state_from_row(
        model, k.base_position.row(i).transpose(), k.base_orientation_wxyz.row(i).transpose(),
        k.base_linear_velocity.row(i).transpose(), k.base_angular_velocity.row(i).transpose()));
    p.q_rad.push_back(k.joint_position.row(i).transpose());
    p.qd_radps.push_back(k.joint_velocity.row(i).transpose());
    p.tau_Nm.push_back(r.dyn.joint_torque.row(i).transpose());
    if (r.dyn.has_drive()) p.tau_drive_Nm.push_back(r.dyn.drive_torque.row(i).transpose());
    if (!p.tau_Nm.back().allFinite())
      throw ConfigError("replay: the torque of sample " + std::to_string(i) +
                        " is not finite (a failed sample cannot be replayed)");
  }
  p.contact_phase = k.contact_phase;
  p.cycle_start_s = r.cycle_start_s;
  p.terrain_y_m = r.terrain_y_m;
  p.terrain_z_m = r.terrain_z_m;
  return p;
}

ArrivalTolerance arrival_tolerance(const TerrainParams& terrain) {
  ArrivalTolerance tol;
  if (terrain.type == TerrainType::kStairs) {
    double going = terrain.tread_depth_m, rise = std::abs(terrain.riser_height_m);
    if (!terrain.step_list.empty()) {  // the shallowest going, the highest riser
      going = std::numeric_limits<double>::infinity();
      rise = 0.0;
      for (const StairStep& s : terrain.step_list) {
        going = std::min(going, s.tread_m);
        rise = std::max(rise, std::abs(s.riser_m));
      }
    }
    tol.horizontal_m = 0.5 * going;
    tol.vertical_m = std::max(0.5 * rise, 0.01);
  } else {
    tol.horizontal_m = tol.vertical_m = 0.05;
  }
  return tol;
}

}  // namespace hexdyn
