#include "hexdyn/core/run_size.hpp"

#include <algorithm>
#include <cmath>

namespace hexdyn {
namespace {

/// Steps h, 2h, 4h, … below `step`: the graded points on each side of an event
/// (planning/grid.cpp). At most about 2,100 for positive doubles.
double graded_steps(double h, double step) {
  if (!(h > 0.0)) return 0.0;
  double n = 0.0;
  for (double d = h; d < step; d *= 2.0) n += 1.0;
  return n;
}

}  // namespace

const char* GridSizeBound::key() const {
  if (transient >= uniform && transient >= graded) return "output.impact_samples";
  if (graded > uniform) return "output.event_step";
  return "output.sample_step";
}

GridSizeBound output_grid_bound(const OutputParams& out, double duration_s, double liftoffs,
                                double touchdowns, double transients) {
  GridSizeBound b;
  b.uniform = std::floor(std::max(0.0, duration_s) / out.sample_step_s + 1e-9) + 2.0;
  if (out.grid != OutputGrid::kAdaptive) return b;
  const double events = liftoffs + touchdowns;
  const double m = std::max(1, out.impact_samples);
  b.transient = transients * (m + 3.0);  // m + 1 across, its peak and its end
  b.graded = events * 2.0 * graded_steps(out.event_step_s, out.sample_step_s);
  b.events = 2.0 * events + transients;  // each event and its left limit; a transient's end
  return b;
}

double planned_duration_s(const Scene& scene) {
  const MotionParams& m = scene.motion;
  const double stride_m =
      scene.gait.stroke_m / scene.gait.duty_factor / std::cos(mean_slope_rad(scene.terrain));
  return m.cycles * stride_m / m.peak_speed_mps + m.ramp_duration_s;
}

GridSizeBound planned_grid_bound(const Scene& scene) {
  const bool transients = scene.contact.model == ContactModel::kCompliant;
  const double swings = scene.robot.legs * (static_cast<double>(scene.motion.cycles) + 1.0);
  const double duration = planned_duration_s(scene) + (transients ? kMaxTransientDuration_s : 0.0);
  return output_grid_bound(scene.output, duration, swings, swings, transients ? swings : 0.0);
}

}  // namespace hexdyn
