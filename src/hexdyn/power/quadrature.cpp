#include "hexdyn/power/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace hexdyn {
namespace {

/// The last sample of the piece that starts at s: the first e ≥ s with a jump after it, or
/// the last sample.
std::size_t piece_end(const std::vector<char>& jump, std::size_t s, std::size_t T) {
  std::size_t e = s;
  while (e + 1 < T && !jump[e]) ++e;
  return e;
}

/// The rule's interpolant on one interval and the term that estimates its error, as
/// polynomials in u = (t − t_k) / h ∈ [0, 1]: p = Σ p[i] uⁱ (degree ≤ 3), q = Σ q[i] uⁱ
/// (degree ≤ 4). `bound`: the piece is one interval (a line, no term to compare with).
struct Local {
  double p[4] = {0.0, 0.0, 0.0, 0.0};
  double q[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  bool bound = false;
};

/// The stencil of interval k of the piece [s, e] (docs in quadrature.hpp), plus, on a piece of
/// at least four intervals, the nearest further sample of the piece (the estimate's). Returns
/// the number of samples written to idx.
int stencil(const std::vector<double>& t, std::size_t s, std::size_t e, std::size_t k,
            std::size_t idx[5]) {
  const std::size_t n = e - s;
  if (n == 1) {
    idx[0] = k;
    idx[1] = k + 1;
    return 2;
  }
  if (n == 2) {
    for (int i = 0; i < 3; ++i) idx[i] = s + static_cast<std::size_t>(i);
    return 3;
  }
  const std::size_t i0 = std::clamp(k == 0 ? std::size_t{0} : k - 1, s, e - 3);
  for (int i = 0; i < 4; ++i) idx[i] = i0 + static_cast<std::size_t>(i);
  if (n == 3) return 4;
  const bool left = i0 > s, right = i0 + 4 <= e;
  if (left && (!right || t[k] - t[i0 - 1] <= t[i0 + 4] - t[k + 1]))
    idx[4] = i0 - 1;
  else
    idx[4] = i0 + 4;
  return 5;
}

/// The interpolant of the stencil in Newton form over u, multiplied out: the rule's terms
/// (up to four) into p, the next one (or, without a fifth sample, the rule's last) into q.
Local local_polynomials(const std::vector<double>& t, SeriesView y, std::size_t s, std::size_t e,
                        std::size_t k) {
  std::size_t idx[5];
  const int m = stencil(t, s, e, k, idx);
  const double t0 = t[k], h = t[k + 1] - t[k];
  double x[5], d[5];
  for (int i = 0; i < m; ++i) {
    x[i] = (t[idx[i]] - t0) / h;
    d[i] = y[idx[i]];
  }
  for (int j = 1; j < m; ++j)  // divided differences: d[i] = y[x_0 … x_i]
    for (int i = m - 1; i >= j; --i) d[i] = (d[i] - d[i - 1]) / (x[i] - x[i - j]);
  Local L;
  L.bound = m == 2;
  double basis[5] = {1.0, 0.0, 0.0, 0.0, 0.0};  // Π_{i<j} (u − x_i)
  L.p[0] = d[0];
  for (int j = 1; j < m; ++j) {
    for (int i = j; i > 0; --i) basis[i] = basis[i - 1] - x[j - 1] * basis[i];
    basis[0] *= -x[j - 1];
    if (j < 4)
      for (int i = 0; i <= j; ++i) L.p[i] += d[j] * basis[i];
    if (j == m - 1)
      for (int i = 0; i <= j; ++i) L.q[i] = d[j] * basis[i];
  }
  return L;
}

double horner(const double* c, int n, double u) {
  double v = 0.0;
  for (int i = n - 1; i >= 0; --i) v = v * u + c[i];
  return v;
}

/// ∫_a^b Σ c_i uⁱ du, n coefficients.
double integral(const double* c, int n, double a, double b) {
  double v = 0.0, pa = a, pb = b;
  for (int i = 0; i < n; ++i, pa *= a, pb *= b) v += c[i] * (pb - pa) / (i + 1);
  return v;
}

/// The roots of p in (a, b), appended to `points` (which holds a and b): p is split into
/// monotone parts at its critical points, and a part whose ends differ in sign is bisected.
void add_roots(const double p[4], double a, double b, double* points, int& count) {
  double cuts[4] = {a, 0.0, 0.0, 0.0};
  int nc = 1;
  // p' = p1 + 2 p2 u + 3 p3 u²: its roots in (a, b), in increasing order.
  const double A = 3.0 * p[3], B = 2.0 * p[2], C = p[1];
  double r[2];
  int nr = 0;
  if (A == 0.0) {
    if (B != 0.0) r[nr++] = -C / B;
  } else {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double qq = -0.5 * (B + std::copysign(std::sqrt(disc), B));
      r[nr++] = qq / A;
      if (qq != 0.0) r[nr++] = C / qq;
    }
  }
  if (nr == 2 && r[1] < r[0]) std::swap(r[0], r[1]);
  for (int i = 0; i < nr; ++i)
    if (r[i] > a && r[i] < b) cuts[nc++] = r[i];
  cuts[nc++] = b;
  for (int i = 0; i + 1 < nc; ++i) {
    double lo = cuts[i], hi = cuts[i + 1];
    double flo = horner(p, 4, lo);
    const double fhi = horner(p, 4, hi);
    if (!(flo * fhi < 0.0)) continue;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      const double fm = horner(p, 4, mid);
      if ((fm < 0.0) == (flo < 0.0)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    points[count++] = 0.5 * (lo + hi);
  }
}

/// ∫_a^b |p| du and ∫_a^b sign(p) q du, split at the roots of p in (a, b).
void abs_integrate(const Local& L, double a, double b, double& ip, double& iq) {
  // Most intervals: |p0| > Σ_{i≥1} |p_i| leaves p no root in [0, 1] (the same result as below,
  // without the search).
  if (std::abs(L.p[0]) > std::abs(L.p[1]) + std::abs(L.p[2]) + std::abs(L.p[3])) {
    const double sign = L.p[0] < 0.0 ? -1.0 : 1.0;
    ip = sign * integral(L.p, 4, a, b);
    iq = sign * integral(L.q, 5, a, b);
    return;
  }
  double points[5] = {a, b, 0.0, 0.0, 0.0};
  int count = 2;
  add_roots(L.p, a, b, points, count);
  for (int i = 1; i < count; ++i)  // at most 5: insertion (std::sort's bounds warn here)
    for (int j = i; j > 0 && points[j] < points[j - 1]; --j) std::swap(points[j], points[j - 1]);
  ip = iq = 0.0;
  for (int i = 0; i + 1 < count; ++i) {
    const double lo = points[i], hi = points[i + 1];
    const double sign = horner(L.p, 4, 0.5 * (lo + hi)) < 0.0 ? -1.0 : 1.0;
    ip += sign * integral(L.p, 4, lo, hi);
    iq += sign * integral(L.q, 5, lo, hi);
  }
}

/// ∫|y| over the part [a, b] ⊆ [0, 1] (in u) of interval k of the piece [s, e], and the
/// estimated error over the whole interval when `error` is given; a jump interval (k == e)
/// takes the trapezoid of the line through its ends.
double interval_integral(const std::vector<double>& t, SeriesView y, std::size_t s, std::size_t e,
                         std::size_t k, double a, double b, double* error) {
  const double h = t[k + 1] - t[k];
  if (k == e) {
    if (error) *error = 0.0;
    const double ya = y[k] + a * (y[k + 1] - y[k]), yb = y[k] + b * (y[k + 1] - y[k]);
    return 0.5 * (b - a) * h * (std::abs(ya) + std::abs(yb));
  }
  const Local L = local_polynomials(t, y, s, e, k);
  double ip = 0.0, iq = 0.0;
  abs_integrate(L, a, b, ip, iq);
  if (error) *error = L.bound ? 0.5 * h * std::abs(y[k + 1] - y[k]) : h * iq;
  return h * ip;
}

}  // namespace

void cubic_abs_integrals(const std::vector<double>& t, const std::vector<char>& jump, SeriesView y,
                         std::vector<double>& out, std::vector<double>* error) {
  const std::size_t T = t.size();
  out.assign(T > 0 ? T - 1 : 0, 0.0);
  if (error) error->assign(out.size(), 0.0);
  for (std::size_t s = 0; s + 1 < T;) {
    const std::size_t e = piece_end(jump, s, T);
    const std::size_t last = std::min(e, T - 2);  // the jump interval [e, e + 1] too
    for (std::size_t k = s; k <= last; ++k)
      out[k] = interval_integral(t, y, s, e, k, 0.0, 1.0, error ? &(*error)[k] : nullptr);
    s = e + 1;
  }
}

void cubic_abs_integrals_except(const std::vector<double>& t, const std::vector<char>& jump,
                                SeriesView y, const std::vector<char>& keep,
                                std::vector<double>& out, std::vector<double>& error) {
  const std::size_t T = t.size();
  for (std::size_t s = 0; s + 1 < T;) {
    const std::size_t e = piece_end(jump, s, T);
    const std::size_t last = std::min(e, T - 2);  // the jump interval [e, e + 1] too
    for (std::size_t k = s; k <= last; ++k)
      if (!keep[k]) out[k] = interval_integral(t, y, s, e, k, 0.0, 1.0, &error[k]);
    s = e + 1;
  }
}

double cubic_abs_integral(const std::vector<double>& t, const std::vector<char>& jump,
                          SeriesView y) {
  thread_local std::vector<double> parts;
  cubic_abs_integrals(t, jump, y, parts, nullptr);
  double sum = 0.0;
  for (double v : parts) sum += v;
  return sum;
}

double cubic_abs_integral_between(const std::vector<double>& t, const std::vector<char>& jump,
                                  SeriesView y, double a, double b) {
  const std::size_t T = t.size();
  if (T < 2 || !(b > a)) return 0.0;
  // The interval a lies in, and the start of its piece.
  auto k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), a) - t.begin());
  k = std::clamp<std::size_t>(k, 1, T - 1) - 1;
  std::size_t s = k;
  while (s > 0 && !jump[s - 1]) --s;
  std::size_t e = piece_end(jump, s, T);
  double sum = 0.0;
  for (; k + 1 < T && t[k] < b; ++k) {
    if (k > e) {  // past the jump interval: the next piece
      s = k;
      e = piece_end(jump, s, T);
    }
    const double h = t[k + 1] - t[k];
    const double ua = std::clamp((a - t[k]) / h, 0.0, 1.0),
                 ub = std::clamp((b - t[k]) / h, 0.0, 1.0);
    if (ub > ua) sum += interval_integral(t, y, s, e, k, ua, ub, nullptr);
  }
  return sum;
}

}  // namespace hexdyn
