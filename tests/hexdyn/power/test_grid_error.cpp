// The output grid's error estimates (power/grid_error.hpp) against exact integrals and maxima
// of functions known in closed form: the cubic estimate is exact for cubics, the parabola
// finds a parabola's vertex, and refining by assess_grid brings the trapezoid of a function with
// kinks, a jump and a sharp peak within the tolerance of its exact integral and maximum.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <iterator>
#include <numeric>
#include <vector>

#include "hexdyn/power/grid_error.hpp"
#include "hexdyn/power/power.hpp"

using namespace hexdyn;

namespace {

std::vector<double> sample(const std::vector<double>& t, const std::function<double(double)>& f) {
  std::vector<double> y;
  for (double x : t) y.push_back(f(x));
  return y;
}

}  // namespace

TEST_CASE("trapezoid_errors: exact for a cubic on an irregular grid", "[grid_error]") {
  // y = 2 − t + 3 t² − 4 t³: ∫_a^b y = F(b) − F(a), F = 2t − t²/2 + t³ − t⁴.
  const auto f = [](double x) { return 2.0 - x + 3.0 * x * x - 4.0 * x * x * x; };
  const auto F = [](double x) { return 2.0 * x - 0.5 * x * x + x * x * x - std::pow(x, 4); };
  const std::vector<double> t{0.0, 0.013, 0.05, 0.09, 0.2, 0.21, 0.5, 0.77};
  const std::vector<double> y = sample(t, f);
  const std::vector<char> jump(t.size(), 0);
  std::vector<double> e;
  trapezoid_errors(t, jump, {y.data(), 1}, e);
  REQUIRE(e.size() == t.size() - 1);
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const double exact = F(t[k + 1]) - F(t[k]) - 0.5 * (t[k + 1] - t[k]) * (y[k] + y[k + 1]);
    CHECK(e[k] == Approx(exact).epsilon(1e-9).margin(1e-15));
  }
}

TEST_CASE("trapezoid_errors: pieces are separate, a jump interval has no error", "[grid_error]") {
  // A quadratic on a piece of two intervals, a jump, then a cubic on four: each estimate is
  // exact for its own piece, and a single-interval piece gets the monotone bound.
  const auto f = [](double x) { return x < 1.0 ? 1.0 + x * x : 10.0 - x * x * x; };
  const auto F = [](double x) {
    return x < 1.0 ? x + x * x * x / 3.0 : 10.0 * x - std::pow(x, 4) / 4;
  };
  const std::vector<double> t{0.0, 0.3, 0.9, 1.0 - 1e-10, 1.0, 1.1,
                              1.4, 1.5, 2.0, 2.5 - 1e-10, 2.5, 2.8};
  std::vector<double> y = sample(t, f);
  y[11] = 0.0;  // after the second jump, a single interval [2.5, 2.8]
  y[10] = 7.0;
  std::vector<char> jump(t.size(), 0);
  jump[3] = jump[9] = 1;
  // The first piece is 0, 0.3, 0.9, 1 − 1e-10 (three intervals, a cubic through four samples
  // of a quadratic: exact); the second 1 … 2.5 − 1e-10.
  std::vector<double> e;
  trapezoid_errors(t, jump, {y.data(), 1}, e);
  for (std::size_t k : {0u, 1u, 2u, 4u, 5u, 6u, 7u, 8u}) {
    const double exact = F(t[k + 1]) - F(t[k]) - 0.5 * (t[k + 1] - t[k]) * (y[k] + y[k + 1]);
    CHECK(e[k] == Approx(exact).epsilon(1e-7).margin(1e-14));
  }
  CHECK(e[3] == 0.0);
  CHECK(e[9] == 0.0);
  CHECK(e[10] == Approx(0.5 * 0.3 * 7.0).epsilon(1e-12));
}

