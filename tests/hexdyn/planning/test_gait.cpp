// Gait and trunk motion planning (gait.hpp, motion.hpp) on the paper scene and on
// variants of it, checked against quantities measured in the test: support fractions
// from the swing times, support counts from densely sampled feet, clearances from
// terrain scans along every swing, derivatives from central finite differences.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/planning/gait.hpp"
#include "hexdyn/planning/motion.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {
namespace {

const std::string kPaperConfig = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";

std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

struct Planned {
  Scene scene;
  RobotModel model;
  MotionPlan plan;
};

Planned plan_scene(const std::vector<Override>& overrides) {
  Scene scene = load_scene(kPaperConfig, overrides);
  RobotModel model = build_robot_model(scene.robot);
  MotionPlan plan = plan_motion(scene, model);
  return Planned{std::move(scene), model, std::move(plan)};
}

/// Five cycles, the middle three steady.
const std::string kFiveCycles = "[3.0, 2.6, 2.6, 2.6, 3.0]";

Planned plan_duty(double beta, const std::string& durations = kFiveCycles) {
  return plan_scene({{"gait.duty_factor", exact(beta)}, {"motion.cycle_durations", durations}});
}

const std::vector<double> kDutyFactors = {0.5, 2.0 / 3.0, 0.75, 5.0 / 6.0};

/// Every lift-off and touchdown time of the plan.
std::vector<double> event_times(const GaitPlan& gait) {
  std::vector<double> t;
  for (const LegPlan& leg : gait.legs)
    for (const Swing& sw : leg.swings) {
      t.push_back(sw.t_liftoff_s);
      t.push_back(sw.t_touchdown_s);
    }
  return t;
}

/// The largest differences of a swing's velocity and acceleration from central differences
/// (step h) of its position and velocity, at `points` − 1 interior instants, skipping those
/// within 3 h of the lift's end and the descent's start (where the jerk jumps).
struct DerivativeErrors {
  double v = 0.0, a = 0.0;
};
DerivativeErrors finite_difference_errors(const Swing& sw, int points, double h) {
  const double t0 = sw.t_liftoff_s, D = sw.t_touchdown_s - t0;
  const double tb[2] = {t0 + sw.lift_end_u * D, t0 + sw.lower_start_u * D};
  DerivativeErrors e;
  for (int i = 1; i < points; ++i) {
    const double t = t0 + D * i / points;
    if (std::abs(t - tb[0]) < 3 * h || std::abs(t - tb[1]) < 3 * h) continue;
    const FootMotion f = swing_foot_motion(sw, t);
    const Vec3 v_fd =
        (swing_foot_motion(sw, t + h).p_W - swing_foot_motion(sw, t - h).p_W) / (2 * h);
    const Vec3 a_fd =
        (swing_foot_motion(sw, t + h).v_W - swing_foot_motion(sw, t - h).v_W) / (2 * h);
    e.v = std::max(e.v, (f.v_W - v_fd).norm());
    e.a = std::max(e.a, (f.a_W - a_fd).norm());
  }
  return e;
}

int support_count(const GaitPlan& gait, double t) {
  int n = 0;
  for (const LegPlan& leg : gait.legs) n += leg_foot_motion(leg, t).in_swing ? 0 : 1;
  return n;
}

TEST_CASE("gait: swings of every leg are ordered, disjoint and inside the run", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const double T = p.plan.trunk.duration_s();
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const auto& swings = p.plan.gait.legs[leg].swings;
      INFO("beta " << beta << " leg " << leg);
      REQUIRE(swings.size() >= static_cast<std::size_t>(p.plan.trunk.cycles()));
      for (std::size_t i = 0; i < swings.size(); ++i) {
        CHECK(swings[i].t_liftoff_s >= 0.0);
        CHECK(swings[i].t_touchdown_s <= T);
        CHECK(swings[i].t_touchdown_s > swings[i].t_liftoff_s);
        if (i > 0) CHECK(swings[i].t_liftoff_s > swings[i - 1].t_touchdown_s);
      }
    }
  }
}

