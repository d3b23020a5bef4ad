#pragma once
/// \file grid_error.hpp
/// Error control of the output grid (docs/theory/output-grid.md#error-control): for series
/// sampled on a grid, the estimated error of the trapezoid rule on every interval and of every
/// sampled peak, and the instants at which new samples reduce them.
///
/// A series is smooth between the grid's contact events and may jump across one. The caller
/// marks those intervals (`jump[k] != 0`: the series may jump between samples k and k + 1,
/// the interval from an event's left-limit sample to the event); the grid's **pieces** are the
/// maximal runs of samples with no jump between them. Every estimate uses the samples of one
/// piece only, and a jump interval is never split.
#include <cstddef>
#include <vector>

#include "hexdyn/power/quadrature.hpp"

namespace hexdyn {

/// Estimated error of the trapezoid rule on every interval of the grid t_s (T increasing
/// instants [s]) for the series y: error[k] (T − 1 entries, written into `error`) is
/// ∫ p dt − trapezoid over [t_k, t_{k+1}], p the interpolant of y through the 4 samples of
/// the interval's piece nearest to it (the interval's two ends and one on each side where the
/// piece has them: a cubic, whose integral is exact for cubics and whose difference to the
/// trapezoid is −h³/12 y'' + O(h⁴) for smooth y), through 3 samples (a quadratic) on a piece
/// of two intervals. An interval that is its piece alone has no neighbour to compare with and
/// gets the bound h |y_{k+1} − y_k| / 2 (the trapezoid's largest error for a monotone y). A
/// jump interval gets 0 (its step is 1e-10 s: the trapezoid resolves the jump).
/// jump: T entries (the last unused).
void trapezoid_errors(const std::vector<double>& t_s, const std::vector<char>& jump, SeriesView y,
                      std::vector<double>& error);

/// The sampled maximum of a series and an estimate of the maximum of the continuous series
/// between samples, which may be smooth, have corners (a series of the L1-penalised allocation
/// does) or jump within a piece. Interval k of a piece may hold a maximum when the series rises
/// into it (its left neighbour's slope a > 0) or falls out of it (its right neighbour's slope
/// b < 0); the estimate is, with both, where the line through t_k with slope a meets the line
/// through t_{k+1} with slope b (exact at a corner, an overestimate of order h² at a smooth
/// maximum); with a alone, the left line at t_{k+1} when the interval's own slope is below b (a
/// rise that ends in a drop within it); with b alone, the right line at t_k when its own slope
/// is above a (a jump up within it). A smooth stretch, whose slopes change monotonically, is
/// neither. Only intervals with an end above half the sampled maximum are
/// looked at, and none shorter than 2 min_step_s (a step the series makes: its neighbours'
/// slopes say nothing of it). `predicted_s` is where the largest estimate lies.
struct PeakEstimate {
  double sampled = 0.0;    ///< max_k y_k
  double predicted = 0.0;  ///< ≥ sampled: the largest estimate, or sampled
  double predicted_s = 0.0;
};

/// The peak estimate of y on t_s; with `refine_at` (may be null), the instants to sample next
/// in every interval whose estimate exceeds the sampled maximum by more than `tolerance` ×
/// |sampled|: its midpoint (when it is at least 2 min_step_s long) and where the lines meet.
PeakEstimate estimate_peak(const std::vector<double>& t_s, const std::vector<char>& jump,
                           SeriesView y, double tolerance, double min_step_s,
                           std::vector<double>* refine_at);

/// The interval errors of the trapezoid rule for |y|, y a smooth signed series: where y keeps
/// its sign on an interval, ± trapezoid_errors of y (y is smooth where |y| has a kink); where
/// it changes sign, ∫|ℓ| − trapezoid of |y| = −h |y_k| |y_{k+1}| / (|y_k| + |y_{k+1}|) for the
/// line ℓ through the ends plus y's own error signed as its larger end, and root[k] is where
/// ℓ crosses zero (NaN on other intervals). A
/// sample at the root leaves the kink of |y| at a sample, where the trapezoid is again of
/// second order.
void abs_trapezoid_errors(const std::vector<double>& t_s, const std::vector<char>& jump,
                          SeriesView y, std::vector<double>& error, std::vector<double>& root);

/// An integral the grid controls: of Σ_{i ∈ terms} |y_i| over the grid by `rule`, for terms
/// given by their index among the assessment's signed series, with the magnitude its error is
/// measured against. Targets that share a term share its rule.
struct IntegralTarget {
  std::vector<int> terms;
  double reference = 0.0;  ///< > 0, in the units of ∫ y dt
  Quadrature rule = Quadrature::kTrapezoid;
};

/// What a grid achieves, and where to refine it.
struct GridAssessment {
  /// Largest estimated relative error of an integral target: |Σ_k error[k]| / reference.
  double integral_error = 0.0;
  /// Largest estimated relative error of a peak: (predicted − sampled) / |sampled| (0 for a
  /// series that is zero everywhere).
  double peak_error = 0.0;
  /// Instants to add, sorted, each at least min_step_s from every sample and from each other;
  /// empty when every estimate is within the tolerance or nothing that exceeds it can be split.
  std::vector<double> refine_at_s;
};

/// Assesses the grid t_s for the integrals of the absolute values of the signed series
/// `terms` and for the peaks (every peak series is ≥ 0 where it matters: its maximum is
/// controlled). An integral's error is estimated by the net |Σ_k error[k]| of its rule's
/// interval errors, summed over its terms (the trapezoid's: abs_trapezoid_errors, the
/// difference to the interpolants' integral; the piecewise cubic's: cubic_abs_integrals, the
/// next term of the interpolant): the errors of the intervals are signed and cancel where a
/// series bends both ways. It is held to half of tolerance × reference: over that, the
/// intervals of largest |error[k]| are split, largest first, until they carry a share of
/// Σ|error| that grows with how far the net error is over (30 % to 90 %), into as many parts
/// (two or three) as the rule's order says bring the net within the budget: for the trapezoid,
/// where a term changes sign, at its root when that lies in the interval's inner 80 %, else at
/// the midpoint (the cubic rule integrates through a sign change). An
/// interval shorter than 2 min_step_s or a jump interval is never split. A peak over its tolerance
/// is refined by estimate_peak, and the sampled maximum's neighbours in its piece are brought
/// within the tolerance of it by bisection. tolerance > 0; min_step_s > 0. With `reuse` (may
/// be null), the cubic estimates of the last assessment of the same terms on a subset of t_s
/// serve where they still hold, and this assessment's are stored there for the next.
GridAssessment assess_grid(const std::vector<double>& t_s, const std::vector<char>& jump,
                           const std::vector<SeriesView>& terms,
                           const std::vector<IntegralTarget>& integrals,
                           const std::vector<SeriesView>& peaks, double tolerance,
                           double min_step_s, CubicEstimates* reuse = nullptr);

}  // namespace hexdyn
