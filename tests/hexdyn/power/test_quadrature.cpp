// The piecewise-cubic rule of the energies (power/quadrature.hpp) against closed forms:
// exact for a cubic on every piece (of at least three intervals; a quadratic on a piece of
// two, a line on one), through the roots of an absolute value, with jumps at left-limit
// samples; fourth order, measured, on |sin| with kinks between samples; spans that add up to
// the whole; and the error estimate against the true error.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "hexdyn/power/quadrature.hpp"

namespace hexdyn {
namespace {

/// Samples of f on an irregular grid over [a, b]: n intervals, steps varying by a factor 3.
void irregular(double a, double b, int n, std::mt19937& rng, const std::function<double(double)>& f,
               std::vector<double>& t, std::vector<double>& y) {
  std::uniform_real_distribution<double> w(1.0, 3.0);
  std::vector<double> steps(n);
  double sum = 0.0;
  for (double& s : steps) sum += (s = w(rng));
  double x = a;
  for (int k = 0; k <= n; ++k) {
    t.push_back(k == n ? b : x);
    y.push_back(f(t.back()));
    if (k < n) x += (b - a) * steps[k] / sum;
  }
}

/// ∫_a^b |c| of c(t) = (t − r1)(t − r2)(t − r3), r1 < r2 < r3, from its antiderivative split
/// at the roots.
double abs_cubic_integral(double r1, double r2, double r3, double a, double b) {
  const double e1 = r1 + r2 + r3, e2 = r1 * r2 + r1 * r3 + r2 * r3, e3 = r1 * r2 * r3;
  const auto F = [&](double x) {
    return x * x * x * x / 4.0 - e1 * x * x * x / 3.0 + e2 * x * x / 2.0 - e3 * x;
  };
  std::vector<double> cuts{a};
  for (double r : {r1, r2, r3})
    if (r > a && r < b) cuts.push_back(r);
  cuts.push_back(b);
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) sum += std::abs(F(cuts[i + 1]) - F(cuts[i]));
  return sum;
}

}  // namespace

TEST_CASE("cubic rule: exact for a cubic per piece, through the roots of |y|", "[power]") {
  std::mt19937 rng(11);
  // Three pieces, split by left-limit samples 1e-10 s before the events at 1 and 2.2; a
  // different cubic on each, changing sign inside the pieces (roots between samples).
  const double roots[3][3] = {{0.13, 0.41, 0.77}, {1.3, 1.55, 2.05}, {2.3, 2.61, 2.99}};
  const double bounds[4] = {0.0, 1.0, 2.2, 3.0};
  std::vector<double> t, y;
  std::vector<char> jump;
  double exact = 0.0;
  for (int p = 0; p < 3; ++p) {
    const double* r = roots[p];
    const auto f = [r](double x) { return (x - r[0]) * (x - r[1]) * (x - r[2]); };
    std::vector<double> tp, yp;
    irregular(bounds[p], bounds[p + 1] - (p < 2 ? 1e-10 : 0.0), 9 + 3 * p, rng, f, tp, yp);
    t.insert(t.end(), tp.begin(), tp.end());
    y.insert(y.end(), yp.begin(), yp.end());
    jump.insert(jump.end(), tp.size(), 0);
    if (p < 2) jump.back() = 1;  // the left limit: the series jumps after it
    exact += abs_cubic_integral(r[0], r[1], r[2], bounds[p], bounds[p + 1] - (p < 2 ? 1e-10 : 0.0));
    if (p < 2) {  // the jump interval's trapezoid
      const double* q = roots[p + 1];
      const double after = (bounds[p + 1] - q[0]) * (bounds[p + 1] - q[1]) * (bounds[p + 1] - q[2]);
      exact += 0.5 * 1e-10 * (std::abs(yp.back()) + std::abs(after));
    }
  }
  CHECK(cubic_abs_integral(t, jump, {y.data(), 1}) == Approx(exact).epsilon(1e-12));
  // The same pieces without their marks: one piece, and the cubics across the jumps do not fit.
  const std::vector<char> none(t.size(), 0);
  CHECK(std::abs(cubic_abs_integral(t, none, {y.data(), 1}) - exact) > 1e-4);
  // The estimated error is the next term: zero on a cubic (to rounding).
  std::vector<double> parts, error;
  cubic_abs_integrals(t, jump, {y.data(), 1}, parts, &error);
  for (double e : error) CHECK(std::abs(e) < 1e-12);
}

