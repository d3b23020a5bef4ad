// Hard cases (docs/validation/hard-cases.md) of kinematics, allocation and gait; the contact and
// grid ones are in test_hard_contact.cpp: each runs the real pipeline (or the touchdown ODE alone)
// on a scene at the edge of what the model can do and checks exactly what comes
// out — finite datasets with the flags set where they must be, or one named exception —
// and, where possible, the numbers against a second computation made here:
//  - a leg within 1e-6 rad of full extension: the IK margin scanned here on the run's
//    sample times, the tibia angle from the law of cosines;
//  - nearly collinear support feet: the tipping moment M g Δy of the COM about the feet, and
//    whether the COM lies outside the feet's triangle;
//  - μ = 0.01 and a low torque limit: the paper run with the same grid, whose rows hold;
//  - 100 gait cycles: the paper run's cycles, cycle by cycle;
//  - a swing over a tall riser with a tiny clearance: Terrain::height under the foot.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <limits>
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
#include "hexdyn/planning/grid.hpp"
#include "hexdyn/planning/terrain.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
using namespace hard;

// ---------------------------------------------------------------------------------------
// Stiff contact
// ---------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------
// A leg at full extension
// ---------------------------------------------------------------------------------------

namespace {

/// Foot of `leg` in its hip frame at time t, computed as robot_state_at does.
Vec3 foot_in_hip_frame(const RobotModel& model, const MotionPlan& plan, int leg, double t) {
  const BaseState trunk = plan.trunk.at(t);
  const FootMotion f = leg_foot_motion(plan.gait.legs[leg], t);
  const Vec3 r_B = trunk.W_R_B.transpose() * (f.p_W - trunk.p_W);
  return model.R_B_H[leg].transpose() * (r_B - model.p_hip_B[leg]);
}

/// Distance of the wrist (femur axis) to the foot in the leg plane: full extension at l2 + l3.
double wrist_distance(const RobotModel& m, int leg, const Vec3& p) {
  const double w = m.lateral_m[leg];
  const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y() - w * w);
  return std::hypot(rho - m.link_length_m[0], p.z() + m.d1_m);
}

struct Stretch {
  int leg = -1;
  double t_s = 0.0;
  double distance_m = 0.0;
};

/// The leg and instant, among every instant the run evaluates IK at (the uniform grid and
/// the touchdowns), where a foot is farthest from its wrist.
Stretch farthest_foot(const Scene& scene) {
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  std::vector<double> times = build_output_grid(scene.output, plan.trunk.duration_s(), {});
  for (const LegPlan& lp : plan.gait.legs)
    for (const Swing& sw : lp.swings) times.push_back(sw.t_touchdown_s);
  Stretch s;
  for (int leg = 0; leg < model.legs(); ++leg)
    for (double t : times) {
      const double d = wrist_distance(model, leg, foot_in_hip_frame(model, plan, leg, t));
      if (d > s.distance_m) s = {leg, t, d};
    }
  return s;
}

}  // namespace

