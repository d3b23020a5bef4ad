#include "hexdyn/config/plausibility.hpp"

#include <cmath>
#include <sstream>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

/// Peak acceleration factor of the smootherstep: max |S''| = 10/√3.
constexpr double kSmootherstepPeak = 5.773502691896258;

/// A derived quantity, 3 significant digits.
std::string num(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

/// A value as given, to 10 significant digits (0.99999 stays 0.99999).
std::string given(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

/// Shortest time for a smootherstep move of `distance` at the acceleration bound [s].
double min_move_time(double distance_m) {
  return std::sqrt(kSmootherstepPeak * distance_m / kMaxPlannedAcceleration);
}

}  // namespace

void check_physical_plausibility(const Scene& scene, const std::string& source) {
  const GaitParams& g = scene.gait;
  const MotionParams& m = scene.motion;
  const double a = kMaxPlannedAcceleration;
  // Messages are built only when a check fails (a sweep checks every scenario).
  const char* why =
      " when no foot or trunk accelerates beyond 100 g (981 m/s^2, far beyond any legged robot's "
      "actuators)";
  auto fail = [&](const std::string& key, const std::string& what) {
    throw ConfigError(source + ": " + key + ": " + what);
  };
  const bool by_durations = !m.cycle_durations_s.empty();
  const char* motion_key = by_durations ? "motion.cycle_durations" : "motion.peak_speed";
  // Trunk travel per cycle along the slope and the shortest (cruise) cycle.
  const double stride_m = g.stroke_m / g.duty_factor;
  const double cycle_s = stride_m / std::cos(mean_slope_rad(scene.terrain)) / m.peak_speed_mps;
  const double swing_s = (1.0 - g.duty_factor) * cycle_s;
  const double clearance = g.swing_clearance_m;
  const double t_lift_min = min_move_time(clearance);
  const double t_lower_min = t_lift_min;
  const double t_swing_min = t_lift_min + t_lower_min + min_move_time(stride_m);
  if (swing_s < t_swing_min) {
    const std::string motion_value =
        by_durations ? "a cruise cycle of " + given(cycle_s) + " s"
                     : given(m.peak_speed_mps) + " m/s (a cruise cycle of " + num(cycle_s) + " s)";
    const std::string need = "expected a swing time (1 - duty factor) x cycle of at least " +
                             num(t_swing_min) + " s (lift by the clearance " + num(clearance) +
                             " m, carry the foot " + num(stride_m) + " m, lower it)" + why;
    // Blame the motion when even the tripod (β = 1/2) could not swing in time.
    if (0.5 * cycle_s < t_swing_min)
      fail(motion_key,
           "got " + motion_value + ", which leaves a swing of " + num(swing_s) + " s; " + need);
    fail("gait.duty_factor", "got " + given(g.duty_factor) + ", which leaves a swing of " +
                                 num(swing_s) + " s in the cruise cycle of " + num(cycle_s) +
                                 " s; " + need + ": a duty factor of at most " +
                                 num(1.0 - t_swing_min / cycle_s));
  }
  if (g.lift_fraction * swing_s < t_lift_min)
    fail("gait.lift_fraction",
         "got " + given(g.lift_fraction) + ", a lift time of " + num(g.lift_fraction * swing_s) +
             " s in the " + num(swing_s) + " s swing; expected at least " + num(t_lift_min) +
             " s to lift the foot by the clearance " + num(clearance) + " m" + why +
             ": a lift fraction of at least " + num(t_lift_min / swing_s));
  if (g.lower_fraction * swing_s < t_lower_min)
    fail("gait.lower_fraction", "got " + given(g.lower_fraction) + ", a lowering time of " +
                                    num(g.lower_fraction * swing_s) + " s in the " + num(swing_s) +
                                    " s swing; expected at least " + num(t_lower_min) +
                                    " s to lower the foot by the clearance " + num(clearance) +
                                    " m" + why + ": a lower fraction of at least " +
                                    num(t_lower_min / swing_s));
  const double t_ramp_min = 1.875 * m.peak_speed_mps / a;
  if (m.ramp_duration_s < t_ramp_min)
    fail(by_durations ? "motion.cycle_durations" : "motion.ramp_duration",
         "got a speed ramp of " + num(m.ramp_duration_s) + " s to " + num(m.peak_speed_mps) +
             " m/s, expected at least " + num(t_ramp_min) +
             " s (the ramp's peak trunk acceleration is 1.875 v / ramp)" + why);
}

}  // namespace hexdyn
