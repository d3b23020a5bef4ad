#include "hexdyn/pipeline/solve_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/core/cancel.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/drive/drive.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/grip/required_friction.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/pipeline/episode_log.hpp"
#include "hexdyn/power/power.hpp"

namespace hexdyn {

/// The allocation of one sample: the back end's answer, the forces and torques of its
/// solution, and what the solution itself violates.
struct SampleSolution {
  /// The back end's outcome (status, iterations, seconds, message); valid until the
  /// solver's next solve.
  const QpOutcome* outcome = nullptr;
  LegArray<Vec3> foot_forces_W;  ///< [N], terrain on foot, world axes, per leg
  JointVector joint_torque;      ///< [N m], per joint
  /// With actuators: the drive torques τ + offset and their bounds [N m] (DriveRows).
  JointVector drive_torque;
  JointVector drive_limit, drive_lower_limit;
  /// Rows and cones the solution violates beyond kViolationThreshold, measured on it
  /// whatever the back end reported, largest first ("trunk force z by 120, torque L1_femur
  /// by 0.45"); empty when none.
  std::string measured_violations;
  double measured_max_violation = 0.0;  ///< largest violation of any row or cone [N or N m]
  /// Excess of the constant rows (swing-leg torques) over their limits [N m], and its name
  /// (AllocationLayout).
  double constant_excess_Nm = 0.0;
  std::string constant_violation;
  /// The grip of the sample (docs/theory/grip.md): |F_t| / F_n per leg (NaN on a swing leg),
  /// the legs whose friction held only with slack, and the required friction (NaN when not
  /// computed or none suffices) with its binding leg and, when NaN, why.
  LegArray<double> utilized_friction{};
  LegArray<bool> slip{};
  double required_friction = 0.0;
  bool required_friction_bound = false;  ///< required_friction is an upper bound (kBelow)
  int required_friction_leg = -1;
  std::string required_friction_message;
};

/// The allocation of one sample with its workspace: the dynamics buffers, the problem and
/// the back end, whose warm start carries from one solve to the next.
/// A contact force of at most this fraction of the robot's weight is round-off: it uses no
/// friction and never counts as pulling.
constexpr double kRoundOffForce = 1e-9;

class SampleSolver {
 public:
  SampleSolver(const Scene& scene, const RobotModel& model)
      : scene_(scene),
        model_(model),
        legs_(allocation_legs(model)),
        data_(model),
        backend_(make_allocation_backend(scene.allocation)) {
    if (model.drive.present) rows_.weight = objective_weights(scene, model);
    // The required friction's probes are polygon problems (its cones become outer polygons),
    // so the active-set back end solves them whatever the scene's back end: Ipopt would
    // cost milliseconds per probe for the same feasibility verdict.
    if (scene.output.required_friction) {
      RequiredFrictionOptions options;
      options.reasons = !scene.output.summary_only;  // a sweep's row names no sample's rows
      required_ = std::make_unique<RequiredFrictionSolver>(
          make_active_set_backend(active_set_options_from(scene.allocation)), options);
    }
  }

  /// Solves sample i of `kin` under contacts `c`; `times` (may be null) as solve_dynamics.
  /// `enough`: RequiredFrictionSolver::solve's (the default asks for μ* itself).
  SampleSolution solve(const KinematicsResult& kin, int i, const SampleContacts& c,
                       StageTimes* times,
                       double enough = -std::numeric_limits<double>::infinity()) {
    std::optional<StageTimer> clock(std::in_place, times, Stage::kRnea);
    const BaseState base = base_state_at(kin, i);
    const JointVector q = kin.joint_position.row(i).transpose();
    const JointVector qd = kin.joint_velocity.row(i).transpose();
    const JointVector qdd = kin.joint_acceleration.row(i).transpose();
    FootNormals normals;  // the surface under each foot: a sphere foot's contact point
    for (int l = 0; l < model_.legs(); ++l) normals[l] = c.W_R_contact[l].col(2);
    const ContactSplit& split = contact_split(model_, data_, base, q, qd, qdd, &normals);
    clock.emplace(times, Stage::kAllocation);
    const bool drive = model_.drive.present;
    if (drive) drive_rows(qd, qdd);
    AllocationLayout& layout = layout_;
    layout = build_allocation_problem(legs_, scene_.allocation, scene_.contact, split,
                                      allocation_phases(c), c.impact_force_N, c.W_R_contact, qp_,
                                      drive ? &rows_ : nullptr);
    SampleSolution s;
    s.outcome = &backend_->solve(qp_);
    forces_from_solution(split, layout, s.outcome->x, s.foot_forces_W, s.joint_torque);
    if (drive) {
      s.drive_torque = s.joint_torque + rows_.offset_Nm;
      s.drive_limit = rows_.limit_Nm;
      s.drive_lower_limit = rows_.lower_Nm;
    }
    clock.emplace(times, Stage::kVerdict);
    // Measured from the solution, not taken from the back end: every row and cone against
    // the fixed threshold (allocation/qp.hpp kViolationThreshold).
    s.measured_violations = describe_violations(qp_, s.outcome->x, kViolationThreshold,
                                                &s.measured_max_violation, violations_);
    s.constant_excess_Nm = layout.constant_excess_Nm;
    clock.emplace(times, Stage::kGrip);
    grip(c, layout, s, enough);
    s.constant_violation = layout.constant_violation;
    return s;
  }

