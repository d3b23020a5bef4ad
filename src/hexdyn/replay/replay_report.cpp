#include "hexdyn/replay/replay_report.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hexdyn/replay/joint_drive.hpp"
#include "hexdyn/replay/lane_sums.hpp"

namespace hexdyn {

using replay_sums::lane_abs_dot;

void finish_report(const ReplayPlan& plan, const TerrainParams& terrain,
                   const DriveTrainParams& drive, bool completed, ReplayResult& r) {
  const std::size_t n = r.t_s.size();
  const std::vector<JointVector>& tau = drive.present ? plan.tau_drive_Nm : plan.tau_Nm;
  std::vector<double> ends(
      plan.cycle_start_s.begin() + std::min<std::size_t>(1, plan.cycle_start_s.size()),
      plan.cycle_start_s.end());
  ends.push_back(plan.t_s.back());
  for (double t_end : ends) {
    if (t_end > r.t_s.back() + 1e-12) break;
    const auto at = std::lower_bound(r.t_s.begin(), r.t_s.end(), t_end - 1e-12);
    const std::size_t i = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(at - r.t_s.begin(), static_cast<std::ptrdiff_t>(n) - 1));
    const BaseState& pb = plan.base[i];
    r.cycle_end_s.push_back(r.t_s[i]);
    r.position_drift_m.push_back(r.base[i].p_W - pb.p_W);
    const Eigen::AngleAxisd d(pb.W_R_B.transpose() * r.base[i].W_R_B);
    r.orientation_drift_rad.push_back(d.angle() * d.axis());
  }
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Index j = 0;
    const double e = r.tracking_error[i].cwiseAbs().maxCoeff(&j);
    if (e > r.max_tracking_error_rad) {
      r.max_tracking_error_rad = e;
      r.max_tracking_error_joint = static_cast<int>(j);
      r.max_tracking_error_time_s = r.t_s[i];
    }
    if (i > 0) {
      const double dt = r.t_s[i] - r.t_s[i - 1];
      const auto power = [&](std::size_t s) { return lane_abs_dot(tau[s], plan.qd_radps[s]); };
      r.energy_plan_J += 0.5 * dt * (power(i) + power(i - 1));
    }
  }
  if (drive.present) {
    const auto power = [&](std::size_t i) {
      return electrical_power_total(drive, plan.tau_drive_Nm[i], plan.qd_radps[i]);
    };
    for (std::size_t i = 1; i < n; ++i)
      r.electrical_energy_plan_J += 0.5 * (r.t_s[i] - r.t_s[i - 1]) * (power(i) + power(i - 1));
    r.electrical_energy_J = r.electrical_J.back();
  }
  r.slip_distance_total_m = r.slip_distance_m.back();
  r.slip_energy_total_J = r.slip_energy_J.back();
  r.damping_total_J = r.damping_energy_J.back();
  r.energy_J = r.actuator_energy_J.back();
  const BaseState& end_plan = plan.base[n - 1];
  const BaseState& end = r.base.back();
  r.final_position_error_m = end.p_W - end_plan.p_W;
  const ArrivalTolerance tol = arrival_tolerance(terrain);
  const double tilt =
      std::acos(std::clamp((end.W_R_B.col(2)).dot(end_plan.W_R_B.col(2)), -1.0, 1.0));
  r.reached_top = completed && r.final_position_error_m.head<2>().norm() <= tol.horizontal_m &&
                  std::abs(r.final_position_error_m.z()) <= tol.vertical_m && tilt <= tol.tilt_rad;
}

}  // namespace hexdyn