TEST_CASE("cubic rule: a quadratic on a piece of two intervals, a line on one", "[power]") {
  // Pieces of 2 and 1 intervals (jump after sample 2, after sample 3) and one of 3.
  const std::vector<double> t{0.0, 0.3, 1.0, 1.0 + 1e-10, 1.5, 1.5 + 1e-10, 1.7, 2.0, 2.6};
  const std::vector<char> jump{0, 0, 1, 0, 1, 0, 0, 0, 0};
  const auto q = [](double x) { return 2.0 + x - 3.0 * x * x; };      // roots 1 ± … : 1.0 > 0.94
  const auto l = [](double x) { return 4.0 * (x - 1.2); };            // a root at 1.2
  const auto c = [](double x) { return (x - 1.8) * (x - 2.4) * x; };  // cubic, roots inside
  const auto piece = [&](double x, int i) { return i == 0 ? q(x) : i == 1 ? l(x) : c(x); };
  const int of[9] = {0, 0, 0, 1, 1, 2, 2, 2, 2};
  std::vector<double> y;
  for (int k = 0; k < 9; ++k) y.push_back(piece(t[k], of[k]));
  // Closed forms: ∫|q| on [0, 1] with its root r = (1 + √25)/6 = 1: q ≥ 0 there;
  // ∫|l| over [1 + 1e-10, 1.5] = 2 (0.2² + 0.3²) − (the 1e-10 sliver: 2·(0.2² − (0.2 − 1e-10)²));
  // ∫|c| over [1.5 + 1e-10, 2.6].
  const double Q = 2.0 + 0.5 - 1.0;
  const double a = 1.0 + 1e-10, L = 2.0 * ((1.2 - a) * (1.2 - a) + 0.3 * 0.3);
  const double C = abs_cubic_integral(0.0, 1.8, 2.4, 1.5 + 1e-10, 2.6);
  const double J = 0.5 * 1e-10 * (std::abs(y[2]) + std::abs(y[3])) +
                   0.5 * 1e-10 * (std::abs(y[4]) + std::abs(y[5]));
  CHECK(cubic_abs_integral(t, jump, {y.data(), 1}) == Approx(Q + L + C + J).epsilon(1e-12));
}

TEST_CASE("cubic rule: fourth order on |sin| with kinks between samples", "[power]") {
  // ∫_0^{3π} |sin t| dt = 6: the kinks at π and 2π fall between samples of the irregular grids
  // (the rule's cubic of the signed series is smooth through them). Halving every step (the
  // same grid refined) divides the error by about 2⁴.
  std::mt19937 rng(5);
  std::vector<double> t0, y0;
  irregular(
      0.0, 3.0 * M_PI, 24, rng, [](double x) { return std::sin(x); }, t0, y0);
  const auto error_at = [&](int halvings) {
    std::vector<double> t = t0;
    for (int i = 0; i < halvings; ++i) {
      std::vector<double> finer;
      for (std::size_t k = 0; k + 1 < t.size(); ++k) {
        finer.push_back(t[k]);
        finer.push_back(0.5 * (t[k] + t[k + 1]));
      }
      finer.push_back(t.back());
      t = finer;
    }
    std::vector<double> y;
    for (double x : t) y.push_back(std::sin(x));
    const std::vector<char> jump(t.size(), 0);
    return std::abs(cubic_abs_integral(t, jump, {y.data(), 1}) - 6.0);
  };
  const double e1 = error_at(2), e2 = error_at(3), e3 = error_at(4);
  const double order = std::log2(e2 / e3);
  INFO("errors " << e1 << " " << e2 << " " << e3 << ", order " << order);
  CHECK(order > 3.7);
  CHECK(order < 4.5);
  CHECK(std::log2(e1 / e2) > 3.5);
}

TEST_CASE("cubic rule: the estimate follows the true error on a smooth series", "[power]") {
  // exp(t) sin(3t) + 2 on an irregular grid: positive (no kinks), so the true error is known.
  std::mt19937 rng(3);
  std::vector<double> t, y;
  const auto f = [](double x) { return std::exp(x) * std::sin(3.0 * x) + 20.0; };
  irregular(0.0, 2.0, 160, rng, f, t, y);
  // ∫ e^x sin 3x = e^x (sin 3x − 3 cos 3x) / 10.
  const auto F = [](double x) {
    return std::exp(x) * (std::sin(3.0 * x) - 3.0 * std::cos(3.0 * x)) / 10.0 + 20.0 * x;
  };
  const std::vector<char> jump(t.size(), 0);
  std::vector<double> parts, error;
  cubic_abs_integrals(t, jump, {y.data(), 1}, parts, &error);
  double sum = 0.0, estimate = 0.0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    sum += parts[k];
    estimate += error[k];
  }
  const double truth = F(2.0) - F(0.0) - sum;
  INFO("true error " << truth << ", estimate " << estimate);
  CHECK(std::abs(truth) > 1e-12);  // the rule is not exact here: the comparison means something
  CHECK(std::abs(estimate) > 0.3 * std::abs(truth));
  CHECK(std::abs(estimate) < 3.0 * std::abs(truth));
}

