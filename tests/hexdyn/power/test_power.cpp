// The power stage's quadrature (power/power.hpp) against closed forms: a piecewise-smooth
// series with jumps whose left limits are given, and a power-like series with kinks.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "hexdyn/power/power.hpp"

namespace hexdyn {

TEST_CASE("integrate_pieces: piecewise-smooth series with jumps, against the closed form",
          "[power]") {
  // y = 2 + sin(3t) on [0, 1), 5 + t² on [1, 1.5), 1 + cos t on [1.5, 2]: jumps at 1 and
  // 1.5, where the sample holds the value after the jump and the left limit is given.
  auto y_of = [](double t) {
    return t < 1.0 ? 2.0 + std::sin(3.0 * t) : t < 1.5 ? 5.0 + t * t : 1.0 + std::cos(t);
  };
  const double exact = (2.0 + (1.0 - std::cos(3.0)) / 3.0) + (2.5 + (1.5 * 1.5 * 1.5 - 1.0) / 3.0) +
                       (0.5 + std::sin(2.0) - std::sin(1.5));
  auto error_with = [&](int n_per_unit, bool with_breaks) {
    // Non-uniform steps: every other step 1.5 times the one before.
    std::vector<double> t;
    const double h = 1.0 / n_per_unit;
    for (double x = 0.0; x < 2.0 - 1e-12;) {
      t.push_back(x);
      const double step = (t.size() % 2 ? 0.8 : 1.2) * h;
      const double next_event = x < 1.0 ? 1.0 : x < 1.5 ? 1.5 : 2.0;
      x = std::min(x + step, next_event);
    }
    t.push_back(2.0);
    std::vector<double> y;
    std::vector<int> breaks;
    std::vector<double> left;
    for (std::size_t k = 0; k < t.size(); ++k) {
      y.push_back(y_of(t[k]));
      if (t[k] == 1.0 || t[k] == 1.5) {
        breaks.push_back(static_cast<int>(k));
        left.push_back(t[k] == 1.0 ? 2.0 + std::sin(3.0) : 5.0 + 1.5 * 1.5);
      }
    }
    REQUIRE(breaks.size() == 2);
    const double value = with_breaks ? integrate_pieces(t, y.data(), 1, breaks, left)
                                     : integrate_series(t, y.data());
    return std::abs(value - exact);
  };
  // With the left limits: at least second order overall (the monotone interpolant loses
  // an order next to extrema), 1e-5 at h = 1/64.
  const double e16 = error_with(16, true), e64 = error_with(64, true);
  const double s16 = error_with(16, false), s64 = error_with(64, false);
  CAPTURE(e16, e64, s16, s64);
  CHECK(e64 < 1e-5);
  CHECK(e16 / e64 > 16.0);
  // Without them each jump is smeared over a step: first order, far worse.
  CHECK(s64 > 100.0 * e64);
  CHECK(s16 / s64 == Approx(4.0).epsilon(0.3));
  // Strided data and a piece of one interval (the trapezoid).
  const std::vector<double> t2{0.0, 1.0, 3.0};
  const double yy[6] = {1.0, -7.0, 3.0, -7.0, 10.0, -7.0};
  CHECK(integrate_pieces(t2, yy, 2, {1}, {5.0}) ==
        Approx(0.5 * (1.0 + 5.0) + 0.5 * 2.0 * (3.0 + 10.0)));
}

TEST_CASE("integrate_pieces: never below zero for a power series with kinks", "[power]") {
  // |sin| sampled coarsely: kinks at the zeros, data ≥ 0. The monotone interpolant keeps
  // every piece's integral between 0 and max·length, and converges to the closed form.
  std::vector<double> t, y;
  for (int k = 0; k <= 40; ++k) {
    t.push_back(0.3 * k);
    y.push_back(std::abs(std::sin(t.back())));
  }
  const double E = integrate_series(t, y.data());
  const double exact = 3.0 * 2.0 + (1.0 - std::cos(12.0 - 3.0 * M_PI));  // ∫₀¹² |sin t| dt
  CHECK(E > 0.0);
  CHECK(E == Approx(exact).epsilon(0.02));
  for (int k = 0; k + 3 < 41; ++k)
    CHECK(integrate_series({t[k], t[k + 1], t[k + 2], t[k + 3]}, &y[k]) >= 0.0);
}

}  // namespace hexdyn