TEST_CASE("abs_trapezoid_errors: |y| of a smooth y that changes sign", "[grid_error]") {
  // y = t² − 0.3 (a root at √0.3): where y keeps its sign the error of |y| is ± y's (exact for
  // a quadratic), and on the interval with the root, ∫|ℓ| − trapezoid of |y| for the line ℓ
  // through its ends plus y's own error, with ℓ's root.
  const auto f = [](double x) { return x * x - 0.3; };
  const std::vector<double> t{0.0, 0.2, 0.35, 0.5, 0.7, 0.8, 1.0};
  const std::vector<double> y = sample(t, f);
  const std::vector<char> jump(t.size(), 0);
  std::vector<double> e, root, plain;
  abs_trapezoid_errors(t, jump, {y.data(), 1}, e, root);
  trapezoid_errors(t, jump, {y.data(), 1}, plain);
  // ∫ (t² − 0.3) over [a, b] − trapezoid = −(b − a)³/6 for this y.
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const double h = t[k + 1] - t[k];
    CHECK(plain[k] == Approx(-h * h * h / 6.0).epsilon(1e-9));
    if (y[k] * y[k + 1] > 0.0) {
      CHECK(std::isnan(root[k]));
      CHECK(e[k] == Approx(y[k] < 0.0 ? h * h * h / 6.0 : -h * h * h / 6.0).epsilon(1e-9));
    } else {
      // The root lies in [0.5, 0.7]: ℓ crosses zero at 0.5 + 0.2 · 0.05 / 0.24.
      REQUIRE(k == 3);
      CHECK(root[k] == Approx(0.5 + 0.2 * 0.05 / 0.24).epsilon(1e-12));
      const double a = std::abs(y[k]), b = std::abs(y[k + 1]);
      CHECK(e[k] == Approx(-h * a * b / (a + b) - h * h * h / 6.0).epsilon(1e-9));
    }
  }
}

TEST_CASE("estimate_peak: a bound at a smooth maximum, exact at a corner", "[grid_error]") {
  const std::vector<double> t{0.0, 0.1, 0.25, 0.3, 0.5, 0.6, 0.9};
  const std::vector<char> jump(t.size(), 0);
  SECTION("a concave parabola: the lines with the neighbours' slopes bound it from above") {
    // For a concave y the left neighbour's secant is at least as steep as y'(t_k), so the line
    // through t_k lies above y to its right, and likewise on the left: the estimate bounds the
    // true maximum 3 (at 0.37, inside [0.3, 0.5]).
    const auto f = [](double x) { return 3.0 - 20.0 * (x - 0.37) * (x - 0.37); };
    const std::vector<double> y = sample(t, f);
    std::vector<double> at;
    const PeakEstimate p = estimate_peak(t, jump, {y.data(), 1}, 1e-4, 1e-8, &at);
    CHECK(p.sampled == Approx(f(0.3)));
    CHECK(p.predicted >= 3.0);
    CHECK(p.predicted_s > 0.3);
    CHECK(p.predicted_s < 0.5);
    // Refined inside the interval that holds the maximum, and next to the sampled maximum.
    CHECK(std::count_if(at.begin(), at.end(), [](double x) { return x > 0.3 && x < 0.5; }) >= 2);
    CHECK(std::count_if(at.begin(), at.end(),
                        [](double x) { return std::abs(x - 0.275) < 1e-12; }) >= 1);
  }
  SECTION("a corner: exact where its straight sides are sampled") {
    // A tent with its apex 5 at 0.41, sides of slope 4 and −9.
    const auto f = [](double x) {
      return x < 0.41 ? 5.0 + 4.0 * (x - 0.41) : 5.0 - 9.0 * (x - 0.41);
    };
    const std::vector<double> y = sample(t, f);
    const PeakEstimate p = estimate_peak(t, jump, {y.data(), 1}, 1e-4, 1e-8, nullptr);
    CHECK(p.predicted == Approx(5.0).epsilon(1e-12));
    CHECK(p.predicted_s == Approx(0.41).epsilon(1e-12));
  }
  SECTION("a rise that ends in a drop within an interval: bounded by the rising line") {
    // Rising with slope 2 up to 0.55, then down by 1.5 at once (a jump within the piece).
    const auto f = [](double x) { return x < 0.55 ? 1.0 + 2.0 * x : 0.5 + 2.0 * x - 1.5; };
    const std::vector<double> y = sample(t, f);
    const PeakEstimate p = estimate_peak(t, jump, {y.data(), 1}, 1e-4, 1e-8, nullptr);
    CHECK(p.predicted >= f(0.55 - 1e-12) - 1e-12);
  }
}

