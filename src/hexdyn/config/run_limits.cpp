#include "hexdyn/config/run_limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/run_size.hpp"

namespace hexdyn {
namespace {

/// A derived quantity, 3 significant digits.
std::string num(double x) { return format_number(x, 3); }

/// x rounded up to 3 significant digits (for "at least x").
std::string num_up(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return num(x);
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  return num(std::ceil(x / unit * (1.0 - 1e-12)) * unit);
}

/// A value as given, to 10 significant digits.
std::string given(double x) { return format_number(x, 10); }

/// The most cycles whose grid bound stays within the limit (0 when even one cycle does not).
int most_cycles(Scene scene) {
  int lo = 0, hi = scene.motion.cycles;
  while (lo < hi) {
    const int mid = lo + (hi - lo + 1) / 2;
    scene.motion.cycles = mid;
    if (planned_grid_bound(scene).total() <= static_cast<double>(kMaxRunSamples))
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

}  // namespace

void check_run_size_limits(const Scene& scene, const std::string& source,
                           const std::string& cycles_key) {
  const MotionParams& m = scene.motion;
  const OutputParams& o = scene.output;
  auto fail = [&](const std::string& key, const std::string& what) {
    throw ConfigError(source + ": " + key + ": " + what);
  };
  const double duration = planned_duration_s(scene);
  if (!(duration <= kMaxRunDuration_s)) {
    const std::string limit = "expected a motion of at most " + num(kMaxRunDuration_s) +
                              " s (about 28 h, hexdyn's limit on one run)";
    if (!m.cycle_durations_s.empty())
      fail("motion.cycle_durations",
           "got " + std::to_string(m.cycles) + " cycles lasting " + num(duration) + " s, " + limit);
    const double travel_m = (duration - m.ramp_duration_s) * m.peak_speed_mps;  // cycles × stride
    fail("motion.peak_speed", "got " + given(m.peak_speed_mps) + " m/s, a motion of " +
                                  num(duration) + " s (" + std::to_string(m.cycles) + " cycles, " +
                                  num(travel_m) + " m), " + limit + ": a peak speed of at least " +
                                  num_up(travel_m / (kMaxRunDuration_s - m.ramp_duration_s)) +
                                  " m/s, or fewer cycles");
  }
  const GridSizeBound b = planned_grid_bound(scene);
  const double cap = static_cast<double>(kMaxRunSamples);
  if (b.total() <= cap) return;
  const std::string over = "up to " + num(b.total()) + " output samples over the " + num(duration) +
                           " s motion, expected at most " + std::to_string(kMaxRunSamples) +
                           " samples (hexdyn's memory limit: about 4.4 kB per sample while a "
                           "run computes, 4.4 GB at the limit; --allow-large does not lift it)";
  // The key named is the one whose term is largest among those that can bring the bound
  // within the limit on their own; the number of cycles when none can.
  const double transients = b.transient / (std::max(1, o.impact_samples) + 3.0);
  // The grid spans the motion and its last transient; the other terms keep their samples.
  const double span =
      duration + (scene.contact.model == ContactModel::kCompliant ? kMaxTransientDuration_s : 0.0);
  const double room_uniform = cap - (b.total() - b.uniform) - 2.0;  // for the uniform points
  const double room_transient = cap - (b.total() - b.transient);
  const bool by_step = room_uniform >= 1.0 && span / room_uniform <= kMaxSampleStep_s;
  const bool by_impact = room_transient >= 4.0 * transients && o.impact_samples > 1;
  const bool by_event = cap >= b.total() - b.graded && b.graded > 0.0;
  double largest = -1.0;
  std::string key;
  if (by_step) key = "output.sample_step", largest = b.uniform;
  if (by_impact && b.transient > largest) key = "output.impact_samples", largest = b.transient;
  if (by_event && b.graded > largest) key = "output.event_step";
  if (key == "output.sample_step")
    fail(key, "got " + given(o.sample_step_s) + " s, " + over + ": a sample step of at least " +
                  num_up(span / room_uniform) + " s");
  if (key == "output.impact_samples")
    fail(key,
         "got " + std::to_string(o.impact_samples) + " across each of up to " + num(transients) +
             " touchdown transients, " + over + ": at most " +
             std::to_string(static_cast<long long>(std::floor(room_transient / transients) - 3.0)) +
             " impact samples");
  if (key == "output.event_step")
    fail(key, "got " + given(o.event_step_s) + " s below output.sample_step " +
                  given(o.sample_step_s) +
                  " s, graded points on both sides of every contact event, " + over +
                  ": a larger event step");
  const int most = m.cycle_durations_s.empty() ? most_cycles(scene) : 0;
  fail(cycles_key, "got " + std::to_string(m.cycles) + " cycles, " + over +
                       (most > 0 ? ": at most " + std::to_string(most) + " cycles at these output.*"
                                 : std::string(": fewer cycles")));
}

}  // namespace hexdyn
