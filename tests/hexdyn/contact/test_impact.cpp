// Tests of the IMPACT contact law and the touchdown transient (src/hexdyn/contact.hpp).
// Expected values are computed here by a second route: hand arithmetic on the law, the
// closed-form undamped Hertz-type impact, the analytic damped linear oscillator, and
// momentum and energy balances.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>

#include "hexdyn/contact/impact.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/sample_models.hpp"

using namespace hexdyn;

namespace {

ContactParams paper_contact() {
  ContactParams c;
  c.stiffness = 1e5;
  c.exponent = 2.2;
  c.damping_max_Nspm = 10.0;
  c.full_damping_depth_m = 1e-5;
  c.friction_coefficient = 0.3;
  return c;
}

double rel_err(double got, double want) { return std::abs(got - want) / std::abs(want); }

/// Maximum penetration of the undamped impact: K D^(e+1)/(e+1) = m v²/2.
double undamped_depth(double K, double e, double m, double v) {
  return std::pow((e + 1.0) * m * v * v / (2.0 * K), 1.0 / (e + 1.0));
}

/// Bisection for a sign change of f on [a, b].
double bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (a + b);
    const double fm = f(mid);
    if ((fm > 0.0) == (fa > 0.0)) {
      a = mid;
      fa = fm;
    } else {
      b = mid;
    }
  }
  return 0.5 * (a + b);
}

bool all_finite(const ImpactTransient& tr) {
  bool ok = std::isfinite(tr.duration_s) && std::isfinite(tr.peak_force_N) &&
            std::isfinite(tr.impulse_Ns) && std::isfinite(tr.rebound_speed_mps) &&
            std::isfinite(tr.max_penetration_m) && std::isfinite(tr.time_of_peak_s);
  for (std::size_t i = 0; i < tr.t_s.size(); ++i)
    ok = ok && std::isfinite(tr.t_s[i]) && std::isfinite(tr.force_N[i]) &&
         std::isfinite(tr.penetration_m[i]) && tr.force_N[i] >= 0.0;
  return ok;
}

}  // namespace

TEST_CASE("impact_step: endpoints, midpoint and the cubic in between", "[contact]") {
  CHECK(impact_step(0.0, 0.0, 0.0, 1.0, 1.0) == 0.0);
  CHECK(impact_step(1.0, 0.0, 0.0, 1.0, 1.0) == 1.0);
  CHECK(impact_step(0.5, 0.0, 0.0, 1.0, 1.0) == Approx(0.5).margin(1e-15));
  // Δ = 0.25: Δ²(3 − 2Δ) = 0.0625 · 2.5 = 0.15625.
  CHECK(impact_step(0.25, 0.0, 0.0, 1.0, 1.0) == Approx(0.15625).margin(1e-15));
  // Outside the interval: the end values.
  CHECK(impact_step(-3.0, 0.0, 0.0, 1.0, 1.0) == 0.0);
  CHECK(impact_step(7.0, 0.0, 0.0, 1.0, 1.0) == 1.0);
  // General end values: from (1, 5) to (3, 9), Δ = 0.5 → 5 + 4 · 0.5 = 7.
  CHECK(impact_step(2.0, 1.0, 5.0, 3.0, 9.0) == Approx(7.0).margin(1e-14));
  CHECK(impact_step(0.0, 1.0, 5.0, 3.0, 9.0) == 5.0);
  CHECK(impact_step(4.0, 1.0, 5.0, 3.0, 9.0) == 9.0);
  // Derivative: 6Δ(1 − Δ)/(x1 − x0) · (h1 − h0); at Δ = 0.5 of [1, 3] with rise 4: 6·0.25/2·4 = 3.
  CHECK(impact_step_derivative(2.0, 1.0, 5.0, 3.0, 9.0) == Approx(3.0).margin(1e-14));
  CHECK(impact_step_derivative(1.0, 1.0, 5.0, 3.0, 9.0) == 0.0);
  CHECK(impact_step_derivative(3.0, 1.0, 5.0, 3.0, 9.0) == 0.0);
  // Derivative against a central difference.
  const double x = 1.3, h = 1e-6;
  const double fd =
      (impact_step(x + h, 1.0, 5.0, 3.0, 9.0) - impact_step(x - h, 1.0, 5.0, 3.0, 9.0)) / (2 * h);
  CHECK(impact_step_derivative(x, 1.0, 5.0, 3.0, 9.0) == Approx(fd).epsilon(1e-6));
}

