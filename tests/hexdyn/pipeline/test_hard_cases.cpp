// Hard cases (README "Hard cases"): each runs the real pipeline (or the touchdown ODE
// alone) on a scene at the edge of what the model can do and checks exactly what comes
// out — finite datasets with the flags set where they must be, or one named exception —
// and, where possible, the numbers against a second computation made here:
//  - stiff contact: momentum balance of every touchdown, the closed-form undamped impact,
//    the sampled impact peak against the ODE's located peak, and the trunk's vertical
//    balance (the other feet cannot pull) against the flags;
//  - a leg within 1e-6 rad of full extension: the IK margin scanned here on the run's
//    sample times, the tibia angle from the law of cosines;
//  - nearly collinear support feet: the tipping moment M g Δy of the COM about the feet;
//  - μ = 0.01 and a low torque limit: the paper run with the same grid, whose rows hold;
//  - sample steps 1e-5 s and 0.5 s: the ODE's peak and impulse, the default grid's energy;
//  - 100 gait cycles: the paper run's cycles, cycle by cycle;
//  - a swing over a tall riser with a tiny clearance: Terrain::height under the foot.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/io/config.hpp"
#include "hexdyn/contact/impact.hpp"
#include "hexdyn/pipeline/dynamics_stage.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/terrain.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

Scene paper_with(const std::vector<Override>& overrides) { return load_scene(kPaper, overrides); }

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

template <typename Matrix>
bool finite(const Matrix& m) {
  return m.allFinite();
}
bool finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

/// Every dataset of a run is finite: kinematics, torques, forces, penetration, power,
/// energies, solver diagnostics and impact records; statuses are 0 or 1 (never failed)
/// and a message accompanies exactly the relaxed samples.
void check_run_finite(const RunResult& r) {
  const KinematicsResult& k = r.kin;
  const DynamicsResult& d = r.dyn;
  REQUIRE(d.present);
  REQUIRE(k.samples() > 1);
  CHECK(finite(k.time_s));
  CHECK(finite(k.base_position));
  CHECK(finite(k.base_linear_velocity));
  CHECK(finite(k.base_linear_acceleration));
  CHECK(finite(k.joint_position));
  CHECK(finite(k.joint_velocity));
  CHECK(finite(k.joint_acceleration));
  CHECK(finite(k.foot_position));
  CHECK(finite(k.foot_velocity));
  CHECK(finite(k.com_position));
  CHECK(finite(d.joint_torque));
  CHECK(finite(d.contact_force));
  CHECK(finite(d.penetration));
  CHECK(d.penetration.minCoeff() >= 0.0);
  CHECK(finite(d.joint_power));
  CHECK(finite(d.total_power_W));
  CHECK(finite(d.energy_joint_J));
  CHECK(finite(d.solver_objective));
  CHECK(std::isfinite(d.energy_total_J));
  CHECK(d.energy_total_J >= 0.0);
  CHECK(std::isfinite(d.cost_of_transport));
  for (const ImpactRecord& im : d.impacts) {
    CHECK(std::isfinite(im.t_start_s));
    CHECK(std::isfinite(im.duration_s));
    CHECK(im.duration_s > 0.0);
    CHECK(std::isfinite(im.peak_force_N));
    CHECK(im.peak_force_N > 0.0);
    CHECK(std::isfinite(im.impulse_Ns));
    CHECK(std::isfinite(im.effective_mass_kg));
    CHECK(std::isfinite(im.approach_speed_mps));
  }
  bool statuses_ok = true, messages_ok = true;
  for (int i = 0; i < k.samples(); ++i) {
    statuses_ok = statuses_ok && (d.solver_status[i] == 0 || d.solver_status[i] == 1);
    messages_ok = messages_ok && (d.solver_messages[i].empty() == (d.solver_status[i] == 0));
  }
  CHECK(statuses_ok);
  CHECK(messages_ok);
}

int count_status(const RunResult& r, int status) {
  return static_cast<int>(std::count(r.dyn.solver_status.begin(), r.dyn.solver_status.end(), status));
}