TEST_CASE("gait: steady-cycle support fraction equals the duty factor", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const TrunkMotion& trunk = p.plan.trunk;
    const int n = trunk.cycles();
    REQUIRE(n == 5);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (int k = 0; k < n; ++k) {
        // Swing time of this cycle in phase units, from the planned swing times.
        double swing = 0.0;
        for (const Swing& sw : p.plan.gait.legs[leg].swings) {
          const double a = trunk.phase(sw.t_liftoff_s), b = trunk.phase(sw.t_touchdown_s);
          swing += std::max(0.0, std::min(b, k + 1.0) - std::max(a, static_cast<double>(k)));
        }
        INFO("beta " << beta << " leg " << leg << " cycle " << k << " swing phase " << swing);
        if (k == 0 || k == n - 1)
          CHECK(1.0 - swing >= beta - 1e-9);  // start and end may keep feet down longer
        else
          CHECK(std::abs((1.0 - swing) - beta) <= 1e-9);
      }
    }
  }
}

TEST_CASE("gait: at least three feet support the robot at every instant", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const double T = p.plan.trunk.duration_s();
    int fewest = kPaperLegs;
    for (int i = 0; i <= 20000; ++i)
      fewest = std::min(fewest, support_count(p.plan.gait, T * i / 20000.0));
    for (double t : event_times(p.plan.gait))
      fewest = std::min(fewest, support_count(p.plan.gait, t));
    INFO("beta " << beta);
    CHECK(fewest >= 3);
    // The gait does lift legs: with β < 1 some instant has fewer than six in support.
    CHECK(fewest < kPaperLegs);
  }
}

TEST_CASE("gait: the tripod alternates {1,4,5} and {2,3,6}, legs 2,3,6 first", "[gait]") {
  const Planned p = plan_duty(0.5);
  const GaitPlan& g = p.plan.gait;
  const double T = p.plan.trunk.duration_s();
  // 0-based groups: legs 2,3,6 → {1,2,5}; legs 1,4,5 → {0,3,4}.
  const std::array<bool, kPaperLegs> first_group{false, true, true, false, false, true};
  int seen_first = 0, seen_second = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double t = T * i / 20000.0;
    std::array<bool, kPaperLegs> swinging{};
    int count = 0;
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      swinging[leg] = leg_foot_motion(g.legs[leg], t).in_swing;
      count += swinging[leg];
    }
    INFO("t " << t);
    if (count == 0) continue;
    REQUIRE(count == 3);
    const bool first = swinging == first_group;
    std::array<bool, kPaperLegs> second_group;
    for (int leg = 0; leg < kPaperLegs; ++leg) second_group[leg] = !first_group[leg];
    CHECK((first || swinging == second_group));
    (first ? seen_first : seen_second) += 1;
  }
  CHECK(seen_first > 0);
  CHECK(seen_second > 0);
  // Legs 2, 3, 6 lift together at the start; 1, 4, 5 after they have touched down.
  for (int leg : {1, 2, 5}) CHECK(g.legs[leg].swings.front().t_liftoff_s == 0.0);
  for (int leg : {0, 3, 4}) {
    CHECK(g.legs[leg].swings.front().t_liftoff_s > 0.0);
    CHECK(g.legs[leg].swings.front().t_liftoff_s >= g.legs[1].swings.front().t_touchdown_s);
  }
  // Members of a group share their swing times.
  for (const auto& group : {std::array<int, 3>{1, 2, 5}, std::array<int, 3>{0, 3, 4}}) {
    const auto& ref = g.legs[group[0]].swings;
    for (int leg : group) {
      REQUIRE(g.legs[leg].swings.size() == ref.size());
      for (std::size_t i = 0; i < ref.size(); ++i) {
        CHECK(g.legs[leg].swings[i].t_liftoff_s == ref[i].t_liftoff_s);
        CHECK(g.legs[leg].swings[i].t_touchdown_s == ref[i].t_touchdown_s);
      }
    }
  }
}