TEST_CASE("hard: a leg within 1e-6 rad of full extension", "[hard][kinematics]") {
  // The uniform grid makes the set of IK instants independent of the links' lengths; the
  // tibia length is then chosen so that the farthest foot of the run is ε short of l2 + l3.
  const std::vector<Override> base = {{"output.grid", "uniform"}};
  const Scene probe = paper_with(base);
  const Stretch far = farthest_foot(probe);
  REQUIRE(far.leg >= 0);
  const double l2 = probe.robot.link_length_m[1];
  const double l3_reach = far.distance_m - l2;  // tibia length for exact full extension
  // Knee angle ε below full extension ↔ gap δ = L − √(l2² + l3² + 2 l2 l3 cos ε) ≈ l2 l3 ε² / (2L).
  const double eps = 0.8e-6;
  const double gap = l2 * l3_reach * eps * eps / (2.0 * far.distance_m);
  const std::string l3 = num(l3_reach + gap);
  const std::string where = "leg " + leg_name(far.leg) + " at t = ";
  INFO("farthest foot: " << leg_name(far.leg) << " at " << far.t_s << " s, " << far.distance_m
                         << " m; tibia " << l3);

  SECTION("default margin 1e-4 m: ReachError naming leg, time and margin") {
    const Scene scene = paper_with({{"output.grid", "uniform"}, {"robot.tibia.length", l3}});
    try {
      run_scene(scene);
      FAIL("no ReachError");
    } catch (const ReachError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(contains(msg, where));
      CHECK(contains(msg, "within robot.ik_min_margin of full extension"));
      CHECK(contains(msg, "required >= 0.0001 m"));
      // The margin it reports is the gap set here (rounded to 6 digits by the message).
      const auto at = msg.find("(margin ");
      REQUIRE(at != std::string::npos);
      CHECK(std::strtod(msg.c_str() + at + 8, nullptr) == Approx(gap).epsilon(0.02));
      CHECK(msg.find('\n') == std::string::npos);
    }
  }

  SECTION("margin 0: finite output, the stretched leg's samples flagged") {
    const Scene scene = paper_with(
        {{"output.grid", "uniform"}, {"robot.tibia.length", l3}, {"robot.ik_min_margin", "0"}});
    const RunResult r = run_scene(scene);
    check_run_finite(r);
    const int i = sample_at(r, far.t_s);
    REQUIRE(i >= 0);
    // The knee is ε short of straight (knee-up branch: β3 ≤ 0).
    const int knee = build_robot_model(scene.robot).joint(far.leg, 2);
    const double beta3 = r.kin.joint_position(i, knee);
    CHECK(beta3 < 0.0);
    CHECK(-beta3 == Approx(eps).epsilon(0.01));
    // Near the singularity the joint rates are ~1/ε: huge, finite, and the sample is flagged
    // with the stretched leg's own torque row.
    CHECK(std::abs(r.kin.joint_velocity(i, knee)) > 1e3);
    INFO(r.dyn.solver_messages[i]);
    CHECK(r.dyn.solver_status[i] == SolverStatus::kRelaxed);
    CHECK(contains(r.dyn.solver_messages[i], "torque " + leg_name(far.leg) + "_"));
  }

  SECTION("margin 0 and exactly at full extension: ReachError, never NaN") {
    // Tibia lengths within ±16 ulp of exact full extension: each run either finishes
    // finite or refuses with a ReachError at the stretched leg; at least one hits the
    // singular Jacobian itself (β3 = 0 exactly), which used to give NaN everywhere.
    int singular = 0, beyond = 0, finished = 0;
    double l3_k = l3_reach;
    for (int k = 0; k < 16; ++k) l3_k = std::nextafter(l3_k, 0.0);
    for (int k = -16; k <= 16; ++k, l3_k = std::nextafter(l3_k, 1.0)) {
      const Scene scene = paper_with({{"output.grid", "uniform"},
                                      {"robot.tibia.length", num(l3_k)},
                                      {"robot.ik_min_margin", "0"}});
      INFO("tibia " << num(l3_k) << " (" << k << " ulp)");
      try {
        const RunResult r = run_scene(scene);
        ++finished;
        CHECK(r.dyn.joint_torque.allFinite());
        CHECK(r.kin.joint_acceleration.allFinite());
        CHECK(std::isfinite(r.dyn.energy_total_J));
      } catch (const ReachError& e) {
        const std::string msg = e.what();
        INFO(msg);
        CHECK(contains(msg, where));
        CHECK(contains(msg, "required >= 0 m"));
        if (contains(msg, "singular leg configuration")) {
          ++singular;
          CHECK(contains(msg, "(margin 0 m"));
          CHECK(contains(msg, "raise robot.ik_min_margin"));
        } else {
          ++beyond;
          CHECK(contains(msg, "beyond full extension"));
        }
      }
    }
    CHECK(singular >= 1);
    CHECK(beyond >= 1);
    CHECK(finished >= 1);
  }
}

// ---------------------------------------------------------------------------------------
// Nearly collinear support feet
// ---------------------------------------------------------------------------------------

