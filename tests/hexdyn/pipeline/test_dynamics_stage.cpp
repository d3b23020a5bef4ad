// The dynamic stage (dynamics_stage.hpp) on cheap scenes: one gait cycle of the paper's
// robot on the paper's stairs, sampled coarsely. Each result is checked against a second
// computation made here: energy against a trapezoid sum of Σ|τ ω| on a much finer grid
// (and the piecewise quadrature against closed forms), the cost of
// transport against the configured stride, impact peaks against the quasi-static weight
// share, the effective mass against the minimum kinetic energy of a unit normal foot
// velocity, the contact frame against its definition, a relaxed allocation against the
// same penalised problem solved as a plain QP with explicit slacks; infeasible scenes
// against the promise that they finish flagged, finite and named.
#include <Eigen/Cholesky>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/io/config.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/pipeline/dynamics_stage.hpp"
#include "hexdyn/allocation/ipopt.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// One gait cycle (the peak-speed form of `motion`) on the paper's uniform 0.1 s grid:
/// about 30 samples, none inside a touchdown transient.
std::vector<Override> cheap_overrides() {
  return {{"motion.cycle_durations", "null"}, {"motion.cycles", "1"},
          {"motion.peak_speed", "0.1"},       {"motion.ramp_duration", "0.5"},
          {"output.grid", "uniform"},         {"output.sample_step", "0.1"}};
}

Scene cheap_scene(std::vector<Override> extra = {}) {
  std::vector<Override> ov = cheap_overrides();
  ov.insert(ov.end(), extra.begin(), extra.end());
  return load_scene(kPaper, ov);
}

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

Vec3 foot_vec(const RowMatrix& m, int i, int l) { return m.row(i).segment<3>(3 * l).transpose(); }

/// Every number of a result is finite.
void check_finite(const RunResult& r) {
  CHECK(r.kin.joint_position.allFinite());
  CHECK(r.kin.joint_velocity.allFinite());
  CHECK(r.kin.joint_acceleration.allFinite());
  CHECK(r.dyn.joint_torque.allFinite());
  CHECK(r.dyn.contact_force.allFinite());
  CHECK(r.dyn.penetration.allFinite());
  CHECK(r.dyn.joint_power.allFinite());
  for (double p : r.dyn.total_power_W) CHECK(std::isfinite(p));
  for (double o : r.dyn.solver_objective) CHECK(std::isfinite(o));
  CHECK(std::isfinite(r.dyn.energy_total_J));
  CHECK(std::isfinite(r.dyn.cost_of_transport));
}

/// The stored torques are τ0 − Σ J_jᵀ F of the stored forces on every sample, relaxed
/// or not (the split recomputed from the sampled motion).
void check_torques_match_forces(const Scene& scene, const RunResult& r) {
  const RobotModel model = build_robot_model(scene.robot);
  RobotData data(model);
  for (int i = 0; i < r.kin.samples(); ++i) {
    const ContactSplit& s = contact_split(
        model, data, base_state_at(r.kin, i), r.kin.joint_position.row(i).transpose(),
        r.kin.joint_velocity.row(i).transpose(), r.kin.joint_acceleration.row(i).transpose());
    VecJ tau = s.tau0;
    double scale = 1.0 + s.tau0.cwiseAbs().maxCoeff();
    for (int l = 0; l < kLegs; ++l) {
      tau -= s.JjT[l] * foot_vec(r.dyn.contact_force, i, l);
      scale =
          std::max(scale, (s.JjT[l] * foot_vec(r.dyn.contact_force, i, l)).cwiseAbs().maxCoeff());
    }
    INFO("sample " << i);
    CHECK((r.dyn.joint_torque.row(i).transpose() - tau).cwiseAbs().maxCoeff() <= 1e-9 * scale);
  }
}