TEST_CASE("gait: support feet stay at their touchdown point", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const double T = p.plan.trunk.duration_s();
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const LegPlan& lp = p.plan.gait.legs[leg];
      INFO("beta " << beta << " leg " << leg);
      // Stance intervals [start, end) and the point the foot must hold.
      struct Stance {
        double start, end;
        Vec3 p;
      };
      std::vector<Stance> stances;
      double start = 0.0;
      Vec3 hold = lp.p_initial_W;
      for (const Swing& sw : lp.swings) {
        CHECK(sw.p_liftoff_W == hold);  // lifts off where it stood
        stances.push_back({start, sw.t_liftoff_s, hold});
        // The swing path ends at its touchdown point.
        CHECK((swing_foot_motion(sw, sw.t_touchdown_s).p_W - sw.p_touchdown_W)
                  .cwiseAbs()
                  .maxCoeff() <= 1e-12);
        CHECK((leg_foot_motion(lp, sw.t_touchdown_s - 1e-9).p_W - sw.p_touchdown_W)
                  .cwiseAbs()
                  .maxCoeff() <= 1e-9);
        start = sw.t_touchdown_s;
        hold = sw.p_touchdown_W;
      }
      stances.push_back({start, T, hold});
      for (const Stance& s : stances) {
        if (s.end <= s.start) continue;
        for (int i = 0; i <= 50; ++i) {
          const double t = s.start + (s.end - s.start) * i / 51.0;
          const FootMotion f = leg_foot_motion(lp, t);
          INFO("t " << t);
          CHECK_FALSE(f.in_swing);
          CHECK(f.p_W == s.p);
          CHECK(f.v_W == Vec3::Zero());
          CHECK(f.a_W == Vec3::Zero());
        }
      }
      // Footholds stand on the terrain.
      for (const Stance& s : stances) CHECK(s.p.z() == p.plan.terrain.height(s.p.x(), s.p.y()));
    }
  }
}

TEST_CASE("gait: swing paths clear the terrain by the swing clearance", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const Terrain& terrain = p.plan.terrain;
    const double clearance = p.scene.gait.swing_clearance_m;
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (const Swing& sw : p.plan.gait.legs[leg].swings) {
        INFO("beta " << beta << " leg " << leg << " swing at " << sw.t_liftoff_s);
        const Vec3 &a = sw.p_liftoff_W, &b = sw.p_touchdown_W;
        // Highest terrain under the horizontal segment, by scanning.
        double highest = -std::numeric_limits<double>::infinity();
        for (int i = 0; i <= 5000; ++i) {
          const Vec3 q = a + (b - a) * (i / 5000.0);
          highest = std::max(highest, terrain.height(q.x(), q.y()));
        }
        double top = -std::numeric_limits<double>::infinity();
        int transfer_points = 0;
        const int N = 2000;
        for (int i = 0; i <= N; ++i) {
          const double t = sw.t_liftoff_s + (sw.t_touchdown_s - sw.t_liftoff_s) * i / N;
          const Vec3 f = swing_foot_motion(sw, t).p_W;
          const double ground = terrain.height(f.x(), f.y());
          top = std::max(top, f.z());
          CHECK(f.z() >= ground - 1e-12);
          const bool at_end = f.head<2>() == a.head<2>() || f.head<2>() == b.head<2>();
          if (!at_end) {
            ++transfer_points;
            if (f.z() - ground < clearance - 1e-12) {
              INFO("t " << t << " foot " << f.transpose() << " ground " << ground);
              CHECK(f.z() - ground >= clearance - 1e-12);
            }
          }
        }
        CHECK(transfer_points > 50);
        CHECK(std::abs(top - (highest + clearance)) <= 1e-12);
        CHECK(std::abs(sw.apex_z_m - (highest + clearance)) <= 1e-12);
      }
    }
  }
}