  /// The legs' phases as the allocation sees them: a loaded touchdown's leg supports from its
  /// touchdown on, its normal force the allocation's (docs/theory/contact.md#loaded-touchdowns);
  /// the paper's transient prescribes it.
  LegArray<ContactPhase> allocation_phases(const SampleContacts& c) const {
    LegArray<ContactPhase> phase = c.phase;
    if (scene_.contact.touchdown == TouchdownModel::kLoaded)
      for (ContactPhase& p : phase)
        if (p == ContactPhase::kImpact) p = ContactPhase::kSupport;
    return phase;
  }

  /// The problem and layout of the last solve.
  const QpProblem& problem() const { return qp_; }
  const AllocationLayout& layout() const { return layout_; }

 private:
  /// The drive train's rows of a sample at joint rates qd and accelerations qdd: offsets,
  /// bounds (a joint without a peak or voltage bound keeps the allocation's limit) and weights.
  void drive_rows(const JointVector& qd, const JointVector& qdd) {
    const DriveTrainParams& drive = model_.drive;
    const AllocationParams& alloc = scene_.allocation;
    rows_.offset_Nm = drive_torque_offset(drive, qd, qdd);
    for (int k = 0; k < model_.joints(); ++k) {
      const DriveLimit lim = drive_torque_limit(drive.joints[k], qd[k]);
      rows_.bound[k] = static_cast<std::int8_t>(lim.bound);
      if (lim.bound != DriveBound::kNone) {
        rows_.limit_Nm[k] = lim.limit_Nm;
        rows_.lower_Nm[k] = lim.lower_Nm;
        continue;
      }
      rows_.limit_Nm[k] =
          alloc.joint_torque_limit_Nm ? (*alloc.joint_torque_limit_Nm)[k] : alloc.torque_limit_Nm;
      rows_.lower_Nm[k] = -rows_.limit_Nm[k];
    }
  }

  /// The grip fields of s (SampleSolution), from its forces and the problem just solved.
  void grip(const SampleContacts& c, const AllocationLayout& layout, SampleSolution& s,
            double enough) {
    // A force below kRoundOffForce of the weight is round-off (a foot carrying 1e-30 N): no
    // force, no friction used. A foot whose force does not press it (a relaxed sample) uses
    // no defined friction: NaN, never +inf (docs/theory/grip.md#utilised-friction).
    const double round_off_N = kRoundOffForce * model_.total_mass_kg * kGravity;
    for (int l = 0; l < model_.legs(); ++l) {
      const Vec3 F_c = c.W_R_contact[l].transpose() * s.foot_forces_W[l];
      const double ft = std::hypot(F_c.x(), F_c.y());
      s.utilized_friction[l] = c.phase[l] == ContactPhase::kSwing
                                   ? std::numeric_limits<double>::quiet_NaN()
                               : F_c.norm() <= round_off_N ? 0.0
                               : F_c.z() > 0.0             ? ft / F_c.z()
                                               : std::numeric_limits<double>::quiet_NaN();
    }
    const auto slipping = slipping_legs(qp_, layout, s.outcome->x);
    for (int l = 0; l < model_.legs(); ++l) s.slip[l] = slipping[l];
    s.required_friction = std::numeric_limits<double>::quiet_NaN();
    if (!required_) return;
    const bool holds = s.outcome->status == SolverStatus::kOptimal &&
                       s.measured_violations.empty() && s.constant_excess_Nm <= kViolationThreshold;
    const RequiredFriction& r =
        required_->solve(qp_, layout, holds ? &s.outcome->x : nullptr, enough);
    s.required_friction = r.mu;
    s.required_friction_bound = r.method == RequiredFrictionMethod::kBelow;
    s.required_friction_leg = r.leg;
    s.required_friction_message = r.message;
    // A sample that needs more friction than the scene's μ cannot hold without slipping. The
    // allocation then gives way on the trunk rows before the friction rows (their slack weighs
    // less, allocation/problem.cpp), so the legs that slip are those at their friction limit
    // and the leg that binds the required friction (docs/theory/grip.md#slip-onset).
    const double mu = scene_.contact.friction_coefficient;
    const double beyond = mu + 1e-9 * std::max(1.0, mu);
    // A bound (a summary-only run) above the scene's μ decides nothing: one probe there does.
    const bool slips = r.method == RequiredFrictionMethod::kBelow
                           ? r.mu > beyond && required_->needs_more_than(layout, beyond)
                           : r.mu > beyond;
    if (!slips) return;
    for (int l = 0; l < model_.legs(); ++l)
      if (leg_friction_use(qp_, layout, s.outcome->x, l) >= mu * (1.0 - 1e-6)) s.slip[l] = true;
    if (r.leg >= 0) s.slip[r.leg] = true;
  }

