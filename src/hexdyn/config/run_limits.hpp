#pragma once
/// \file run_limits.hpp
/// The size limits of one run (core/run_size.hpp), checked on a scene whose keys are each in
/// range (config.cpp), before anything is planned: the planned motion's duration and an upper
/// bound of its output samples. Each refusal is one ConfigError line "SOURCE: key: got X, …
/// expected at most LIMIT (…)", naming the key whose change brings the run within the limit.
#include <string>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Largest output.sample_step [s] (config.cpp reads it in (0, 100]).
inline constexpr double kMaxSampleStep_s = 100.0;

/// Throws ConfigError when `scene` plans a motion longer than kMaxRunDuration_s (naming
/// motion.peak_speed, or motion.cycle_durations) or an output grid of more than
/// kMaxRunSamples samples. The key named for the samples is, of output.sample_step,
/// output.impact_samples and output.event_step, the one adding most samples among those
/// whose change alone brings the bound within the limit (with the value that does); when
/// none can, `cycles_key` (motion.cycles, motion.travel or motion.cycle_durations) with the
/// most cycles that fit.
void check_run_size_limits(const Scene& scene, const std::string& source,
                           const std::string& cycles_key);

}  // namespace hexdyn