/// Kinetic energy of the robot [J] from the body velocities of robot_momentum (computed
/// body by body, independently of the mass matrix).
double kinetic_energy(const RobotModel& model, RobotData& data, const BaseState& base,
                      const VecJ& q, const VecJ& qd) {
  robot_momentum(model, data, base, q, qd);
  double ke = 0.0;
  for (int b = 0; b < kBodies; ++b) {
    const RigidInertia& in = model.inertia[b];
    const Mat3& R = data.X_world_body[b].R;
    const Vec3& w = data.omega_body_W[b];
    ke += 0.5 * in.mass_kg * data.v_com_body_W[b].squaredNorm() +
          0.5 * w.dot(R * in.inertia_com * R.transpose() * w);
  }
  return ke;
}

/// Effective mass of a foot along n with the trunk at rest, as the smallest kinetic
/// energy (×2) over leg joint rates that give the foot a unit velocity along n (the
/// impulse a unit normal velocity change costs). The leg's inertia comes from the
/// kinetic energy by polarisation, the foot Jacobian from the analytic leg kinematics.
double effective_mass_by_energy(const RobotModel& model, RobotData& data, const BaseState& base,
                                const VecJ& q, int leg, const Vec3& n_W) {
  BaseState still = base;
  still.v_W.setZero();
  still.omega_W.setZero();
  auto ke = [&](const Vec3& rates) {
    VecJ qd = VecJ::Zero();
    qd.segment<3>(joint_index(leg, 0)) = rates;
    return kinetic_energy(model, data, still, q, qd);
  };
  Mat3 M;
  for (int a = 0; a < 3; ++a) M(a, a) = 2.0 * ke(Vec3::Unit(a));
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      M(a, b) = M(b, a) = ke(Vec3::Unit(a) + Vec3::Unit(b)) - 0.5 * M(a, a) - 0.5 * M(b, b);
  const Mat3 J_W =
      base.W_R_B * model.R_B_H[leg] * leg_jacobian_H(model, leg, q.segment<3>(joint_index(leg, 0)));
  // Rates with nᵀ J q̇ = 1: q̇ = x0 + N z, x0 = a/|a|², N an orthonormal basis of a⊥.
  const Vec3 a = J_W.transpose() * n_W.normalized();
  const Vec3 x0 = a / a.squaredNorm();
  Eigen::Matrix<double, 3, 2> N;
  N.col(0) = a.unitOrthogonal();
  N.col(1) = a.normalized().cross(N.col(0));
  const Eigen::Vector2d z = -(N.transpose() * M * N).ldlt().solve(N.transpose() * M * x0);
  const Vec3 qd = x0 + N * z;
  return qd.dot(M * qd);
}

/// The L1-penalised objective the relaxed allocation minimises (allocation_qp.hpp):
/// f(x) + ρ Σ w_i · (violation of row i at x), violations in row units.
double penalised_objective(const QpProblem& p, const Eigen::VectorXd& x, double rho) {
  double v = 0.0;
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    const double w = p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0;
    if (p.lower[i] > -kQpInfinity) v += w * std::max(0.0, p.lower[i] - c);
    if (p.upper[i] < kQpInfinity) v += w * std::max(0.0, c - p.upper[i]);
  }
  return p.objective(x) + rho * v;
}

/// The same minimisation written as an ordinary QP in (x, s): one slack s_i ≥ 0 per row,
/// lower_i − s_i ≤ C_i x ≤ upper_i + s_i, objective f(x) + ρ Σ w_i s_i (a 1e-12 diagonal
/// keeps H definite). Its optimum is the penalised optimum.
QpProblem explicit_slack_problem(const QpProblem& p, double rho) {
  const int n = p.variables(), m = p.inequalities();
  QpProblem q;
  q.resize(n + m, 0, 3 * m);
  q.H.topLeftCorner(n, n) = p.H;
  q.H.bottomRightCorner(m, m).diagonal().setConstant(1e-12);
  q.g.head(n) = p.g;
  q.constant = p.constant;
  for (int i = 0; i < m; ++i) {
    q.g[n + i] = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
    q.C.row(i).head(n) = p.C.row(i);
    q.C(i, n + i) = 1.0;
    q.lower[i] = p.lower[i];
    q.C.row(m + i).head(n) = p.C.row(i);
    q.C(m + i, n + i) = -1.0;
    q.upper[m + i] = p.upper[i];
    q.C(2 * m + i, n + i) = 1.0;
    q.lower[2 * m + i] = 0.0;
  }
  return q;
}