int legs_in_phase(const RunResult& r, int i, ContactPhase ph) {
  int n = 0;
  for (int l = 0; l < kLegs; ++l) n += r.kin.contact_phase(i, l) == static_cast<std::int8_t>(ph);
  return n;
}

/// Normal force of foot l at sample i [N]: every foothold is on a tread (normal +z).
double normal_force(const RunResult& r, int i, int l) { return r.dyn.contact_force(i, 3 * l + 2); }

double sum_force(const RunResult& r, int i, int axis) {
  double s = 0.0;
  for (int l = 0; l < kLegs; ++l) s += r.dyn.contact_force(i, 3 * l + axis);
  return s;
}

/// The number after "NAME by " in a relaxed message; NaN when NAME is not named.
double violation_of(const std::string& msg, const std::string& name) {
  const auto at = msg.find(name + " by ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(msg.c_str() + at + name.size() + 4, nullptr);
}

/// The rows named by a relaxed message ("relaxed: A by x, B by y (impact ...)").
std::vector<std::string> named_rows(const std::string& msg) {
  std::vector<std::string> rows;
  std::string body = msg.substr(msg.find(':') + 1);
  body = body.substr(0, body.rfind(" (impact "));
  std::stringstream ss(body);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto by = item.find(" by ");
    std::string name = item.substr(0, by);
    name.erase(0, name.find_first_not_of(' '));
    rows.push_back(name);
  }
  return rows;
}

/// Index of the first sample at time t (±1e-9 s); −1 when none.
int sample_at(const RunResult& r, double t) {
  const auto& ts = r.kin.time_s;
  const auto it = std::lower_bound(ts.begin(), ts.end(), t - 1e-9);
  if (it == ts.end() || *it > t + 1e-9) return -1;
  return static_cast<int>(it - ts.begin());
}

/// ∫ Σ|τ ω| dt over [t0, t1] by the trapezoid rule on the samples (t0, t1 are samples).
double energy_between(const RunResult& r, double t0, double t1) {
  const int a = sample_at(r, t0), b = sample_at(r, t1);
  REQUIRE(a >= 0);
  REQUIRE(b > a);
  double e = 0.0;
  for (int i = a; i < b; ++i)
    e += 0.5 * (r.dyn.total_power_W[i] + r.dyn.total_power_W[i + 1]) * (r.kin.time_s[i + 1] - r.kin.time_s[i]);
  return e;
}


}  // namespace

// ---------------------------------------------------------------------------------------
// Stiff contact
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: stiff touchdown ODE, K to 1e9, e 1 to 3, p to 1e-9 m, v to 1 m/s", "[hard][contact]") {
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
                           std::isfinite(tr.penetration_m[i]) && (i == 0 || tr.t_s[i] > tr.t_s[i - 1]);
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
              const double tau = 2.0 * std::sqrt(M_PI) * std::tgamma(1.0 + 1.0 / n1) / std::tgamma(0.5 + 1.0 / n1);
              CHECK(tr.peak_force_N == Approx(K * std::pow(D, e)).epsilon(1e-8));
              CHECK(tr.max_penetration_m == Approx(D).epsilon(1e-8));
              CHECK(tr.duration_s == Approx(tau * D / v).epsilon(1e-7));
              CHECK(tr.rebound_speed_mps == Approx(v).epsilon(1e-8));
            }
          }
  CHECK(n == 72);
}

