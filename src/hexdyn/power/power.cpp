#include "hexdyn/power/power.hpp"

#include <gsl/gsl_interp.h>

namespace hexdyn {

double integrate_series(const std::vector<double>& t, const double* y, int stride) {
  return integrate_pieces(t, y, stride, {}, {});
}

namespace {

/// ∫ over points (t_k, y_k), k < n (integrate_pieces explains the rule).
double integrate_piece(const double* t, const double* y, std::size_t n) {
  if (n < 2) return 0.0;
  if (n == 2) return 0.5 * (t[1] - t[0]) * (y[0] + y[1]);
  gsl_interp* interp = gsl_interp_alloc(gsl_interp_steffen, n);
  gsl_interp_accel* acc = gsl_interp_accel_alloc();
  gsl_interp_init(interp, t, y, n);
  const double value = gsl_interp_eval_integ(interp, t, y, t[0], t[n - 1], acc);
  gsl_interp_accel_free(acc);
  gsl_interp_free(interp);
  return value;
}

}  // namespace

double integrate_pieces(const std::vector<double>& t, const double* y, int stride,
                        const std::vector<int>& break_index,
                        const std::vector<double>& left_value) {
  const std::size_t n = t.size();
  if (n < 2) return 0.0;
  std::vector<double> ys;
  ys.reserve(n);
  double total = 0.0;
  std::size_t a = 0;  // first sample of the current piece
  auto close_piece = [&](std::size_t b, double y_end) {
    ys.clear();
    for (std::size_t k = a; k < b; ++k) ys.push_back(y[k * stride]);
    ys.push_back(y_end);
    total += integrate_piece(t.data() + a, ys.data(), b - a + 1);
    a = b;
  };
  for (std::size_t k = 0; k < break_index.size(); ++k) {
    const auto b = static_cast<std::size_t>(break_index[k]);
    if (b <= a || b >= n) continue;
    close_piece(b, left_value[k]);
  }
  close_piece(n - 1, y[(n - 1) * stride]);
  return total;
}

PowerResult compute_power(const KinematicsResult& kin, const RowMatrix& joint_torque,
                          double total_mass_kg, double distance_m,
                          const std::vector<PowerJump>& jumps) {
  const int T = kin.samples();
  PowerResult p;
  p.joint_power = joint_torque.cwiseProduct(kin.joint_velocity);
  p.total_power_W.assign(T, 0.0);
  RowMatrix abs_power = p.joint_power.cwiseAbs();
  for (int i = 0; i < T; ++i) p.total_power_W[i] = abs_power.row(i).sum();
  std::vector<int> breaks;
  for (const PowerJump& j : jumps) breaks.push_back(j.index);
  std::vector<double> left(jumps.size());
  p.energy_joint_J.assign(kJoints, 0.0);
  p.energy_total_J = 0.0;
  for (int j = 0; j < kJoints; ++j) {
    for (std::size_t k = 0; k < jumps.size(); ++k) left[k] = jumps[k].abs_power_left_W(j);
    p.energy_joint_J[j] = integrate_pieces(kin.time_s, abs_power.data() + j, kJoints, breaks, left);
    p.energy_total_J += p.energy_joint_J[j];
  }
  p.distance_m = distance_m;
  p.cost_of_transport = p.energy_total_J / (total_mass_kg * kGravity * distance_m);
  return p;
}

}  // namespace hexdyn