/// Allocation problem of the paper scene at time t (phases and impact forces as the run
/// sets them); returns the number of legs in their touchdown transient.
int paper_problem_at(const Scene& scene, double t, QpProblem& qp) {
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  RobotKinematicState s;
  robot_state_at(model, plan, t, s);
  BaseState base;
  base.W_R_B = s.trunk.W_R_B;
  base.p_W = s.trunk.p_W;
  base.v_W = s.trunk.v_W;
  base.omega_W = s.trunk.omega_W;
  base.a_W = s.trunk.a_W;
  base.omegadot_W = s.trunk.omegadot_W;
  const ContactSplit& split = contact_split(model, data, base, s.q, s.qd, s.qdd);
  std::array<ContactPhase, kLegs> phase{};
  std::array<double, kLegs> f_impact{};
  std::array<Mat3, kLegs> W_R_c;
  std::array<int, kLegs> offset{};
  int impacts = 0;
  for (int l = 0; l < kLegs; ++l) {
    phase[l] = s.feet[l].in_swing ? ContactPhase::kSwing : ContactPhase::kSupport;
    W_R_c[l] = contact_frame(plan.terrain.normal(s.feet[l].p_W.x(), s.feet[l].p_W.y()));
  }
  for (const Touchdown& td : tds) {
    if (!td.transient.occurred || t < td.t_s || t >= td.t_s + td.transient.duration_s) continue;
    phase[td.leg] = ContactPhase::kImpact;
    f_impact[td.leg] = transient_force_at(td.transient, t - td.t_s);
    ++impacts;
  }
  build_allocation_problem(scene.allocation, scene.contact, split, phase, f_impact, W_R_c, qp,
                           offset, nullptr);
  return impacts;
}

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

}  // namespace

/// Trapezoid sum of Σ_k |τ_k ω_k| over a result's samples [J].
double trapezoid_energy(const RunResult& r) {
  double E = 0.0;
  for (int i = 0; i + 1 < r.kin.samples(); ++i)
    E += 0.5 * (r.kin.time_s[i + 1] - r.kin.time_s[i]) * (r.dyn.total_power_W[i] + r.dyn.total_power_W[i + 1]);
  return E;
}

TEST_CASE("integrate_pieces: piecewise-smooth series with jumps, against the closed form", "[dynamics_stage]") {
  // y = 2 + sin(3t) on [0, 1), 5 + t² on [1, 1.5), 1 + cos t on [1.5, 2]: jumps at 1 and
  // 1.5, where the sample holds the value after the jump and the left limit is given.
  auto y_of = [](double t) { return t < 1.0 ? 2.0 + std::sin(3.0 * t) : t < 1.5 ? 5.0 + t * t : 1.0 + std::cos(t); };
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
    const double value = with_breaks ? integrate_pieces(t, y.data(), 1, breaks, left) : integrate_series(t, y.data());
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
  CHECK(integrate_pieces(t2, yy, 2, {1}, {5.0}) == Approx(0.5 * (1.0 + 5.0) + 0.5 * 2.0 * (3.0 + 10.0)));
}

TEST_CASE("integrate_pieces: never below zero for a power series with kinks", "[dynamics_stage]") {
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
  for (int k = 0; k + 3 < 41; ++k) CHECK(integrate_series({t[k], t[k + 1], t[k + 2], t[k + 3]}, &y[k]) >= 0.0);
}