TEST_CASE("hard: stiff contact through the pipeline, K 1e9, p 1e-9 m, touchdown at 1 m/s", "[hard][contact]") {
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
    CHECK(count_status(r, 2) == 0);
    REQUIRE(prep.touchdowns.size() == r.dyn.impacts.size());
    REQUIRE(r.dyn.impacts.size() == 18);
    const double mg = r.total_mass_kg * kGravity;
    for (const Touchdown& td : prep.touchdowns) {
      INFO("touchdown of " << leg_name(td.leg) << " at " << td.t_s << " s");
      const ImpactTransient& tr = td.transient;
      REQUIRE(tr.occurred);
      CHECK_FALSE(tr.truncated);
      CHECK(td.approach_speed_mps == Approx(1.0).epsilon(1e-9));
      CHECK(tr.impulse_Ns == Approx(td.effective_mass_kg * (td.approach_speed_mps + tr.rebound_speed_mps)).epsilon(1e-9));
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
      for (int l = 0; l < kLegs; ++l)
        if (r.kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kImpact)) impact_z += normal_force(r, i, l);
      if (impact_z <= 2.0 * mg) continue;
      ++overloaded;
      INFO("t = " << r.kin.time_s[i] << " s: impact forces " << impact_z << " N: " << r.dyn.solver_messages[i]);
      CHECK(r.dyn.solver_status[i] == 1);
      CHECK(contains(r.dyn.solver_messages[i], "trunk force z"));
      CHECK(contains(r.dyn.solver_messages[i], "(impact "));
    }
    CHECK(overloaded > 18);
  }
}

TEST_CASE("hard: a soft, slow touchdown outlasts the 1 s guard: truncated, finite, flagged", "[hard][contact]") {
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
          Approx(td.effective_mass_kg * (td.approach_speed_mps + td.transient.rebound_speed_mps)).epsilon(1e-9));
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
    if (legs_in_phase(r, i, ContactPhase::kSupport) > 0 || legs_in_phase(r, i, ContactPhase::kImpact) == 0) continue;
    ++unsupported;
    INFO("t = " << r.kin.time_s[i] << " s: " << r.dyn.solver_messages[i]);
    CHECK(r.dyn.solver_status[i] == 1);
    CHECK(violation_of(r.dyn.solver_messages[i], "trunk force z") == Approx(mg).epsilon(0.05));
  }
  CHECK(unsupported > 100);
}

// ---------------------------------------------------------------------------------------
// A leg at full extension
// ---------------------------------------------------------------------------------------

