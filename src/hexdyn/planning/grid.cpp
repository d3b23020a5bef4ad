#include "hexdyn/planning/grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/run_size.hpp"

namespace hexdyn {

namespace {

/// The grid's size, bounded before anything is allocated (core/run_size.hpp): the scene
/// reader bounded it from the keys; the planned events are checked here again. Throws
/// ConfigError beyond kMaxRunSamples.
GridSizeBound checked_grid_bound(const OutputParams& out, double duration_s,
                                 const std::vector<GridEvent>& events) {
  double transients = 0.0;
  for (const GridEvent& e : events) transients += e.duration_s > 0.0 ? 1.0 : 0.0;
  const GridSizeBound bound =
      output_grid_bound(out, duration_s, static_cast<double>(events.size()), 0.0, transients);
  if (!(bound.total() <= static_cast<double>(kMaxRunSamples)))
    throw ConfigError(std::string(bound.key()) + ": the output grid of the " +
                      format_number(duration_s, 4) + " s run would have up to " +
                      format_number(bound.total(), 4) + " samples, expected at most " +
                      std::to_string(kMaxRunSamples));
  return bound;
}

}  // namespace

std::vector<double> build_output_grid(const OutputParams& out, double duration_s,
                                      const std::vector<GridEvent>& events,
                                      std::vector<std::int8_t>* sample_kind) {
  const GridSizeBound bound = checked_grid_bound(out, duration_s, events);
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(bound.total()));
  const auto n = static_cast<std::int64_t>(std::floor(duration_s / out.sample_step_s + 1e-9));
  for (std::int64_t i = 0; i <= n; ++i) t.push_back(static_cast<double>(i) * out.sample_step_s);
  t.push_back(duration_s);
  if (out.grid == OutputGrid::kAdaptive) {
    for (const GridEvent& e : events) {
      const double h = out.event_step_s;
      const double t0 = e.t_s, t1 = e.t_s + e.duration_s;
      if (e.duration_s > 0.0) {
        const int m = std::max(1, out.impact_samples);
        for (int j = 0; j <= m; ++j) t.push_back(t0 + e.duration_s * j / m);
        t.push_back(t0 + e.peak_offset_s);
        t.push_back(t1);  // the end, exactly as the contact schedule computes it
      }
      t.push_back(t0);
      // Geometric grading away from the event on both sides, up to the uniform step.
      for (double d = h; d < out.sample_step_s; d *= 2.0) {
        t.push_back(t0 - d);
        t.push_back(t1 + d);
      }
    }
  }
  std::sort(t.begin(), t.end());
  // Points closer than 1e-9 s are merged into the later one, so that the sample at an
  // event is never before it (a touchdown sample is the first one on the ground).
  std::vector<double> grid;
  for (double x : t) {
    if (x < 0.0 || x > duration_s) continue;
    if (!grid.empty() && x - grid.back() < 1e-9) {
      grid.back() = x;
      continue;
    }
    grid.push_back(x);
  }
  if (grid.back() < duration_s - 1e-9) grid.push_back(duration_s);

  // Left limits (docs/theory/output-grid.md#event-samples). Every point closer than 1e-9 s
  // before an event was merged into one at or after it, so none lies in [e − offset, e).
  std::vector<double> left;
  if (out.grid == OutputGrid::kAdaptive) {
    for (const GridEvent& e : events) {
      left.push_back(e.t_s - kLeftLimitOffset_s);
      if (e.duration_s > 0.0) left.push_back(e.t_s + e.duration_s - kLeftLimitOffset_s);
    }
    std::sort(left.begin(), left.end());
    std::vector<double> kept;
    for (double x : left) {
      if (x <= 0.0 || x >= duration_s) continue;
      if (!kept.empty() && x - kept.back() < 1e-9) continue;  // merged into the earliest
      kept.push_back(x);
    }
    left = std::move(kept);
  }
  std::vector<double> merged;
  std::vector<std::int8_t> kind;
  merged.reserve(grid.size() + left.size());
  kind.reserve(grid.size() + left.size());
  std::size_t a = 0, b = 0;
  while (a < grid.size() || b < left.size()) {
    if (b < left.size() && a < grid.size() && left[b] == grid[a]) {
      ++b;  // cannot happen (see above); keeps the grid strictly increasing regardless
      continue;
    }
    if (b < left.size() && (a == grid.size() || left[b] < grid[a])) {
      merged.push_back(left[b++]);
      kind.push_back(kSampleLeftLimit);
    } else {
      merged.push_back(grid[a++]);
      kind.push_back(kSampleOrdinary);
    }
  }
  if (sample_kind) *sample_kind = std::move(kind);
  return merged;
}

}  // namespace hexdyn