TEST_CASE("dynamics stage: energy is the integral of the power series, and the cost of transport",
          "[dynamics_stage]") {
  // A non-uniform grid (refined at events) exercises the integration with varying steps.
  const Scene scene = cheap_scene(
      {{"output.grid", "adaptive"}, {"output.event_step", "0.01"}, {"output.impact_samples", "2"}});
  const RunResult r = run_scene(scene);
  const KinematicsResult& k = r.kin;
  const DynamicsResult& d = r.dyn;
  const int T = k.samples();
  REQUIRE(T > 30);
  check_finite(r);
  // Grid steps do vary.
  double h_min = 1e9, h_max = 0.0;
  for (int i = 0; i + 1 < T; ++i) {
    h_min = std::min(h_min, k.time_s[i + 1] - k.time_s[i]);
    h_max = std::max(h_max, k.time_s[i + 1] - k.time_s[i]);
  }
  REQUIRE(h_max > 10.0 * h_min);

  // Power per joint and in total, from the torques and the joint rates.
  std::vector<double> P(T, 0.0);
  for (int i = 0; i < T; ++i) {
    for (int j = 0; j < kJoints; ++j) {
      const double p = d.joint_torque(i, j) * k.joint_velocity(i, j);
      CHECK(d.joint_power(i, j) == p);
      P[i] += std::abs(p);
    }
    CHECK(std::abs(d.total_power_W[i] - P[i]) <= 1e-14 * std::max(1.0, P[i]));
  }
  // Energy: against a second quadrature, the trapezoid sum of Σ|τ ω| on a grid a hundred
  // times finer everywhere (1 ms, 10 µs at events: a jump smeared over 10 µs costs
  // ~1e-6), which it must match far better than the trapezoid on its own grid does.
  const RunResult fine = run_scene(cheap_scene({{"output.grid", "adaptive"},
                                                {"output.sample_step", "1e-3"},
                                                {"output.event_step", "1e-5"},
                                                {"output.impact_samples", "200"}}));
  const double E_fine = trapezoid_energy(fine);
  const double E = d.energy_total_J;
  REQUIRE(E > 0.0);
  CAPTURE(E, E_fine, trapezoid_energy(r));
  CHECK(std::abs(E - E_fine) <= 1e-3 * E_fine);
  CHECK(std::abs(trapezoid_energy(r) - E_fine) > 5.0 * std::abs(E - E_fine));
  // The fine run's own energy converges to the same value.
  CHECK(std::abs(fine.dyn.energy_total_J - E_fine) <= 1e-5 * E_fine);
  REQUIRE(d.energy_joint_J.size() == static_cast<std::size_t>(kJoints));
  double sum_joint = 0.0;
  for (int j = 0; j < kJoints; ++j) {
    INFO("joint " << j);
    double E_joint_fine = 0.0;
    for (int i = 0; i + 1 < fine.kin.samples(); ++i)
      E_joint_fine += 0.5 * (fine.kin.time_s[i + 1] - fine.kin.time_s[i]) *
                      (std::abs(fine.dyn.joint_power(i, j)) + std::abs(fine.dyn.joint_power(i + 1, j)));
    CHECK(std::abs(d.energy_joint_J[j] - E_joint_fine) <= 5e-3 * std::max(E_joint_fine, 1e-2 * E));
    sum_joint += d.energy_joint_J[j];
  }
  CHECK(std::abs(sum_joint - E) <= 1e-12 * E);

  // Cost of transport E / (m g d): mass summed from the configured bodies, d the trunk
  // travel along the slope, s0/β per cycle horizontally.
  const RobotParams& rp = scene.robot;
  const double m = rp.trunk.mass_kg + rp.payload.mass_kg +
                   kLegs * (rp.link[0].mass_kg + rp.link[1].mass_kg + rp.link[2].mass_kg);
  const double slope = std::atan(scene.terrain.riser_height_m / scene.terrain.tread_depth_m);
  const double distance =
      scene.motion.cycles * (scene.gait.stroke_m / scene.gait.duty_factor) / std::cos(slope);
  CHECK(scene.motion.cycles == 1);
  CHECK(std::abs(r.total_mass_kg - m) <= 1e-12 * m);
  CHECK(std::abs(d.distance_m - distance) <= 1e-12 * distance);
  CHECK(std::abs(d.cost_of_transport - E / (m * kGravity * distance)) <=
        1e-12 * d.cost_of_transport);
  // The trunk did travel that far.
  const Vec3 travel = k.base_position.row(T - 1) - k.base_position.row(0);
  CHECK(std::abs(travel.norm() - distance) <= 1e-9);

  // One impact record per touchdown (every swing ends in one) at the swing's end.
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  std::vector<std::pair<int, double>> swing_ends;
  for (int l = 0; l < kLegs; ++l)
    for (const Swing& sw : plan.gait.legs[l].swings) swing_ends.emplace_back(l, sw.t_touchdown_s);
  REQUIRE(d.impacts.size() == swing_ends.size());
  for (const ImpactRecord& rec : d.impacts) {
    const auto hit = std::count_if(swing_ends.begin(), swing_ends.end(), [&](const auto& e) {
      return e.first == rec.leg && e.second == rec.t_start_s;
    });
    CHECK(hit == 1);
  }
}

