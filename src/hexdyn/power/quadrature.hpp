#pragma once
/// \file quadrature.hpp
/// The piecewise-cubic rule by which the energies are integrated over the stored samples
/// (docs/theory/output-grid.md#energy-from-the-samples), and its error estimate.
///
/// The samples are split into **pieces** at the marked jump intervals (`jump[k] != 0`: the
/// series may jump between samples k and k + 1, the interval from an event's left-limit sample
/// to the event). On a piece of n intervals, interval k integrates the polynomial p_k that
/// interpolates the samples of its **stencil**: for n ≥ 3 the four samples k − 1 … k + 2,
/// shifted inwards at the piece's ends (k … k + 3 on the first interval, k − 2 … k + 1 on the
/// last: a cubic); for n = 2 the piece's three samples (a quadratic); for n = 1 its two (a
/// line). For an absolute-value integrand |y| it is ∫|p_k| over the interval, split at the roots
/// of p_k in it (y's sign changes are kinks of |y|, p_k is smooth through them). A jump
/// interval takes the trapezoid 0.5 h (|y_k| + |y_{k+1}|) (its step is 1e-10 s). The rule is
/// exact for polynomials of degree ≤ 3 on every piece of at least three intervals, and its error
/// on a smooth y falls as h⁴.
#include <cstddef>
#include <vector>

namespace hexdyn {

/// The quadrature rule an integral is computed by: the trapezoid (power/power.hpp) or the
/// piecewise-cubic rule below.
enum class Quadrature { kTrapezoid, kCubic };

/// Samples y[k * stride] of a series, k = 0 … T − 1, one per grid point.
struct SeriesView {
  const double* y = nullptr;
  int stride = 1;
  double operator[](std::size_t k) const { return y[k * static_cast<std::size_t>(stride)]; }
};

/// The piecewise-cubic estimates of one assessment, kept for the next on a grid that adds
/// samples to this one: an interval whose samples k − 3 … k + 4 were all there, consecutive,
/// has the same stencil and so the same integral and error, which are taken instead of
/// computed again (bit for bit the same). The last assessment's are those of the run's own
/// grid, which the energies (power/power.hpp) take instead of computing them again.
struct CubicEstimates {
  std::vector<double> t_s;                    ///< the grid they belong to
  std::vector<std::vector<double>> integral;  ///< per term (empty for a trapezoid term)
  std::vector<std::vector<double>> error;     ///< per term
  /// per term, ∫y dt (signed) over each interval (CubicTarget::signed_integral)
  std::vector<std::vector<double>> signed_integral;
};

/// ∫|y| dt over every interval of the grid t_s (T increasing instants [s]) by the piecewise-cubic
/// rule: `integral` gets T − 1 entries. With `error` (may be null; T − 1 entries), the rule's
/// estimated error per interval, signed, from the next term of the interpolant: for a stencil
/// inside a piece of at least four intervals, the integral (signed as |p_k| is) of the Newton
/// term the nearest fifth sample of the piece adds (of order h⁵ y⁗ on a smooth y); on a piece of
/// three or two intervals, the rule's own highest term (the difference to one degree less); on
/// a piece of one interval the bound h |y_{k+1} − y_k| / 2; on a jump interval 0.
/// jump: T entries (the last unused).
void cubic_abs_integrals(const std::vector<double>& t_s, const std::vector<char>& jump,
                         SeriesView y, std::vector<double>& integral, std::vector<double>* error);

/// One series of a batch and where its interval integrals (and, when error is not null, its
/// errors) go: T − 1 entries each.
struct CubicTarget {
  SeriesView y;
  double* integral = nullptr;
  double* error = nullptr;
  /// when not null: ∫y dt (signed) over each interval by the same stencils, ∫p_k over a smooth
  /// interval and the trapezoid over a jump interval (T − 1 entries); their sum and that of the
  /// |y| integrals split ∫|y| into its positive and negative parts, (∫|y| ± ∫y) / 2, to rounding
  double* signed_integral = nullptr;
};

/// cubic_abs_integrals of several series on one grid at once (each interval's stencil is
/// built once for all), on the intervals k with !(*keep)[k] when keep is given (the others
/// are left as they are). The same numbers, to the bit, as one series at a time.
void cubic_abs_integrals_batch(const std::vector<double>& t_s, const std::vector<char>& jump,
                               const std::vector<CubicTarget>& targets,
                               const std::vector<char>* keep = nullptr);

/// The sum of cubic_abs_integrals: ∫|y| dt over [t_0, t_{T−1}] by the rule.
double cubic_abs_integral(const std::vector<double>& t_s, const std::vector<char>& jump,
                          SeriesView y);

/// ∫|y| dt over [a, b] ⊆ [t_0, t_{T−1}] (a ≤ b) by the rule: whole intervals as above, and the
/// interval a bound falls in integrates its own p_k up to the bound, so that the integrals over
/// adjacent spans add up to the whole (to rounding). `whole` (may be null; T − 1 entries): the
/// series' cubic_abs_integrals, taken for the intervals wholly inside [a, b].
double cubic_abs_integral_between(const std::vector<double>& t_s, const std::vector<char>& jump,
                                  SeriesView y, double a, double b, const double* whole = nullptr);

}  // namespace hexdyn