TEST_CASE("gait: touchdown speed, rest at lift-off, C2 swing paths", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const double v_td = p.scene.gait.touchdown_speed_mps;
    REQUIRE(v_td > 0.0);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (const Swing& sw : p.plan.gait.legs[leg].swings) {
        INFO("beta " << beta << " leg " << leg << " swing at " << sw.t_liftoff_s);
        const double t0 = sw.t_liftoff_s, t1 = sw.t_touchdown_s, D = t1 - t0;
        // Touchdown: straight down at the touchdown speed, at t_td and just before it.
        const FootMotion td = swing_foot_motion(sw, t1);
        CHECK((td.v_W - Vec3(0, 0, -v_td)).cwiseAbs().maxCoeff() <= 1e-12);
        CHECK((leg_foot_motion(p.plan.gait.legs[leg], t1 - 1e-9).v_W - Vec3(0, 0, -v_td))
                  .cwiseAbs()
                  .maxCoeff() <= 1e-6);
        // Lift-off: at rest.
        const FootMotion lo = swing_foot_motion(sw, t0);
        CHECK(lo.v_W.cwiseAbs().maxCoeff() <= 1e-12);
        CHECK(lo.a_W.cwiseAbs().maxCoeff() <= 1e-12);
        CHECK((lo.p_W - sw.p_liftoff_W).cwiseAbs().maxCoeff() <= 1e-15);
        // Continuity of position, velocity and acceleration across the phase boundaries.
        REQUIRE(sw.lift_end_u > 0.0);
        REQUIRE(sw.lower_start_u > sw.lift_end_u);
        REQUIRE(sw.lower_start_u < 1.0);
        const double tb[2] = {t0 + sw.lift_end_u * D, t0 + sw.lower_start_u * D};
        for (double t : tb) {
          const double eps = 1e-9;
          const FootMotion m = swing_foot_motion(sw, t - eps), pl = swing_foot_motion(sw, t + eps);
          INFO("boundary " << t);
          CHECK((pl.p_W - m.p_W).cwiseAbs().maxCoeff() <= 1e-9);
          CHECK((pl.v_W - m.v_W).cwiseAbs().maxCoeff() <= 1e-6);
          CHECK((pl.a_W - m.a_W).cwiseAbs().maxCoeff() <= 1e-4);
        }
        // Velocity and acceleration against central differences, away from the
        // boundaries (where the jerk jumps) and the ends.
        const double h = 1e-5;
        double v_peak = 0.0, a_peak = 0.0;
        for (int i = 0; i <= 400; ++i) {
          const FootMotion f = swing_foot_motion(sw, t0 + D * i / 400.0);
          v_peak = std::max(v_peak, f.v_W.norm());
          a_peak = std::max(a_peak, f.a_W.norm());
        }
        const DerivativeErrors e = finite_difference_errors(sw, 400, h);
        CHECK(v_peak > 0.0);
        CHECK(a_peak > 0.0);
        CHECK(e.v <= 1e-5 * v_peak);
        CHECK(e.a <= 1e-5 * a_peak);
      }
    }
  }
}