TEST_CASE(
    "dynamics stage: each paper touchdown gives one impact above the quasi-static weight share",
    "[dynamics_stage]") {
  const Scene scene = load_scene(kPaper);
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  std::size_t swings = 0;
  for (const LegPlan& leg : plan.gait.legs) swings += leg.swings.size();
  REQUIRE(swings > 0);
  REQUIRE(tds.size() == swings);
  const double mg = model.total_mass_kg * kGravity;
  for (const Touchdown& td : tds) {
    INFO("leg L" << td.leg + 1 << " at t = " << td.t_s << " s");
    // One touchdown per swing of that leg, at its end, with the configured speed.
    const auto& sws = plan.gait.legs[td.leg].swings;
    CHECK(std::count_if(sws.begin(), sws.end(),
                        [&](const Swing& s) { return s.t_touchdown_s == td.t_s; }) == 1);
    CHECK(std::abs(td.approach_speed_mps - scene.gait.touchdown_speed_mps) <= 1e-12);
    CHECK(td.normal_W == Vec3::UnitZ());
    REQUIRE(td.transient.occurred);
    CHECK_FALSE(td.transient.truncated);
    CHECK(td.transient.duration_s > 0.0);
    // Feet in support just after the transient (the plan's stance legs).
    const double t_after = td.t_s + td.transient.duration_s + 1e-9;
    int support = 0;
    for (const LegPlan& leg : plan.gait.legs) support += !leg_foot_motion(leg, t_after).in_swing;
    REQUIRE(support >= 3);
    INFO("peak " << td.transient.peak_force_N << " N, share " << mg / support << " N of " << support
                 << " feet");
    CHECK(td.transient.peak_force_N > mg / support);
    // The peak lies inside the transient and is the largest sampled force.
    CHECK(td.transient.time_of_peak_s > 0.0);
    CHECK(td.transient.time_of_peak_s < td.transient.duration_s);
    CHECK(*std::max_element(td.transient.force_N.begin(), td.transient.force_N.end()) <=
          td.transient.peak_force_N * (1.0 + 1e-12));
  }
}

TEST_CASE("dynamics stage: a touchdown at zero approach speed produces no impact",
          "[dynamics_stage]") {
  // Adaptive grid: had a transient occurred, samples would fall inside it.
  const Scene scene = cheap_scene({{"gait.touchdown_speed", "0"},
                                   {"output.grid", "adaptive"},
                                   {"output.event_step", "0.01"},
                                   {"output.impact_samples", "4"}});
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  REQUIRE(!tds.empty());
  for (const Touchdown& td : tds) {
    INFO("leg L" << td.leg + 1 << " at t = " << td.t_s << " s");
    CHECK(std::abs(td.approach_speed_mps) <= 1e-12);
    CHECK_FALSE(td.transient.occurred);
    CHECK(td.transient.peak_force_N == 0.0);
    CHECK(td.transient.impulse_Ns == 0.0);
    CHECK(transient_force_at(td.transient, 1e-5) == 0.0);
  }
  const RunResult r = run_scene(scene);
  check_finite(r);
  CHECK(r.dyn.impacts.empty());
  int touchdown_samples = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    INFO("sample " << i << " t = " << r.kin.time_s[i] << " s: " << r.dyn.solver_messages[i]);
    for (int l = 0; l < kLegs; ++l) CHECK(r.kin.contact_phase(i, l) != 1);
    CHECK_FALSE(contains(r.dyn.solver_messages[i], "impact"));
    CHECK(r.dyn.solver_status[i] == 0);
    for (const Touchdown& td : tds) touchdown_samples += r.kin.time_s[i] == td.t_s;
  }
  // The grid does hold the touchdown instants, where an impact would start.
  CHECK(touchdown_samples > 0);
}

