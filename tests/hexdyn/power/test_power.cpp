// The power stage's quadrature (power/power.hpp) against closed forms: the trapezoid rule
// over the samples, its restriction to sub-intervals with interpolated bounds (whose pieces
// add up to the whole), and the energy of a series with jumps resolved by left-limit samples.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "hexdyn/power/power.hpp"

namespace hexdyn {

TEST_CASE("trapezoid: exact for piecewise-linear data, second order for smooth data", "[power]") {
  // A piecewise-linear function sampled at its kinks integrates exactly.
  const std::vector<double> t{0.0, 0.5, 2.0, 2.25, 3.0};
  const std::vector<double> y{1.0, 3.0, -1.0, 0.0, 4.0};
  const double exact =
      0.5 * (1 + 3) * 0.5 + 0.5 * (3 - 1) * 1.5 + 0.5 * (-1 + 0) * 0.25 + 0.5 * (0 + 4) * 0.75;
  CHECK(trapezoid(t, y.data()) == Approx(exact).epsilon(1e-15));
  // Strided data: every other value.
  const double yy[6] = {1.0, -7.0, 3.0, -7.0, 10.0, -7.0};
  CHECK(trapezoid({0.0, 1.0, 3.0}, yy, 2) == Approx(0.5 * (1.0 + 3.0) + 0.5 * 2.0 * (3.0 + 10.0)));
  // sin on [0, π]: error ∝ h², the ratio 4 when h halves.
  auto error = [](int n) {
    std::vector<double> tt, yv;
    for (int k = 0; k <= n; ++k) {
      tt.push_back(M_PI * k / n);
      yv.push_back(std::sin(tt.back()));
    }
    return std::abs(trapezoid(tt, yv.data()) - 2.0);
  };
  CHECK(error(32) / error(64) == Approx(4.0).epsilon(0.01));
}

TEST_CASE("trapezoid: a jump resolved by a left-limit sample 1e-10 before it", "[power]") {
  // y = 2 + t on [0, 1), 5 − t on [1, 2]: with a sample at 1 − 1e-10 holding the value before
  // the jump, the trapezoid of the linear pieces is exact up to the 1e-10 sliver; without it
  // the jump is smeared over the step before (error = jump · h / 2).
  const double exact = 2.5 + 3.5;
  std::vector<double> t, y, t_plain, y_plain;
  for (int k = 0; k <= 8; ++k) {
    const double x = 0.25 * k;
    if (k == 4) {
      t.push_back(1.0 - 1e-10);
      y.push_back(3.0 - 1e-10);
    }
    t.push_back(x);
    y.push_back(x < 1.0 ? 2.0 + x : 5.0 - x);
    t_plain.push_back(x);
    y_plain.push_back(y.back());
  }
  CHECK(trapezoid(t, y.data()) == Approx(exact).epsilon(1e-9));
  CHECK(std::abs(trapezoid(t_plain, y_plain.data()) - exact) == Approx(1.0 * 0.25 / 2.0));
}

TEST_CASE("trapezoid_between: pieces add up to the whole and interpolate at the bounds",
          "[power]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(0.01, 0.3), value(0.0, 50.0);
  std::vector<double> t{0.0}, y{value(rng)};
  for (int k = 0; k < 60; ++k) {
    t.push_back(t.back() + step(rng));
    y.push_back(value(rng));
  }
  const double whole = trapezoid(t, y.data());
  // Bounds between samples, on samples and at the ends.
  for (std::vector<double> cuts :
       {std::vector<double>{0.0, 1.234, 3.0, t[20], t.back()}, std::vector<double>{0.0, t.back()},
        std::vector<double>{0.0, t[1], t[2], 0.5 * (t[2] + t[3]), t.back()}}) {
    std::sort(cuts.begin(), cuts.end());
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
      sum += trapezoid_between(t, y.data(), cuts[k], cuts[k + 1]);
    CHECK(sum == Approx(whole).epsilon(1e-13));
  }
  // Inside one interval: the integral of the line through its two samples.
  const double a = t[5] + 0.25 * (t[6] - t[5]), b = t[5] + 0.75 * (t[6] - t[5]);
  const double slope = (y[6] - y[5]) / (t[6] - t[5]);
  const double ya = y[5] + slope * (a - t[5]), yb = y[5] + slope * (b - t[5]);
  CHECK(trapezoid_between(t, y.data(), a, b) == Approx(0.5 * (b - a) * (ya + yb)).epsilon(1e-13));
  CHECK(trapezoid_between(t, y.data(), 2.0, 2.0) == 0.0);
}

}  // namespace hexdyn