TEST_CASE("impact_normal_force: hand-checked points of eq. 7", "[contact]") {
  const ContactParams c = paper_contact();  // K = 1e5, e = 2.2, C = 10, p = 1e-5
  const double K = 1e5, e = 2.2, C = 10.0, p = 1e-5;

  SECTION("no force out of contact, whatever the rate") {
    CHECK(impact_normal_force(c, 0.0, 1.0) == 0.0);
    CHECK(impact_normal_force(c, -1e-3, 1.0) == 0.0);
    CHECK(impact_normal_force(c, -1e-3, -1.0) == 0.0);
  }
  SECTION("half damping at δ = p/2") {
    const double delta = p / 2, rate = 0.1;
    const double want = K * std::pow(delta, e) + C * 0.5 * rate;
    CHECK(impact_normal_force(c, delta, rate) == Approx(want).epsilon(1e-14));
  }
  SECTION("full damping from δ = p on") {
    for (double delta : {p, 2 * p, 1e-3}) {
      const double rate = 0.07;
      const double want = K * std::pow(delta, e) + C * rate;
      CHECK(impact_normal_force(c, delta, rate) == Approx(want).epsilon(1e-14));
    }
  }
  SECTION("no sticky pull on a fast rebound: the clip gives 0") {
    // K δ^e = 1e5 · (1e-4)^2.2 ≈ 1.6e-4 N, C δ̇ = −10 N.
    const double delta = 1e-4, rate = -1.0;
    REQUIRE(K * std::pow(delta, e) + C * rate < 0.0);
    CHECK(impact_normal_force(c, delta, rate) == 0.0);
  }
  SECTION("a slow rebound keeps a reduced positive force") {
    // K δ^e = 1e5 · (1e-3)^2.2 = 10^-1.6 ≈ 0.0251 N; C δ̇ = −0.01 N.
    const double delta = 1e-3, rate = -1e-3;
    const double want = std::pow(10.0, -1.6) - 0.01;
    CHECK(impact_normal_force(c, delta, rate) == Approx(want).epsilon(1e-12));
  }
}

TEST_CASE("static_penetration inverts the spring law", "[contact]") {
  const ContactParams c = paper_contact();
  CHECK(static_penetration(c, 0.0) == 0.0);
  CHECK(static_penetration(c, -5.0) == 0.0);
  for (double F : {0.1, 21.9, 300.0}) {
    const double delta = static_penetration(c, F);
    CHECK(delta == Approx(std::pow(F / 1e5, 1.0 / 2.2)).epsilon(1e-14));
    CHECK(impact_normal_force(c, delta, 0.0) == Approx(F).epsilon(1e-12));
  }
}

TEST_CASE("simulate_touchdown: no approach, no impact", "[contact]") {
  for (double v : {0.0, -0.2}) {
    const ImpactTransient tr = simulate_touchdown(paper_contact(), 0.3, v);
    CHECK_FALSE(tr.occurred);
    CHECK_FALSE(tr.truncated);
    CHECK(tr.peak_force_N == 0.0);
    CHECK(tr.impulse_Ns == 0.0);
    CHECK(tr.duration_s == 0.0);
    CHECK(transient_force_at(tr, 0.0) == 0.0);
    CHECK(transient_force_at(tr, 1e-3) == 0.0);
    CHECK(transient_penetration_at(tr, 1e-3) == 0.0);
  }
}

TEST_CASE("simulate_touchdown: momentum and energy balance of the paper's contact", "[contact]") {
  const ContactParams c = paper_contact();
  for (double m : {0.05, 0.3, 2.0}) {
    for (double v : {0.02, 0.05, 0.3}) {
      CAPTURE(m, v);
      const ImpactTransient tr = simulate_touchdown(c, m, v);
      REQUIRE(tr.occurred);
      REQUIRE_FALSE(tr.truncated);
      REQUIRE(all_finite(tr));
      // Impulse (integrated force) = change of momentum m (v_in + v_out).
      CHECK(rel_err(tr.impulse_Ns, m * (v + tr.rebound_speed_mps)) < 1e-6);
      // The damper only removes energy; the foot does leave.
      CHECK(tr.rebound_speed_mps <= v);
      CHECK(tr.rebound_speed_mps > 0.0);
      // Trapezoidal quadrature of the dense samples, a third computation of the impulse.
      double J = 0.0;
      for (std::size_t i = 1; i < tr.t_s.size(); ++i)
        J += 0.5 * (tr.force_N[i] + tr.force_N[i - 1]) * (tr.t_s[i] - tr.t_s[i - 1]);
      CHECK(rel_err(J, tr.impulse_Ns) < 1e-3);
      // Samples: start at touchdown with zero force, end at the duration with zero force.
      CHECK(tr.t_s.front() == 0.0);
      CHECK(tr.force_N.front() == 0.0);
      CHECK(tr.t_s.back() == tr.duration_s);
      CHECK(tr.force_N.back() == 0.0);
      // The located peak is the largest sample and sits at its own sample.
      double largest = 0.0;
      for (double f : tr.force_N) largest = std::max(largest, f);
      CHECK(tr.peak_force_N == Approx(largest).epsilon(1e-12));
      CHECK(transient_force_at(tr, tr.time_of_peak_s) == Approx(tr.peak_force_N).epsilon(1e-12));
      CHECK(transient_force_at(tr, -1e-6) == 0.0);
      CHECK(transient_force_at(tr, tr.duration_s * 1.01) == 0.0);
    }
  }
}