TEST_CASE("gait: a blended swing moves across over the whole swing at (ud - ul)^2 the peak",
          "[gait]") {
  // The paper's stairs with 0.02 m of clearance, staged and blended: the same footholds, times
  // and vertical motion; the blended foot moves across from lift-off to touchdown.
  const std::vector<Override> base = {{"gait.swing_clearance", "0.02"}};
  std::vector<Override> blended_overrides = base;
  blended_overrides.push_back({"gait.swing_profile", "blended"});
  const Planned staged = plan_scene(base), blended = plan_scene(blended_overrides);
  const Terrain& terrain = blended.plan.terrain;
  int swings = 0;
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const auto& s_sw = staged.plan.gait.legs[leg].swings;
    const auto& b_sw = blended.plan.gait.legs[leg].swings;
    REQUIRE(s_sw.size() == b_sw.size());
    for (std::size_t k = 0; k < s_sw.size(); ++k) {
      const Swing &a = s_sw[k], &b = b_sw[k];
      INFO("leg " << leg << " swing at " << a.t_liftoff_s);
      REQUIRE(a.t_liftoff_s == b.t_liftoff_s);
      REQUIRE((a.p_touchdown_W - b.p_touchdown_W).norm() == 0.0);
      const double t0 = a.t_liftoff_s, D = a.t_touchdown_s - t0;
      const double dxy = (a.p_touchdown_W - a.p_liftoff_W).head<2>().norm();
      if (dxy < 1e-6) continue;
      ++swings;
      // Peak horizontal accelerations by dense sampling, and the vertical motion compared.
      double peak_staged = 0.0, peak_blended = 0.0, dz = 0.0, below = 0.0;
      const int N = 4000;
      for (int i = 0; i <= N; ++i) {
        const double t = t0 + D * i / N;
        const FootMotion fs = swing_foot_motion(a, t), fb = swing_foot_motion(b, t);
        peak_staged = std::max(peak_staged, fs.a_W.head<2>().norm());
        peak_blended = std::max(peak_blended, fb.a_W.head<2>().norm());
        dz = std::max(dz, std::abs(fs.p_W.z() - fb.p_W.z()));
        below = std::max(below, terrain.height(fb.p_W.x(), fb.p_W.y()) - fb.p_W.z());
      }
      const double ratio = (a.lower_start_u - a.lift_end_u) * (a.lower_start_u - a.lift_end_u);
      CHECK(std::abs(peak_blended / peak_staged - ratio) <= 1e-3 * ratio);
      CHECK(dz == 0.0);
      CHECK(below <= 1e-12);
      // Halfway through the lift the blended foot has moved across, the staged one not.
      const double t_lift = t0 + 0.5 * a.lift_end_u * D;
      CHECK((swing_foot_motion(a, t_lift).p_W - a.p_liftoff_W).head<2>().norm() == 0.0);
      CHECK((swing_foot_motion(b, t_lift).p_W - b.p_liftoff_W).head<2>().norm() > 1e-3 * dxy);
      // Rest at lift-off, straight down at touchdown, derivatives against central differences.
      CHECK(swing_foot_motion(b, t0).v_W.norm() <= 1e-12);
      CHECK(swing_foot_motion(b, t0 + D).v_W.head<2>().norm() <= 1e-12);
      const DerivativeErrors e = finite_difference_errors(b, 200, 1e-5);
      CHECK(e.v <= 1e-5 * dxy / D);
      CHECK(e.a <= 1e-5 * peak_blended);
    }
  }
  CHECK(swings > 12);
}

TEST_CASE("gait: a blended swing into a riser is refused, naming the leg and the depth", "[gait]") {
  // A slow lift (0.7 of the swing): moving across while it lifts, a foot meets a 0.05 m riser.
  const std::vector<Override> slow = {{"gait.lift_fraction", "0.7"}};
  std::vector<Override> o = slow;
  o.push_back({"gait.swing_profile", "blended"});
  CHECK_THROWS_WITH(plan_scene(o),
                    Catch::Matches("leg L[1-6], swing at t = .* s: the blended swing path passes "
                                   "0.01[0-9]+ m below the terrain under it .*staged.*"));
  // A second computation: the same swings planned staged, then moved across as blended (the
  // transfer over the whole swing) and scanned densely, pass more than 1 cm below the terrain
  // (the message names the first such swing, the scan finds the deepest).
  const Planned p = plan_scene(slow);
  double deepest = 0.0;
  for (const LegPlan& leg : p.plan.gait.legs)
    for (Swing sw : leg.swings) {
      sw.transfer_start_u = 0.0;
      sw.transfer_end_u = 1.0;
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      for (int i = 0; i <= 20000; ++i) {
        const Vec3 f = swing_foot_position(sw, sw.t_liftoff_s + D * i / 20000.0);
        deepest = std::max(deepest, p.plan.terrain.height(f.x(), f.y()) - f.z());
      }
    }
  CHECK(deepest > 0.01);
}

