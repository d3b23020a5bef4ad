// Hard cases (docs/validation/hard-cases.md) of contact and sampling: each runs the real pipeline
// (or the touchdown ODE alone) on a scene at the edge of what the model can do and checks exactly
// what comes out, and the numbers against a second computation made here:
//  - stiff contact: momentum balance of every touchdown, the closed-form undamped impact,
//    the sampled impact peak against the ODE's located peak, and the trunk's vertical
//    balance (the other feet cannot pull) against the flags;
//  - sample steps 1e-5 s and 0.5 s: the ODE's peak and impulse, the default grid's energy.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/impact.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/hard_case_checks.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/planning/terrain.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
using namespace hard;

TEST_CASE("hard: stiff touchdown ODE, K to 1e9, e 1 to 3, p to 1e-9 m, v to 1 m/s",
          "[hard][contact]") {
  // The corners of the range (and C_max from 0 to the paper's 1e4 N s/m), for a foot of
  // the paper robot's effective mass (~0.08 kg).
  const double m = 0.08;
  int n = 0;
  for (double K : {1e5, 1e9})
    for (double e : {1.0, 2.2, 3.0})
      for (double p : {1e-5, 1e-9})
        for (double v : {0.05, 1.0})
          for (double C : {0.0, 10.0, 1e4}) {
            const ContactParams c = test::contact_params(K, e, C, p);
            INFO("K " << K << " e " << e << " p " << p << " v " << v << " C " << C);
            const ImpactTransient tr = simulate_touchdown(c, m, v);
            ++n;
            REQUIRE(tr.occurred);
            CHECK_FALSE(tr.truncated);
            CHECK(contains(tr.message, "ended:"));
            CHECK(std::isfinite(tr.peak_force_N));
            CHECK(std::isfinite(tr.impulse_Ns));
            CHECK(std::isfinite(tr.duration_s));
            CHECK(std::isfinite(tr.max_penetration_m));
            CHECK(tr.duration_s > 0.0);
            CHECK(tr.steps < 5000);
            bool samples_ok = tr.t_s.size() == tr.force_N.size() && tr.t_s.size() >= 8;
            for (std::size_t i = 0; i < tr.t_s.size(); ++i)
              samples_ok = samples_ok && std::isfinite(tr.force_N[i]) && tr.force_N[i] >= 0.0 &&
                           std::isfinite(tr.penetration_m[i]) &&
                           (i == 0 || tr.t_s[i] > tr.t_s[i - 1]);
            CHECK(samples_ok);
            // Momentum: the impulse turns the approach speed into the rebound speed.
            CHECK(tr.impulse_Ns == Approx(m * (v + tr.rebound_speed_mps)).epsilon(1e-9));
            // Energy: the damper only takes energy away.
            CHECK(tr.rebound_speed_mps <= v * (1.0 + 1e-8));
            CHECK(tr.rebound_speed_mps >= 0.0);
            if (C == 0.0) {
              // Undamped: closed form. K D^(e+1)/(e+1) = m v²/2, peak K D^e, duration
              // 2 (D/v) ∫₀¹ du/√(1 − u^(e+1)) = (D/v) 2√π Γ(1+1/(e+1)) / Γ(1/2+1/(e+1)).
              const double D = std::pow((e + 1.0) * m * v * v / (2.0 * K), 1.0 / (e + 1.0));
              const double n1 = e + 1.0;
              const double tau =
                  2.0 * std::sqrt(M_PI) * std::tgamma(1.0 + 1.0 / n1) / std::tgamma(0.5 + 1.0 / n1);
              CHECK(tr.peak_force_N == Approx(K * std::pow(D, e)).epsilon(1e-8));
              CHECK(tr.max_penetration_m == Approx(D).epsilon(1e-8));
              CHECK(tr.duration_s == Approx(tau * D / v).epsilon(1e-7));
              CHECK(tr.rebound_speed_mps == Approx(v).epsilon(1e-8));
            }
          }
  CHECK(n == 72);
}

