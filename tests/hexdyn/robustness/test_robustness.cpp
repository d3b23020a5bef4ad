// The robustness study (robustness/robustness.hpp): its draws against their distributions,
// the Wilson interval against the roots of its defining quadratic, the perturbed world
// against the changes worked out by hand, a study of zero error against the plain replay,
// and failures made on purpose classified as made.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/stairs.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/run.hpp"
#include "hexdyn/robustness/robustness.hpp"
#include "hexdyn/robustness/world.hpp"

using namespace hexdyn;

namespace {

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

/// Kolmogorov–Smirnov statistic of `x` against the CDF `F`.
template <class F>
double ks_statistic(std::vector<double> x, F cdf) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, (static_cast<double>(i) + 1.0) / n - f, f - static_cast<double>(i) / n});
  }
  return d;
}

/// The pooled values of perturbation p over `replays` draws of `spec`.
std::vector<double> pooled(const PerturbationSpec& spec, Perturbation p, const DrawSizes& sizes,
                           int replays, std::uint64_t seed) {
  std::vector<double> out;
  for (int i = 0; i < replays; ++i) {
    const WorldDraw d = draw_world(spec, sizes, seed, static_cast<std::uint64_t>(i));
    out.insert(out.end(), d[p].begin(), d[p].end());
  }
  return out;
}

Scene paper(const std::vector<Override>& overrides) {
  return load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml", overrides);
}

/// The one replay of a study of the paper scene with `overrides` (robustness.replays 1).
ReplayOutcome one_replay(std::vector<Override> overrides) {
  overrides.push_back({"robustness.replays", "1"});
  const RobustnessResult r = run_robustness(paper(overrides), 1);
  REQUIRE(r.outcomes.size() == 1);
  return r.outcomes.front();
}

}  // namespace

TEST_CASE("draws follow their distributions (Kolmogorov-Smirnov, 10,000 values)") {
  PerturbationSpec spec;
  spec[Perturbation::kRiserHeight] = {DistributionKind::kNormal, 0.01, 0.015, 0.0, 0.0};
  spec[Perturbation::kFriction] = {DistributionKind::kUniform, 0.0, 0.0, -0.2, 0.1};
  const DrawSizes sizes{10, 18, 18};
  // The truncated normal's CDF on [−b, b], from the standard normal's by erfc.
  const double b = 0.015, s = 0.01, lo = normal_cdf(-b / s), hi = normal_cdf(b / s);
  const std::vector<double> risers = pooled(spec, Perturbation::kRiserHeight, sizes, 1000, 7);
  REQUIRE(risers.size() == 10000);
  const double d_normal =
      ks_statistic(risers, [&](double x) { return (normal_cdf(x / s) - lo) / (hi - lo); });
  const std::vector<double> mu = pooled(spec, Perturbation::kFriction, sizes, 10000, 7);
  const double d_uniform = ks_statistic(mu, [](double x) { return (x + 0.2) / 0.3; });
  // The 1 % critical value of the KS statistic for n = 10,000: 1.628 / sqrt(n).
  CHECK(d_normal < 1.628 / 100.0);
  CHECK(d_uniform < 1.628 / 100.0);
  CHECK(*std::max_element(risers.begin(), risers.end()) <= b);
  CHECK(*std::min_element(risers.begin(), risers.end()) >= -b);
  // Neighbouring steps are independent: their correlation is that of 1,000 independent pairs.
  double sxy = 0.0, sxx = 0.0;
  for (int i = 0; i < 1000; ++i) {
    sxy += risers[static_cast<std::size_t>(10 * i)] * risers[static_cast<std::size_t>(10 * i + 1)];
    sxx += risers[static_cast<std::size_t>(10 * i)] * risers[static_cast<std::size_t>(10 * i)];
  }
  CHECK(std::abs(sxy / sxx) < 4.0 / std::sqrt(1000.0));
  // A draw depends on the seed and the replay's index alone.
  CHECK(draw_world(spec, sizes, 7, 123).values == draw_world(spec, sizes, 7, 123).values);
  CHECK(draw_world(spec, sizes, 7, 123).values != draw_world(spec, sizes, 8, 123).values);
  CHECK(draw_world(spec, sizes, 7, 123).values != draw_world(spec, sizes, 7, 124).values);
}