TEST_CASE("gait: a sphere foot's normal blends from lift-off to touchdown, C2", "[gait][sphere]") {
  // The normal under a sphere foot (docs/theory/model.md#sphere-feet): every terrain hexdyn
  // has keeps one normal over a run, so the blend is checked on made-up normals.
  const Planned p = plan_duty(0.5);
  const Swing& sw = p.plan.gait.legs[2].swings.at(1);
  const Vec3 n0 = Vec3::UnitZ(), n1 = Vec3(0.3, -0.4, 1.0).normalized();
  const double t0 = sw.t_liftoff_s, D = sw.t_touchdown_s - t0;
  const double t_lift = t0 + sw.lift_end_u * D, t_lower = t0 + sw.lower_start_u * D;
  // n0 during the lift, n1 during the descent, at rest there.
  for (double t : {t0, 0.5 * (t0 + t_lift), t_lift}) {
    const FootNormal n = swing_foot_normal(sw, n0, n1, t);
    CHECK((n.n_W - n0).norm() <= 1e-15);
    CHECK(n.nd_W.norm() <= 1e-12);
  }
  for (double t : {t_lower, 0.5 * (t_lower + t0 + D), t0 + D}) {
    const FootNormal n = swing_foot_normal(sw, n0, n1, t);
    CHECK((n.n_W - n1).norm() <= 1e-15);
    CHECK(n.nd_W.norm() <= 1e-12);
    CHECK(n.ndd_W.norm() <= 1e-9);
  }
  // Unit, and its derivatives against central differences over the transfer.
  const double h = 1e-5;
  double nd_peak = 0.0, ndd_peak = 0.0, nd_err = 0.0, ndd_err = 0.0;
  for (int i = 1; i < 200; ++i) {
    const double t = t_lift + (t_lower - t_lift) * i / 200.0;
    const FootNormal n = swing_foot_normal(sw, n0, n1, t);
    const FootNormal a = swing_foot_normal(sw, n0, n1, t - h),
                     b = swing_foot_normal(sw, n0, n1, t + h);
    CHECK(std::abs(n.n_W.norm() - 1.0) <= 1e-15);
    nd_peak = std::max(nd_peak, n.nd_W.norm());
    ndd_peak = std::max(ndd_peak, n.ndd_W.norm());
    nd_err = std::max(nd_err, (n.nd_W - (b.n_W - a.n_W) / (2 * h)).norm());
    ndd_err = std::max(ndd_err, (n.ndd_W - (b.nd_W - a.nd_W) / (2 * h)).norm());
  }
  CHECK(nd_peak > 0.0);
  CHECK(nd_err <= 1e-6 * nd_peak);
  CHECK(ndd_err <= 1e-6 * ndd_peak);
  // A leg's normal is the terrain's: +z on the paper's stairs, in support and in swing.
  for (double t = 0.0; t < p.plan.trunk.duration_s(); t += 0.37) {
    const FootNormal n = leg_foot_normal(p.plan.gait.legs[2], p.plan.terrain, t);
    CHECK(n.n_W == Vec3::UnitZ());
    CHECK(n.nd_W == Vec3::Zero());
  }
}

TEST_CASE("gait: footholds keep the margin from every nosing and riser", "[gait]") {
  for (double beta : kDutyFactors) {
    const Planned p = plan_duty(beta);
    const double margin = p.scene.gait.foothold_margin_m;
    REQUIRE(margin > 0.0);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const LegPlan& lp = p.plan.gait.legs[leg];
      INFO("beta " << beta << " leg " << leg);
      CHECK(p.plan.terrain.edge_distance(lp.p_initial_W.y()) >= margin - 1e-12);
      for (const Swing& sw : lp.swings)
        CHECK(p.plan.terrain.edge_distance(sw.p_touchdown_W.y()) >= margin - 1e-12);
    }
  }
}