TEST_CASE("hard: stiff contact through the pipeline, K 1e9, p 1e-9 m, touchdown at 1 m/s",
          "[hard][contact]") {
  struct Case {
    const char* K;
    const char* e;
  };
  for (const Case& c : {Case{"1e9", "1.0"}, Case{"1e9", "3.0"}, Case{"1e5", "1.0"}}) {
    INFO("K " << c.K << " e " << c.e << ", p 1e-9 m, touchdown speed 1 m/s");
    const Scene scene = paper_with({{"contact.stiffness", c.K},
                                    {"contact.exponent", c.e},
                                    {"contact.full_damping_depth", "1e-9"},
                                    {"gait.touchdown_speed", "1.0"}});
    const PreparedScene prep = prepare_scene(scene);
    const RunResult r = run_scene(scene);
    check_run_finite(r);
    CHECK(count_status(r, SolverStatus::kFailed) == 0);
    REQUIRE(prep.touchdowns.size() == r.dyn.impacts.size());
    REQUIRE(r.dyn.impacts.size() == 18);
    const double mg = r.total_mass_kg * kGravity;
    for (const Touchdown& td : prep.touchdowns) {
      INFO("touchdown of " << leg_name(td.leg) << " at " << td.t_s << " s");
      const ImpactTransient& tr = td.transient;
      REQUIRE(tr.occurred);
      CHECK_FALSE(tr.truncated);
      CHECK(td.approach_speed_mps == Approx(1.0).epsilon(1e-9));
      CHECK(tr.impulse_Ns ==
            Approx(td.effective_mass_kg * (td.approach_speed_mps + tr.rebound_speed_mps))
                .epsilon(1e-9));
      CHECK(tr.rebound_speed_mps <= td.approach_speed_mps * (1.0 + 1e-8));
      // The adaptive grid samples the located peak: the stored normal force there is it.
      const int i_peak = sample_at(r, td.t_s + tr.time_of_peak_s);
      REQUIRE(i_peak >= 0);
      CHECK(r.kin.contact_phase(i_peak, td.leg) == static_cast<std::int8_t>(ContactPhase::kImpact));
      CHECK(normal_force(r, i_peak, td.leg) == Approx(tr.peak_force_N).epsilon(1e-6));
    }
    // Where the impact forces alone lift more than twice the weight, no support foot can
    // pull back: the trunk's vertical row must give way, and the sample says so.
    int overloaded = 0;
    for (int i = 0; i < r.kin.samples(); ++i) {
      double impact_z = 0.0;
      for (int l = 0; l < r.kin.contact_phase.cols(); ++l)
        if (r.kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kImpact))
          impact_z += normal_force(r, i, l);
      if (impact_z <= 2.0 * mg) continue;
      ++overloaded;
      INFO("t = " << r.kin.time_s[i] << " s: impact forces " << impact_z
                  << " N: " << r.dyn.solver_messages[i]);
      CHECK(r.dyn.solver_status[i] == SolverStatus::kRelaxed);
      CHECK(contains(r.dyn.solver_messages[i], "trunk force z"));
      CHECK(contains(r.dyn.solver_messages[i], "(impact "));
    }
    CHECK(overloaded > 18);
  }
}