TEST_CASE("dynamics stage: foot effective mass equals the minimum-energy normal impulse",
          "[dynamics_stage]") {
  // The paper's touchdowns, in the state at touchdown.
  const Scene scene = load_scene(kPaper);
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  REQUIRE(!tds.empty());
  RobotKinematicState s;
  for (const Touchdown& td : tds) {
    robot_state_at(model, plan, td.t_s, s);
    BaseState base;
    base.W_R_B = s.trunk.W_R_B;
    base.p_W = s.trunk.p_W;
    const double expected = effective_mass_by_energy(model, data, base, s.q, td.leg, td.normal_W);
    INFO("leg L" << td.leg + 1 << " at t = " << td.t_s << " s: " << td.effective_mass_kg << " vs "
                 << expected);
    CHECK(std::abs(td.effective_mass_kg - expected) <= 1e-10 * expected);
    // Bounded by the leg's mass: the foot never drags more than its own leg.
    CHECK(expected <
          scene.robot.link[0].mass_kg + scene.robot.link[1].mass_kg + scene.robot.link[2].mass_kg);
  }
  // Random robots, states and directions; base velocities do not matter.
  std::mt19937 rng(20240611);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const RobotModel rm = build_robot_model(test::random_robot_params(rng));
    RobotData rd(rm);
    BaseState base;
    base.W_R_B = random_rotation(rng);
    base.p_W = Vec3(g(rng), g(rng), g(rng));
    base.v_W = Vec3(g(rng), g(rng), g(rng));
    base.omega_W = Vec3(g(rng), g(rng), g(rng));
    VecJ q;
    for (int l = 0; l < kLegs; ++l) q.segment<3>(joint_index(l, 0)) = test::random_leg_angles(rng);
    const int leg = trial % kLegs;
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const double got = foot_effective_mass(rm, rd, base, q, leg, n);
    const double expected = effective_mass_by_energy(rm, rd, base, q, leg, n);
    INFO("trial " << trial << ": " << got << " vs " << expected);
    CHECK(std::isfinite(got));
    CHECK(got > 0.0);
    CHECK(std::abs(got - expected) <= 1e-9 * expected);
  }
}

/// Checks every sample of `r`: none failed, each relaxed one's message passes `named`;
/// with a torque limit > 0, each optimal one has no message and |τ| within the limit.
/// Returns the number of relaxed samples.
static int check_flagged_samples(const RunResult& r, const std::function<bool(const std::string&)>& named,
                                 double torque_limit_Nm = 0.0) {
  int relaxed = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    const int st = r.dyn.solver_status[i];
    const std::string& msg = r.dyn.solver_messages[i];
    INFO("sample " << i << " t = " << r.kin.time_s[i] << " s, status " << st << ": " << msg);
    CHECK(st != 2);
    if (st == 1) {
      ++relaxed;
      CHECK(named(msg));
    }
    if (st == 0 && torque_limit_Nm > 0.0) {
      CHECK(msg.empty());
      CHECK(r.dyn.joint_torque.row(i).cwiseAbs().maxCoeff() <= torque_limit_Nm + 1e-6);
    }
  }
  return relaxed;
}

TEST_CASE(
    "dynamics stage: a torque limit that cannot hold gives flagged, finite samples naming torques",
    "[dynamics_stage]") {
  const Scene scene = cheap_scene({{"allocation.torque_limit", "0.5"}});
  RunResult r;
  REQUIRE_NOTHROW(r = run_scene(scene));
  check_finite(r);
  const int relaxed = check_flagged_samples(r, [](const std::string& msg) { return contains(msg, "torque"); }, 0.5);
  CHECK(relaxed > 0);
  check_torques_match_forces(scene, r);
}