TEST_CASE("simulate_touchdown: undamped impact against the closed form", "[contact]") {
  // With C_max = 0 the impact is elastic: F_peak = K^(1/(e+1)) ((e+1) m v²/2)^(e/(e+1)),
  // maximum penetration D, rebound speed = approach speed, and the contact lasts
  // 2 (D/v) ∫₀¹ du/√(1 − u^(e+1)) = 2 (D/v) √π Γ(1 + 1/n)/Γ(1/2 + 1/n), n = e + 1.
  for (double e : {1.0, 1.5, 2.2, 3.0}) {
    for (double K : {1e4, 1e5, 1e8}) {
      const double m = 0.25, v = 0.1;
      CAPTURE(e, K);
      const ImpactTransient tr = simulate_touchdown(test::contact_params(K, e, 0.0, 1e-5), m, v);
      REQUIRE(tr.occurred);
      REQUIRE_FALSE(tr.truncated);
      const double n = e + 1.0;
      const double F_peak = std::pow(K, 1.0 / n) * std::pow(n * m * v * v / 2.0, e / n);
      const double D = undamped_depth(K, e, m, v);
      const double T =
          2.0 * (D / v) * std::sqrt(M_PI) * std::tgamma(1.0 + 1.0 / n) / std::tgamma(0.5 + 1.0 / n);
      CHECK(rel_err(tr.peak_force_N, F_peak) < 1e-6);
      CHECK(rel_err(tr.max_penetration_m, D) < 1e-6);
      CHECK(rel_err(tr.rebound_speed_mps, v) < 1e-6);
      CHECK(rel_err(tr.impulse_Ns, 2.0 * m * v) < 1e-6);
      CHECK(rel_err(tr.duration_s, T) < 1e-6);
      CHECK(rel_err(tr.time_of_peak_s, T / 2.0) < 1e-6);
    }
  }
}

TEST_CASE("simulate_touchdown: the linear spring against the harmonic oscillator", "[contact]") {
  // e = 1, C = 0: F(t) = m v ω sin(ω t), ω = √(K/m), duration π/ω. Checks the dense output
  // and linear interpolation on an arbitrary grid.
  const double K = 2e4, m = 0.5, v = 0.2;
  const double w = std::sqrt(K / m);
  const ImpactTransient tr = simulate_touchdown(test::contact_params(K, 1.0, 0.0, 1e-6), m, v);
  REQUIRE_FALSE(tr.truncated);
  CHECK(rel_err(tr.duration_s, M_PI / w) < 1e-8);
  const double F_peak = m * v * w;
  double worst = 0.0;
  for (int i = 0; i <= 997; ++i) {
    const double t = tr.duration_s * i / 997.0;
    worst = std::max(worst, std::abs(transient_force_at(tr, t) - F_peak * std::sin(w * t)));
    const double delta = (v / w) * std::sin(w * t);
    CHECK(transient_penetration_at(tr, t) == Approx(delta).margin(1e-4 * v / w));
  }
  CHECK(worst < 1e-3 * F_peak);
}

TEST_CASE("simulate_touchdown: damped linear contact against the analytic solution", "[contact]") {
  // e = 1 and a full damping depth p far below the penetration: m δ̈ + C δ̇ + K δ = 0 with
  // δ(t) = (v/ω_d) e^(−ζωt) sin(ω_d t). The transient ends where K δ + C δ̇ returns to 0.
  const double K = 1e4, m = 0.1, C = 10.0, v = 0.5, p = 1e-9;
  const double w = std::sqrt(K / m), zeta = C / (2.0 * std::sqrt(K * m));
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  auto delta = [&](double t) { return (v / wd) * std::exp(-zeta * w * t) * std::sin(wd * t); };
  auto rate = [&](double t) {
    return v * std::exp(-zeta * w * t) * (std::cos(wd * t) - (zeta * w / wd) * std::sin(wd * t));
  };
  auto force = [&](double t) { return K * delta(t) + C * rate(t); };
  auto force_rate = [&](double t) {  // dF/dt = K δ̇ + C δ̈, δ̈ = −(K δ + C δ̇)/m
    return K * rate(t) - C * force(t) / m;
  };
  // F > 0 right after touchdown and < 0 at the end of the first half period.
  const double t_end = bisect(force, 1e-9, M_PI / wd);
  const double t_peak = bisect(force_rate, 0.0, t_end);
  const ImpactTransient tr = simulate_touchdown(test::contact_params(K, 1.0, C, p), m, v);
  REQUIRE_FALSE(tr.truncated);
  CHECK(rel_err(tr.duration_s, t_end) < 1e-6);
  CHECK(rel_err(tr.rebound_speed_mps, -rate(t_end)) < 1e-6);
  CHECK(rel_err(tr.peak_force_N, force(t_peak)) < 1e-6);
  CHECK(rel_err(tr.time_of_peak_s, t_peak) < 1e-5);
  CHECK(rel_err(tr.impulse_Ns, m * (v - rate(t_end))) < 1e-6);
  // It ends by the clip, with the foot still below the surface.
  CHECK(tr.penetration_m.back() == Approx(delta(t_end)).epsilon(1e-5));
  CHECK(tr.penetration_m.back() > 0.0);
}

