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

/// The geometry of interval k's stencil, shared by every series on the grid: the samples
/// (idx), their abscissae x in u, the divided differences' denominators and the Newton basis
/// polynomials Π_{i<j} (u − x_i), multiplied out.
struct StencilGeometry {
  int m = 0;  ///< samples in the stencil (2 … 5)
  std::size_t idx[5] = {0, 0, 0, 0, 0};
  double den[5][5] = {};    ///< den[j][i] = x[i] − x[i − j], j ≤ i
  double basis[5][5] = {};  ///< basis[j][i]: coefficient of uⁱ of Π_{i<j} (u − x_i)
};

StencilGeometry stencil_geometry(const std::vector<double>& t, std::size_t s, std::size_t e,
                                 std::size_t k) {
  StencilGeometry g;
  g.m = stencil(t, s, e, k, g.idx);
  const double t0 = t[k], h = t[k + 1] - t[k];
  double x[5];
  for (int i = 0; i < g.m; ++i) x[i] = (t[g.idx[i]] - t0) / h;
  for (int j = 1; j < g.m; ++j)
    for (int i = g.m - 1; i >= j; --i) g.den[j][i] = x[i] - x[i - j];
  double basis[5] = {1.0, 0.0, 0.0, 0.0, 0.0};
  g.basis[0][0] = 1.0;
  for (int j = 1; j < g.m; ++j) {
    for (int i = j; i > 0; --i) basis[i] = basis[i - 1] - x[j - 1] * basis[i];
    basis[0] *= -x[j - 1];
    for (int i = 0; i <= j; ++i) g.basis[j][i] = basis[i];
  }
  return g;
}

/// The interpolant of the stencil in Newton form over u, multiplied out: the rule's terms
/// (up to four) into p, the next one (or, without a fifth sample, the rule's last) into q.
Local local_polynomials(const StencilGeometry& g, SeriesView y) {
  const int m = g.m;
  double d[5];
  for (int i = 0; i < m; ++i) d[i] = y[g.idx[i]];
  for (int j = 1; j < m; ++j)  // divided differences: d[i] = y[x_0 … x_i]
    for (int i = m - 1; i >= j; --i) d[i] = (d[i] - d[i - 1]) / g.den[j][i];
  Local L;
  L.bound = m == 2;
  L.p[0] = d[0];
  for (int j = 1; j < m; ++j) {
    if (j < 4)
      for (int i = 0; i <= j; ++i) L.p[i] += d[j] * g.basis[j][i];
    if (j == m - 1)
      for (int i = 0; i <= j; ++i) L.q[i] = d[j] * g.basis[j][i];
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
  if (a == 0.0 && b == 1.0) {  // the whole interval: the loop below, unrolled (the same bits)
    double v = 0.0 + c[0];
    v += c[1] * 0.5;
    v += c[2] / 3.0;
    v += c[3] * 0.25;
    if (n == 5) v += c[4] / 5.0;
    return v;
  }
  double v = 0.0, pa = a, pb = b;
  for (int i = 0; i < n; ++i, pa *= a, pb *= b) v += c[i] * (pb - pa) / (i + 1);
  return v;
}

/// The root of the cubic p in (lo, hi), where p is monotone and changes sign (negative at lo
/// when `negative_at_lo`): the bracket is narrowed to two adjacent doubles, and their midpoint
/// returned. Newton steps from the last point evaluated, kept inside the bracket (a bisection
/// where one would leave it), close in on the root; once a step no longer moves the point, the
/// next double towards the bracket's far end closes the bracket. The adjacent pair is where p's
/// computed sign changes, so the answer is bisection's, in a few evaluations instead of about 60.
double bracketed_root(const double p[4], double lo, double hi, bool negative_at_lo) {
  const auto narrow = [&](double x) {  // the bracket's end on x's side moves to x
    if ((horner(p, 4, x) < 0.0) == negative_at_lo) {
      lo = x;
      return true;
    }
    hi = x;
    return false;
  };
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 16; ++it) {  // Newton inside the bracket
    if (!(x > lo && x < hi)) break;
    const bool below = narrow(x);
    const double dfx = p[1] + x * (2.0 * p[2] + x * 3.0 * p[3]);
    double next = dfx != 0.0 ? x - horner(p, 4, x) / dfx : 0.5 * (lo + hi);
    if (next == x)  // converged: the neighbour towards the far end closes the bracket
      next = below ? std::nextafter(x, hi) : std::nextafter(x, lo);
    // A step that leaves the bracket, or gains less than a bisection would, bisects.
    if (!(next > lo && next < hi) || std::abs(next - x) > 0.5 * (hi - lo)) next = 0.5 * (lo + hi);
    x = next;
  }
  for (int it = 0; it < 100; ++it) {  // bisection, to two adjacent doubles
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    narrow(mid);
  }
  return 0.5 * (lo + hi);
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
    const double lo = cuts[i], hi = cuts[i + 1];
    const double flo = horner(p, 4, lo);
    const double fhi = horner(p, 4, hi);
    if (!(flo * fhi < 0.0)) continue;
    points[count++] = bracketed_root(p, lo, hi, flo < 0.0);
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

/// The trapezoid of |y| over the part [a, b] ⊆ [0, 1] (in u) of the jump interval k, on the
/// line through its ends.
double jump_integral(const std::vector<double>& t, SeriesView y, std::size_t k, double a,
                     double b) {
  const double h = t[k + 1] - t[k];
  const double ya = y[k] + a * (y[k + 1] - y[k]), yb = y[k] + b * (y[k + 1] - y[k]);
  return 0.5 * (b - a) * h * (std::abs(ya) + std::abs(yb));
}

/// ∫|y| over the part [a, b] ⊆ [0, 1] (in u) of interval k (not a jump interval) of stencil
/// geometry g, the estimated error over the whole interval when `error` is given, and ∫y over
/// the whole interval (CubicTarget::signed_integral) when `signed_part` is.
double smooth_integral(const std::vector<double>& t, const StencilGeometry& g, SeriesView y,
                       std::size_t k, double a, double b, double* error,
                       double* signed_part = nullptr) {
  const double h = t[k + 1] - t[k];
  const Local L = local_polynomials(g, y);
  double ip = 0.0, iq = 0.0;
  abs_integrate(L, a, b, ip, iq);
  if (error) *error = L.bound ? 0.5 * h * std::abs(y[k + 1] - y[k]) : h * iq;
  if (signed_part) *signed_part = h * integral(L.p, 4, 0.0, 1.0);
  return h * ip;
}

/// ∫y over the jump interval k (CubicTarget::signed_integral): the trapezoid of y.
double jump_signed(const std::vector<double>& t, SeriesView y, std::size_t k) {
  return 0.5 * (t[k + 1] - t[k]) * (y[k] + y[k + 1]);
}

/// ∫|y| over the part [a, b] ⊆ [0, 1] (in u) of interval k of the piece [s, e], and the
/// estimated error over the whole interval when `error` is given; a jump interval (k == e)
/// takes the trapezoid of the line through its ends.
double interval_integral(const std::vector<double>& t, SeriesView y, std::size_t s, std::size_t e,
                         std::size_t k, double a, double b, double* error) {
  if (k == e) {
    if (error) *error = 0.0;
    return jump_integral(t, y, k, a, b);
  }
  return smooth_integral(t, stencil_geometry(t, s, e, k), y, k, a, b, error);
}

}  // namespace