namespace hexdyn {

TEST_CASE("compute_power: cubic energies of cubic powers per piece, and the known estimates",
          "[power]") {
  // Joint j's power τ ω is a cubic (t − r1)(t − r2)(t − r3 − j/40) on [0, 1 − 1e-10] and a
  // quadratic 0.5 − t² + j/50 after the jump at 1 (a left-limit sample 1e-10 s before it): the
  // rule integrates |τ ω| exactly on each piece, from the antiderivative split at the roots.
  // For a hexapod's 18 joints and a quadruped's 12: the joints are the torques' columns.
  const int J = GENERATE(18, 12);
  CAPTURE(J);
  std::vector<double> t;
  for (int k = 0; k <= 23; ++k) t.push_back(std::pow(k / 23.0, 1.2) * (1.0 - 1e-10));
  for (int k = 0; k <= 30; ++k) t.push_back(1.0 + k / 30.0);
  const auto T = static_cast<Eigen::Index>(t.size());
  KinematicsResult kin;
  kin.time_s = t;
  kin.sample_kind.assign(t.size(), 0);
  kin.sample_kind[23] = 1;
  kin.joint_velocity.resize(T, J);
  RowMatrix torque(T, J);
  const auto power = [](int j, double x) {
    return x < 1.0 ? (x - 0.1) * (x - 0.45) * (x - 0.8 - j / 40.0) : 0.5 - x * x + j / 50.0;
  };
  for (Eigen::Index i = 0; i < T; ++i)
    for (int j = 0; j < J; ++j) {
      torque(i, j) = 2.0 + j;  // ω = P / τ
      kin.joint_velocity(i, j) = power(j, t[i]) / (2.0 + j);
    }
  const PowerResult p = compute_power(kin, torque, 10.0, 1.0, {0.0, 0.55, 1.5});
  double total = 0.0;
  for (int j = 0; j < J; ++j) {
    // ∫|P| piece by piece, by fine midpoint sums of the closed forms (independent of the rule).
    double exact = 0.0;
    const int n = 400000;
    for (int piece = 0; piece < 2; ++piece) {
      const double a = piece == 0 ? 0.0 : 1.0, b = piece == 0 ? 1.0 - 1e-10 : 2.0;
      for (int i = 0; i < n; ++i)
        exact += std::abs(power(j, a + (i + 0.5) * (b - a) / n)) * (b - a) / n;
    }
    exact += 0.5 * 1e-10 * (std::abs(power(j, 1.0 - 1e-10)) + std::abs(power(j, 1.0)));
    CHECK(p.energy_joint_J[j] == Approx(exact).epsilon(1e-8));
    // The positive and negative parts, by the same midpoint sums of max(0, P) and min(0, P).
    double positive = 0.0, negative = 0.0;
    for (int piece = 0; piece < 2; ++piece) {
      const double a = piece == 0 ? 0.0 : 1.0, b = piece == 0 ? 1.0 - 1e-10 : 2.0;
      for (int i = 0; i < n; ++i) {
        const double v = power(j, a + (i + 0.5) * (b - a) / n) * (b - a) / n;
        (v > 0.0 ? positive : negative) += v;
      }
    }
    CHECK(p.positive_work_joint_J[j] == Approx(positive).epsilon(1e-8).margin(1e-12));
    CHECK(p.negative_work_joint_J[j] == Approx(negative).epsilon(1e-8).margin(1e-12));
    CHECK(p.negative_work_joint_J[j] < 0.0);
    total += p.energy_joint_J[j];
  }
  CHECK(p.energy_total_J == Approx(total).epsilon(1e-15));
  CHECK(p.positive_work_J - p.negative_work_J == Approx(p.energy_total_J).epsilon(1e-14));
  REQUIRE(p.energy_cycle_J.size() == 3);
  CHECK(p.energy_cycle_J[0] + p.energy_cycle_J[1] + p.energy_cycle_J[2] ==
        Approx(p.energy_total_J).epsilon(1e-13));
  // Given the interval integrals of these samples (as the grid's last assessment keeps them),
  // the energies are the same bits; given another grid's, they are computed as before.
  CubicEstimates known;
  known.t_s = t;
  known.integral.resize(J);
  std::vector<double> ignored;
  const RowMatrix joint_power = torque.cwiseProduct(kin.joint_velocity);
  std::vector<char> jump(t.size(), 0);
  jump[23] = 1;
  for (int j = 0; j < J; ++j)
    cubic_abs_integrals(t, jump, {joint_power.data() + j, J}, known.integral[j], &ignored);
  const PowerResult q =
      compute_power(kin, torque, 10.0, 1.0, {0.0, 0.55, 1.5}, Quadrature::kCubic, &known);
  CHECK(q.energy_joint_J == p.energy_joint_J);
  CHECK(q.energy_cycle_J == p.energy_cycle_J);
  for (auto& v : known.integral) std::fill(v.begin(), v.end(), 1.0);
  known.t_s.back() += 1e-9;  // not these samples: ignored
  const PowerResult r =
      compute_power(kin, torque, 10.0, 1.0, {0.0, 0.55, 1.5}, Quadrature::kCubic, &known);
  CHECK(r.energy_joint_J == p.energy_joint_J);
}

}  // namespace hexdyn
