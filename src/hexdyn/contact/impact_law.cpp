// The compliant law of paper eq. 7–8 and the sampled transient's interpolation
// (contact/impact.hpp; docs/theory/contact.md#compliant-impact-law). The transient's
// integration is in impact.cpp.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

#include "hexdyn/contact/impact.hpp"

namespace hexdyn {

double impact_step(double x, double x0, double h0, double x1, double h1) {
  if (x <= x0) return x1 <= x0 && x >= x0 ? h1 : h0;
  if (x >= x1) return h1;
  const double d = (x - x0) / (x1 - x0);
  return h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d);
}

double impact_step_derivative(double x, double x0, double h0, double x1, double h1) {
  if (x <= x0 || x >= x1) return 0.0;
  const double w = x1 - x0;
  const double d = (x - x0) / w;
  return (h1 - h0) * 6.0 * d * (1.0 - d) / w;
}

double impact_normal_force(const ContactParams& c, double delta_m, double delta_rate_mps) {
  if (!(delta_m > 0.0)) return 0.0;
  const double spring = c.stiffness * std::pow(delta_m, c.exponent);
  const double step = impact_step(delta_m, 0.0, 0.0, c.full_damping_depth_m, 1.0);
  return std::max(0.0, spring + c.damping_max_Nspm * step * delta_rate_mps);  // eq. 7
}

double static_penetration(const ContactParams& c, double normal_force_N) {
  if (!(normal_force_N > 0.0)) return 0.0;
  return std::pow(normal_force_N / c.stiffness, 1.0 / c.exponent);
}

namespace {
double interpolate(const std::vector<double>& t, const std::vector<double>& value, double at) {
  if (t.empty() || at < t.front() || at > t.back()) return 0.0;
  const auto hi = std::upper_bound(t.begin(), t.end(), at);
  if (hi == t.end()) return value.back();
  const auto i = static_cast<std::size_t>(std::distance(t.begin(), hi));
  if (i == 0) return value.front();
  const double t0 = t[i - 1], t1 = t[i];
  const double a = t1 > t0 ? (at - t0) / (t1 - t0) : 1.0;
  return (1.0 - a) * value[i - 1] + a * value[i];
}
}  // namespace

double transient_force_at(const ImpactTransient& tr, double t_since_touchdown_s) {
  if (!tr.occurred) return 0.0;
  return interpolate(tr.t_s, tr.force_N, t_since_touchdown_s);
}

double transient_penetration_at(const ImpactTransient& tr, double t_since_touchdown_s) {
  if (!tr.occurred) return 0.0;
  return interpolate(tr.t_s, tr.penetration_m, t_since_touchdown_s);
}

}  // namespace hexdyn