namespace {

/// How far the point p lies outside the triangle abc [m] (0 inside or on it): the distance to
/// the nearest of its sides where p is outside.
double distance_outside(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& tri) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const double orientation = cross(tri[1] - tri[0], tri[2] - tri[0]);
  bool inside = true;
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& a = tri[k];
    const Eigen::Vector2d& b = tri[(k + 1) % 3];
    if (cross(b - a, p - a) * orientation < 0.0) inside = false;
    const double u = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (a + u * (b - a) - p).norm());
  }
  return inside ? 0.0 : nearest;
}

}  // namespace

TEST_CASE("hard: three support feet nearly collinear", "[hard][allocation]") {
  // Hips 1 mm apart along the trunk: each tripod's feet stand on one line across the
  // stairs (a triangle 0.5 m wide and 2 mm deep), and the COM is off it by up to s0/2.
  const Scene scene = paper_with({{"robot.hips.y", "[0.001, 0.0, -0.001]"}});
  const RunResult r = run_scene(scene);
  check_run_finite(r);
  const double mg = r.total_mass_kg * kGravity;
  // The trunk's moment about the feet's line is the weight's tipping moment M g Δy up to the
  // motion's own terms, which the check below allows 0.15 N m: a COM farther than 0.15 / (M g)
  // outside the feet's triangle tips the trunk whatever the motion, one nearer may not.
  const double slack_m = 0.15 / mg;
  int tripods = 0, relaxed = 0;
  double worst_tipping = 0.0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    if (legs_in_phase(r, i, ContactPhase::kSupport) != 3 ||
        legs_in_phase(r, i, ContactPhase::kImpact) != 0)
      continue;
    ++tripods;
    std::vector<Eigen::Vector2d> feet;
    double y_feet = 0.0;
    for (int l = 0; l < r.kin.contact_phase.cols(); ++l) {
      if (r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kSupport)) continue;
      feet.emplace_back(r.kin.foot_position(i, 3 * l), r.kin.foot_position(i, 3 * l + 1));
      y_feet += feet.back().y() / 3.0;
    }
    const Eigen::Vector2d a = feet[1] - feet[0], b = feet[2] - feet[0];
    const double area = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    const double side = std::max({a.norm(), b.norm(), (feet[2] - feet[1]).norm()});
    const Eigen::Vector2d com(r.kin.com_position(i, 0), r.kin.com_position(i, 1));
    const double dy = com.y() - y_feet;
    const double outside = distance_outside(com, feet);
    const std::string& msg = r.dyn.solver_messages[i];
    INFO("t = " << r.kin.time_s[i] << " s, COM " << dy << " m off the feet's line, " << outside
                << " m outside their triangle: " << msg);
    CHECK(area / (side * side) < 3e-3);
    CHECK(sum_force(r, i, 2) == Approx(mg).epsilon(0.03));
    if (outside > slack_m) CHECK(r.dyn.solver_status[i] == SolverStatus::kRelaxed);
    if (r.dyn.solver_status[i] != SolverStatus::kRelaxed) {
      // Held exactly: the COM is within the motion's slack of the support.
      CHECK(r.dyn.solver_status[i] == SolverStatus::kOptimal);
      CHECK(outside <= slack_m);
      continue;
    }
    ++relaxed;
    // The only row that gives way is the moment about the feet's line (trunk x), by the
    // tipping moment of the weight about that line; the weight itself is carried.
    CHECK(named_rows(msg) == std::vector<std::string>{"trunk moment x"});
    const double tipping = mg * std::abs(dy);
    worst_tipping = std::max(worst_tipping, tipping);
    CHECK(violation_of(msg, "trunk moment x") == Approx(tipping).margin(0.05 * tipping + 0.15));
  }
  CHECK(tripods > 0.4 * r.kin.samples());
  CHECK(relaxed > 0.9 * tripods);
  CHECK(worst_tipping > 3.0);
}

