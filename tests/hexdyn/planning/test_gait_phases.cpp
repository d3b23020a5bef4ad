// Lift-off phases (gait.hpp): the wave gait for legs given by side and rank, checked for six
// legs bit for bit against the six expressions the hexapod's gait was written with, and for
// two, four and eight legs against the swings counted on a dense sampling of the cycle; and
// gait.phases, whose swings are where the phases put them.
#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/gait_cases.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/gait.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {
namespace {

double frac(double x) { return x - std::floor(x); }

/// The hexapod's wave gait as six expressions, legs L1 … L6 (FL, FR, ML, MR, RL, RR).
std::array<double, 6> six_leg_literals(double beta) {
  const double s = 1.0 - beta;
  return {frac(0.5 + 2.0 * s), frac(2.0 * s), frac(0.5 + s), frac(s), 0.5, 0.0};
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

using test::paired_legs;
using test::swinging;

/// Cycle phases spread over one cycle, none on a multiple of 1/48 (where a swing may begin or
/// end for the duty factors below).
std::vector<double> sample_phases() {
  std::vector<double> tau;
  for (int i = 0; i < 4801; ++i) tau.push_back((i + 0.37) / 4801.0);
  return tau;
}

/// How many times each leg lifts off over one cycle of `tau` samples (stance → swing,
/// cyclically).
std::vector<int> liftoffs(const std::vector<double>& phi, double beta) {
  const std::vector<double> tau = sample_phases();
  std::vector<int> n(phi.size(), 0);
  for (std::size_t leg = 0; leg < phi.size(); ++leg)
    for (std::size_t i = 0; i < tau.size(); ++i) {
      const double before = i == 0 ? tau.back() - 1.0 : tau[i - 1];
      n[leg] += !swinging(phi[leg], beta, before) && swinging(phi[leg], beta, tau[i]);
    }
  return n;
}

/// The least and the largest number of legs in swing over the sampled cycle, in all and on
/// one side.
struct SwingCounts {
  int least = 1 << 20, most = 0, most_one_side = 0;
};
SwingCounts swing_counts(const std::vector<GaitLeg>& legs, const std::vector<double>& phi,
                         double beta) {
  SwingCounts c;
  for (double tau : sample_phases()) {
    int all = 0, left = 0, right = 0;
    for (std::size_t leg = 0; leg < legs.size(); ++leg) {
      if (!swinging(phi[leg], beta, tau)) continue;
      ++all;
      ++(legs[leg].side == LegSide::kLeft ? left : right);
    }
    c.least = std::min(c.least, all);
    c.most = std::max(c.most, all);
    c.most_one_side = std::max({c.most_one_side, left, right});
  }
  return c;
}

TEST_CASE("gait phases: a hexapod model's gait legs are the conventions' six", "[gait][phases]") {
  const std::vector<GaitLeg> expected = test::hexapod_legs();
  for (const std::string scene : {"/configs/paper.yaml", "/configs/robots/kraby_stairs.yaml",
                                  "/configs/robots/pexod_stairs.yaml"}) {
    INFO(scene);
    const std::vector<GaitLeg> legs =
        gait_legs(build_robot_model(load_scene(std::string(HEXDYN_SOURCE_DIR) + scene).robot));
    REQUIRE(legs.size() == expected.size());
    for (std::size_t leg = 0; leg < legs.size(); ++leg) {
      CHECK(legs[leg].side == expected[leg].side);
      CHECK(legs[leg].rank == expected[leg].rank);
    }
  }
}

TEST_CASE("gait phases: six legs give the six expressions' bits for every duty factor",
          "[gait][phases]") {
  const std::vector<GaitLeg> legs = test::hexapod_legs();
  std::vector<double> betas;
  for (int i = 0; i < 10000; ++i) betas.push_back(0.5 + 0.5 * i / 10000.0);  // [1/2, 1)
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> uniform(0.5, 1.0);
  for (int i = 0; i < 10000; ++i) betas.push_back(uniform(rng));
  // The configs' values, p/q as the scene reader takes them, and the range's ends.
  for (double b : {0.5, 2.0 / 3.0, 0.75, 5.0 / 6.0, 7.0 / 8.0, 0.6, 0.55, 0.9, 0.99})
    betas.push_back(b);
  betas.push_back(std::nextafter(1.0, 0.0));
  betas.push_back(std::nextafter(0.5, 1.0));
  int checked = 0;
  for (double beta : betas) {
    const std::vector<double> general = wave_gait_phases(legs, beta);
    const std::array<double, 6> literal = six_leg_literals(beta);
    REQUIRE(general.size() == literal.size());
    for (int leg = 0; leg < static_cast<int>(literal.size()); ++leg) {
      INFO("beta " << beta << " leg " << leg_name(leg));
      REQUIRE(general[leg] == literal[leg]);
      REQUIRE(same_bits(general[leg], literal[leg]));
      ++checked;
    }
  }
  CHECK(checked == 6 * 20011);
}

TEST_CASE("gait phases: a quadruped at 3/4 swings one leg at a time, each once a cycle",
          "[gait][phases]") {
  const std::vector<GaitLeg> legs = paired_legs(2);
  const std::vector<double> phi = wave_gait_phases(legs, 0.75);
  const SwingCounts c = swing_counts(legs, phi, 0.75);
  CHECK(c.least == 1);
  CHECK(c.most == 1);
  for (int n : liftoffs(phi, 0.75)) CHECK(n == 1);
  // The crawl: rear right, front right, rear left, front left.
  CHECK(phi == std::vector<double>{0.75, 0.25, 0.5, 0.0});
}

TEST_CASE("gait phases: an octopod's wave keeps one leg of a side in the air at most",
          "[gait][phases]") {
  const std::vector<GaitLeg> legs = paired_legs(4);
  for (double beta : {0.75, 7.0 / 8.0}) {
    INFO("beta " << beta);
    const std::vector<double> phi = wave_gait_phases(legs, beta);
    const SwingCounts c = swing_counts(legs, phi, beta);
    // 8 (1 − β) legs in the air at every instant: 2 at 3/4, 1 at 7/8.
    const int in_air = static_cast<int>(std::lround(8 * (1.0 - beta)));
    CHECK(c.least == in_air);
    CHECK(c.most == in_air);
    CHECK(c.most_one_side == 1);
    for (int n : liftoffs(phi, beta)) CHECK(n == 1);
  }
  // At β = 1/2 a side's four legs alternate: neighbours never in the air together.
  const std::vector<double> phi = wave_gait_phases(legs, 0.5);
  for (double tau : sample_phases())
    for (std::size_t a = 0; a + 2 < legs.size(); ++a)
      CHECK(!(swinging(phi[a], 0.5, tau) && swinging(phi[a + 2], 0.5, tau)));
}

TEST_CASE("gait phases: a biped alternates its legs, the sides half a cycle apart",
          "[gait][phases]") {
  const std::vector<GaitLeg> legs = paired_legs(1);
  const SwingCounts half = swing_counts(legs, wave_gait_phases(legs, 0.5), 0.5);
  CHECK(half.least == 1);
  CHECK(half.most == 1);
  const std::vector<double> phi = wave_gait_phases(legs, 0.75);
  const SwingCounts c = swing_counts(legs, phi, 0.75);
  CHECK(c.least == 0);  // double support between the swings
  CHECK(c.most == 1);
  CHECK(std::abs(frac(phi[0] - phi[1]) - 0.5) == 0.0);
  for (int n : liftoffs(phi, 0.75)) CHECK(n == 1);
}

TEST_CASE("gait phases: ranks must number each side's legs once", "[gait][phases]") {
  const std::vector<GaitLeg> twice{{LegSide::kLeft, 0}, {LegSide::kLeft, 0}};
  CHECK_THROWS_AS(wave_gait_phases(twice, 0.75), std::invalid_argument);
  const std::vector<GaitLeg> gap{{LegSide::kLeft, 0}, {LegSide::kLeft, 2}};
  CHECK_THROWS_AS(wave_gait_phases(gap, 0.75), std::invalid_argument);
  const std::vector<GaitLeg> negative{{LegSide::kRight, -1}};
  CHECK_THROWS_AS(wave_gait_phases(negative, 0.75), std::invalid_argument);
  CHECK(wave_gait_phases(std::vector<GaitLeg>{}, 0.75).empty());
}

const std::string kPaperConfig = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";

MotionPlan plan_paper(const std::vector<Override>& overrides, Scene* scene_out = nullptr) {
  const Scene scene = load_scene(kPaperConfig, overrides);
  if (scene_out) *scene_out = scene;
  return plan_motion(scene, build_robot_model(scene.robot));
}

TEST_CASE("gait phases: gait.phases puts every swing where its phase says", "[gait][phases]") {
  // Five cycles at β = 3/4; the phases on a grid of 1/8, not the wave gait's.
  const std::vector<double> phi{0.0, 0.5, 0.25, 0.75, 0.125, 0.625};
  const double beta = 0.75;
  Scene scene;
  const MotionPlan p = plan_paper({{"gait.duty_factor", "3/4"},
                                   {"motion.cycle_durations", "[3.0, 2.6, 2.6, 2.6, 3.0]"},
                                   {"gait.phases", test::phases_text(phi)}},
                                  &scene);
  REQUIRE(scene.gait.liftoff_phases == phi);
  const MotionPlan wave = plan_paper(
      {{"gait.duty_factor", "3/4"}, {"motion.cycle_durations", "[3.0, 2.6, 2.6, 2.6, 3.0]"}});
  int differ = 0;
  // Phases of the three inner cycles at odd sixteenths: never on a lift-off or a touchdown.
  for (int k = 16; k < 64; k += 2) {
    const double tau = (k + 1) / 16.0;
    const double t = p.trunk.time_at_phase(tau);
    for (int leg = 0; leg < static_cast<int>(p.gait.legs.size()); ++leg) {
      INFO("tau " << tau << " leg " << leg_name(leg));
      const bool expected = swinging(phi[leg], beta, tau);
      CHECK(leg_foot_motion(p.gait.legs[leg], t).in_swing == expected);
      differ += leg_foot_motion(wave.gait.legs[leg], t).in_swing != expected;
    }
  }
  CHECK(differ > 0);  // the wave gait's schedule is another
  // Each leg's swings last 1 − β of a cycle and begin at its phase.
  for (int leg = 0; leg < static_cast<int>(p.gait.legs.size()); ++leg)
    for (const Swing& sw : p.gait.legs[leg].swings) {
      if (sw.t_liftoff_s <= 0.0 || sw.t_touchdown_s >= p.trunk.duration_s()) continue;
      const double start = p.trunk.phase(sw.t_liftoff_s);
      const double end = p.trunk.phase(sw.t_touchdown_s);
      INFO("leg " << leg_name(leg) << " swing from phase " << start);
      CHECK(std::abs(frac(start - phi[leg] + 0.5) - 0.5) < 1e-9);
      CHECK(end - start == Approx(1.0 - beta).margin(1e-9));
    }
}

TEST_CASE("gait phases: gait.phases equal to the wave gait's plan the same swings",
          "[gait][phases]") {
  for (double beta : {0.5, 2.0 / 3.0, 0.75, 5.0 / 6.0}) {
    INFO("beta " << beta);
    const std::vector<Override> base{{"gait.duty_factor", format_number(beta, 17)}};
    std::vector<Override> given = base;
    given.push_back(
        {"gait.phases", test::phases_text(wave_gait_phases(test::hexapod_legs(), beta))});
    const MotionPlan a = plan_paper(base), b = plan_paper(given);
    CHECK(a.gait.liftoff_phase == b.gait.liftoff_phase);
    REQUIRE(a.gait.legs.size() == b.gait.legs.size());
    for (int leg = 0; leg < static_cast<int>(a.gait.legs.size()); ++leg) {
      REQUIRE(a.gait.legs[leg].swings.size() == b.gait.legs[leg].swings.size());
      for (std::size_t i = 0; i < a.gait.legs[leg].swings.size(); ++i) {
        const Swing &x = a.gait.legs[leg].swings[i], &y = b.gait.legs[leg].swings[i];
        CHECK(x.t_liftoff_s == y.t_liftoff_s);
        CHECK(x.t_touchdown_s == y.t_touchdown_s);
        CHECK(x.p_touchdown_W == y.p_touchdown_W);
      }
    }
  }
}

}  // namespace
}  // namespace hexdyn
