#include "hexdyn/power/power.hpp"

#include <algorithm>

namespace hexdyn {

double trapezoid(const std::vector<double>& t, const double* y, int stride) {
  double sum = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k)
    sum += 0.5 * (t[k] - t[k - 1]) * (y[(k - 1) * stride] + y[k * stride]);
  return sum;
}

namespace {

/// The piecewise-linear interpolant of (t, y) at x ∈ [t.front(), t.back()], and the index
/// k of the first sample with t[k] > x (t.size() when none).
double interpolate(const std::vector<double>& t, const double* y, double x, std::size_t& k) {
  k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  if (k == 0) return y[0];
  if (k == t.size()) return y[t.size() - 1];
  const double w = (x - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

}  // namespace

double trapezoid_between(const std::vector<double>& t, const double* y, double a, double b) {
  if (t.size() < 2 || b <= a) return 0.0;
  std::size_t ka = 0, kb = 0;
  const double ya = interpolate(t, y, a, ka), yb = interpolate(t, y, b, kb);
  // Samples strictly inside (a, b): t[ka] … t[j] with t[j] < b.
  double sum = 0.0, t_prev = a, y_prev = ya;
  for (std::size_t k = ka; k < t.size() && t[k] < b; ++k) {
    sum += 0.5 * (t[k] - t_prev) * (y_prev + y[k]);
    t_prev = t[k];
    y_prev = y[k];
  }
  return sum + 0.5 * (b - t_prev) * (y_prev + yb);
}

Quadrature energy_rule(OutputGrid grid) {
  return grid == OutputGrid::kAdaptive ? Quadrature::kCubic : Quadrature::kTrapezoid;
}

std::vector<char> jump_intervals(const KinematicsResult& kin) {
  constexpr std::int8_t kLeftLimit = 1;  // planning/grid.hpp kSampleLeftLimit
  std::vector<char> jump(kin.time_s.size(), 0);
  for (std::size_t k = 0; k < kin.sample_kind.size() && k < jump.size(); ++k)
    jump[k] = kin.sample_kind[k] == kLeftLimit;
  return jump;
}

namespace {

/// Each joint's interval integrals of |τ_k ω_k| and of τ_k ω_k by the piecewise-cubic rule:
/// `known`'s when they belong to this grid, else computed into `own` (all joints at once).
const CubicEstimates& joint_interval_estimates(const KinematicsResult& kin,
                                               const RowMatrix& joint_power,
                                               const std::vector<char>& jump,
                                               const CubicEstimates* known, CubicEstimates& own) {
  const std::size_t n = kin.time_s.empty() ? 0 : kin.time_s.size() - 1;
  const auto J = static_cast<std::size_t>(joint_power.cols());
  bool usable = known && known->t_s == kin.time_s && known->integral.size() >= J &&
                known->signed_integral.size() >= J;
  for (std::size_t j = 0; usable && j < J; ++j)
    usable = known->integral[j].size() == n && known->signed_integral[j].size() == n;
  if (usable) return *known;
  own.integral.assign(J, std::vector<double>(n, 0.0));
  own.signed_integral.assign(J, std::vector<double>(n, 0.0));
  std::vector<CubicTarget> targets;
  for (std::size_t j = 0; j < J; ++j)
    targets.push_back({{joint_power.data() + j, static_cast<int>(J)},
                       own.integral[j].data(),
                       nullptr,
                       own.signed_integral[j].data()});
  cubic_abs_integrals_batch(kin.time_s, jump, targets);
  return own;
}

/// The positive and negative parts of each joint's work (PowerResult), from its energy and
/// its signed integral by the same rule: the sum of `parts`' signed interval terms (the cubic
/// rule), or the trapezoid when `parts` is null.
void split_work(const KinematicsResult& kin, const CubicEstimates* parts, PowerResult& p) {
  const int J = static_cast<int>(p.joint_power.cols());
  p.positive_work_joint_J.assign(J, 0.0);
  p.negative_work_joint_J.assign(J, 0.0);
  for (int j = 0; j < J; ++j) {
    const double* y = p.joint_power.data() + j;
    double net = 0.0;
    if (parts)
      for (double v : parts->signed_integral[j]) net += v;
    else
      net = trapezoid(kin.time_s, y, J);
    // |net| ≤ E_k holds for the rule's parts; the clamp keeps the signs through rounding.
    p.positive_work_joint_J[j] = std::max(0.0, 0.5 * (p.energy_joint_J[j] + net));
    p.negative_work_joint_J[j] = std::min(0.0, 0.5 * (net - p.energy_joint_J[j]));
    p.positive_work_J += p.positive_work_joint_J[j];
    p.negative_work_J += p.negative_work_joint_J[j];
  }
}

}  // namespace

PowerResult compute_power(const KinematicsResult& kin, const RowMatrix& joint_torque,
                          double total_mass_kg, double distance_m,
                          const std::vector<double>& cycle_start_s, Quadrature rule,
                          const CubicEstimates* known) {
  const int T = kin.samples();
  const int J = static_cast<int>(joint_torque.cols());
  PowerResult p;
  p.joint_power = joint_torque.cwiseProduct(kin.joint_velocity);
  p.total_power_W.assign(T, 0.0);
  const RowMatrix abs_power = p.joint_power.cwiseAbs();
  for (int i = 0; i < T; ++i) p.total_power_W[i] = abs_power.row(i).sum();
  const bool cubic = rule == Quadrature::kCubic;
  const std::vector<char> jump = cubic ? jump_intervals(kin) : std::vector<char>{};
  CubicEstimates own;
  const CubicEstimates* parts =
      cubic ? &joint_interval_estimates(kin, p.joint_power, jump, known, own) : nullptr;
  p.energy_joint_J.assign(J, 0.0);
  for (int j = 0; j < J; ++j) {
    if (!cubic) {
      p.energy_joint_J[j] = trapezoid(kin.time_s, abs_power.data() + j, J);
      continue;
    }
    for (double e : parts->integral[j]) p.energy_joint_J[j] += e;
  }
  split_work(kin, parts, p);
  if (cubic) {
    for (double e : p.energy_joint_J) p.energy_total_J += e;
  } else {
    p.energy_total_J = trapezoid(kin.time_s, p.total_power_W.data());
  }
  // Cycle k runs from its start to the next one's; the last to the run's end (a final
  // transient may outlast the motion).
  const double t_end = T > 0 ? kin.time_s.back() : 0.0;
  for (std::size_t k = 0; k < cycle_start_s.size(); ++k) {
    const double a = cycle_start_s[k];
    const double b = k + 1 < cycle_start_s.size() ? std::min(cycle_start_s[k + 1], t_end) : t_end;
    double e = 0.0;
    if (!cubic) e = trapezoid_between(kin.time_s, p.total_power_W.data(), a, b);
    for (int j = 0; cubic && j < J; ++j)
      e += cubic_abs_integral_between(kin.time_s, jump, {p.joint_power.data() + j, J}, a, b,
                                      parts->integral[j].data());
    p.energy_cycle_J.push_back(e);
  }
  p.distance_m = distance_m;
  p.cost_of_transport = p.energy_total_J / (total_mass_kg * kGravity * distance_m);
  return p;
}

}  // namespace hexdyn