// ---------------------------------------------------------------------------------------
// μ = 0.01
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: friction coefficient 0.01", "[hard][allocation]") {
  // Both on the grid as built (output.tolerance 0): refined, each would have a grid of its own.
  const Scene scene =
      paper_with({{"contact.friction_coefficient", "0.01"}, {"output.tolerance", "0"}});
  const RunResult r = run_scene(scene);
  const RunResult ref = run_scene(paper_with({{"output.tolerance", "0"}}));  // μ = 0.3
  check_run_finite(r);
  REQUIRE(r.kin.time_s == ref.kin.time_s);
  const double mu = 0.01;
  const double reach = mu * std::cos(M_PI / 4.0);  // inscribed 4-sided pyramid
  int flagged_support = 0, must_slip = 0;
  double worst_friction = 0.0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    const std::string& msg = r.dyn.solver_messages[i];
    INFO("t = " << r.kin.time_s[i] << " s: " << msg);
    // Friction is never exceeded (contact rows give way last): no foot slips.
    CHECK_FALSE(contains(allocation_part(msg), "friction"));
    for (int l = 0; l < r.kin.contact_phase.cols(); ++l) {
      if (r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kSupport)) continue;
      const double fn = normal_force(r, i, l);
      const double ft = std::max(std::abs(r.dyn.contact_force(i, 3 * l)),
                                 std::abs(r.dyn.contact_force(i, 3 * l + 1)));
      worst_friction = std::max(worst_friction, ft - reach * fn);
    }
    if (legs_in_phase(r, i, ContactPhase::kImpact) != 0) continue;
    // Without impacts the paper's μ = 0.3 holds every row, so a flag here is friction's.
    CHECK(ref.dyn.solver_status[i] == SolverStatus::kOptimal);
    if (r.dyn.solver_status[i] == SolverStatus::kRelaxed) {
      ++flagged_support;
      for (const std::string& row : named_rows(msg))
        CHECK((row == "trunk force y" || row == "trunk force x" || row == "trunk moment z"));
    }
    // The horizontal force the motion needs (the μ = 0.3 run, whose rows hold) beyond what
    // μ = 0.01 can give: that sample must be flagged at the trunk's y row.
    const double needed_y = std::abs(sum_force(ref, i, 1));
    if (needed_y > 1.5 * reach * sum_force(r, i, 2)) {
      ++must_slip;
      CHECK(r.dyn.solver_status[i] == SolverStatus::kRelaxed);
      CHECK(contains(msg, "trunk force y"));
      CHECK(std::abs(sum_force(r, i, 1)) <= reach * sum_force(r, i, 2) + 1e-6);
    }
  }
  CHECK(worst_friction <= 1e-6);
  CHECK(flagged_support > 50);
  CHECK(must_slip > 20);
}

// ---------------------------------------------------------------------------------------
// Torque limit too low
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: torque limit too low for the load", "[hard][allocation]") {
  const double limit = 1.0;  // N m; the paper's stance needs up to ~2 N m at the femurs
  // Both on the grid as built (output.tolerance 0): refined, each would have a grid of its own.
  const Scene scene = paper_with({{"allocation.torque_limit", "1.0"}, {"output.tolerance", "0"}});
  const RunResult r = run_scene(scene);
  const RunResult ref = run_scene(paper_with({{"output.tolerance", "0"}}));  // 6 N m
  const RobotModel model = build_robot_model(scene.robot);
  check_run_finite(r);
  REQUIRE(r.kin.time_s == ref.kin.time_s);
  const double mg = r.total_mass_kg * kGravity;
  int over = 0, torque_only = 0, unchanged = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    const std::string& msg = r.dyn.solver_messages[i];
    INFO("t = " << r.kin.time_s[i] << " s: " << msg);
    const Eigen::RowVectorXd tau = r.dyn.joint_torque.row(i);
    const double tau_max = tau.cwiseAbs().maxCoeff();
    // |τ| above the limit only on flagged samples.
    if (tau_max > limit + 1e-6) {
      ++over;
      CHECK(r.dyn.solver_status[i] == SolverStatus::kRelaxed);
    }
    if (legs_in_phase(r, i, ContactPhase::kImpact) != 0) continue;
    if (r.dyn.solver_status[i] == SolverStatus::kRelaxed) {
      // Outside impacts only torque rows give way (the weakest rows); each by exactly the
      // stored torque's excess over the limit, and the trunk still carries its weight.
      ++torque_only;
      CHECK(ref.dyn.solver_status[i] == SolverStatus::kOptimal);
      for (const std::string& row : named_rows(msg)) {
        REQUIRE(row.rfind("torque L", 0) == 0);
        const int leg = row[8] - '1';
        const std::string joint = row.substr(10);
        const int j = joint == "coxa" ? 0 : joint == "femur" ? 1 : 2;
        // (The message prints 3 significant digits.)
        CHECK(violation_of(msg, row) ==
              Approx(std::abs(tau[model.joint(leg, j)]) - limit).epsilon(5e-3).margin(1e-6));
      }
      CHECK(sum_force(r, i, 2) == Approx(mg).epsilon(0.03));
    } else if (ref.dyn.joint_torque.row(i).cwiseAbs().maxCoeff() <= limit - 1e-9 &&
               ref.dyn.solver_status[i] == SolverStatus::kOptimal) {
      // Where the 6 N m optimum is within 1 N m already, the low limit changes nothing.
      ++unchanged;
      CHECK((r.dyn.joint_torque.row(i) - ref.dyn.joint_torque.row(i)).cwiseAbs().maxCoeff() <=
            1e-6);
    }
  }
  CHECK(over > 100);
  CHECK(torque_only > 100);
  INFO("samples unchanged by the low limit: " << unchanged);
}

