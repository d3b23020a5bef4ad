// Gait patterns (model/gait_pattern.hpp, gait.pattern): the phases of each pattern for four,
// six and eight legs against tables written out here from the patterns' definitions (which legs
// swing together), the hexapod's trot at β = ½ against the wave gait bit for bit and through
// the planner, the patterns that do not fit a robot refused in one line naming the pattern and
// the leg count, and the pattern and phases a scene resolves to.
#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/gait_cases.hpp"
#include "hexdyn/model/gait_pattern.hpp"
#include "hexdyn/planning/plan.hpp"
#include "hexdyn/temp_dir.hpp"
#include "hexdyn/urdf_writer.hpp"

namespace hexdyn {
namespace {

using test::paired_legs;

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// The tables. Legs in the order of docs/theory/conventions.md: L1 front left, L2 front right,
// then the next rank's left and right, …; a leg at 0 swings in the first half of the cycle,
// one at ½ in the second.
//
// Trot: diagonal neighbours together. The front right leg starts (0) with the left leg of the
// next rank, whose right neighbour goes with the front left (½), and so on down the sides.
// Pace: all right legs at 0, all left legs at ½. Bound: the rear half of each side at 0, the
// front half at ½.
const std::vector<double> kQuadTrot{0.5, 0.0, 0.0, 0.5};   // FL+HR against FR+HL
const std::vector<double> kQuadPace{0.5, 0.0, 0.5, 0.0};   // left against right
const std::vector<double> kQuadBound{0.5, 0.5, 0.0, 0.0};  // front pair against hind pair
// Six legs: the trot is the paper's tripod, 2-3-6 first, then 1-4-5.
const std::vector<double> kHexTrot{0.5, 0.0, 0.0, 0.5, 0.5, 0.0};
const std::vector<double> kHexPace{0.5, 0.0, 0.5, 0.0, 0.5, 0.0};
const std::vector<double> kOctTrot{0.5, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.5};
const std::vector<double> kOctPace{0.5, 0.0, 0.5, 0.0, 0.5, 0.0, 0.5, 0.0};
const std::vector<double> kOctBound{0.5, 0.5, 0.5, 0.5, 0.0, 0.0, 0.0, 0.0};
// The wave at β = ¾, s = ¼: on the right side the rear leg (rank 3) lifts at 0 and each leg in
// front of it a quarter later, 0, ¼, ½, ¾ from rear to front; the left side half a cycle after.
//   right ranks 0 … 3: ¾, ½, ¼, 0;  left ranks 0 … 3: ¾ + ½ = ¼, 0, ¾, ½ (mod 1).
const std::vector<double> kOctWave34{0.25, 0.75, 0.0, 0.5, 0.75, 0.25, 0.5, 0.0};
// Four legs at β = ¾: the crawl, rear right 0, front right ¼, rear left ½, front left ¾.
const std::vector<double> kQuadWave34{0.75, 0.25, 0.5, 0.0};

TEST_CASE("gait patterns: phases of four, six and eight legs as the tables say",
          "[gait][patterns]") {
  const std::vector<GaitLeg> quad = paired_legs(2), hex = test::hexapod_legs(),
                             oct = paired_legs(4);
  for (double beta : {0.5, 0.6, 0.75, 0.9}) {
    INFO("beta " << beta);
    CHECK(gait_pattern_phases(GaitPattern::kTrot, quad, beta) == kQuadTrot);
    CHECK(gait_pattern_phases(GaitPattern::kPace, quad, beta) == kQuadPace);
    CHECK(gait_pattern_phases(GaitPattern::kBound, quad, beta) == kQuadBound);
    CHECK(gait_pattern_phases(GaitPattern::kTrot, hex, beta) == kHexTrot);
    CHECK(gait_pattern_phases(GaitPattern::kPace, hex, beta) == kHexPace);
    CHECK(gait_pattern_phases(GaitPattern::kTrot, oct, beta) == kOctTrot);
    CHECK(gait_pattern_phases(GaitPattern::kPace, oct, beta) == kOctPace);
    CHECK(gait_pattern_phases(GaitPattern::kBound, oct, beta) == kOctBound);
  }
  CHECK(gait_pattern_phases(GaitPattern::kWave, quad, 0.75) == kQuadWave34);
  CHECK(gait_pattern_phases(GaitPattern::kWave, oct, 0.75) == kOctWave34);
  // The two-leg patterns: at every instant of a cycle no more than half the legs swing, and
  // at β = ½ exactly half (no flight phase, no instant on all feet).
  for (const auto* legs : {&quad, &hex, &oct})
    for (GaitPattern p : {GaitPattern::kTrot, GaitPattern::kPace, GaitPattern::kBound}) {
      if (!gait_pattern_misfit(p, *legs).empty()) continue;
      for (double beta : {0.5, 0.6, 0.75}) {
        const std::vector<double> phi = gait_pattern_phases(p, *legs, beta);
        for (int i = 0; i < 1000; ++i) {
          const double tau = (i + 0.5) / 1000.0;
          const auto up = std::count_if(phi.begin(), phi.end(),
                                        [&](double f) { return test::swinging(f, beta, tau); });
          INFO(gait_pattern_word(p) << " legs " << legs->size() << " beta " << beta);
          CHECK(2 * up <= static_cast<long>(legs->size()));
          if (beta == 0.5) CHECK(2 * up == static_cast<long>(legs->size()));
        }
      }
    }
}

TEST_CASE("gait patterns: the hexapod's trot at β = ½ is the wave gait, bit for bit",
          "[gait][patterns]") {
  const std::vector<GaitLeg> hex = test::hexapod_legs();
  const std::vector<double> trot = gait_pattern_phases(GaitPattern::kTrot, hex, 0.5);
  const std::vector<double> wave = wave_gait_phases(hex, 0.5);
  REQUIRE(trot.size() == wave.size());
  for (std::size_t leg = 0; leg < trot.size(); ++leg) CHECK(same_bits(trot[leg], wave[leg]));
  // Through the scene and the planner: the paper's tripod with gait.pattern trot plans the
  // same swings as without it.
  const std::string paper = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";
  const Scene a = load_scene(paper), b = load_scene(paper, {{"gait.pattern", "trot"}});
  CHECK(a.gait.pattern == GaitPattern::kWave);
  CHECK(b.gait.pattern == GaitPattern::kTrot);
  const MotionPlan pa = plan_motion(a, build_robot_model(a.robot));
  const MotionPlan pb = plan_motion(b, build_robot_model(b.robot));
  CHECK(pa.gait.liftoff_phase == pb.gait.liftoff_phase);
  REQUIRE(pa.gait.legs.size() == pb.gait.legs.size());
  for (std::size_t leg = 0; leg < pa.gait.legs.size(); ++leg) {
    const auto &x = pa.gait.legs[leg].swings, &y = pb.gait.legs[leg].swings;
    REQUIRE(x.size() == y.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      CHECK(x[i].t_liftoff_s == y[i].t_liftoff_s);
      CHECK(x[i].t_touchdown_s == y[i].t_touchdown_s);
      CHECK(x[i].p_touchdown_W == y[i].p_touchdown_W);
      CHECK(x[i].apex_z_m == y[i].apex_z_m);
    }
  }
}

const char* kFiveLegScene = R"(name: five_legs
robot: {urdf: five.urdf, forward_axis: +x}
terrain: {type: flat, height: 0.0}
gait: {duty_factor: 0.75, stroke: 0.02, swing_clearance: 0.02, touchdown_speed: 0.05}
motion: {posture: {height: auto, start_y: 0.0}, peak_speed: 0.04, cycles: 2, ramp_duration: 1.0}
allocation: {friction: pyramid4, torque_limit: 50}
contact: {stiffness: 3.9810717055349725e11, exponent: 2.2, damping_max: 1.0e4,
          full_damping_depth: 1.0e-5, friction_coefficient: 0.6}
output: {sample_step: 0.05}
)";

/// The message of the ConfigError that loading throws; "" when it loads.
std::string load_error(const std::string& path, const std::vector<Override>& overrides) {
  try {
    (void)load_scene(path, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

/// One line naming the key, the pattern and the leg count.
void check_one_line(const std::string& message, const std::string& expected) {
  INFO(message);
  CHECK(message.find(expected) != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);
}

TEST_CASE("gait patterns: a pattern the legs do not fit is one line at gait.pattern",
          "[gait][patterns]") {
  const std::string paper = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";
  // Three legs a side: no front and rear halves.
  check_one_line(load_error(paper, {{"gait.pattern", "bound"}}),
                 "gait.pattern: got bound for a robot of 6 legs (3 on the left, 3 on the right): "
                 "bound swings the front half of each side against the rear half");
  check_one_line(load_error(paper, {{"gait.pattern", "bound"}}),
                 "patterns that fit: wave, trot, pace, custom");
  // Pattern and phases: custom needs them, the others take none.
  check_one_line(load_error(paper, {{"gait.pattern", "custom"}}),
                 "gait.pattern: got custom without gait.phases");
  check_one_line(
      load_error(paper, {{"gait.pattern", "trot"},
                         {"gait.phases", "{L1: 0, L2: 0.5, L3: 0.5, L4: 0, L5: 0, L6: 0.5}"}}),
      "gait.pattern: got trot with gait.phases");
  check_one_line(load_error(paper, {{"gait.pattern", "gallop"}}),
                 "gait.pattern: got gallop, expected one of wave, trot, pace, bound, custom");
  const Scene custom =
      load_scene(paper, {{"gait.pattern", "custom"},
                         {"gait.phases", "{L1: 0, L2: 0.5, L3: 0.5, L4: 0, L5: 0, L6: 0.5}"}});
  CHECK(custom.gait.pattern == GaitPattern::kCustom);

  // Five legs, three on the left and two on the right (a walker written as URDF text): no
  // diagonal or front-rear pairs; pace and wave fit.
  const testing::TempDir dir("gait_patterns");
  std::mt19937 rng(5u);
  dir.write("five.urdf", test::urdf_text(test::walking_urdf_robot(rng, 5, 3)));
  const std::string five = dir.write("five.yaml", kFiveLegScene);
  check_one_line(load_error(five, {{"gait.pattern", "trot"}}),
                 "gait.pattern: got trot for a robot of 5 legs (3 on the left, 2 on the right): "
                 "trot pairs each leg with a diagonal neighbour");
  check_one_line(load_error(five, {{"gait.pattern", "bound"}}),
                 "gait.pattern: got bound for a robot of 5 legs (3 on the left, 2 on the right)");
  check_one_line(load_error(five, {{"gait.pattern", "bound"}}),
                 "patterns that fit: wave, pace, custom");
  CHECK(load_scene(five, {{"gait.pattern", "pace"}}).gait.pattern == GaitPattern::kPace);
  CHECK(load_scene(five).gait.pattern == GaitPattern::kWave);
  // One side empty: nothing that pairs the sides fits.
  const std::vector<GaitLeg> one_side{{LegSide::kLeft, 0}, {LegSide::kLeft, 1}};
  for (GaitPattern p : {GaitPattern::kTrot, GaitPattern::kPace, GaitPattern::kBound}) {
    const std::string m = gait_pattern_misfit(p, one_side);
    INFO(m);
    CHECK(m.find("got " + gait_pattern_word(p) +
                 " for a robot of 2 legs (2 on the left, 0 on "
                 "the right)") != std::string::npos);
    CHECK_THROWS_AS(gait_pattern_phases(p, one_side, 0.75), std::invalid_argument);
  }
  CHECK(gait_pattern_misfit(GaitPattern::kWave, one_side).empty());
}

TEST_CASE("gait patterns: the resolved configuration records the pattern and its phases",
          "[gait][patterns]") {
  const std::string solo = std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/solo12_flat.yaml";
  // Not given: wave, recorded as chosen.
  const Scene wave = load_scene(solo);
  const std::string& w = wave.resolved_yaml;
  INFO(w);
  CHECK(w.find("  pattern: wave\n") != std::string::npos);
  CHECK(w.find("auto:\n") != std::string::npos);
  CHECK(w.find("    pattern: auto\n") != std::string::npos);
  CHECK(w.find("phases: {L1: 0.75, L2: 0.25, L3: 0.5, L4: 0}") != std::string::npos);
  // Given: trot, its phases in the record; the resolved configuration reads back to both.
  const Scene trot = load_scene(solo, {{"gait.pattern", "trot"}, {"gait.duty_factor", "0.6"}});
  const std::string& t = trot.resolved_yaml;
  INFO(t);
  CHECK(t.find("  pattern: trot\n") != std::string::npos);
  CHECK(t.find("    pattern: auto\n") == std::string::npos);
  CHECK(t.find("phases: {L1: 0.5, L2: 0, L3: 0, L4: 0.5}") != std::string::npos);
  const Scene again = load_scene_from_string(t, "resolved.yaml");
  CHECK(again.gait.pattern == GaitPattern::kTrot);
  CHECK(again.gait.liftoff_phases.empty());
  CHECK(again.resolved_yaml == t);
  // gait.phases without a pattern: custom, recorded as chosen; the phases stay the scene's.
  const Scene given = load_scene(solo, {{"gait.phases", "{L1: 0, L2: 0.5, L3: 0.5, L4: 0}"}});
  CHECK(given.gait.pattern == GaitPattern::kCustom);
  CHECK(given.resolved_yaml.find("  pattern: custom\n") != std::string::npos);
  CHECK(given.resolved_yaml.find("    pattern: auto\n") != std::string::npos);
}

}  // namespace

// A balanced scene's plan stands on all its feet at each end while its trunk shifts the weight
// (docs/theory/balance.md): its trunk holds still for t_s at the start and at the end, t_s at
// least 2/ω for the plan's own trunk height h above its feet (ω = √(g/h)), and between the holds
// it is the straight twin's plan delayed by t_s, its swings whole: the same footholds, the same
// fractions and the same durations. A balanced plan once shortened the swings that reached into
// those spans instead, to a third of their length and nine times their accelerations.
TEST_CASE("gait: a balanced plan stands still at its ends and keeps every swing whole", "[gait]") {
  const std::string solo =
      std::string(HEXDYN_SOURCE_DIR) + "/configs/robots/solo12_trot_balanced.yaml";
  const Scene balanced = load_scene(solo, {{"motion.ramp_duration", "0.3"}}),
              straight =
                  load_scene(solo, {{"motion.ramp_duration", "0.3"}, {"motion.trunk", "straight"}});
  const RobotModel model = build_robot_model(balanced.robot);
  CHECK(settle_time_s(straight, model) == 0.0);
  const Vec3 p0(0.0, 0.0, 0.16);
  const MotionPlan b = plan_motion_with(balanced, model, p0, balanced.gait.foot_lateral_m);
  const MotionPlan s = plan_motion_with(straight, model, p0, straight.gait.foot_lateral_m);
  double feet_z = 0.0;
  for (const LegPlan& leg : s.gait.legs) feet_z += leg.p_initial_W.z();
  const double h = p0.z() - feet_z / 4.0;
  const double hold = b.trunk.hold_s(), Ts = s.trunk.duration_s(), Tb = b.trunk.duration_s();
  CHECK(hold == settle_time_s(balanced, model));
  CHECK(hold >= 2.0 / std::sqrt(model.gravity_W.norm() / h));
  CHECK(s.trunk.hold_s() == 0.0);
  CHECK(Tb == Approx(Ts + 2.0 * hold).margin(1e-12));
  // The trunk: still over each hold, the straight twin's motion delayed by the hold between.
  for (int i = 0; i <= 50; ++i) {
    for (double t : {hold * i / 50.0, Tb - hold * i / 50.0}) {
      const BaseState x = b.trunk.straight_at(t);
      const Vec3 end = t < 0.5 * Tb ? s.trunk.straight_at(0.0).p_W : s.trunk.straight_at(Ts).p_W;
      CHECK((x.p_W - end).norm() < 1e-12);
      CHECK(x.v_W.norm() == 0.0);
      CHECK(x.a_W.norm() == 0.0);
    }
    const double t = Ts * i / 50.0;
    const BaseState x = b.trunk.straight_at(t + hold), y = s.trunk.straight_at(t);
    CHECK((x.p_W - y.p_W).norm() < 1e-9);
    CHECK((x.v_W - y.v_W).norm() < 1e-9);
    CHECK((x.a_W - y.a_W).norm() < 1e-8);
  }
  bool swings_at_start = false;
  for (int l = 0; l < 4; ++l) {
    REQUIRE(b.gait.legs[l].swings.size() == s.gait.legs[l].swings.size());
    for (std::size_t i = 0; i < s.gait.legs[l].swings.size(); ++i) {
      const Swing& x = b.gait.legs[l].swings[i];
      const Swing& y = s.gait.legs[l].swings[i];
      CHECK(x.p_liftoff_W == y.p_liftoff_W);
      CHECK(x.p_touchdown_W == y.p_touchdown_W);
      CHECK(x.lift_end_u == y.lift_end_u);
      CHECK(x.lower_start_u == y.lower_start_u);
      CHECK(x.t_liftoff_s == Approx(y.t_liftoff_s + hold).margin(1e-9));
      CHECK(x.t_touchdown_s == Approx(y.t_touchdown_s + hold).margin(1e-9));
      CHECK(x.t_liftoff_s >= hold - 1e-12);
      CHECK(x.t_touchdown_s <= Tb - hold + 1e-12);
      swings_at_start =
          swings_at_start || y.t_liftoff_s < 2.0 / std::sqrt(model.gravity_W.norm() / h);
    }
  }
  CHECK(swings_at_start);  // the straight twin swings where a balanced plan must stand
}

}  // namespace hexdyn