TEST_CASE("gait: a sphere foot keeps the margin with the sphere, or names leg, step and margin",
          "[gait][sphere]") {
  const double r = 0.03;
  const Planned p = plan_scene({{"robot.foot_radius", exact(r)}});
  const Terrain& terrain = p.plan.terrain;
  const double margin = p.scene.gait.foothold_margin_m;
  int at_margin = 0;
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const LegPlan& lp = p.plan.gait.legs[leg];
    std::vector<double> footholds = {lp.p_initial_W.y()};
    for (const Swing& sw : lp.swings) {
      footholds.push_back(sw.p_touchdown_W.y());
      // The apex clears the highest terrain under the sphere's shadow, scanned, by Δh.
      const double lo = std::min(sw.p_liftoff_W.y(), sw.p_touchdown_W.y()) - r;
      const double hi = std::max(sw.p_liftoff_W.y(), sw.p_touchdown_W.y()) + r;
      double highest = -std::numeric_limits<double>::infinity();
      for (int i = 0; i <= 5000; ++i)
        highest = std::max(highest, terrain.height(0.0, lo + (hi - lo) * i / 5000.0));
      CHECK(std::abs(sw.apex_z_m - (highest + p.scene.gait.swing_clearance_m)) <= 1e-12);
    }
    for (double y : footholds) {
      INFO("leg " << leg << " foothold y " << y);
      // The sphere's horizontal extent [y - r, y + r] keeps the margin from the tread's edges.
      CHECK(terrain.edge_distance(y) >= margin + r - 1e-12);
      if (terrain.edge_distance(y) <= margin + r + 1e-12) ++at_margin;
    }
  }
  CHECK(at_margin >= 3);  // the rule moved footholds: the point foot's margin would not do
  // No tread deep enough: one line naming the leg, the step and the margin.
  CHECK_THROWS_AS(plan_scene({{"robot.foot_radius", "0.03"}, {"gait.foothold_margin", "0.11"}}),
                  PlanningError);
  CHECK_THROWS_WITH(
      plan_scene({{"robot.foot_radius", "0.03"}, {"gait.foothold_margin", "0.11"}}),
      Catch::Matches("leg L[1-6], stance from t = .* s on step [0-9]+ of 12 .*gait.foothold_margin "
                     "0.11 m .*radius 0.03 m.*2 \\(margin \\+ radius\\) = 0.28 m"));
  CHECK_NOTHROW(plan_scene({{"robot.foot_radius", "0.03"}, {"gait.foothold_margin", "0.095"}}));
}

