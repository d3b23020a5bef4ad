#pragma once
/// \file grid.hpp
/// The output grid (docs/theory/output-grid.md): the instants at which a run is sampled,
/// uniform, or refined around contact events.
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// An instant around which the output grid is refined: a touchdown (with its transient
/// of `duration_s`, whose force peak is at t_s + peak_offset_s) or a lift-off.
struct GridEvent {
  double t_s = 0.0;
  double duration_s = 0.0;
  double peak_offset_s = 0.0;
};

/// The output grid on [0, duration_s] [s], increasing: uniform at sample_step from 0 to
/// the end, and for the adaptive grid, in addition, `impact_samples` points across each
/// transient, its peak instant, and points graded geometrically (factor 2) from the
/// finest step up to sample_step on both sides of every event. Points closer than 1e-9 s
/// are merged into the later one.
std::vector<double> build_output_grid(const OutputParams& output, double duration_s,
                                      const std::vector<GridEvent>& events);

}  // namespace hexdyn
