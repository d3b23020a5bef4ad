#pragma once
/// \file grid.hpp
/// The output grid (docs/theory/output-grid.md): the instants at which a run is sampled,
/// uniform, or refined around contact events.
#include <cstdint>
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// An instant around which the output grid is refined: a touchdown (with its transient
/// of `duration_s`, whose force peak is at t_s + peak_offset_s) or a lift-off. Its
/// contact events are t_s and, for a transient, t_s + duration_s (its end).
struct GridEvent {
  double t_s = 0.0;
  double duration_s = 0.0;
  double peak_offset_s = 0.0;
};

/// How far before a contact event its left-limit sample lies [s]
/// (docs/theory/output-grid.md#event-samples): far below any merged gap (1e-9 s), far above
/// the rounding of t.
inline constexpr double kLeftLimitOffset_s = 1e-10;

/// /sample_kind codes: an ordinary sample, or the left limit of a contact event.
inline constexpr std::int8_t kSampleOrdinary = 0;
inline constexpr std::int8_t kSampleLeftLimit = 1;

/// The output grid on [0, duration_s] [s], strictly increasing: uniform at sample_step from
/// 0 to the end, and for the adaptive grid, in addition, `impact_samples` points across
/// each transient, its end and peak instant, and points graded geometrically (factor 2)
/// from the finest step up to sample_step on both sides of every event. These points,
/// when closer than 1e-9 s, are merged into the later one. The adaptive grid adds, last,
/// the **left limit** of every contact event e > kLeftLimitOffset_s (a touchdown, the end
/// of its transient, a lift-off): the point e − kLeftLimitOffset_s (left limits closer
/// than 1e-9 s to each other are merged into the earliest one; no other point lies in
/// [e − kLeftLimitOffset_s, e)). `sample_kind` (may be null) receives one code per point
/// (kSampleOrdinary, kSampleLeftLimit). The uniform grid has no left limits.
std::vector<double> build_output_grid(const OutputParams& output, double duration_s,
                                      const std::vector<GridEvent>& events,
                                      std::vector<std::int8_t>* sample_kind = nullptr);

}  // namespace hexdyn
