#pragma once
/// \file run_size.hpp
/// How large one run may grow, computed from the scene's keys alone, before anything is
/// planned or allocated (docs/user/faults.md#sizes). Every quantity that grows with the input
/// is bounded here, in double or 64-bit arithmetic (no int can overflow on the way):
///   cycles        motion.cycles, the length of motion.cycle_durations, the cycles of
///                 motion.travel: at most kMaxCycles;
///   duration      the planned motion: at most kMaxRunDuration_s;
///   samples       an upper bound of the output grid's samples (planning/grid.hpp): at most
///                 kMaxRunSamples, whatever `--allow-large` says.
/// The scene reader (config/config.cpp) refuses a scene beyond them with one line naming the key;
/// the grid builder checks the bound again on the planned events before it allocates.
#include <cstdint>
#include <string>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Most gait cycles of one run: 10,000 (the paper walks 3). Planning holds the touchdown
/// transients of every cycle, about 0.1 MB a cycle for the paper robot (1.1 GB and 12 s for
/// 10,000 cycles); also the longest motion.cycle_durations list.
inline constexpr int kMaxCycles = 10000;

/// Longest planned motion [s]: 100,000 s, about 28 hours of walking.
inline constexpr double kMaxRunDuration_s = 1e5;

/// Most output samples of one run, a limit of memory that no flag lifts: a run holds about
/// 4.4 kB per sample while it computes and writes (measured on the paper scene: 377 MB at
/// 86,000 samples), so 1,000,000 samples need about 4.4 GB and give a result file of about
/// 1.5 GB (io/output.hpp estimated_result_file_bytes). Five times io/output.hpp's
/// kLargeResultSamples, which `--allow-large` lifts.
inline constexpr std::int64_t kMaxRunSamples = 1000000;

/// Longest touchdown transient [s]: the integration's guard (contact/impact.hpp
/// ImpactOptions::max_duration_s, checked there against this value).
inline constexpr double kMaxTransientDuration_s = 1.0;

/// The output grid's samples, bounded from above term by term (planning/grid.hpp
/// build_output_grid builds at most their sum). Doubles: a term may exceed any integer.
struct GridSizeBound {
  double uniform = 0.0;    ///< every output.sample_step over the run, and its end
  double transient = 0.0;  ///< output.impact_samples + 3 points per touchdown transient
  double graded = 0.0;     ///< points graded by factors of 2 from output.event_step, each event
  double events = 0.0;     ///< the events themselves and their left limits
  double total() const { return uniform + transient + graded + events; }
  /// The output key whose term is the largest: output.sample_step, output.impact_samples or
  /// output.event_step.
  const char* key() const;
};

/// The bound of a grid of `duration_s` [s] with `liftoffs` lift-offs and `touchdowns`
/// touchdowns, `transients` of which have a transient (the adaptive grid's events; the
/// uniform grid has none).
GridSizeBound output_grid_bound(const OutputParams& output, double duration_s, double liftoffs,
                                double touchdowns, double transients);

/// The planned motion's duration [s], from validated motion keys: cycles × stride / peak speed
/// + ramp (planning/motion.hpp TrunkMotion::duration_s), which for motion.cycle_durations is
/// their sum.
double planned_duration_s(const Scene& scene);

/// The bound of a scene's output grid, before planning: its duration plus the longest
/// transient, and for each leg at most cycles + 1 swings (a lift-off and a touchdown each;
/// every touchdown with a transient when contacts are compliant).
GridSizeBound planned_grid_bound(const Scene& scene);

}  // namespace hexdyn