namespace {

/// Foot of `leg` in its hip frame at time t, computed as robot_state_at does.
Vec3 foot_in_hip_frame(const RobotModel& model, const MotionPlan& plan, int leg, double t) {
  const TrunkState trunk = plan.trunk.at(t);
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
  for (int leg = 0; leg < kLegs; ++leg)
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
  INFO("farthest foot: " << leg_name(far.leg) << " at " << far.t_s << " s, " << far.distance_m << " m; tibia " << l3);

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
    const Scene scene = paper_with({{"output.grid", "uniform"}, {"robot.tibia.length", l3}, {"robot.ik_min_margin", "0"}});
    const RunResult r = run_scene(scene);
    check_run_finite(r);
    const int i = sample_at(r, far.t_s);
    REQUIRE(i >= 0);
    // The knee is ε short of straight (knee-up branch: β3 ≤ 0).
    const double beta3 = r.kin.joint_position(i, joint_index(far.leg, 2));
    CHECK(beta3 < 0.0);
    CHECK(-beta3 == Approx(eps).epsilon(0.01));
    // Near the singularity the joint rates are ~1/ε: huge, finite, and the sample is flagged
    // with the stretched leg's own torque row.
    CHECK(std::abs(r.kin.joint_velocity(i, joint_index(far.leg, 2))) > 1e3);
    INFO(r.dyn.solver_messages[i]);
    CHECK(r.dyn.solver_status[i] == 1);
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
      const Scene scene = paper_with({{"output.grid", "uniform"}, {"robot.tibia.length", num(l3_k)},
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

TEST_CASE("hard: three support feet nearly collinear", "[hard][allocation]") {
  // Hips 1 mm apart along the trunk: each tripod's feet stand on one line across the
  // stairs (a triangle 0.5 m wide and 2 mm deep), and the COM is off it by up to s0/2.
  const Scene scene = paper_with({{"robot.hips.y", "[0.001, 0.0, -0.001]"}});
  const RunResult r = run_scene(scene);
  check_run_finite(r);
  const double mg = r.total_mass_kg * kGravity;
  int tripods = 0;
  double worst_tipping = 0.0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    if (legs_in_phase(r, i, ContactPhase::kSupport) != 3 || legs_in_phase(r, i, ContactPhase::kImpact) != 0) continue;
    ++tripods;
    std::vector<Eigen::Vector2d> feet;
    double y_feet = 0.0;
    for (int l = 0; l < kLegs; ++l) {
      if (r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kSupport)) continue;
      feet.emplace_back(r.kin.foot_position(i, 3 * l), r.kin.foot_position(i, 3 * l + 1));
      y_feet += feet.back().y() / 3.0;
    }
    const Eigen::Vector2d a = feet[1] - feet[0], b = feet[2] - feet[0];
    const double area = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    const double side = std::max({a.norm(), b.norm(), (feet[2] - feet[1]).norm()});
    const double dy = r.kin.com_position(i, 1) - y_feet;
    const std::string& msg = r.dyn.solver_messages[i];
    INFO("t = " << r.kin.time_s[i] << " s, COM " << dy << " m off the feet: " << msg);
    CHECK(area / (side * side) < 3e-3);
    // The only row that gives way is the moment about the feet's line (trunk x), by the
    // tipping moment of the weight about that line; the weight itself is carried.
    CHECK(r.dyn.solver_status[i] == 1);
    CHECK(named_rows(msg) == std::vector<std::string>{"trunk moment x"});
    const double tipping = mg * std::abs(dy);
    worst_tipping = std::max(worst_tipping, tipping);
    CHECK(violation_of(msg, "trunk moment x") == Approx(tipping).margin(0.05 * tipping + 0.15));
    CHECK(sum_force(r, i, 2) == Approx(mg).epsilon(0.03));
  }
  CHECK(tripods > 0.4 * r.kin.samples());
  CHECK(worst_tipping > 3.0);
}

// ---------------------------------------------------------------------------------------
// μ = 0.01
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: friction coefficient 0.01", "[hard][allocation]") {
  const Scene scene = paper_with({{"contact.friction_coefficient", "0.01"}});
  const RunResult r = run_scene(scene);
  const RunResult ref = run_scene(paper_with({}));  // μ = 0.3, same grid
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
    CHECK_FALSE(contains(msg, "friction"));
    for (int l = 0; l < kLegs; ++l) {
      if (r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kSupport)) continue;
      const double fn = normal_force(r, i, l);
      const double ft = std::max(std::abs(r.dyn.contact_force(i, 3 * l)), std::abs(r.dyn.contact_force(i, 3 * l + 1)));
      worst_friction = std::max(worst_friction, ft - reach * fn);
    }
    if (legs_in_phase(r, i, ContactPhase::kImpact) != 0) continue;
    // Without impacts the paper's μ = 0.3 holds every row, so a flag here is friction's.
    CHECK(ref.dyn.solver_status[i] == 0);
    if (r.dyn.solver_status[i] == 1) {
      ++flagged_support;
      for (const std::string& row : named_rows(msg)) CHECK((row == "trunk force y" || row == "trunk force x" || row == "trunk moment z"));
    }
    // The horizontal force the motion needs (the μ = 0.3 run, whose rows hold) beyond what
    // μ = 0.01 can give: that sample must be flagged at the trunk's y row.
    const double needed_y = std::abs(sum_force(ref, i, 1));
    if (needed_y > 1.5 * reach * sum_force(r, i, 2)) {
      ++must_slip;
      CHECK(r.dyn.solver_status[i] == 1);
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
  const Scene scene = paper_with({{"allocation.torque_limit", "1.0"}});
  const RunResult r = run_scene(scene);
  const RunResult ref = run_scene(paper_with({}));  // 6 N m, same grid
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
      CHECK(r.dyn.solver_status[i] == 1);
    }
    if (legs_in_phase(r, i, ContactPhase::kImpact) != 0) continue;
    if (r.dyn.solver_status[i] == 1) {
      // Outside impacts only torque rows give way (the weakest rows); each by exactly the
      // stored torque's excess over the limit, and the trunk still carries its weight.
      ++torque_only;
      CHECK(ref.dyn.solver_status[i] == 0);
      for (const std::string& row : named_rows(msg)) {
        REQUIRE(row.rfind("torque L", 0) == 0);
        const int leg = row[8] - '1';
        const std::string joint = row.substr(10);
        const int j = joint == "coxa" ? 0 : joint == "femur" ? 1 : 2;
        // (The message prints 3 significant digits.)
        CHECK(violation_of(msg, row) == Approx(std::abs(tau[joint_index(leg, j)]) - limit).epsilon(5e-3).margin(1e-6));
      }
      CHECK(sum_force(r, i, 2) == Approx(mg).epsilon(0.03));
    } else if (ref.dyn.joint_torque.row(i).cwiseAbs().maxCoeff() <= limit - 1e-9 && ref.dyn.solver_status[i] == 0) {
      // Where the 6 N m optimum is within 1 N m already, the low limit changes nothing.
      ++unchanged;
      CHECK((r.dyn.joint_torque.row(i) - ref.dyn.joint_torque.row(i)).cwiseAbs().maxCoeff() <= 1e-6);
    }
  }
  CHECK(over > 100);
  CHECK(torque_only > 100);
  INFO("samples unchanged by the low limit: " << unchanged);
}