// ---------------------------------------------------------------------------------------
// Sample steps of 1e-5 s and of 0.5 s
// ---------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------
// 100 gait cycles
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: 100 gait cycles are periodic and take linear time", "[hard][pipeline]") {
  std::string durations = "[3.0";
  for (int k = 0; k < 98; ++k) durations += ", 2.6";
  durations += ", 3.0]";
  const Scene scene = paper_with({{"motion.cycle_durations", durations}, {"terrain.steps", "110"}});
  const RunResult r = run_scene(scene);
  const RunResult paper = run_scene(paper_with({}));
  check_run_finite(r);
  CHECK(r.dyn.impacts.size() == 600);
  CHECK(r.wall_time_s < 30.0);
  INFO("100 cycles: " << r.kin.samples() << " samples in " << r.wall_time_s << " s; paper: "
                      << paper.kin.samples() << " in " << paper.wall_time_s << " s");
  // Samples grow linearly: 98 cruise cycles of the paper's cruise cycle.
  const int paper_cycle2 = sample_at(paper, 5.6) - sample_at(paper, 3.0);
  CHECK(r.kin.samples() == Approx(paper.kin.samples() + 97.0 * paper_cycle2).epsilon(0.01));
  // Every relaxed sample is inside a touchdown transient, as in the paper's run.
  int relaxed_outside = 0;
  for (int i = 0; i < r.kin.samples(); ++i)
    relaxed_outside += r.dyn.solver_status[i] != SolverStatus::kOptimal &&
                       !contains(r.dyn.solver_messages[i], "(impact ");
  CHECK(relaxed_outside == 0);
  // Energy per cycle: the cruise cycles repeat the paper's cruise cycle; first and last
  // are the paper's ramp cycles.
  const double e_ramp_up = energy_between(paper, 0.0, 3.0);
  const double e_cruise = energy_between(paper, 3.0, 5.6);
  const double e_ramp_down = energy_between(paper, 5.6, paper.kin.time_s.back());
  CHECK(energy_between(r, 0.0, 3.0) == Approx(e_ramp_up).epsilon(1e-6));
  double lo = 1e300, hi = 0.0;
  for (int k = 0; k < 98; ++k) {
    const double e = energy_between(r, 3.0 + 2.6 * k, 3.0 + 2.6 * (k + 1));
    lo = std::min(lo, e);
    hi = std::max(hi, e);
  }
  INFO("cruise cycles: " << lo << " to " << hi << " J; paper's: " << e_cruise << " J");
  CHECK((hi - lo) <= 1e-6 * e_cruise);
  CHECK(lo == Approx(e_cruise).epsilon(1e-6));
  const double t_last = 3.0 + 2.6 * 98;
  CHECK(energy_between(r, t_last, r.kin.time_s.back()) == Approx(e_ramp_down).epsilon(1e-6));
  // hexdyn's own energy grows linearly with the cycles: the 100-cycle run costs the
  // three-cycle run plus 97 times what one more cruise cycle adds (a four-cycle run).
  const RunResult r3 = run_scene(paper_with({{"terrain.steps", "110"}}));
  const RunResult r4 = run_scene(
      paper_with({{"motion.cycle_durations", "[3.0, 2.6, 2.6, 3.0]"}, {"terrain.steps", "110"}}));
  const double e_cycle = r4.dyn.energy_total_J - r3.dyn.energy_total_J;
  CHECK(e_cycle == Approx(e_cruise).epsilon(5e-3));
  CHECK(r.dyn.energy_total_J == Approx(r3.dyn.energy_total_J + 97.0 * e_cycle).epsilon(1e-6));
}

