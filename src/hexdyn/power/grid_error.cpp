#include "hexdyn/power/grid_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

namespace hexdyn {
namespace {

/// The share of the tolerance an integral's estimate is refined to: for the trapezoid a half
/// (on the stair grid its net estimate ran up to 10 % below the error against a converged
/// grid); for the piecewise cubic a fifth (on a fast climb its net estimate of a joint's energy
/// ran 2.4 times below that error: the next term's signs cancel more).
constexpr double kIntegralSafety = 0.5;
constexpr double kCubicIntegralSafety = 0.2;

/// The last sample of the piece that starts at s: the first e ≥ s with a jump after it, or
/// the last sample.
std::size_t piece_end(const std::vector<char>& jump, std::size_t s, std::size_t T) {
  std::size_t e = s;
  while (e + 1 < T && !jump[e]) ++e;
  return e;
}

/// Pushes the m − 1 points that split [a, b] into m equal parts, m ≥ 2, as far as they stay
/// min_step_s apart (fewer parts on a shorter interval; none below 2 min_step_s).
void push_split(double a, double b, int m, double min_step_s, std::vector<double>& out) {
  m = std::min(m, static_cast<int>((b - a) / min_step_s));
  for (int i = 1; i < m; ++i) out.push_back(a + (b - a) * i / m);
}

/// Parts an interval is split into by the peaks' refinement.
constexpr int kPeakSplit = 2;

}  // namespace

void trapezoid_errors(const std::vector<double>& t, const std::vector<char>& jump, SeriesView y,
                      std::vector<double>& error) {
  const std::size_t T = t.size();
  error.assign(T > 0 ? T - 1 : 0, 0.0);
  // Divided differences of consecutive samples: d1[k] = y[k, k+1], d2[k] = y[k, k+1, k+2],
  // d3[k] = y[k … k+3], within a piece.
  thread_local std::vector<double> d1, d2, d3;
  d1.resize(T);
  d2.resize(T);
  d3.resize(T);
  for (std::size_t s = 0; s + 1 < T;) {
    const std::size_t e = piece_end(jump, s, T);
    const std::size_t n = e - s;  // intervals in the piece
    for (std::size_t k = s; k < e; ++k) d1[k] = (y[k + 1] - y[k]) / (t[k + 1] - t[k]);
    for (std::size_t k = s; k + 1 < e; ++k) d2[k] = (d1[k + 1] - d1[k]) / (t[k + 2] - t[k]);
    for (std::size_t k = s; k + 2 < e; ++k) d3[k] = (d2[k + 1] - d2[k]) / (t[k + 3] - t[k]);
    for (std::size_t k = s; k < e; ++k) {
      const double h = t[k + 1] - t[k], h3 = h * h * h;
      if (n == 1) {
        error[k] = 0.5 * h * std::abs(y[k + 1] - y[k]);
      } else if (n == 2) {
        error[k] = -h3 / 6.0 * d2[s];
      } else {
        // The cubic through k − 1 … k + 2 (shifted inwards at the piece's ends): with the nodes
        // a = k, b = k + 1, then c (k − 1, or k + 2 on the first interval), y[a,b,c] and y[a…d].
        const std::size_t i0 = std::clamp(k == 0 ? 0 : k - 1, s, e - 3);
        const bool first = k == s;
        const double abc = first ? d2[k] : d2[k - 1];
        const double c_minus_a = first ? t[k + 2] - t[k] : t[k - 1] - t[k];
        error[k] = -h3 / 6.0 * abc + d3[i0] * (-h3 * h / 12.0 + c_minus_a * h3 / 6.0);
      }
    }
    s = e + 1;  // the jump interval [e, e + 1] keeps its 0
  }
}

PeakEstimate estimate_peak(const std::vector<double>& t, const std::vector<char>& jump,
                           SeriesView y, double tolerance, double min_step_s,
                           std::vector<double>* refine_at) {
  const std::size_t T = t.size();
  PeakEstimate p;
  if (T == 0) return p;
  p.sampled = y[0];
  p.predicted_s = t[0];
  for (std::size_t k = 1; k < T; ++k)
    if (y[k] > p.sampled) {
      p.sampled = y[k];
      p.predicted_s = t[k];
    }
  p.predicted = p.sampled;
  const double threshold = p.sampled + tolerance * std::abs(p.sampled);
  // The sampled maximum's neighbours in its piece come within four times the tolerance of
  // it (at a smooth maximum, the series between two samples exceeds them by about a quarter of
  // their difference): an interval next to it whose other end is lower by more is bisected.
  // Near a corner this puts samples on the straight parts on either side, from which the lines
  // below locate it.
  if (refine_at) {
    std::size_t i = 0;
    while (y[i] != p.sampled) ++i;
    const double low = p.sampled - 4.0 * tolerance * std::abs(p.sampled);
    if (i > 0 && !jump[i - 1] && y[i - 1] < low)
      push_split(t[i - 1], t[i], kPeakSplit, min_step_s, *refine_at);
    if (i + 1 < T && !jump[i] && y[i + 1] < low)
      push_split(t[i], t[i + 1], kPeakSplit, min_step_s, *refine_at);
  }
  const auto slope = [&](std::size_t k) { return (y[k + 1] - y[k]) / (t[k + 1] - t[k]); };
  // Only intervals with an end above half the sampled maximum are looked at: the lines
  // would need to double the series within one interval to reach the maximum from below.
  const double half = 0.5 * p.sampled;
  for (std::size_t s = 0; s < T;) {
    const std::size_t e = piece_end(jump, s, T);
    // Interval k may hold a maximum when the series rises into it (its left neighbour's
    // slope a > 0) or falls out of it (its right neighbour's slope b < 0): the line through
    // its left end with slope a and the line through its right end with slope b bound it.
    for (std::size_t k = s; e > s + 1 && k < e; ++k) {
      if (!(y[k] > half || y[k + 1] > half)) continue;
      const double a = k > s ? slope(k - 1) : 0.0, b = k + 1 < e ? slope(k + 1) : 0.0;
      const double h = t[k + 1] - t[k];
      // An interval too short to split is taken as a step the series makes (the L1-penalised
      // allocation jumps within a piece): its neighbours' slopes say nothing of it.
      if (h < 2.0 * min_step_s) continue;
      double x = 0.0, v = 0.0;
      const double own = slope(k);
      if (a > 0.0 && b < 0.0) {  // both: where the lines meet (exact at a corner)
        x = std::clamp((y[k + 1] - y[k] - b * t[k + 1] + a * t[k]) / (a - b), t[k], t[k + 1]);
        v = std::min(y[k] + a * (x - t[k]), y[k + 1] + b * (x - t[k + 1]));
      } else if (a > 0.0 && own < b) {  // rising into it, a drop within: the left line's end
        x = t[k + 1];
        v = y[k] + a * h;
      } else if (b < 0.0 && own > a) {  // a rise within it, then falling: the right line's start
        x = t[k];
        v = y[k + 1] - b * h;
      } else {
        continue;
      }
      if (v > p.predicted) {
        p.predicted = v;
        p.predicted_s = x;
      }
      if (!refine_at || !(v > threshold)) continue;
      push_split(t[k], t[k + 1], kPeakSplit, min_step_s, *refine_at);
      refine_at->push_back(x);
    }
    s = e + 1;
  }
  return p;
}

void abs_trapezoid_errors(const std::vector<double>& t, const std::vector<char>& jump, SeriesView y,
                          std::vector<double>& error, std::vector<double>& root) {
  trapezoid_errors(t, jump, y, error);
  root.assign(error.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < error.size(); ++k) {
    const double a = y[k], b = y[k + 1];
    if (jump[k]) continue;
    if (a * b >= 0.0) {  // |y| = ±y on the whole interval
      if (a + b < 0.0) error[k] = -error[k];
      continue;
    }
    // A sign change: ∫|ℓ| − trapezoid of |y| for the line ℓ through the ends, −h |a||b| /
    // (|a| + |b|), plus y's own curvature error signed as the larger end's side; and where ℓ
    // crosses zero.
    const double h = t[k + 1] - t[k];
    error[k] = -h * std::abs(a) * std::abs(b) / (std::abs(a) + std::abs(b)) +
               (a + b < 0.0 ? -error[k] : error[k]);
    root[k] = t[k] + h * a / (a - b);
  }
}

namespace {

/// Marks in `split` (parts per interval) the intervals an integral over its budget refines: the
/// intervals of largest |error|, largest first, until they carry a share of Σ|error| that grows
/// with how far the net error is over the budget (half of it at twice the budget, 90 % far over
/// it), each into two or three parts as far as the net is over: the rule's error falls as the
/// step to the power order_h (2 for the trapezoid, 4 for the piecewise cubic), so m parts take
/// the net error to about net / m^order_h (more parts overshoot: the errors of the parts do not
/// all fall alike). Jump intervals and intervals shorter than
/// 2 min_step_s are never marked. error: |error| per interval; order: a workspace.
void mark_integral_splits(const std::vector<double>& t, const std::vector<char>& jump,
                          const std::vector<double>& error, double net, double budget, int order_h,
                          double min_step_s, std::vector<std::size_t>& order,
                          std::vector<char>& split) {
  const std::size_t n = error.size();
  const double share =
      std::clamp(1.0 - budget / net, 0.3, 0.9) * std::accumulate(error.begin(), error.end(), 0.0);
  // The largest first: sorted in growing prefixes (most passes need few intervals).
  order.resize(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto larger = [&](std::size_t i, std::size_t j) {
    return error[i] > error[j] || (error[i] == error[j] && i < j);
  };
  const int m =
      std::clamp(static_cast<int>(std::ceil(std::pow(net / budget, 1.0 / order_h))), 2, 3);
  double chosen = 0.0;
  for (std::size_t pos = 0, sorted = 0; pos < n && chosen < share; ++pos) {
    if (pos == sorted) {
      sorted = std::min(n, std::max<std::size_t>(64, 4 * sorted));
      std::partial_sort(order.begin() + static_cast<std::ptrdiff_t>(pos),
                        order.begin() + static_cast<std::ptrdiff_t>(sorted), order.end(), larger);
    }
    const std::size_t k = order[pos];
    if (jump[k] || t[k + 1] - t[k] < 2.0 * min_step_s) continue;
    chosen += error[k];
    split[k] = static_cast<char>(std::max<int>(split[k], m));
  }
}

/// The instants that split the marked intervals: where a term changes sign (the one whose kink
/// errs most: the trapezoid of |y| is then of second order at the kink) when that root lies in
/// the interval's inner 80 % (near an end a line's root can stall, as regula falsi on a convex
/// stretch does), or else the points that cut it into its parts.
void place_splits(const std::vector<double>& t, const std::vector<char>& split,
                  const std::vector<std::vector<double>>& term_error,
                  const std::vector<std::vector<double>>& term_root, double min_step_s,
                  std::vector<double>& candidates) {
  for (std::size_t k = 0; k < split.size(); ++k) {
    if (!split[k]) continue;
    double x = std::numeric_limits<double>::quiet_NaN(), worst = 0.0;
    const double margin = std::max(min_step_s, 0.1 * (t[k + 1] - t[k]));
    for (std::size_t i = 0; i < term_root.size(); ++i) {
      const double r = term_root[i][k];
      if (std::isnan(r) || !(std::abs(term_error[i][k]) > worst)) continue;
      if (r - t[k] < margin || t[k + 1] - r < margin) continue;
      worst = std::abs(term_error[i][k]);
      x = r;
    }
    if (std::isnan(x))
      push_split(t[k], t[k + 1], split[k], min_step_s, candidates);
    else
      candidates.push_back(x);
  }
}

/// The candidates sorted, each at least min_step_s from every sample and from the one before,
/// none inside a jump interval.
std::vector<double> admissible(std::vector<double> candidates, const std::vector<double>& t,
                               const std::vector<char>& jump, double min_step_s) {
  std::sort(candidates.begin(), candidates.end());
  std::vector<double> out;
  for (double x : candidates) {
    const auto k = std::upper_bound(t.begin(), t.end(), x) - t.begin();
    if (k == 0 || k == static_cast<std::ptrdiff_t>(t.size())) continue;
    if (jump[k - 1]) continue;
    if (x - t[k - 1] < min_step_s || t[k] - x < min_step_s) continue;
    if (!out.empty() && x - out.back() < min_step_s) continue;
    out.push_back(x);
  }
  return out;
}

/// Which intervals of the grid t keep the estimates of the grid old (keep[k] != 0, and
/// old_k[k] their index there): those whose samples k − 3 … k + 4 (as far as t has them) are
/// samples of old, consecutive there. None when old is not a subset of t.
void kept_intervals(const std::vector<double>& t, const std::vector<double>& old,
                    std::vector<char>& keep, std::vector<std::ptrdiff_t>& old_k) {
  const std::size_t T = t.size();
  keep.assign(T - 1, 0);
  old_k.assign(T, -1);  // first per sample: its index in old, or −1
  std::size_t i = 0;
  for (std::size_t j = 0; j < T && i < old.size(); ++j)
    if (t[j] == old[i]) old_k[j] = static_cast<std::ptrdiff_t>(i++);
  if (i != old.size()) return;
  for (std::size_t k = 0; k + 1 < T; ++k) {
    if (old_k[k] < 0) continue;
    const std::ptrdiff_t shift = static_cast<std::ptrdiff_t>(k) - old_k[k];
    const std::size_t lo = k >= 3 ? k - 3 : 0, hi = std::min(k + 4, T - 1);
    bool same = true;
    for (std::size_t j = lo; j <= hi && same; ++j)
      same = old_k[j] >= 0 && static_cast<std::ptrdiff_t>(j) - old_k[j] == shift;
    keep[k] = same;
  }
  for (std::size_t k = 0; k + 1 < T; ++k) old_k[k] = keep[k] ? old_k[k] : -1;
}

/// The cubic rule's interval integrals and errors of every term that uses it, from `reuse`
/// where its grid's estimates hold (kept_intervals), computed elsewhere; then stored in it.
void cubic_term_estimates(const std::vector<double>& t, const std::vector<char>& jump,
                          const std::vector<SeriesView>& terms, const std::vector<Quadrature>& rule,
                          std::vector<std::vector<double>>& integral,
                          std::vector<std::vector<double>>& error, CubicEstimates* reuse) {
  // The signed integrals too, kept for the energies' split into positive and negative work.
  thread_local std::vector<std::vector<double>> signed_part;
  signed_part.resize(terms.size());
  const std::size_t n = t.size() - 1;
  thread_local std::vector<char> keep;
  thread_local std::vector<std::ptrdiff_t> old_k;
  const bool usable = reuse && reuse->integral.size() == terms.size() &&
                      reuse->signed_integral.size() == terms.size() && !reuse->t_s.empty();
  if (usable) kept_intervals(t, reuse->t_s, keep, old_k);
  // The terms whose estimates are all new, and those that keep some: each batch builds an
  // interval's stencil once for all its terms.
  thread_local std::vector<CubicTarget> fresh, rest;
  fresh.clear();
  rest.clear();
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (rule[i] != Quadrature::kCubic) continue;
    integral[i].assign(n, 0.0);
    error[i].assign(n, 0.0);
    signed_part[i].assign(n, 0.0);
    const CubicTarget target{terms[i], integral[i].data(), error[i].data(), signed_part[i].data()};
    if (!usable || reuse->integral[i].size() + 1 != reuse->t_s.size()) {
      fresh.push_back(target);
      continue;
    }
    for (std::size_t k = 0; k < n; ++k)
      if (keep[k]) {
        const auto old = static_cast<std::size_t>(old_k[k]);
        integral[i][k] = reuse->integral[i][old];
        error[i][k] = reuse->error[i][old];
        signed_part[i][k] = reuse->signed_integral[i][old];
      }
    rest.push_back(target);
  }
  cubic_abs_integrals_batch(t, jump, fresh);
  cubic_abs_integrals_batch(t, jump, rest, &keep);
  if (!reuse) return;
  reuse->t_s = t;
  reuse->integral.assign(terms.size(), {});
  reuse->error.assign(terms.size(), {});
  // The signed parts are this function's own: handed over, the thread's buffer takes the old.
  reuse->signed_integral.resize(terms.size());
  for (std::size_t i = 0; i < terms.size(); ++i) {
    reuse->signed_integral[i].clear();
    if (rule[i] != Quadrature::kCubic) continue;
    reuse->integral[i] = integral[i];
    reuse->error[i] = error[i];
    reuse->signed_integral[i].swap(signed_part[i]);
  }
}

}  // namespace

GridAssessment assess_grid(const std::vector<double>& t, const std::vector<char>& jump,
                           const std::vector<SeriesView>& terms,
                           const std::vector<IntegralTarget>& integrals,
                           const std::vector<SeriesView>& peaks, double tolerance,
                           double min_step_s, CubicEstimates* reuse) {
  GridAssessment a;
  const std::size_t T = t.size();
  if (T < 2) return a;
  const std::size_t n = T - 1;
  // Every term's interval errors and sign changes, once: the targets share them (the buffers
  // keep their capacity from one assessment to the next).
  thread_local std::vector<std::vector<double>> term_error, term_root, term_integral;
  term_error.resize(terms.size());
  term_root.resize(terms.size());
  term_integral.resize(terms.size());
  std::vector<Quadrature> rule(terms.size(), Quadrature::kTrapezoid);
  for (const IntegralTarget& target : integrals)
    for (int i : target.terms) rule[static_cast<std::size_t>(i)] = target.rule;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (rule[i] == Quadrature::kTrapezoid) {
      abs_trapezoid_errors(t, jump, terms[i], term_error[i], term_root[i]);
      continue;
    }
    // The cubic rule integrates through a sign change: no roots to split at.
    term_root[i].assign(n, std::numeric_limits<double>::quiet_NaN());
  }
  cubic_term_estimates(t, jump, terms, rule, term_integral, term_error, reuse);
  std::vector<double> candidates, error(n);
  std::vector<std::size_t> order;
  std::vector<char> split(n, 0);
  for (const IntegralTarget& target : integrals) {
    std::fill(error.begin(), error.end(), 0.0);
    for (int i : target.terms) {
      const double* e = term_error[i].data();
      for (std::size_t k = 0; k < n; ++k) error[k] += e[k];
    }
    // The net of the intervals' estimated errors: they are signed and cancel where the series
    // bends both ways. Held to a share of the tolerance (kIntegralSafety).
    const double net = std::abs(std::accumulate(error.begin(), error.end(), 0.0));
    const double budget =
        (target.rule == Quadrature::kCubic ? kCubicIntegralSafety : kIntegralSafety) * tolerance *
        target.reference;
    if (target.reference > 0.0)
      a.integral_error = std::max(a.integral_error, net / target.reference);
    if (!(net > budget)) continue;
    for (double& e : error) e = std::abs(e);
    const int order_h = target.rule == Quadrature::kTrapezoid ? 2 : 4;
    mark_integral_splits(t, jump, error, net, budget, order_h, min_step_s, order, split);
  }
  place_splits(t, split, term_error, term_root, min_step_s, candidates);
  for (const SeriesView& y : peaks) {
    const PeakEstimate p = estimate_peak(t, jump, y, tolerance, min_step_s, &candidates);
    if (p.sampled != 0.0)
      a.peak_error = std::max(a.peak_error, (p.predicted - p.sampled) / std::abs(p.sampled));
  }
  a.refine_at_s = admissible(std::move(candidates), t, jump, min_step_s);
  return a;
}

}  // namespace hexdyn