  /// The objective's weights of τ_drive²: 1 for torque_squared; for copper_loss each joint's
  /// R / (G k_t η)² over the largest, the same minimiser as the loss itself, while the slack
  /// penalties keep the scale they have against Σ τ² (docs/theory/drive-train.md#objective).
  static JointVector objective_weights(const Scene& scene, const RobotModel& model) {
    const int joints = model.drive.joints.size();
    JointVector w = JointVector::Ones(joints);
    if (scene.allocation.objective != AllocationObjective::kCopperLoss) return w;
    double largest = 0.0;
    for (int k = 0; k < joints; ++k) {
      w[k] = copper_loss_weight(model.drive.joints[k]);
      largest = std::max(largest, w[k]);
    }
    return w / largest;
  }

  const Scene& scene_;
  const RobotModel& model_;
  AllocationLegs legs_;  ///< the model's leg table as the allocation reads it
  RobotData data_;
  std::unique_ptr<AllocationBackend> backend_;
  QpProblem qp_;
  AllocationLayout layout_;
  ViolationWorkspace violations_;
  DriveRows rows_;
  std::unique_ptr<RequiredFrictionSolver> required_;  ///< null: output.required_friction false
};

namespace {

/// A sample's status and message: the back end's, made relaxed when the solution itself
/// violates a row or cone beyond the fixed threshold (kViolationThreshold; the back end's
/// own threshold follows allocation.tolerance and may be far looser) or when a constant
/// row (a swing-leg torque that no force can change) exceeds its limit by more than the
/// same threshold; the legs in their impact transient are named.
struct SampleVerdict {
  SolverStatus status = SolverStatus::kOptimal;
  std::string message;         ///< empty for an optimal sample
  double max_violation = 0.0;  ///< largest measured violation [N or N m]
};

SampleVerdict sample_verdict(const RobotModel& model, const SampleSolution& s,
                             const SampleContacts& c, double torque_limit_Nm) {
  const QpOutcome& outcome = *s.outcome;
  SampleVerdict v{outcome.status, outcome.message,
                  std::max(outcome.max_violation, s.measured_max_violation)};
  if (v.status == SolverStatus::kOptimal && !s.measured_violations.empty()) {
    v.status = SolverStatus::kRelaxed;
    v.message = "relaxed: " + s.measured_violations;
  }
  const bool constant_violated =
      s.constant_excess_Nm > kViolationThreshold * std::max(1.0, torque_limit_Nm);
  if (constant_violated) v.max_violation = std::max(v.max_violation, s.constant_excess_Nm);
  if (constant_violated && v.status == SolverStatus::kOptimal) {
    v.status = SolverStatus::kRelaxed;
    v.message = "relaxed: " + s.constant_violation;
  } else if (constant_violated) {
    v.message += ", " + s.constant_violation;
  }
  if (v.status == SolverStatus::kOptimal) {
    v.message.clear();
    return v;
  }
  std::string legs;
  for (int l = 0; l < model.legs(); ++l)
    if (c.phase[l] == ContactPhase::kImpact) legs += " " + model.leg(l).name;
  if (!legs.empty()) v.message += " (impact" + legs + ")";
  return v;
}

/// A result of T samples of `model`'s legs and joints, every per-sample field zero (the drive
/// train's too, with `drive`; the required friction with `required`).
DynamicsResult empty_result(const RobotModel& model, int T, bool drive, bool required) {
  const int J = model.joints(), L = model.legs();
  DynamicsResult dyn;
  dyn.present = true;
  dyn.joint_torque.setZero(T, J);
  dyn.contact_force.setZero(T, 3 * L);
  dyn.penetration.setZero(T, L);
  dyn.utilized_friction.setConstant(T, L, std::numeric_limits<double>::quiet_NaN());
  dyn.slip.setZero(T, L);
  if (required) {
    dyn.required_friction.assign(T, std::numeric_limits<double>::quiet_NaN());
    dyn.required_friction_leg.assign(T, -1);
  }
  dyn.solver_status.assign(T, SolverStatus::kOptimal);
  dyn.solver_iterations.assign(T, 0.0);
  dyn.solver_objective.assign(T, 0.0);
  dyn.solver_seconds.assign(T, 0.0);
  dyn.solver_messages.assign(T, std::string());
  dyn.solver_max_violation.assign(T, 0.0);
  if (drive) {
    dyn.drive_torque.setZero(T, J);
    dyn.drive_torque_limit.setZero(T, J);
    dyn.drive_torque_lower_limit.setZero(T, J);
  }
  return dyn;
}

}  // namespace

DynamicsSolver::DynamicsSolver(const Scene& scene, const RobotModel& model)
    : scene_(scene), model_(model), solver_(std::make_unique<SampleSolver>(scene, model)) {}

DynamicsSolver::~DynamicsSolver() = default;

DynamicsResult DynamicsSolver::solve(const KinematicsResult& kin, const ContactSchedule& contacts,
                                     StageTimes* times, WarmStart warm) {
  const int T = kin.samples();
  if (static_cast<int>(contacts.samples.size()) != T)
    throw SolverError("solve_dynamics: contact schedule of " +
                      std::to_string(contacts.samples.size()) + " samples, expected " +
                      std::to_string(T));
  DynamicsResult dyn =
      empty_result(model_, T, model_.drive.present, scene_.output.required_friction);
  const int L = model_.legs();
  for (int i = 0; i < T; ++i) {
    check_cancelled();
    report_progress("dynamics", i, T, "samples");
    const SampleContacts& c = contacts.samples[i];
    SampleSolver* solver = solver_.get();
    if (warm == WarmStart::kSamePhases) {
      int key = 0;  // base 3: 3^kMaxLegs fits an int
      for (int l = 0; l < L; ++l) key = 3 * key + static_cast<int>(c.phase[l]);
      auto it = std::find_if(by_phases_.begin(), by_phases_.end(),
                             [key](const auto& e) { return e.first == key; });
      if (it == by_phases_.end()) {
        by_phases_.emplace_back(key, std::make_unique<SampleSolver>(scene_, model_));
        it = by_phases_.end() - 1;
      }
      solver = it->second.get();
    }
    bool transient = false;
    for (int l = 0; l < L; ++l) transient = transient || c.phase[l] == ContactPhase::kImpact;
    const SampleSolution solution = solver->solve(kin, i, c, times, enough(transient));
    if (std::isfinite(solution.required_friction) && !solution.required_friction_bound)
      largest_mu_[transient] = std::max(largest_mu_[transient], solution.required_friction);
    const StageTimer clock(times, Stage::kVerdict);
    SampleVerdict verdict = sample_verdict(model_, solution, c, scene_.allocation.torque_limit_Nm);
    const auto& tau = solution.joint_torque;
    dyn.solver_status[i] = verdict.status;
    dyn.solver_iterations[i] = solution.outcome->iterations;
    dyn.solver_objective[i] =
        dyn.has_drive() ? solution.drive_torque.squaredNorm() : tau.squaredNorm();
    if (dyn.has_drive()) {
      dyn.drive_torque.row(i) = solution.drive_torque.transpose();
      dyn.drive_torque_limit.row(i) = solution.drive_limit.transpose();
      dyn.drive_torque_lower_limit.row(i) = solution.drive_lower_limit.transpose();
    }
    dyn.solver_seconds[i] = solution.outcome->seconds;
    dyn.solver_max_violation[i] = verdict.max_violation;
    dyn.joint_torque.row(i) = tau.transpose();
    for (int l = 0; l < L; ++l) {
      const Vec3& F_W = solution.foot_forces_W[l];
      dyn.contact_force.row(i).segment<3>(3 * l) = F_W.transpose();
      double delta = c.impact_penetration_m[l];
      if (c.phase[l] == ContactPhase::kSupport && scene_.contact.model == ContactModel::kCompliant)
        delta = static_penetration(scene_.contact, std::max(0.0, F_W.dot(c.W_R_contact[l].col(2))));
      dyn.penetration(i, l) = delta;
    }
    for (int l = 0; l < L; ++l) {
      dyn.utilized_friction(i, l) = solution.utilized_friction[l];
      dyn.slip(i, l) = solution.slip[l] ? 1 : 0;
    }
    if (!dyn.required_friction.empty()) {
      dyn.required_friction[i] = solution.required_friction;
      dyn.required_friction_leg[i] = static_cast<std::int8_t>(solution.required_friction_leg);
      if (!solution.required_friction_message.empty())
        verdict.message +=
            (verdict.message.empty() ? "" : "; ") + solution.required_friction_message;
    }
    dyn.solver_messages[i] = std::move(verdict.message);
  }
  return dyn;
}

double DynamicsSolver::enough(bool transient) const {
  // The largest μ* so far of the sample's kind (the summary's maxima: sweep/scenario.cpp).
  return scene_.output.summary_only ? largest_mu_[transient]
                                    : -std::numeric_limits<double>::infinity();
}

SampleProblem solve_sample_problem(const Scene& scene, const RobotModel& model,
                                   const KinematicsResult& kin, int i, const SampleContacts& c) {
  SampleSolver solver(scene, model);
  const SampleSolution s = solver.solve(kin, i, c, nullptr);
  SampleProblem p;
  p.qp = solver.problem();
  p.layout = solver.layout();
  p.legs = model.legs();
  for (int l = 0; l < p.legs; ++l) p.phase[l] = c.phase[l];
  p.x = s.outcome->x;
  p.status = sample_verdict(model, s, c, scene.allocation.torque_limit_Nm).status;
  p.required_friction = s.required_friction;
  p.required_friction_leg = s.required_friction_leg;
  return p;
}

void finish_dynamics(const Scene& scene, const RobotModel& model, const MotionPlan& plan,
                     const KinematicsResult& kin, const std::vector<Touchdown>& touchdowns,
                     DynamicsResult& dyn, std::ostream* log, StageTimes* times,
                     const CubicEstimates* estimates) {
  for (const Touchdown& td : touchdowns)
    if (td.transient.truncated && log)
      *log << "hexdyn: touchdown of " << model.leg(td.leg).name << " at t = " << td.t_s
           << " s: transient " << td.transient.message << "\n";
  dyn.impacts = impact_records(touchdowns);
  EpisodeLog episodes(log);
  for (int i = 0; i < kin.samples(); ++i) {
    if (dyn.solver_status[i] == SolverStatus::kOptimal) {
      episodes.close();
      continue;
    }
    bool touchdown = false;  // some leg in its touchdown transient
    for (int l = 0; l < model.legs() && i < kin.contact_phase.rows(); ++l)
      touchdown =
          touchdown || kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kImpact);
    episodes.add(kin.time_s[i], dyn.solver_status[i], touchdown, dyn.solver_max_violation[i],
                 dyn.solver_messages[i]);
  }
  episodes.flush();