// ---------------------------------------------------------------------------------------
// A swing that would hit a riser
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: swing over a 0.1 m riser with a 1 um clearance", "[hard][gait]") {
  // Risers twice the paper's and a clearance of 1e-6 m: the straight line from lift-off to
  // touchdown runs through the riser; the planner lifts to the upper tread + Δh first.
  const double clearance = 1e-6, riser = 0.1;
  const double z0 =
      riser * (0.412 / 0.25 + 0.5) + 0.13;  // the paper's 0.13 m above the tread-centre line
  const Scene scene = paper_with({{"gait.swing_clearance", num(clearance)},
                                  {"terrain.riser_height", num(riser)},
                                  {"motion.initial_position", "[0.0, 0.412, " + num(z0) + "]"}});
  const PreparedScene prep = prepare_scene(scene);
  const RunResult r = run_scene(scene);
  check_run_finite(r);
  CHECK(count_status(r, SolverStatus::kFailed) == 0);
  const Terrain terrain(scene.terrain);
  const TerrainParams& tp = scene.terrain;
  // Every sampled foot is on or above the terrain; support feet exactly on it.
  for (int i = 0; i < r.kin.samples(); ++i)
    for (int l = 0; l < prep.model.legs(); ++l) {
      const double x = r.kin.foot_position(i, 3 * l), y = r.kin.foot_position(i, 3 * l + 1),
                   z = r.kin.foot_position(i, 3 * l + 2);
      INFO("t = " << r.kin.time_s[i] << " s, " << leg_name(l) << " at (" << x << ", " << y << ", "
                  << z << ")");
      CHECK(z >= terrain.height(x, y) - 1e-12);
      if (r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kSwing))
        CHECK(z == Approx(terrain.height(x, y)).margin(1e-12));
    }
  // Densely along every swing, and at every riser a swing crosses.
  auto tread = [&](double y) {
    return static_cast<int>(std::floor((y - tp.first_riser_y_m) / tp.tread_depth_m)) + 1;
  };
  int crossings = 0;
  for (int leg = 0; leg < prep.model.legs(); ++leg)
    for (const Swing& sw : prep.plan.gait.legs[leg].swings) {
      INFO(leg_name(leg) << " swing from " << sw.t_liftoff_s << " s");
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      bool above = true;
      for (int k = 0; k <= 4000; ++k) {
        const Vec3 p = swing_foot_motion(sw, sw.t_liftoff_s + D * k / 4000.0).p_W;
        above = above && p.z() >= terrain.height(p.x(), p.y()) - 1e-12;
      }
      CHECK(above);
      for (int k = tread(sw.p_liftoff_W.y()) + 1; k <= tread(sw.p_touchdown_W.y()); ++k) {
        const double y_riser = tp.first_riser_y_m + (k - 1) * tp.tread_depth_m;
        const double top = terrain.height(0.0, y_riser);  // the tread above the riser
        // The straight path would pass below the riser's top edge ...
        const Vec3 &a = sw.p_liftoff_W, &b = sw.p_touchdown_W;
        CHECK(a.z() + (b.z() - a.z()) * (y_riser - a.y()) / (b.y() - a.y()) < top);
        // ... the planned one crosses it Δh above (bisection on the monotone transfer).
        double lo = sw.t_liftoff_s, hi = sw.t_touchdown_s;
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          (swing_foot_motion(sw, mid).p_W.y() < y_riser ? lo : hi) = mid;
        }
        const double z_cross = swing_foot_motion(sw, hi).p_W.z();
        CHECK(z_cross - top == Approx(clearance).margin(1e-12));
        ++crossings;
      }
    }
  CHECK(crossings >= 12);
}

}  // namespace hexdyn