TEST_CASE("simulate_touchdown: hard and extreme parameters stay finite and terminate",
          "[contact]") {
  SECTION("stiff contact, tiny damping depth, fast approach") {
    for (double e : {1.0, 3.0}) {
      for (double m : {0.01, 10.0}) {
        for (double C : {0.0, 10.0}) {
          CAPTURE(e, m, C);
          const ImpactTransient tr =
              simulate_touchdown(test::contact_params(1e9, e, C, 1e-9), m, 1.0);
          REQUIRE(tr.occurred);
          CHECK_FALSE(tr.truncated);
          CHECK(all_finite(tr));
          CHECK(tr.peak_force_N > 0.0);
          CHECK(rel_err(tr.impulse_Ns, m * (1.0 + tr.rebound_speed_mps)) < 1e-6);
          CHECK(tr.rebound_speed_mps <= 1.0 * (1.0 + 1e-9));
        }
      }
    }
  }
  SECTION("corners of the supported range") {
    for (double K : {1e3, 1e9})
      for (double e : {1.0, 3.0})
        for (double p : {1e-9, 1e-2})
          for (double v : {1e-3, 1.0})
            for (double m : {0.01, 10.0})
              for (double C : {0.0, 10.0, 1e3}) {
                CAPTURE(K, e, p, v, m, C);
                const ImpactTransient tr =
                    simulate_touchdown(test::contact_params(K, e, C, p), m, v);
                CHECK(all_finite(tr));
                CHECK(tr.steps <= ImpactOptions{}.max_steps);
                CHECK(tr.duration_s <= ImpactOptions{}.max_duration_s * (1.0 + 1e-12));
                if (!tr.truncated)
                  CHECK(rel_err(tr.impulse_Ns, m * (v + tr.rebound_speed_mps)) < 1e-6);
              }
  }
  SECTION("the guards flag the result instead of hanging") {
    ImpactOptions few_steps;
    few_steps.max_steps = 10;
    const ImpactTransient a = simulate_touchdown(paper_contact(), 0.3, 0.05, few_steps);
    CHECK(a.truncated);
    CHECK(a.steps == 10);
    CHECK(all_finite(a));
    CHECK_FALSE(a.message.empty());
    ImpactOptions short_time;
    short_time.max_duration_s = 1e-4;
    const ImpactTransient b = simulate_touchdown(paper_contact(), 0.3, 0.05, short_time);
    CHECK(b.truncated);
    CHECK(b.duration_s == Approx(1e-4).epsilon(1e-9));
    CHECK(all_finite(b));
  }
}

TEST_CASE("simulate_touchdown: invalid input is rejected at the boundary", "[contact]") {
  CHECK_THROWS_AS(simulate_touchdown(test::contact_params(0.0, 2.2, 10, 1e-5), 0.3, 0.05),
                  ConfigError);
  CHECK_THROWS_AS(simulate_touchdown(test::contact_params(1e5, 0.5, 10, 1e-5), 0.3, 0.05),
                  ConfigError);
  CHECK_THROWS_AS(simulate_touchdown(test::contact_params(1e5, 2.2, -1, 1e-5), 0.3, 0.05),
                  ConfigError);
  CHECK_THROWS_AS(simulate_touchdown(test::contact_params(1e5, 2.2, 10, 0.0), 0.3, 0.05),
                  ConfigError);
  CHECK_THROWS_AS(simulate_touchdown(paper_contact(), 0.0, 0.05), SolverError);
  CHECK_THROWS_AS(simulate_touchdown(paper_contact(), std::nan(""), 0.05), SolverError);
  CHECK_THROWS_AS(simulate_touchdown(paper_contact(), 0.3, std::numeric_limits<double>::infinity()),
                  SolverError);
}