TEST_CASE("the Wilson interval is the pair of roots of its score equation") {
  const double z = 1.959963984540054;
  for (const auto& [k, n] : std::vector<std::pair<long, long>>{
           {0, 10}, {10, 10}, {7, 10}, {950, 1000}, {1, 3}, {500, 1000}}) {
    // (p̂ − p)² = z² p (1 − p) / n:  (1 + z²/n) p² − (2 p̂ + z²/n) p + p̂² = 0.
    const double ph = static_cast<double>(k) / n, a = 1.0 + z * z / n, b = -(2.0 * ph + z * z / n),
                 c = ph * ph, root = std::sqrt(b * b - 4.0 * a * c);
    const WilsonInterval w = wilson_interval(k, n);
    CHECK(w.low == Approx((-b - root) / (2.0 * a)).margin(1e-12));
    CHECK(w.high == Approx((-b + root) / (2.0 * a)).margin(1e-12));
  }
  // Brown, Cai and DasGupta (2001): 0 of 10 gives [0, 0.2775] at 95 %.
  CHECK(wilson_interval(0, 10).high == Approx(0.2775).margin(5e-5));
}

TEST_CASE("a perturbed world changes what its draw says, and a draw of zeros nothing") {
  const Scene scene = paper({{"actuators.default.model", "dynamixel_mx64"}});
  const RobotModel model = build_robot_model(scene.robot);
  const ReplayPlan plan = plan_from_result(model, run_scene(scene));
  const DrawSizes sizes = world_draw_sizes(model, scene.terrain);
  REQUIRE(sizes.steps == scene.terrain.steps);
  PerturbationSpec none;
  const World same =
      perturbed_world(model, scene.contact, scene.terrain, plan, draw_world(none, sizes, 1, 0));
  CHECK(same.terrain_y_m == plan.terrain_y_m);
  CHECK(same.terrain_z_m == plan.terrain_z_m);
  CHECK(same.model.total_mass_kg == model.total_mass_kg);
  CHECK(same.contact.stiffness == scene.contact.stiffness);

  WorldDraw d = draw_world(none, sizes, 1, 0);
  for (double& x : d.values[static_cast<int>(Perturbation::kRiserHeight)]) x = 0.001;
  d.values[static_cast<int>(Perturbation::kTrunkMass)] = {0.1};
  d.values[static_cast<int>(Perturbation::kPayloadMass)] = {0.5};
  d.values[static_cast<int>(Perturbation::kPayloadCom)] = {0.01, -0.02, 0.03};
  d.values[static_cast<int>(Perturbation::kTorqueConstant)][4] = -0.5;
  d.values[static_cast<int>(Perturbation::kFriction)] = {-0.1};
  const World w = perturbed_world(model, scene.contact, scene.terrain, plan, d);
  // Tread k stands k mm higher: the profile's highest vertex is the top tread, 12 mm higher.
  const double top = *std::max_element(plan.terrain_z_m.begin(), plan.terrain_z_m.end());
  CHECK(*std::max_element(w.terrain_z_m.begin(), w.terrain_z_m.end()) ==
        Approx(top + 0.001 * scene.terrain.steps));
  // Masses: the trunk's share grows by a tenth, and the payload adds its own.
  const double trunk = model.trunk_only.mass_kg;
  CHECK(w.model.total_mass_kg == Approx(model.total_mass_kg + 0.1 * trunk + 0.5));
  const RigidInertia& b0 = model.inertia[0];
  const Vec3 point = model.trunk_only.com_m + Vec3(0.01, -0.02, 0.03);
  const Vec3 com = (b0.mass_kg * b0.com_m + 0.1 * trunk * model.trunk_only.com_m + 0.5 * point) /
                   (b0.mass_kg + 0.1 * trunk + 0.5);
  CHECK((w.model.inertia[0].com_m - com).norm() < 1e-12);
  CHECK(w.model.drive.joints[4].torque_constant_NmpA ==
        Approx(0.5 * model.drive.joints[4].torque_constant_NmpA));
  CHECK(w.model.drive.joints[3].torque_constant_NmpA == model.drive.joints[3].torque_constant_NmpA);
  CHECK(w.contact.static_friction == Approx(scene.contact.static_friction - 0.1));
}