TEST_CASE("trunk: parallel to the slope, at rest at both ends, C2 speed", "[gait]") {
  const Planned p = plan_scene({});
  const TrunkMotion& trunk = p.plan.trunk;
  const double hs = p.scene.terrain.riser_height_m, bs = p.scene.terrain.tread_depth_m;
  const Vec3 slope_dir = Vec3(0.0, bs, hs).normalized();
  const double T = trunk.duration_s();
  double v_max = 0.0, a_max = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = T * i / 2000.0;
    const BaseState s = trunk.at(t);
    INFO("t " << t);
    CHECK((s.W_R_B.col(1) - slope_dir).cwiseAbs().maxCoeff() <= 1e-14);
    CHECK((s.W_R_B.col(0) - Vec3::UnitX()).cwiseAbs().maxCoeff() <= 1e-14);
    // The trunk moves along the slope.
    CHECK((s.v_W - s.v_W.dot(slope_dir) * slope_dir).norm() <= 1e-15);
    v_max = std::max(v_max, s.v_W.norm());
    a_max = std::max(a_max, s.a_W.norm());
  }
  CHECK(trunk.at(0.0).v_W.norm() == 0.0);
  CHECK(trunk.at(T).v_W.norm() == 0.0);
  CHECK(trunk.speed(0.0) == 0.0);
  CHECK(trunk.speed(T) == 0.0);
  CHECK((trunk.at(0.0).p_W - p.scene.motion.initial_position_m).norm() <= 1e-15);
  // Cruise speed: one stride along the slope (s0/β horizontally) per 2.6 s cruise cycle.
  const double stride = std::hypot(0.125 / 0.5, 0.125 / 0.5 * hs / bs);
  CHECK(std::abs(trunk.cruise_speed_mps() - stride / 2.6) <= 1e-12);
  CHECK(v_max <= trunk.cruise_speed_mps() * (1.0 + 1e-15));
  CHECK(v_max >= trunk.cruise_speed_mps() * (1.0 - 1e-12));  // it is reached
  // Velocity and acceleration against central differences of the position.
  const double h = 1e-4;
  double v_err = 0.0, a_err = 0.0, a2_err = 0.0;
  for (int i = 1; i < 2000; ++i) {
    const double t = T * i / 2000.0;
    if (t - 2 * h <= 0.0 || t + 2 * h >= T) continue;
    const BaseState s = trunk.at(t), sp = trunk.at(t + h), sm = trunk.at(t - h);
    v_err = std::max(v_err, (s.v_W - (sp.p_W - sm.p_W) / (2 * h)).norm());
    a_err = std::max(a_err, (s.a_W - (sp.v_W - sm.v_W) / (2 * h)).norm());
    const double H = 1e-3;
    const Vec3 a_pp = (trunk.at(t + H).p_W - 2.0 * s.p_W + trunk.at(t - H).p_W) / (H * H);
    a2_err = std::max(a2_err, (s.a_W - a_pp).norm());
  }
  INFO("v_err " << v_err << " a_err " << a_err << " a2_err " << a2_err << " a_max " << a_max);
  CHECK(a_max > 0.0);
  CHECK(v_err <= 1e-6 * v_max);
  CHECK(a_err <= 1e-5 * a_max);
  CHECK(a2_err <= 1e-4 * a_max);
  // Speed and acceleration are continuous at the ends of the ramps.
  for (double t : {trunk.ramp_duration_s(), T - trunk.ramp_duration_s()}) {
    CHECK(std::abs(trunk.speed(t + 1e-9) - trunk.speed(t - 1e-9)) <= 1e-10);
    CHECK(std::abs(trunk.acceleration(t + 1e-9) - trunk.acceleration(t - 1e-9)) <= 1e-8);
  }
}

TEST_CASE("trunk: cycle boundaries reproduce the paper's cycle durations", "[gait]") {
  const Planned p = plan_scene({});
  const TrunkMotion& trunk = p.plan.trunk;
  REQUIRE(trunk.cycles() == 3);
  const double expected[3] = {3.0, 2.6, 3.0};
  for (int k = 0; k < 3; ++k) {
    const double d = trunk.time_at_phase(k + 1.0) - trunk.time_at_phase(k);
    INFO("cycle " << k << " duration " << d);
    CHECK(std::abs(d - expected[k]) <= 1e-9);
  }
  CHECK(std::abs(trunk.duration_s() - 8.6) <= 1e-9);
  CHECK(trunk.time_at_phase(0.0) == 0.0);
  // Each cycle advances the trunk one stride along the slope.
  for (int k = 0; k <= 3; ++k) {
    const Vec3 pos = trunk.at(trunk.time_at_phase(k)).p_W;
    CHECK((pos - trunk.position_at_phase(k)).norm() <= 1e-9);
  }
  // The changed duty factor keeps the cycle durations.
  const Planned q = plan_scene({{"gait.duty_factor", "0.75"}});
  for (int k = 0; k < 3; ++k)
    CHECK(std::abs(q.plan.trunk.time_at_phase(k + 1.0) - q.plan.trunk.time_at_phase(k) -
                   expected[k]) <= 1e-9);
}

}  // namespace
}  // namespace hexdyn
