// The paper scene end to end (pipeline.hpp), checked sample by sample against second
// computations that do not go through the allocation:
//  - the whole-robot momentum rate, differentiated numerically from robot_momentum of
//    the prescribed motion, equals gravity plus the stored contact forces (forces and
//    moments about the world origin);
//  - the trunk rows of the equations of motion and the joint torques, recomputed from
//    contact_split with the stored forces;
//  - friction, normal-force and torque limits, zero force on swing feet, impact forces
//    equal to the touchdown transients, penetrations from the spring law;
//  - the KKT conditions of the allocation QP, rebuilt and solved again with Ipopt on a
//    subset of samples, whose solution reproduces the stored forces;
//  - every number finite.
// The run takes most of the time: it is computed once (paper_run), and each SECTION of the
// one TEST_CASE checks one of these behaviours on it.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/kkt_check.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace hexdyn {
namespace {
using test::check_kkt;

/// Step of the momentum finite differences [s]. The stencils below are 4th order:
/// truncation ~h⁴·d⁵p/dt⁵ ≈ 1e-14 N, round-off ~10·ε·|p|/h ≈ 1e-11 N for |p| ≈ 1.
constexpr double kFdStep = 1e-4;

/// Agreement of an allocation re-solved with Ipopt with the stored (active-set) forces [N]:
/// Ipopt's tolerance (1e-9) fixes the forces to ~1e-5 N on the worst-conditioned samples
/// (measured 1.6e-5 N against a solve at tolerance 1e-13).
constexpr double kForceAgreement = 1e-4;

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

/// Instants where the prescribed motion is not smooth: the trunk's speed ramps begin and
/// end, and each swing's lift-off, end of lift, start of descent and touchdown (where
/// the foot velocity jumps to zero). Between two of them every position is C^∞.
std::vector<double> motion_breakpoints(const MotionPlan& plan) {
  const double T = plan.trunk.duration_s(), tr = plan.trunk.ramp_duration_s();
  std::vector<double> b = {0.0, tr, T - tr, T};
  for (const LegPlan& leg : plan.gait.legs) {
    for (const Swing& sw : leg.swings) {
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      b.push_back(sw.t_liftoff_s);
      b.push_back(sw.t_liftoff_s + sw.lift_end_u * D);
      b.push_back(sw.t_liftoff_s + sw.lower_start_u * D);
      b.push_back(sw.t_touchdown_s);
    }
  }
  std::sort(b.begin(), b.end());
  return b;
}

/// True when no breakpoint lies in [lo, hi] (or in (lo, hi] with open_lo).
bool smooth_on(const std::vector<double>& bp, double lo, double hi, bool open_lo) {
  for (double x : bp)
    if ((open_lo ? x > lo : x >= lo) && x <= hi) return false;
  return true;
}

struct MomentumRate {
  bool ok = false;
  Vec3 linear = Vec3::Zero();     ///< dP/dt [N]
  Vec3 angular_O = Vec3::Zero();  ///< dL_O/dt [N m], about the world origin
  Vec3 com_W = Vec3::Zero();      ///< whole-robot COM at t [m]
};

/// Momentum rate of the prescribed motion at t, by a 4th-order finite difference that
/// stays on the smooth piece the sample belongs to: central when no breakpoint lies
/// within 2h, otherwise one-sided forward (a sample at a breakpoint is on the later
/// piece: a touchdown sample is the first one on the ground) or backward.
MomentumRate momentum_rate(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                           const std::vector<double>& bp, double t, double h) {
  RobotKinematicState s;
  auto momentum_at = [&](double tt) {
    robot_state_at(model, plan, tt, s);
    return robot_momentum(model, data, s.trunk, s.q, s.qd);
  };
  MomentumRate r;
  const double* w = nullptr;
  double dir = 1.0;
  int first = 0;
  static constexpr double kCentral[5] = {1.0, -8.0, 0.0, 8.0, -1.0};       // offsets −2..2
  static constexpr double kForward[5] = {-25.0, 48.0, -36.0, 16.0, -3.0};  // offsets 0..4
  if (smooth_on(bp, t - 2 * h, t + 2 * h, false)) {
    w = kCentral, first = -2;
  } else if (smooth_on(bp, t, t + 4 * h, true)) {
    w = kForward, first = 0;
  } else if (smooth_on(bp, t - 4 * h, t, false)) {
    w = kForward, first = 0, dir = -1.0;
  } else {
    return r;
  }
  for (int k = 0; k < 5; ++k) {
    if (w[k] == 0.0) continue;
    const Momentum& m = momentum_at(t + dir * (first + k) * h);
    r.linear += dir * w[k] * m.linear_W;
    r.angular_O += dir * w[k] * m.angular_O_W;
  }
  r.linear /= 12.0 * h;
  r.angular_O /= 12.0 * h;
  r.com_W = momentum_at(t).com_W;
  r.ok = true;
  return r;
}

template <typename Matrix>
bool all_finite(const Matrix& m) {
  return m.allFinite();
}
bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

Vec3 foot_vec(const RowMatrix& m, int i, int l) { return m.row(i).segment<3>(3 * l).transpose(); }

/// The paper run and what the checks rebuild from its scene: model, plan, touchdown
/// transients and the motion's breakpoints (deterministic: the same as the run's).
struct PaperRun {
  Scene scene = load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml");
  std::ostringstream log;  ///< what the run printed
  RunResult run = run_scene(scene, &log);
  RobotModel model = build_robot_model(scene.robot);
  MotionPlan plan = plan_motion(scene, model);
  std::vector<Touchdown> touchdowns = [this] {
    RobotData data(model);
    return resolve_touchdowns(model, data, plan, scene.contact);
  }();
  std::vector<double> breakpoints = motion_breakpoints(plan);
  double mg = model.total_mass_kg * kGravity;  ///< weight [N]
};

/// The run takes most of the time: it is computed once for every section.
const PaperRun& paper_run() {
  static const PaperRun r;
  return r;
}

/// A relaxed sample may leave a row violated by the solver's tolerance without naming it.
constexpr double kUnnamedTolerance = 1e-6;

/// The stored contact forces of sample i [N], world axes, per leg.
std::array<Vec3, kPaperLegs> stored_forces(const DynamicsResult& dyn, int i) {
  std::array<Vec3, kPaperLegs> F;
  for (int l = 0; l < kPaperLegs; ++l) F[l] = foot_vec(dyn.contact_force, i, l);
  return F;
}

/// Some leg of sample i is in its touchdown transient.
bool any_impact_leg(const KinematicsResult& kin, int i) {
  bool any_impact = false;
  for (int l = 0; l < kPaperLegs; ++l) any_impact = any_impact || kin.contact_phase(i, l) == 1;
  return any_impact;
}

/// contact_split at sample i of the stored kinematics.
const ContactSplit& split_at(const RobotModel& model, RobotData& data, const KinematicsResult& kin,
                             int i) {
  const BaseState base = base_state_at(kin, i);
  const PaperJointVector q = kin.joint_position.row(i).transpose();
  const PaperJointVector qd = kin.joint_velocity.row(i).transpose();
  const PaperJointVector qdd = kin.joint_acceleration.row(i).transpose();
  return contact_split(model, data, base, q, qd, qdd);
}

void require_sizes(const RunResult& run) {
  const KinematicsResult& kin = run.kin;
  const DynamicsResult& dyn = run.dyn;
  const int T = kin.samples();
  REQUIRE(T > 100);
  REQUIRE(dyn.present);
  REQUIRE(dyn.joint_torque.rows() == T);
  REQUIRE(dyn.contact_force.rows() == T);
  REQUIRE(dyn.penetration.rows() == T);
  REQUIRE(dyn.joint_power.rows() == T);
  REQUIRE(static_cast<int>(dyn.solver_status.size()) == T);
  REQUIRE(static_cast<int>(dyn.solver_messages.size()) == T);
  REQUIRE(static_cast<int>(dyn.total_power_W.size()) == T);
}

/// The log: what relaxed means said once before the relaxed lines; a kind of episode
/// (relaxed in or outside touchdown transients) that occurs once is one line, a kind that
/// repeats is one summary line counting its episodes and samples. Episodes and kinds counted
/// here from /solver/status and the contact phases: runs of consecutive relaxed samples,
/// split where the touchdown flag changes.
void check_relaxed_log(const PaperRun& r) {
  const DynamicsResult& dyn = r.run.dyn;
  const KinematicsResult& kin = r.run.kin;
  std::array<int, 2> episodes{}, samples{};  // [0] outside touchdowns, [1] in them
  int previous = -1;                         // kind of the previous sample, -1 not relaxed
  for (int i = 0; i < kin.samples(); ++i) {
    if (dyn.solver_status[i] != SolverStatus::kRelaxed) {
      previous = -1;
      continue;
    }
    const bool touchdown =
        (kin.contact_phase.row(i).array() == static_cast<std::int8_t>(ContactPhase::kImpact)).any();
    if (previous != int(touchdown)) ++episodes[touchdown];
    ++samples[touchdown];
    previous = touchdown;
  }
  REQUIRE(episodes[1] > 1);
  std::istringstream lines(r.log.str());
  std::string line;
  int notes = 0, relaxed_lines = 0;
  std::array<int, 2> summaries{};
  while (std::getline(lines, line)) {
    if (line.find("docs/theory/allocation.md#relaxed-samples") != std::string::npos) {
      CHECK(relaxed_lines == 0);  // before the first episode
      CHECK(line.find("touchdown transient") != std::string::npos);
      ++notes;
    }
    if (line.find(" sample(s) relaxed: ") != std::string::npos) ++relaxed_lines;
    for (int k = 0; k < 2; ++k) {
      const std::string head = "hexdyn: " + std::to_string(episodes[k]) +
                               " episodes of relaxed samples " +
                               (k ? "in touchdown transients, " : "outside touchdowns, ") +
                               std::to_string(samples[k]) + " samples from t = ";
      if (line.rfind(head, 0) == 0) {
        ++summaries[k];
        ++relaxed_lines;
        CHECK(line.size() < 400);
      }
    }
  }
  CHECK(notes == 1);
  for (int k = 0; k < 2; ++k) CHECK(summaries[k] == (episodes[k] > 1 ? 1 : 0));
  CHECK(relaxed_lines == (episodes[0] > 0) + (episodes[1] > 0));
}

/// No NaN or Inf anywhere.
void check_all_finite(const RunResult& run) {
  const KinematicsResult& kin = run.kin;
  const DynamicsResult& dyn = run.dyn;
  CHECK(all_finite(kin.time_s));
  CHECK(all_finite(kin.base_position));
  CHECK(all_finite(kin.base_orientation_wxyz));
  CHECK(all_finite(kin.base_linear_velocity));
  CHECK(all_finite(kin.base_angular_velocity));
  CHECK(all_finite(kin.base_linear_acceleration));
  CHECK(all_finite(kin.base_angular_acceleration));
  CHECK(all_finite(kin.joint_position));
  CHECK(all_finite(kin.joint_velocity));
  CHECK(all_finite(kin.joint_acceleration));
  CHECK(all_finite(kin.foot_position));
  CHECK(all_finite(kin.foot_velocity));
  CHECK(all_finite(kin.com_position));
  CHECK(all_finite(dyn.joint_torque));
  CHECK(all_finite(dyn.contact_force));
  CHECK(all_finite(dyn.penetration));
  CHECK(all_finite(dyn.joint_power));
  CHECK(all_finite(dyn.total_power_W));
  CHECK(all_finite(dyn.energy_joint_J));
  CHECK(all_finite(dyn.solver_iterations));
  CHECK(all_finite(dyn.solver_objective));
  CHECK(all_finite(dyn.solver_seconds));
  CHECK(std::isfinite(dyn.energy_total_J));
  CHECK(std::isfinite(dyn.cost_of_transport));
  for (const ImpactRecord& r : dyn.impacts) {
    CHECK(std::isfinite(r.t_start_s));
    CHECK(std::isfinite(r.duration_s));
    CHECK(std::isfinite(r.peak_force_N));
    CHECK(std::isfinite(r.impulse_Ns));
  }
}

/// Every sample is solved, exactly outside touchdown transients; a relaxed sample's
/// message names an impact.
void check_solver_status(const RunResult& run) {
  const KinematicsResult& kin = run.kin;
  const DynamicsResult& dyn = run.dyn;
  const int T = kin.samples();
  int status0 = 0, relaxed = 0, failed = 0, impact_samples = 0;
  for (int i = 0; i < T; ++i) {
    const SolverStatus status = dyn.solver_status[i];
    const std::string& msg = dyn.solver_messages[i];
    INFO("sample " << i << " t = " << kin.time_s[i] << " s, status " << status << ", message '"
                   << msg << "'");
    status0 += status == SolverStatus::kOptimal;
    relaxed += status == SolverStatus::kRelaxed;
    failed += status == SolverStatus::kFailed;
    CHECK((status == SolverStatus::kOptimal || status == SolverStatus::kRelaxed));
    CHECK(msg.empty() == (status == SolverStatus::kOptimal));
    const bool any_impact = any_impact_leg(kin, i);
    impact_samples += any_impact;
    // Outside touchdown transients every sample is solved exactly.
    if (!any_impact) CHECK(status == SolverStatus::kOptimal);
    if (status != SolverStatus::kOptimal) CHECK(contains(msg, "(impact"));
  }
  INFO("samples " << T << ": " << status0 << " optimal, " << relaxed << " relaxed, " << failed
                  << " failed; " << impact_samples << " with an impact leg");
  CHECK(failed == 0);
  CHECK(impact_samples > 0);
  // Relaxed samples exist (impacts): the checks on relaxed samples are not vacuous.
  CHECK(relaxed > 0);
}

/// Leg l of sample i (force f [N], terrain normal n_W): zero force and penetration in
/// swing; in a transient, the transient's normal force and penetration; in support, the
/// spring law's static penetration; friction and minimum normal force held, or named in
/// the message of a relaxed sample.
void check_leg(const PaperRun& r, int i, int l, const Vec3& f, const Vec3& n_W) {
  const KinematicsResult& kin = r.run.kin;
  const DynamicsResult& dyn = r.run.dyn;
  const double t = kin.time_s[i];
  const SolverStatus status = dyn.solver_status[i];
  const std::string& msg = dyn.solver_messages[i];
  INFO("leg L" << l + 1);
  const int phase = kin.contact_phase(i, l);
  const double f_n = f.dot(n_W);
  const double f_t = (f - f_n * n_W).norm();
  // The transient (if any) this leg is in at t.
  const Touchdown* active = nullptr;
  for (const Touchdown& td : r.touchdowns)
    if (td.leg == l && td.transient.occurred && t >= td.t_s && t < td.t_s + td.transient.duration_s)
      active = &td;
  if (phase == 0) {
    CHECK(f.cwiseAbs().maxCoeff() == 0.0);
    CHECK(dyn.penetration(i, l) == 0.0);
    CHECK(leg_foot_motion(r.plan.gait.legs[l], t).in_swing);
    return;
  }
  CHECK_FALSE(leg_foot_motion(r.plan.gait.legs[l], t).in_swing);
  CHECK((phase == 1) == (active != nullptr));
  if (phase == 1 && active != nullptr) {
    // The known normal force of the impact law, applied along n.
    const double f_tr = transient_force_at(active->transient, t - active->t_s);
    CHECK(std::abs(f_n - f_tr) <= 1e-9 * std::max(1.0, f_tr));
    CHECK(std::abs(dyn.penetration(i, l) -
                   transient_penetration_at(active->transient, t - active->t_s)) <= 1e-15);
  }
  if (phase == 2) {
    // Static penetration of the spring law, δ = (F_n/K)^(1/e).
    const double delta =
        f_n > 0.0 ? std::pow(f_n / r.scene.contact.stiffness, 1.0 / r.scene.contact.exponent) : 0.0;
    CHECK(std::abs(dyn.penetration(i, l) - delta) <= 1e-9 * delta + 1e-15);
  }
  const double mu = r.scene.contact.friction_coefficient;
  const double f_min = r.scene.allocation.min_normal_force_N;
  const bool friction_ok = f_t <= mu * f_n * (1.0 + 1e-9) + 1e-9;
  const bool normal_ok = phase != 2 || f_n >= f_min - 1e-9;
  if (status == SolverStatus::kOptimal) {
    CHECK(friction_ok);
    CHECK(normal_ok);
  } else {
    if (f_t > mu * f_n + kUnnamedTolerance)
      CHECK(contains(msg, "friction L" + std::to_string(l + 1)));
    if (phase == 2 && f_n < f_min - kUnnamedTolerance)
      CHECK(contains(msg, "normal L" + std::to_string(l + 1)));
  }
}

/// Contact phases, forces and penetrations of every leg on every sample (check_leg).
void check_contacts(const PaperRun& r) {
  const KinematicsResult& kin = r.run.kin;
  const DynamicsResult& dyn = r.run.dyn;
  for (int i = 0; i < kin.samples(); ++i) {
    INFO("sample " << i << " t = " << kin.time_s[i] << " s, status " << dyn.solver_status[i]
                   << ", message '" << dyn.solver_messages[i] << "'");
    const std::array<Vec3, kPaperLegs> F = stored_forces(dyn, i);
    for (int l = 0; l < kPaperLegs; ++l) {
      const Vec3 p = foot_vec(kin.foot_position, i, l);
      check_leg(r, i, l, F[l], r.plan.terrain.normal(p.x(), p.y()));
    }
  }
}

/// Joint torques: τ = τ0 − Σ J_jᵀ F with the stored forces, within the torque limit, or
/// named in the message of a relaxed sample.
void check_torques(const PaperRun& r) {
  const KinematicsResult& kin = r.run.kin;
  const DynamicsResult& dyn = r.run.dyn;
  const double tau_max = r.scene.allocation.torque_limit_Nm;
  RobotData data(r.model);
  double worst_tau_res = 0.0;
  for (int i = 0; i < kin.samples(); ++i) {
    const SolverStatus status = dyn.solver_status[i];
    const std::string& msg = dyn.solver_messages[i];
    INFO("sample " << i << " t = " << kin.time_s[i] << " s, status " << status << ", message '"
                   << msg << "'");
    const std::array<Vec3, kPaperLegs> F = stored_forces(dyn, i);
    const ContactSplit& split = split_at(r.model, data, kin, i);
    PaperJointVector tau = split.tau0;
    double tau_scale = 1.0 + split.tau0.cwiseAbs().maxCoeff();
    for (int l = 0; l < kPaperLegs; ++l) {
      tau -= split.JjT[l] * F[l];
      tau_scale = std::max(tau_scale, (split.JjT[l] * F[l]).cwiseAbs().maxCoeff());
    }
    const PaperJointVector tau_stored = dyn.joint_torque.row(i).transpose();
    const double tau_res = (tau_stored - tau).cwiseAbs().maxCoeff();
    worst_tau_res = std::max(worst_tau_res, tau_res / tau_scale);
    CHECK(tau_res <= 1e-9 * tau_scale);
    for (int k = 0; k < kPaperJoints; ++k) {
      if (status == SolverStatus::kOptimal) {
        CHECK(std::abs(tau_stored[k]) <= tau_max + 1e-6);
      } else if (std::abs(tau_stored[k]) > tau_max + kUnnamedTolerance) {
        CHECK(contains(msg, "torque " + joint_name(k / kPaperLegJoints, k % kPaperLegJoints)));
      }
    }
  }
  INFO("worst torque residual (relative) " << worst_tau_res);
}

/// The trunk rows Σ J_bᵀ F = trunk_rhs hold on every optimal sample (to 1e-8 of the weight,
/// moments of the weight times 1 m), or a relaxed sample's message names the trunk.
void check_trunk_rows(const PaperRun& r) {
  const KinematicsResult& kin = r.run.kin;
  const DynamicsResult& dyn = r.run.dyn;
  const double mg = r.mg;
  RobotData data(r.model);
  double worst_trunk_res = 0.0;
  for (int i = 0; i < kin.samples(); ++i) {
    const SolverStatus status = dyn.solver_status[i];
    const std::string& msg = dyn.solver_messages[i];
    INFO("sample " << i << " t = " << kin.time_s[i] << " s, status " << status << ", message '"
                   << msg << "'");
    const std::array<Vec3, kPaperLegs> F = stored_forces(dyn, i);
    const ContactSplit& split = split_at(r.model, data, kin, i);
    Vec6 trunk = Vec6::Zero();
    for (int l = 0; l < kPaperLegs; ++l) trunk += split.JbT[l] * F[l];
    const Vec6 trunk_res = trunk - split.trunk_rhs;
    const double trunk_force_res = trunk_res.head<3>().cwiseAbs().maxCoeff();
    const double trunk_moment_res = trunk_res.tail<3>().cwiseAbs().maxCoeff();
    const bool trunk_holds =
        trunk_force_res <= 1e-8 * std::max(mg, split.trunk_rhs.head<3>().cwiseAbs().maxCoeff()) &&
        trunk_moment_res <=
            1e-8 * std::max(mg * 1.0, split.trunk_rhs.tail<3>().cwiseAbs().maxCoeff());
    if (status == SolverStatus::kOptimal) {
      worst_trunk_res = std::max({worst_trunk_res, trunk_force_res / mg, trunk_moment_res / mg});
      CHECK(trunk_holds);
    } else if (!trunk_holds) {
      CHECK(contains(msg, "trunk"));
    }
  }
  INFO("worst trunk-row residual / mg " << worst_trunk_res);
}

/// Momentum balance dP/dt = m g + Σ F, dL_O/dt = c × m g + Σ p × F, the rates differentiated
/// numerically from the prescribed motion: on every optimal sample to 1e-8 of the weight
/// (moments: of the weight times 1 m); a relaxed sample off balance names the trunk.
void check_momentum_balance(const PaperRun& r) {
  const KinematicsResult& kin = r.run.kin;
  const DynamicsResult& dyn = r.run.dyn;
  const int T = kin.samples();
  const Vec3 gravity_force_W(0.0, 0.0, -r.mg);
  // Balances to 1e-8 of the weight; moments to 1e-8 of the weight times 1 m.
  const double force_tol = 1e-8 * r.mg;
  const double moment_tol = 1e-8 * r.mg * 1.0;
  RobotData data(r.model);
  int checked = 0, skipped = 0, relaxed_nonzero = 0;
  double worst_force_res = 0.0, worst_moment_res = 0.0;
  for (int i = 0; i < T; ++i) {
    const SolverStatus status = dyn.solver_status[i];
    const std::string& msg = dyn.solver_messages[i];
    INFO("sample " << i << " t = " << kin.time_s[i] << " s, status " << status << ", message '"
                   << msg << "'");
    const MomentumRate rate =
        momentum_rate(r.model, data, r.plan, r.breakpoints, kin.time_s[i], kFdStep);
    if (!rate.ok) {
      ++skipped;
      continue;
    }
    ++checked;
    Vec3 force = gravity_force_W, moment = rate.com_W.cross(gravity_force_W);
    const std::array<Vec3, kPaperLegs> F = stored_forces(dyn, i);
    for (int l = 0; l < kPaperLegs; ++l) {
      force += F[l];
      moment += foot_vec(kin.foot_position, i, l).cross(F[l]);
    }
    const double f_res = (rate.linear - force).cwiseAbs().maxCoeff();
    const double m_res = (rate.angular_O - moment).cwiseAbs().maxCoeff();
    INFO("momentum rate residual: force " << f_res << " N, moment " << m_res << " N m");
    if (status == SolverStatus::kOptimal) {
      worst_force_res = std::max(worst_force_res, f_res);
      worst_moment_res = std::max(worst_moment_res, m_res);
      CHECK(f_res <= force_tol);
      CHECK(m_res <= moment_tol);
    } else if (f_res > force_tol || m_res > moment_tol) {
      ++relaxed_nonzero;
      CHECK(contains(msg, "trunk"));
    }
  }
  INFO("momentum balance checked on " << checked << " samples (" << skipped
                                      << " without a smooth stencil); worst force "
                                      << worst_force_res << " N, moment " << worst_moment_res
                                      << " N m; relaxed samples off balance: " << relaxed_nonzero);
  // The momentum balance is checked on (nearly) every sample; a stencil is missing only
  // where two breakpoints lie within 4h of each other on both sides of a sample.
  CHECK(skipped <= T / 100);
  // At least one relaxed sample breaks the balance: the check on relaxed samples is not
  // vacuous.
  CHECK(relaxed_nonzero > 0);
}

/// The samples whose allocation is solved again: 30 optimal samples spread over the run
/// and up to 12 optimal samples with an impact leg.
std::vector<int> kkt_samples_of(const RunResult& run) {
  std::vector<int> kkt_candidates, kkt_impact_candidates;
  for (int i = 0; i < run.kin.samples(); ++i)
    if (run.dyn.solver_status[i] == SolverStatus::kOptimal)
      (any_impact_leg(run.kin, i) ? kkt_impact_candidates : kkt_candidates).push_back(i);
  std::vector<int> kkt_samples;
  const std::size_t stride = std::max<std::size_t>(1, kkt_candidates.size() / 30);
  for (std::size_t k = 0; k < kkt_candidates.size(); k += stride)
    kkt_samples.push_back(kkt_candidates[k]);
  const std::size_t n_imp = kkt_impact_candidates.size();
  for (std::size_t k = 0; k < std::min<std::size_t>(12, n_imp); ++k)
    kkt_samples.push_back(kkt_impact_candidates[k * n_imp / std::min<std::size_t>(12, n_imp)]);
  return kkt_samples;
}

/// KKT of the allocation on a subset of samples (kkt_samples_of), rebuilt from the stored
/// phases and impact forces and solved again by the other back end (Ipopt, cold, at a
/// tolerance of 1e-12: at 1e-9 its scaled optimality test can stop short on a sample whose
/// multipliers are large), a computation independent of the run's active-set solver.
void check_allocation_kkt(const PaperRun& r) {
  const KinematicsResult& kin = r.run.kin;
  const DynamicsResult& dyn = r.run.dyn;
  const std::vector<int> kkt_samples = kkt_samples_of(r.run);
  REQUIRE(kkt_samples.size() >= 30);
  IpoptOptions reference_options = ipopt_options_from(r.scene.allocation);
  reference_options.tolerance = 1e-12;
  auto backend = make_ipopt_backend(reference_options);
  RobotData data(r.model);
  QpProblem qp;
  int kkt_with_impact = 0;
  double worst_force_diff = 0.0;
  for (int i : kkt_samples) {
    INFO("KKT sample " << i << " t = " << kin.time_s[i] << " s");
    const ContactSplit& split = split_at(r.model, data, kin, i);
    std::array<ContactPhase, kPaperLegs> phase{};
    std::array<double, kPaperLegs> f_impact{};
    std::array<Mat3, kPaperLegs> W_R_c;
    for (int l = 0; l < kPaperLegs; ++l) {
      phase[l] = static_cast<ContactPhase>(kin.contact_phase(i, l));
      const Vec3 p = foot_vec(kin.foot_position, i, l);
      W_R_c[l] = contact_frame(r.plan.terrain.normal(p.x(), p.y()));
      f_impact[l] = phase[l] == ContactPhase::kImpact
                        ? foot_vec(dyn.contact_force, i, l).dot(W_R_c[l].col(2))
                        : 0.0;
      kkt_with_impact += phase[l] == ContactPhase::kImpact;
    }
    const AllocationLayout layout = build_allocation_problem(r.scene.allocation, r.scene.contact,
                                                             split, phase, f_impact, W_R_c, qp);
    CHECK(layout.constant_excess_Nm == 0.0);
    backend->reset_warm_start();
    const QpOutcome& out = backend->solve(qp);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(check_kkt(qp, out, 1e-6));
    // The QP is strictly convex (each support leg's J_j is invertible), so the stored
    // solution is this one up to the solver's accuracy: the objective to ~1e-11 relative,
    // the forces to ~1e-5 N where the smallest eigenvalue of H is ~0.01 m² (Ipopt's tol
    // 1e-9 bounds the scaled optimality error, not the distance to the optimum).
    CHECK(std::abs(out.objective - dyn.solver_objective[i]) <= 1e-9 * (1.0 + out.objective));
    std::array<Vec3, kPaperLegs> F_new;
    PaperJointVector tau_new;
    forces_from_solution(split, layout, out.x, F_new, tau_new);
    for (int l = 0; l < kPaperLegs; ++l) {
      const double d = (F_new[l] - foot_vec(dyn.contact_force, i, l)).cwiseAbs().maxCoeff();
      worst_force_diff = std::max(worst_force_diff, d);
      CHECK(d <= kForceAgreement);
    }
  }
  INFO("KKT checked on " << kkt_samples.size() << " samples; worst force difference "
                         << worst_force_diff << " N");
  CHECK(kkt_with_impact > 0);
}

}  // namespace

TEST_CASE("paper run: physics holds on every sample", "[paper][pipeline]") {
  const PaperRun& r = paper_run();
  require_sizes(r.run);
  SECTION("every number is finite") { check_all_finite(r.run); }
  SECTION("the log says once what a relaxed sample means") { check_relaxed_log(r); }
  SECTION("every sample is solved, exactly outside touchdown transients") {
    check_solver_status(r.run);
  }
  SECTION("contact phases, forces and penetrations follow the contact model") { check_contacts(r); }
  SECTION("joint torques are tau0 - sum Jj^T F, within their limit") { check_torques(r); }
  SECTION("the trunk rows hold with the stored forces") { check_trunk_rows(r); }
  SECTION("the momentum rate is gravity plus the contact forces") { check_momentum_balance(r); }
  SECTION("one impact record per touchdown transient") {
    int occurred = 0;
    for (const Touchdown& td : r.touchdowns) occurred += td.transient.occurred;
    CHECK(static_cast<int>(r.run.dyn.impacts.size()) == occurred);
  }
  SECTION("the allocation re-solved by Ipopt meets its KKT conditions and the stored forces") {
    check_allocation_kkt(r);
  }
}

}  // namespace hexdyn