TEST_CASE("a study of zero error is the plain replay, every time") {
  const Scene scene = paper({{"robustness.replays", "3"}});
  const RobustnessResult r = run_robustness(scene, 2);
  const RobotModel model = build_robot_model(scene.robot);
  const ReplayPlan plan = plan_from_result(model, run_scene(scene));
  const ReplayResult plain = replay_plan(model, scene.contact, scene.replay, scene.terrain, plan);
  double slip = 0.0;
  for (int l = 0; l < model.legs(); ++l) slip = std::max(slip, plain.slip_distance_total_m[l]);
  CHECK(r.p_success == 1.0);
  CHECK(r.successes == 3);
  for (const ReplayOutcome& o : r.outcomes) {
    CHECK(o.reached_top);
    CHECK(o.energy_J == plain.energy_J);
    CHECK(o.steps == plain.steps);
    CHECK(o.slip_m == slip);
    CHECK(o.drift_m == (plain.base.back().p_W - plan.base.back().p_W).head<2>().norm());
  }
}

TEST_CASE("failures made on purpose are classified as made") {
  // The paper's swing clears the treads by 2 mm: risers 4 mm higher each are met by the toes.
  CHECK(one_replay({{"robustness.perturbations.riser_height.distribution", "uniform"},
                    {"robustness.perturbations.riser_height.low", "0.004"},
                    {"robustness.perturbations.riser_height.high", "0.004"}})
            .failure == FailureClass::kStubbed);
  // μ = 0.05 instead of 0.3.
  CHECK(one_replay({{"robustness.perturbations.friction.distribution", "uniform"},
                    {"robustness.perturbations.friction.low", "-0.25"},
                    {"robustness.perturbations.friction.high", "-0.25"}})
            .failure == FailureClass::kSlipped);
  // MX-28 servos climb; with half their torque constant they saturate.
  const std::vector<Override> mx28{{"actuators.default.model", "dynamixel_mx28"}};
  CHECK(one_replay(mx28).failure == FailureClass::kNone);
  std::vector<Override> weak = mx28;
  weak.insert(weak.end(), {{"robustness.perturbations.torque_constant.distribution", "uniform"},
                           {"robustness.perturbations.torque_constant.low", "-0.5"},
                           {"robustness.perturbations.torque_constant.high", "-0.5"}});
  const ReplayOutcome o = one_replay(weak);
  CHECK(o.failure == FailureClass::kSaturated);
  CHECK(o.saturation_s > 0.05);
}