TEST_CASE("cubic rule: spans add up to the whole, bounds cut the interval's cubic", "[power]") {
  std::mt19937 rng(9);
  const auto f = [](double x) { return (x - 0.7) * (x - 1.9) * (x + 0.5); };
  std::vector<double> t, y;
  irregular(0.0, 1.0 - 1e-10, 7, rng, f, t, y);
  std::vector<double> t2, y2;
  irregular(
      1.0, 3.0, 11, rng, [](double x) { return 1.0 - x * x; }, t2, y2);
  std::vector<char> jump(t.size(), 0);
  jump.back() = 1;
  t.insert(t.end(), t2.begin(), t2.end());
  y.insert(y.end(), y2.begin(), y2.end());
  jump.resize(t.size(), 0);
  const SeriesView v{y.data(), 1};
  const double whole = cubic_abs_integral(t, jump, v);
  const std::vector<double> cuts{0.0, 0.37, 1.0 - 0.5e-10, 1.4, 2.999, 3.0};
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    sum += cubic_abs_integral_between(t, jump, v, cuts[i], cuts[i + 1]);
  CHECK(sum == Approx(whole).epsilon(1e-13));
  CHECK(cubic_abs_integral_between(t, jump, v, 0.0, 3.0) == Approx(whole).epsilon(1e-14));
  // Within a piece the span is the cubic's closed form: ∫_{0.2}^{0.6} |f| and ∫_{1.2}^{2.5} |1 −
  // x²|.
  CHECK(cubic_abs_integral_between(t, jump, v, 0.2, 0.6) ==
        Approx(abs_cubic_integral(-0.5, 0.7, 1.9, 0.2, 0.6)).epsilon(1e-12));
  const double G = (2.5 - 2.5 * 2.5 * 2.5 / 3.0) - (1.2 - 1.2 * 1.2 * 1.2 / 3.0);
  CHECK(cubic_abs_integral_between(t, jump, v, 1.2, 2.5) == Approx(-G).epsilon(1e-12));
}

}  // namespace hexdyn

namespace hexdyn {

TEST_CASE("cubic rule: a batch gives each series' numbers to the bit", "[power]") {
  std::mt19937 rng(5);
  std::vector<double> t, y0;
  // Roots close together (0.5 and 0.5 + 1e-7) and sign changes between samples.
  irregular(
      0.0, 2.0, 40, rng, [](double x) { return (x - 0.5) * (x - 0.5 - 1e-7) * (x - 1.3); }, t, y0);
  const std::size_t T = t.size();
  std::vector<char> jump(T, 0);
  jump[17] = 1;
  // Three series interleaved (stride 3): the cubic, a sine and a constant.
  std::vector<double> y(3 * T);
  for (std::size_t k = 0; k < T; ++k) {
    y[3 * k] = y0[k];
    y[3 * k + 1] = std::sin(7.0 * t[k]);
    y[3 * k + 2] = -0.25;
  }
  std::vector<std::vector<double>> integral(3, std::vector<double>(T - 1)),
      error(3, std::vector<double>(T - 1));
  std::vector<CubicTarget> targets;
  for (int i = 0; i < 3; ++i)
    targets.push_back({{y.data() + i, 3}, integral[i].data(), error[i].data()});
  cubic_abs_integrals_batch(t, jump, targets);
  for (int i = 0; i < 3; ++i) {
    std::vector<double> one, one_error;
    cubic_abs_integrals(t, jump, {y.data() + i, 3}, one, &one_error);
    CHECK(one == integral[i]);
    CHECK(one_error == error[i]);
  }
  // With `keep`, the kept intervals are left alone.
  std::vector<char> keep(T - 1, 0);
  for (std::size_t k = 0; k < T - 1; k += 3) keep[k] = 1;
  std::vector<double> part(T - 1, -7.0), part_error(T - 1, -7.0);
  cubic_abs_integrals_batch(t, jump, {{{y.data(), 3}, part.data(), part_error.data()}}, &keep);
  for (std::size_t k = 0; k < T - 1; ++k) {
    CHECK(part[k] == (keep[k] ? -7.0 : integral[0][k]));
    CHECK(part_error[k] == (keep[k] ? -7.0 : error[0][k]));
  }
  // The whole intervals of a span taken from the integrals: the same as computed.
  for (double a : {0.0, 0.33, 1.0})
    CHECK(cubic_abs_integral_between(t, jump, {y.data() + 1, 3}, a, 1.9, integral[1].data()) ==
          cubic_abs_integral_between(t, jump, {y.data() + 1, 3}, a, 1.9));
  // The cubic piece through its nearly double root: the closed form.
  const double before_jump = cubic_abs_integral_between(t, jump, {y.data(), 3}, 0.0, t[17]);
  double exact = 0.0;
  {
    const double r1 = 0.5, r2 = 0.5 + 1e-7, r3 = 1.3;
    exact = abs_cubic_integral(r1, r2, r3, 0.0, t[17]);
  }
  CHECK(before_jump == Approx(exact).epsilon(1e-12));
}

}  // namespace hexdyn