  const StageTimer clock(times, Stage::kPower);
  PowerResult power =
      compute_power(kin, dyn.joint_torque, model.total_mass_kg, plan.trunk.total_travel_m(),
                    plan.trunk.cycle_start_times(), energy_rule(scene.output.grid), estimates);
  dyn.joint_power = std::move(power.joint_power);
  dyn.total_power_W = std::move(power.total_power_W);
  dyn.energy_joint_J = std::move(power.energy_joint_J);
  dyn.energy_total_J = power.energy_total_J;
  dyn.positive_work_joint_J = std::move(power.positive_work_joint_J);
  dyn.negative_work_joint_J = std::move(power.negative_work_joint_J);
  dyn.positive_work_J = power.positive_work_J;
  dyn.negative_work_J = power.negative_work_J;
  dyn.energy_cycle_J = std::move(power.energy_cycle_J);
  dyn.distance_m = power.distance_m;
  dyn.cost_of_transport = power.cost_of_transport;
  if (dyn.has_drive())
    dyn.electrical = compute_electrical(model.drive, kin.time_s, kin.joint_velocity,
                                        dyn.drive_torque, model.total_mass_kg, dyn.distance_m);
}

DynamicsResult solve_dynamics(const Scene& scene, const RobotModel& model, const MotionPlan& plan,
                              const KinematicsResult& kin, const ContactSchedule& contacts,
                              const std::vector<Touchdown>& touchdowns, std::ostream* log,
                              StageTimes* times) {
  DynamicsSolver solver(scene, model);
  DynamicsResult dyn = solver.solve(kin, contacts, times);
  finish_dynamics(scene, model, plan, kin, touchdowns, dyn, log, times);
  return dyn;
}

}  // namespace hexdyn