void cubic_abs_integrals_batch(const std::vector<double>& t, const std::vector<char>& jump,
                               const std::vector<CubicTarget>& targets,
                               const std::vector<char>* keep) {
  const std::size_t T = targets.empty() ? 0 : t.size();
  for (std::size_t s = 0; s + 1 < T;) {
    const std::size_t e = piece_end(jump, s, T);
    const std::size_t last = std::min(e, T - 2);  // the jump interval [e, e + 1] too
    for (std::size_t k = s; k <= last; ++k) {
      if (keep && (*keep)[k]) continue;
      if (k == e) {
        for (const CubicTarget& c : targets) {
          c.integral[k] = jump_integral(t, c.y, k, 0.0, 1.0);
          if (c.error) c.error[k] = 0.0;
          if (c.signed_integral) c.signed_integral[k] = jump_signed(t, c.y, k);
        }
        continue;
      }
      const StencilGeometry g = stencil_geometry(t, s, e, k);
      for (const CubicTarget& c : targets)
        c.integral[k] = smooth_integral(t, g, c.y, k, 0.0, 1.0, c.error ? c.error + k : nullptr,
                                        c.signed_integral ? c.signed_integral + k : nullptr);
    }
    s = e + 1;
  }
}

void cubic_abs_integrals(const std::vector<double>& t, const std::vector<char>& jump, SeriesView y,
                         std::vector<double>& out, std::vector<double>* error) {
  out.assign(t.size() > 0 ? t.size() - 1 : 0, 0.0);
  if (error) error->assign(out.size(), 0.0);
  cubic_abs_integrals_batch(t, jump, {{y, out.data(), error ? error->data() : nullptr}}, nullptr);
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
                                  SeriesView y, double a, double b, const double* whole) {
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
    if (whole && ua == 0.0 && ub == 1.0)
      sum += whole[k];
    else if (ub > ua)
      sum += interval_integral(t, y, s, e, k, ua, ub, nullptr);
  }
  return sum;
}

}  // namespace hexdyn