TEST_CASE(
    "dynamics stage: friction that cannot hold gives flagged, finite samples naming friction or "
    "trunk",
    "[dynamics_stage]") {
  const Scene scene = cheap_scene({{"contact.friction_coefficient", "0.01"}});
  RunResult r;
  REQUIRE_NOTHROW(r = run_scene(scene));
  check_finite(r);
  const int relaxed = check_flagged_samples(
      r, [](const std::string& msg) { return contains(msg, "friction") || contains(msg, "trunk"); });
  CHECK(relaxed > 0);
  check_torques_match_forces(scene, r);
}

TEST_CASE("dynamics stage: a relaxed allocation minimises the penalised violation",
          "[dynamics_stage]") {
  // Samples whose rows cannot all hold: inside the paper's touchdown transients (the
  // known impact forces), and during stance with a 0.5 N m torque limit. The scene's back
  // end's answer must be the minimiser of its penalised problem, which Ipopt finds as a
  // plain QP once the slacks are explicit variables (too many for the active-set back end).
  struct Case {
    std::vector<Override> overrides;
    double t_s;
  };
  const std::vector<Case> cases = {{{}, 3.0001},
                                   {{}, 1.7002},
                                   {{{"allocation.torque_limit", "0.5"}}, 0.1},
                                   {{{"allocation.torque_limit", "0.5"}}, 2.0}};
  for (const Case& c : cases) {
    const Scene scene = load_scene(kPaper, c.overrides);
    const double rho = ipopt_options_from(scene.allocation).slack_penalty;
    QpProblem qp;
    paper_problem_at(scene, c.t_s, qp);
    auto backend = make_allocation_backend(scene.allocation);
    const QpOutcome relaxed = backend->solve(qp);
    const QpProblem explicit_qp = explicit_slack_problem(qp, rho);
    auto ipopt = make_ipopt_backend(ipopt_options_from(scene.allocation));
    const QpOutcome reference = ipopt->solve(explicit_qp);
    const Eigen::VectorXd x_ref = reference.x.head(qp.variables());
    const double j_relaxed = penalised_objective(qp, relaxed.x, rho);
    const double j_ref = penalised_objective(qp, x_ref, rho);
    INFO("t = " << c.t_s << " s" << (c.overrides.empty() ? "" : ", torque limit 0.5 N m")
                << ": relaxed " << relaxed.message);
    INFO("penalised objective: back end "
         << j_relaxed << ", minimum " << j_ref
         << "; violations at the minimum: " << describe_violations(qp, x_ref, 1e-9));
    REQUIRE(reference.status == 0);
    CHECK(relaxed.status == 1);
    CHECK(j_relaxed <= j_ref + 1e-6 * std::abs(j_ref));
  }
}

TEST_CASE("dynamics stage: contact frames are orthonormal, right-handed, with n third",
          "[dynamics_stage]") {
  std::vector<Vec3> normals = {Vec3::UnitZ(),   -Vec3::UnitZ(),         Vec3::UnitX(),
                               -Vec3::UnitX(),  Vec3::UnitY(),          Vec3(1.0, 0.0, 1e-12),
                               Vec3(0, 0, 7.0), Vec3(0.0, -0.196, 0.98)};
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < 200; ++k) normals.emplace_back(g(rng), g(rng), g(rng));
  for (const Vec3& n : normals) {
    INFO("n = " << n.transpose());
    const Mat3 R = contact_frame(n);
    CHECK(R.allFinite());
    CHECK((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() <= 1e-14);
    CHECK(std::abs(R.determinant() - 1.0) <= 1e-14);
    CHECK((R.col(2) - n.normalized()).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((R.col(0).cross(R.col(1)) - R.col(2)).cwiseAbs().maxCoeff() <= 1e-14);
    // t1 is the world x axis made orthogonal to n, when x is not along n.
    const Vec3 x_perp = Vec3::UnitX() - n.normalized().x() * n.normalized();
    if (x_perp.norm() > 1e-6)
      CHECK((R.col(0) - x_perp.normalized()).cwiseAbs().maxCoeff() <= 1e-12);
  }
  // On a tread the frame is the world frame.
  CHECK((contact_frame(Vec3::UnitZ()) - Mat3::Identity()).cwiseAbs().maxCoeff() == 0.0);
}

}  // namespace hexdyn