TEST_CASE("assess_grid: refinement brings integrals and peaks within the tolerance",
          "[grid_error]") {
  // |sin| kinks, a jump at t = 1 (with its left-limit sample), and a narrow peak at 1.6.
  const auto f = [](double x) {
    const double bump = 4.0 * std::exp(-std::pow((x - 1.6) / 0.01, 2));
    return std::abs(std::sin(9.0 * x)) * (1.0 + x) + (x >= 1.0 ? 2.0 : 0.0) + bump;
  };
  // The exact integral and maximum, by a composite Simpson rule on 2·10⁶ intervals per piece
  // (a second computation, independent of the sampling under test).
  const auto simpson = [&](double a, double b) {
    const int n = 2000000;
    const double h = (b - a) / n;
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
    return s * h / 3.0;
  };
  const double exact = simpson(0.0, 1.0 - 1e-10) + simpson(1.0, 2.0);
  double f_max = 0.0;
  for (int i = 0; i <= 4000000; ++i) f_max = std::max(f_max, f(2.0 * i / 4000000.0));

  for (double tol : {1e-3, 1e-4, 1e-5}) {
    std::vector<double> t;
    for (int i = 0; i <= 40; ++i) t.push_back(0.05 * i);
    t.insert(t.begin() + 20, 1.0 - 1e-10);  // left limit of the jump
    std::vector<char> jump;
    int passes = 0;
    GridAssessment a;
    for (;; ++passes) {
      jump.assign(t.size(), 0);
      for (std::size_t k = 0; k + 1 < t.size(); ++k) jump[k] = t[k + 1] - t[k] < 1e-9;
      const std::vector<double> y = sample(t, f);
      a = assess_grid(t, jump, {{y.data(), 1}}, {{{0}, exact}}, {{y.data(), 1}}, tol, 1e-8);
      if (a.refine_at_s.empty() || passes == 60) break;
      std::vector<double> merged;
      std::merge(t.begin(), t.end(), a.refine_at_s.begin(), a.refine_at_s.end(),
                 std::back_inserter(merged));
      t = std::move(merged);
    }
    const std::vector<double> y = sample(t, f);
    INFO("tolerance " << tol << ", " << t.size() << " samples, " << passes << " passes");
    CHECK(passes < 60);
    CHECK(a.integral_error <= tol);
    CHECK(a.peak_error <= tol);
    CHECK(std::abs(trapezoid(t, y.data()) - exact) <= tol * exact);
    CHECK(*std::max_element(y.begin(), y.end()) >= f_max * (1.0 - tol));
    // No finer than needed: far fewer samples than the uniform step that the trapezoid's
    // error bound h² max|f''| L / 12 ≤ tol E needs (max|f''| = 2·4/0.01² at the narrow peak,
    // L = 2).
    const double uniform = 2.0 / std::sqrt(12.0 * tol * exact / (8e4 * 2.0));
    CHECK(static_cast<double>(t.size()) < 0.25 * uniform);
  }
}

TEST_CASE("assess_grid: the cubic estimates kept from pass to pass are those computed again",
          "[grid_error]") {
  // A signed series with sign changes, a jump at t = 1 (with its left-limit sample) and a
  // narrow peak, refined for its cubic-rule integral: each pass assessed once with the last
  // pass's estimates kept where no sample was added near them and once from scratch; the
  // assessments must agree bit for bit.
  const auto f = [](double x) {
    return std::sin(9.0 * x) * (1.0 + x) + (x >= 1.0 ? 2.0 : 0.0) +
           4.0 * std::exp(-std::pow((x - 1.6) / 0.01, 2));
  };
  std::vector<double> t;
  for (int i = 0; i <= 40; ++i) t.push_back(0.05 * i);
  t.insert(t.begin() + 20, 1.0 - 1e-10);
  CubicEstimates kept;
  int passes = 0, refined = 0;
  for (; passes < 30; ++passes) {
    std::vector<char> jump(t.size(), 0);
    for (std::size_t k = 0; k + 1 < t.size(); ++k) jump[k] = t[k + 1] - t[k] < 1e-9;
    const std::vector<double> y = sample(t, f);
    const std::vector<SeriesView> terms{{y.data(), 1}};
    const std::vector<IntegralTarget> targets{{{0}, 2.0, Quadrature::kCubic}};
    const GridAssessment fresh = assess_grid(t, jump, terms, targets, terms, 1e-7, 1e-8);
    const GridAssessment reused = assess_grid(t, jump, terms, targets, terms, 1e-7, 1e-8, &kept);
    INFO("pass " << passes << ", " << t.size() << " samples");
    CHECK(reused.integral_error == fresh.integral_error);
    CHECK(reused.peak_error == fresh.peak_error);
    CHECK(reused.refine_at_s == fresh.refine_at_s);
    if (fresh.refine_at_s.empty()) break;
    refined += static_cast<int>(fresh.refine_at_s.size());
    std::vector<double> merged;
    std::merge(t.begin(), t.end(), fresh.refine_at_s.begin(), fresh.refine_at_s.end(),
               std::back_inserter(merged));
    t = std::move(merged);
  }
  CHECK(passes >= 3);
  CHECK(refined > 100);
}