TEST_CASE("hard: a soft, slow touchdown outlasts the 1 s guard: truncated, finite, flagged",
          "[hard][contact]") {
  // K = 1e5 N/m³ with no damping at 1 mm/s: the undamped contact would last ~3 s.
  const Scene scene = paper_with({{"contact.stiffness", "1e5"},
                                  {"contact.exponent", "3.0"},
                                  {"contact.damping_max", "0"},
                                  {"gait.touchdown_speed", "0.001"}});
  const PreparedScene prep = prepare_scene(scene);
  REQUIRE(prep.touchdowns.size() == 18);
  for (const Touchdown& td : prep.touchdowns) {
    INFO("touchdown of " << leg_name(td.leg) << " at " << td.t_s << " s: " << td.transient.message);
    CHECK(td.transient.truncated);
    CHECK(contains(td.transient.message, "stopped by the duration guard (max_duration_s = 1 s)"));
    CHECK(td.transient.duration_s == Approx(1.0).epsilon(1e-9));
    // Still a consistent partial transient: momentum balance up to the stop.
    CHECK(td.transient.impulse_Ns ==
          Approx(td.effective_mass_kg * (td.approach_speed_mps + td.transient.rebound_speed_mps))
              .epsilon(1e-9));
  }
  const RunResult r = run_scene(scene);
  check_run_finite(r);
  REQUIRE(r.dyn.impacts.size() == 18);
  for (const ImpactRecord& im : r.dyn.impacts) CHECK(im.duration_s == Approx(1.0).epsilon(1e-9));
  // A foot in its transient carries only the (sub-millinewton) transient force; while a
  // whole tripod is in it and the other swings, the trunk's weight row gives way, flagged.
  const double mg = r.total_mass_kg * kGravity;
  int unsupported = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    if (legs_in_phase(r, i, ContactPhase::kSupport) > 0 ||
        legs_in_phase(r, i, ContactPhase::kImpact) == 0)
      continue;
    ++unsupported;
    INFO("t = " << r.kin.time_s[i] << " s: " << r.dyn.solver_messages[i]);
    CHECK(r.dyn.solver_status[i] == SolverStatus::kRelaxed);
    CHECK(violation_of(r.dyn.solver_messages[i], "trunk force z") == Approx(mg).epsilon(0.05));
  }
  CHECK(unsupported > 100);
}

TEST_CASE("hard: sample step 1e-5 s resolves every touchdown transient", "[hard][grid]") {
  // One gait cycle at 0.3 m/s with the paper's 0.8 s ramps (1.65 s, 165 000 uniform
  // samples, ~3 s of run time).
  const std::vector<Override> shorter = {{"motion.cycle_durations", "null"},
                                         {"motion.cycles", "1"},
                                         {"motion.peak_speed", "0.3"},
                                         {"motion.ramp_duration", "0.8"}};
  std::vector<Override> fine = shorter;
  fine.insert(
      fine.end(),
      {{"output.grid", "uniform"}, {"output.sample_step", "1e-5"}, {"output.event_step", "1e-5"}});
  const Scene scene = paper_with(fine);
  const PreparedScene prep = prepare_scene(scene);
  const RunResult r = run_scene(scene);
  check_run_finite(r);
  // Uniform 1e-5 s steps to the end of the motion, extended past it by the last touchdown's
  // transient (the last tripod touches down as the motion ends).
  const int T = r.kin.samples();
  REQUIRE(T == static_cast<int>(prep.grid.size()));
  const double t_end = r.kin.time_s.back();
  CHECK(t_end > prep.plan.trunk.duration_s());
  CHECK(T == Approx(t_end / 1e-5).margin(2));
  REQUIRE(prep.touchdowns.size() == 6);
  double worst_peak = 0.0;
  for (const Touchdown& td : prep.touchdowns) {
    const ImpactTransient& tr = td.transient;
    INFO("touchdown of " << leg_name(td.leg) << " at " << td.t_s << " s, " << tr.duration_s
                         << " s long");
    REQUIRE(tr.occurred);
    const auto first = std::lower_bound(r.kin.time_s.begin(), r.kin.time_s.end(), td.t_s);
    double peak = 0.0, impulse = 0.0;
    int inside = 0;
    for (auto it = first; it != r.kin.time_s.end() && *it < td.t_s + tr.duration_s; ++it) {
      const int i = static_cast<int>(it - r.kin.time_s.begin());
      CHECK(r.kin.contact_phase(i, td.leg) == static_cast<std::int8_t>(ContactPhase::kImpact));
      peak = std::max(peak, normal_force(r, i, td.leg));
      ++inside;
    }
    // Impulse of the sampled force, trapezoids from touchdown (F = 0) to the end (F = 0).
    std::vector<double> t = {td.t_s}, f = {0.0};
    for (auto it = first; it != r.kin.time_s.end() && *it < td.t_s + tr.duration_s; ++it) {
      t.push_back(*it);
      f.push_back(normal_force(r, static_cast<int>(it - r.kin.time_s.begin()), td.leg));
    }
    t.push_back(td.t_s + tr.duration_s);
    f.push_back(0.0);
    for (std::size_t k = 0; k + 1 < t.size(); ++k)
      impulse += 0.5 * (f[k] + f[k + 1]) * (t[k + 1] - t[k]);
    CHECK(inside >= static_cast<int>(tr.duration_s / 1e-5) - 1);
    // Some sample lies within half a step of the located peak, and the force is unimodal:
    // the sampled peak is at least the lower of the two forces half a step either side.
    const double half = 0.5e-5;
    const double bound = std::min(transient_force_at(tr, tr.time_of_peak_s - half),
                                  transient_force_at(tr, tr.time_of_peak_s + half));
    CHECK(peak <= tr.peak_force_N * (1.0 + 1e-9));
    CHECK(peak >= bound * (1.0 - 1e-9));
    CHECK(peak == Approx(tr.peak_force_N).epsilon(0.015));
    worst_peak = std::max(worst_peak, 1.0 - peak / tr.peak_force_N);
    CHECK(impulse == Approx(tr.impulse_Ns).epsilon(0.01));
  }
  // Flags only inside the transients (the impact tripod cannot carry the trunk).
  int relaxed_outside = 0;
  for (int i = 0; i < T; ++i)
    relaxed_outside += r.dyn.solver_status[i] != SolverStatus::kOptimal &&
                       legs_in_phase(r, i, ContactPhase::kImpact) == 0;
  CHECK(relaxed_outside == 0);
  INFO("largest shortfall of a sampled peak: " << 100.0 * worst_peak << " %");
  CHECK(worst_peak < 0.015);
  // The default grid of the same motion gives the same energy to 1%.
  const RunResult coarse = run_scene(paper_with(shorter));
  CHECK(r.dyn.energy_total_J == Approx(coarse.dyn.energy_total_J).epsilon(0.01));
}