TEST_CASE("the scene refuses perturbations that would make a world unphysical") {
  const auto refused = [](const std::vector<Override>& o, const std::string& key) {
    try {
      (void)paper(o);
    } catch (const ConfigError& e) {
      CHECK_THAT(e.what(), Catch::Contains(key));
      return true;
    }
    return false;
  };
  CHECK(refused({{"robustness.perturbations.riser_height.distribution", "normal"},
                 {"robustness.perturbations.riser_height.sigma", "0.02"},
                 {"robustness.perturbations.riser_height.bound", "0.06"}},
                "robustness.perturbations.riser_height"));
  CHECK(refused({{"robustness.perturbations.friction.distribution", "uniform"},
                 {"robustness.perturbations.friction.low", "-0.3"},
                 {"robustness.perturbations.friction.high", "0"}},
                "robustness.perturbations.friction"));
  CHECK(refused({{"robustness.perturbations.torque_constant.distribution", "normal"},
                 {"robustness.perturbations.torque_constant.sigma", "0.1"}},
                "robustness.perturbations.torque_constant"));
  CHECK(refused({{"robustness.perturbations.trunk_mass.distribution", "uniform"},
                 {"robustness.perturbations.trunk_mass.low", "-1"},
                 {"robustness.perturbations.trunk_mass.high", "0"}},
                "robustness.perturbations.trunk_mass"));
  CHECK(refused({{"robustness.perturbations.payload_com.distribution", "uniform"},
                 {"robustness.perturbations.payload_com.low", "-0.01"},
                 {"robustness.perturbations.payload_com.high", "0.01"}},
                "robustness.perturbations.payload_com"));
  CHECK(refused({{"robustness.perturbations.nosing.distribution", "uniform"},
                 {"robustness.perturbations.nosing.low", "-0.01"},
                 {"robustness.perturbations.nosing.high", "0"}},
                "robustness.perturbations.nosing"));
}

TEST_CASE("the tolerated scale passes, a scale one bisection step larger fails") {
  // μ lowered by a fixed 0.3 × s (uniform low = high): each scale's one replay is decided by s
  // alone, so the search's answer can be checked by studies at that scale and just above it.
  const std::vector<Override> study{{"robustness.replays", "1"},
                                    {"robustness.perturbations.friction.distribution", "uniform"},
                                    {"robustness.perturbations.friction.low", "-0.06"},
                                    {"robustness.perturbations.friction.high", "-0.06"},
                                    {"robustness.tolerance.replays", "1"},
                                    {"robustness.tolerance.max_scale", "4.5"},
                                    {"robustness.tolerance.bisections", "4"}};
  const RobustnessResult r = run_robustness(paper(study), 1);
  REQUIRE(r.tolerance.size() == 1);
  const ToleranceResult& t = r.tolerance.front();
  // μ = 0.3 − 0.06 s reaches 0 at s = 5: the scales searched stop short of it.
  CHECK(t.max_scale == 4.5);
  CHECK(t.probes == 5);
  CHECK_FALSE(t.censored);
  CHECK(t.magnitude == Approx(0.06 * t.scale));
  const double step = 4.5 / 16.0;  // the bisection's resolution
  const auto fraction_at = [&](double scale) {
    std::vector<Override> o{
        {"robustness.replays", "1"},
        {"robustness.perturbations.friction.distribution", "uniform"},
        {"robustness.perturbations.friction.low", std::to_string(-0.06 * scale)},
        {"robustness.perturbations.friction.high", std::to_string(-0.06 * scale)}};
    return run_robustness(paper(o), 1).p_success;
  };
  CHECK(fraction_at(t.scale) == 1.0);
  CHECK(fraction_at(t.scale + step) == 0.0);
}

TEST_CASE("a tolerance search never draws an unphysical world") {
  // Risers of 0.05 m with errors bounded at 0.02 m × s: s must stay below 2.5.
  const RobustnessResult r =
      run_robustness(paper({{"robustness.replays", "1"},
                            {"robustness.perturbations.riser_height.distribution", "normal"},
                            {"robustness.perturbations.riser_height.sigma", "0.001"},
                            {"robustness.perturbations.riser_height.bound", "0.02"},
                            {"robustness.tolerance.replays", "1"},
                            {"robustness.tolerance.max_scale", "10"},
                            {"robustness.tolerance.bisections", "0"}}),
                     1);
  REQUIRE(r.tolerance.size() == 1);
  CHECK(r.tolerance.front().max_scale < 2.5);
  CHECK(r.tolerance.front().max_scale > 2.5 * (1.0 - 1e-9));
}
