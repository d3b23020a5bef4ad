#pragma once
/// \file outcome.hpp
/// What became of one replay on a perturbed world, and what many replays say
/// (docs/theory/robustness.md#outcomes): whether the robot reached the top, the first way it
/// failed, its drift, slip, energy and worst margin; and the Wilson score interval of a
/// success probability.
#include <cstdint>
#include <string>

#include "hexdyn/core/result.hpp"
#include "hexdyn/replay/replay.hpp"
#include "hexdyn/robustness/world.hpp"

namespace hexdyn {

/// The failure classes, in the order of the file's flag meanings (codes 0 …).
enum class FailureClass : std::int8_t {
  kNone = 0,       ///< reached the top with every bound kept
  kSlipped = 1,    ///< a foot slid further than FailureBounds::slip_m
  kStubbed = 2,    ///< a swing foot met a riser or nosing (a face tilted > stub_tilt_rad)
  kSaturated = 3,  ///< a drive spent longer than saturation_s at its torque–speed bound
  kFell = 4,       ///< the trunk fell (replay.hpp kFallHeightFraction, kFallTilt_rad) or the
                   ///< integration diverged
  kDrifted = 5,    ///< ended farther from the plan's end than drift_m, or at another height
};
inline constexpr int kFailureClassCount = 6;
/// "none", "slipped", "stubbed", "saturated", "fell", "drifted".
const char* failure_class_name(FailureClass c);

/// The criteria of a margin (ReplayOutcome::margin_criterion), in flag order.
enum class MarginCriterion : std::int8_t { kSlip = 0, kDrift = 1, kSaturation = 2 };
const char* margin_criterion_name(MarginCriterion c);

/// One replay's outcome.
struct ReplayOutcome {
  bool reached_top = false;  ///< failure == kNone
  FailureClass failure = FailureClass::kNone;
  /// When the failure began: the first sample past its bound (the replay's end for a drift) [s];
  /// NaN without a failure.
  double failure_time_s = std::numeric_limits<double>::quiet_NaN();
  double drift_m = 0.0;  ///< horizontal distance of the trunk's end from the plan's end [m]
  /// The trunk's height above the world's terrain at the end, less the plan's above its own [m].
  double height_error_m = 0.0;
  double slip_m = 0.0;               ///< largest slip distance of one foot [m]
  double energy_J = 0.0;             ///< ∫ Σ|τ q̇| dt of the replay [J]
  double electrical_energy_J = 0.0;  ///< with actuators; NaN without [J]
  double saturation_s = 0.0;         ///< longest time one joint spent saturated [s]
  /// The least of 1 − value / bound over slip, drift and (with actuators) saturation: 1 untouched,
  /// 0 at a bound, negative beyond; and which criterion gave it.
  double margin = 1.0;
  MarginCriterion margin_criterion = MarginCriterion::kSlip;
  long steps = 0;        ///< integrator steps
  double seconds = 0.0;  ///< wall time of the replay [s]
};

/// The outcome of replay `r` of a plan on `world`. `plan` is the replayed plan: its trunk at the
/// end, and its contact phases (ReplayPlan::contact_phase, whose rows are the replay's samples)
/// for the stubbed toes; `plan_terrain` the nominal terrain (the plan's height above it); `drift_m`
/// the resolved FailureBounds::drift_m. The failure is the class whose bound was passed first;
/// a replay that ended early but for a fall counts as fallen.
ReplayOutcome classify_replay(const ReplayResult& r, const ReplayPlan& plan, const World& world,
                              const TerrainParams& plan_terrain, const FailureBounds& bounds);

/// The Wilson score interval of a binomial proportion: `successes` of `n` trials, z the
/// standard normal quantile of the confidence (1.959963984540054: 95 %). [0, 1] for n = 0.
struct WilsonInterval {
  double low = 0.0, high = 1.0;
};
WilsonInterval wilson_interval(long successes, long n, double z = 1.959963984540054);

}  // namespace hexdyn