TEST_CASE("hard: sample step 0.5 s", "[hard][grid]") {
  const RunResult ref = run_scene(paper_with({}));
  SECTION("adaptive grid: still refined at every event, energy within 2.5% of the default grid's") {
    const RunResult r = run_scene(paper_with({{"output.sample_step", "0.5"}}));
    check_run_finite(r);
    CHECK(r.dyn.impacts.size() == 18);
    int impact_samples = 0;
    for (int i = 0; i < r.kin.samples(); ++i)
      impact_samples += legs_in_phase(r, i, ContactPhase::kImpact) > 0;
    CHECK(impact_samples > 18 * paper_with({}).output.impact_samples);
    // Between events the power is sampled up to 0.5 s apart: the smooth part of the
    // integral loses ~2%.
    CHECK(r.dyn.energy_total_J == Approx(ref.dyn.energy_total_J).epsilon(0.025));
  }
  SECTION(
      "uniform grid: 19 samples, no transient sampled, energy within 5% of the default grid's") {
    const RunResult r =
        run_scene(paper_with({{"output.sample_step", "0.5"}, {"output.grid", "uniform"}}));
    check_run_finite(r);
    CHECK(r.kin.samples() == 19);
    // The transients (0.46 ms) fall between samples: no sample in impact, none relaxed;
    // the 18 touchdowns are still in /impacts with their peaks.
    int impact_samples = 0;
    for (int i = 0; i < r.kin.samples(); ++i)
      impact_samples += legs_in_phase(r, i, ContactPhase::kImpact) > 0;
    CHECK(impact_samples == 0);
    CHECK(count_status(r, SolverStatus::kRelaxed) == 0);
    REQUIRE(r.dyn.impacts.size() == ref.dyn.impacts.size());
    for (std::size_t k = 0; k < r.dyn.impacts.size(); ++k)
      CHECK(r.dyn.impacts[k].peak_force_N == ref.dyn.impacts[k].peak_force_N);
    CHECK(r.dyn.energy_total_J == Approx(ref.dyn.energy_total_J).epsilon(0.05));
  }
}

}  // namespace hexdyn