// ---------------------------------------------------------------------------------------
// Sample steps of 1e-5 s and of 0.5 s
// ---------------------------------------------------------------------------------------

TEST_CASE("hard: sample step 1e-5 s resolves every touchdown transient", "[hard][grid]") {
  // One gait cycle at 0.3 m/s with the paper's 0.8 s ramps (1.65 s, 165 000 uniform
  // samples, ~3 s of run time).
  const std::vector<Override> shorter = {{"motion.cycle_durations", "null"}, {"motion.cycles", "1"},
                                         {"motion.peak_speed", "0.3"},       {"motion.ramp_duration", "0.8"}};
  std::vector<Override> fine = shorter;
  fine.insert(fine.end(), {{"output.grid", "uniform"}, {"output.sample_step", "1e-5"}, {"output.event_step", "1e-5"}});
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
    INFO("touchdown of " << leg_name(td.leg) << " at " << td.t_s << " s, " << tr.duration_s << " s long");
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
    for (std::size_t k = 0; k + 1 < t.size(); ++k) impulse += 0.5 * (f[k] + f[k + 1]) * (t[k + 1] - t[k]);
    CHECK(inside >= static_cast<int>(tr.duration_s / 1e-5) - 1);
    // Some sample lies within half a step of the located peak, and the force is unimodal:
    // the sampled peak is at least the lower of the two forces half a step either side.
    const double half = 0.5e-5;
    const double bound = std::min(transient_force_at(tr, tr.time_of_peak_s - half), transient_force_at(tr, tr.time_of_peak_s + half));
    CHECK(peak <= tr.peak_force_N * (1.0 + 1e-9));
    CHECK(peak >= bound * (1.0 - 1e-9));
    CHECK(peak == Approx(tr.peak_force_N).epsilon(0.015));
    worst_peak = std::max(worst_peak, 1.0 - peak / tr.peak_force_N);
    CHECK(impulse == Approx(tr.impulse_Ns).epsilon(0.01));
  }
  // Flags only inside the transients (the impact tripod cannot carry the trunk).
  int relaxed_outside = 0;
  for (int i = 0; i < T; ++i)
    relaxed_outside += r.dyn.solver_status[i] != 0 && legs_in_phase(r, i, ContactPhase::kImpact) == 0;
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
    for (int i = 0; i < r.kin.samples(); ++i) impact_samples += legs_in_phase(r, i, ContactPhase::kImpact) > 0;
    CHECK(impact_samples > 18 * paper_with({}).output.impact_samples);
    // Between events the power is sampled up to 0.5 s apart: the smooth part of the
    // integral loses ~2%.
    CHECK(r.dyn.energy_total_J == Approx(ref.dyn.energy_total_J).epsilon(0.025));
  }
  SECTION("uniform grid: 19 samples, no transient sampled, energy within 5% of the default grid's") {
    const RunResult r = run_scene(paper_with({{"output.sample_step", "0.5"}, {"output.grid", "uniform"}}));
    check_run_finite(r);
    CHECK(r.kin.samples() == 19);
    // The transients (0.46 ms) fall between samples: no sample in impact, none relaxed;
    // the 18 touchdowns are still in /impacts with their peaks.
    int impact_samples = 0;
    for (int i = 0; i < r.kin.samples(); ++i) impact_samples += legs_in_phase(r, i, ContactPhase::kImpact) > 0;
    CHECK(impact_samples == 0);
    CHECK(count_status(r, 1) == 0);
    REQUIRE(r.dyn.impacts.size() == ref.dyn.impacts.size());
    for (std::size_t k = 0; k < r.dyn.impacts.size(); ++k)
      CHECK(r.dyn.impacts[k].peak_force_N == ref.dyn.impacts[k].peak_force_N);
    CHECK(r.dyn.energy_total_J == Approx(ref.dyn.energy_total_J).epsilon(0.05));
  }
}

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
  INFO("100 cycles: " << r.kin.samples() << " samples in " << r.wall_time_s << " s; paper: " << paper.kin.samples()
                      << " in " << paper.wall_time_s << " s");
  // Samples grow linearly: 98 cruise cycles of the paper's cruise cycle.
  const int paper_cycle2 = sample_at(paper, 5.6) - sample_at(paper, 3.0);
  CHECK(r.kin.samples() == Approx(paper.kin.samples() + 97.0 * paper_cycle2).epsilon(0.01));
  // Every relaxed sample is inside a touchdown transient, as in the paper's run.
  int relaxed_outside = 0;
  for (int i = 0; i < r.kin.samples(); ++i)
    relaxed_outside += r.dyn.solver_status[i] != 0 && !contains(r.dyn.solver_messages[i], "(impact ");
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
  const RunResult r4 = run_scene(paper_with({{"motion.cycle_durations", "[3.0, 2.6, 2.6, 3.0]"}, {"terrain.steps", "110"}}));
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
  const double z0 = riser * (0.412 / 0.25 + 0.5) + 0.13;  // the paper's 0.13 m above the tread-centre line
  const Scene scene = paper_with({{"gait.swing_clearance", num(clearance)},
                                  {"terrain.riser_height", num(riser)},
                                  {"motion.initial_position", "[0.0, 0.412, " + num(z0) + "]"}});
  const PreparedScene prep = prepare_scene(scene);
  const RunResult r = run_scene(scene);
  check_run_finite(r);
  CHECK(count_status(r, 2) == 0);
  const Terrain terrain(scene.terrain);
  const TerrainParams& tp = scene.terrain;
  // Every sampled foot is on or above the terrain; support feet exactly on it.
  for (int i = 0; i < r.kin.samples(); ++i)
    for (int l = 0; l < kLegs; ++l) {
      const double x = r.kin.foot_position(i, 3 * l), y = r.kin.foot_position(i, 3 * l + 1), z = r.kin.foot_position(i, 3 * l + 2);
      INFO("t = " << r.kin.time_s[i] << " s, " << leg_name(l) << " at (" << x << ", " << y << ", " << z << ")");
      CHECK(z >= terrain.height(x, y) - 1e-12);
      if (r.kin.contact_phase(i, l) != static_cast<std::int8_t>(ContactPhase::kSwing))
        CHECK(z == Approx(terrain.height(x, y)).margin(1e-12));
    }
  // Densely along every swing, and at every riser a swing crosses.
  auto tread = [&](double y) { return static_cast<int>(std::floor((y - tp.first_riser_y_m) / tp.tread_depth_m)) + 1; };
  int crossings = 0;
  for (int leg = 0; leg < kLegs; ++leg)
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
