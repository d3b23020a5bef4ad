#include "hexdyn/robustness/outcome.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The first sample at which a foot's slip distance passes the bound (NaN: none).
double slip_time(const ReplayResult& r, int legs, double bound_m) {
  for (std::size_t i = 0; i < r.t_s.size(); ++i)
    for (int l = 0; l < legs; ++l)
      if (r.slip_distance_m[i][l] > bound_m) return r.t_s[i];
  return kNaN;
}

/// The first sample at which a foot the plan has in swing carries more than the bound's share
/// of the weight on a face steeper than its tilt: a riser, or a nosing's rounded edge.
double stub_time(const ReplayResult& r, const RowMatrixI8& phase, const World& w,
                 const FailureBounds& b) {
  const double weight = w.model.total_mass_kg * w.model.gravity_W.norm();
  const double cos_tilt = std::cos(b.stub_tilt_rad);
  for (std::size_t i = 0; i < r.t_s.size(); ++i)
    for (int l = 0; l < w.model.legs(); ++l)
      if (phase(static_cast<Eigen::Index>(i), l) ==
              static_cast<std::int8_t>(ContactPhase::kSwing) &&
          r.normal_N[i][l] > b.stub_force_fraction * weight && r.normal_W[i][l].z() < cos_tilt)
        return r.t_s[i];
  return kNaN;
}

/// The first sample at which a joint's time at its bound, summed over the intervals that end
/// at a saturated sample, passes the bound; the replay's end when only the integrator's exact
/// total (ReplayResult::saturation_time_s) does; NaN when neither does.
double saturation_time(const ReplayResult& r, const FailureBounds& b, double longest_s) {
  if (r.saturated.empty() || !(longest_s > b.saturation_s)) return kNaN;
  std::vector<double> sum(static_cast<std::size_t>(r.saturated.front().size()), 0.0);
  for (std::size_t i = 1; i < r.t_s.size(); ++i)
    for (std::size_t j = 0; j < sum.size(); ++j) {
      if (r.saturated[i][static_cast<Eigen::Index>(j)] == 0.0) continue;
      sum[j] += r.t_s[i] - r.t_s[i - 1];
      if (sum[j] > b.saturation_s) return r.t_s[i];
    }
  return r.t_s.back();
}

void set_margin(ReplayOutcome& o, const FailureBounds& b, bool driven) {
  const std::array<double, 3> used{o.slip_m / b.slip_m, o.drift_m / b.drift_m,
                                   driven ? o.saturation_s / b.saturation_s : 0.0};
  o.margin = 1.0;
  for (std::size_t k = 0; k < used.size(); ++k)
    if (1.0 - used[k] < o.margin || k == 0) {
      o.margin = 1.0 - used[k];
      o.margin_criterion = static_cast<MarginCriterion>(k);
    }
}

}  // namespace

const char* failure_class_name(FailureClass c) {
  static constexpr std::array<const char*, kFailureClassCount> kNames{
      "none", "slipped", "stubbed", "saturated", "fell", "drifted"};
  return kNames[static_cast<std::size_t>(c)];
}

const char* margin_criterion_name(MarginCriterion c) {
  static constexpr std::array<const char*, 3> kNames{"slip", "drift", "saturation"};
  return kNames[static_cast<std::size_t>(c)];
}

ReplayOutcome classify_replay(const ReplayResult& r, const ReplayPlan& plan, const World& world,
                              const TerrainParams& plan_terrain, const FailureBounds& b) {
  ReplayOutcome o;
  const int legs = world.model.legs();
  for (int l = 0; l < legs; ++l) o.slip_m = std::max(o.slip_m, r.slip_distance_total_m[l]);
  for (double s : r.saturation_time_s) o.saturation_s = std::max(o.saturation_s, s);
  o.energy_J = r.energy_J;
  o.electrical_energy_J = world.model.drive.present ? r.electrical_energy_J : kNaN;
  o.steps = r.steps;
  o.seconds = r.seconds;
  // Where the trunk ended against the plan's end: horizontally, and in height above each one's
  // own terrain (stairs a riser off lift the trunk with them: no drift).
  const Vec3 end = r.base.back().p_W, planned = plan.base.back().p_W;
  o.drift_m = (end - planned).head<2>().norm();
  o.height_error_m = (end.z() - Terrain(world.terrain).height(end.x(), end.y())) -
                     (planned.z() - Terrain(plan_terrain).height(planned.x(), planned.y()));
  const bool completed = r.message.empty() && r.t_s.size() == plan.t_s.size();
  // Each class's time (NaN: not met), the earliest wins; a tie goes to the first in class order.
  std::array<double, kFailureClassCount> at{};
  at.fill(kNaN);
  at[1] = slip_time(r, legs, b.slip_m);
  at[2] = stub_time(r, plan.contact_phase, world, b);
  at[3] = saturation_time(r, b, o.saturation_s);
  if (!completed) at[4] = r.t_s.back();
  if (completed && (o.drift_m > b.drift_m ||
                    std::abs(o.height_error_m) > arrival_tolerance(plan_terrain).vertical_m))
    at[5] = r.t_s.back();
  for (int c = 1; c < kFailureClassCount; ++c)
    if (!std::isnan(at[static_cast<std::size_t>(c)]) &&
        !(at[static_cast<std::size_t>(c)] >= o.failure_time_s)) {
      o.failure = static_cast<FailureClass>(c);
      o.failure_time_s = at[static_cast<std::size_t>(c)];
    }
  o.reached_top = o.failure == FailureClass::kNone;
  set_margin(o, b, world.model.drive.present);
  return o;
}

WilsonInterval wilson_interval(long successes, long n, double z) {
  if (n <= 0) return {};
  const double nn = static_cast<double>(n), p = static_cast<double>(successes) / nn;
  const double z2 = z * z, denom = 1.0 + z2 / nn;
  const double centre = (p + z2 / (2.0 * nn)) / denom;
  const double half = z / denom * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace hexdyn
