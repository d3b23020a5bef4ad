#include "hexdyn/replay/replay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "hexdyn/contact/simulation_contact.hpp"
#include "hexdyn/contact/stick_slip.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/dynamics/forward_dynamics.hpp"
#include "hexdyn/model/root_link.hpp"
#include "hexdyn/planning/terrain.hpp"
#include "hexdyn/replay/joint_drive.hpp"
#include "hexdyn/replay/lane_sums.hpp"
#include "hexdyn/replay/plan_checks.hpp"
#include "hexdyn/replay/replay_report.hpp"
#include "hexdyn/replay/step_system.hpp"

namespace hexdyn {
namespace {

using replay_sums::lane_abs_dot;
using replay_sums::lane_dot;

/// Per-leg 3-vectors, every entry zero (the unused legs' too).
LegArray<Vec3> zero_vectors() {
  LegArray<Vec3> v;
  v.fill(Vec3::Zero());
  return v;
}

/// The integrator's state: trunk pose and twist (accelerations unused), joint angles, rates.
struct SimState {
  BaseState base;
  JointVector q, qd;  ///< model.joints() each

  DofVector nu() const {
    DofVector v(6 + qd.size());
    v << base.v_W, base.omega_W, qd;
    return v;
  }
  bool finite() const {
    return base.p_W.allFinite() && base.W_R_B.allFinite() && base.v_W.allFinite() &&
           base.omega_W.allFinite() && q.allFinite() && qd.allFinite();
  }
};

/// What a step of [t, t + h] follows: the planned joint angles and rates at its end (the
/// implicit PD's targets) and the feedforward torque at its start, the instant of the
/// explicit gravity and velocity terms it was planned to balance
/// (docs/theory/replay.md#integrator).
struct PlanPoint {
  JointVector q, qd, tau;
};

/// The linear interpolation weight of the plan's sample k + 1 against k at t.
double plan_weight(const ReplayPlan& p, std::size_t k, double t) {
  const std::size_t k1 = std::min(k + 1, p.t_s.size() - 1);
  const double span = p.t_s[k1] - p.t_s[k];
  return span > 0.0 ? std::clamp((t - p.t_s[k]) / span, 0.0, 1.0) : 0.0;
}

/// The plan point of a step from t_start to t_end within the plan's samples k and k + 1.
PlanPoint plan_at(const ReplayPlan& p, std::size_t k, double t_start, double t_end) {
  const std::size_t k1 = std::min(k + 1, p.t_s.size() - 1);
  const double u = plan_weight(p, k, t_end), u0 = plan_weight(p, k, t_start);
  const std::vector<JointVector>& tau = p.tau_drive_Nm.empty() ? p.tau_Nm : p.tau_drive_Nm;
  return PlanPoint{(1.0 - u) * p.q_rad[k] + u * p.q_rad[k1],
                   (1.0 - u) * p.qd_radps[k] + u * p.qd_radps[k1],
                   (1.0 - u0) * tau[k] + u0 * tau[k1]};
}

/// The contact of every foot at a state: geometry, normals, forces and their linearisation
/// (the first `legs` entries of each per-leg array).
struct Contacts {
  int legs = 0;  ///< the model's legs
  LegArray<TerrainContactPoint> geometry;
  FootNormals normals = zero_vectors();
  LegArray<FootContactForce> law;
  LegArray<Vec3> force_W = zero_vectors();
  LegArray<DofJacobian> J;  ///< of the contact points (rnea.hpp foot_jacobians)
};

/// Fills `c` for state `s`.
void evaluate_contacts(const RobotModel& model, RobotData& data, const ContactParams& params,
                       const ReplayPlan& plan, const SimState& s, Contacts& c) {
  update_kinematics(model, data, s.base, s.q);
  c.legs = model.legs();
  for (int l = 0; l < c.legs; ++l) {
    const Vec3 centre_W = data.X_world_body[model.foot_body(l)].apply_point(model.p_foot_last[l]);
    c.geometry[l] =
        plan.terrain_map
            ? height_map_contact(*plan.terrain_map, centre_W, model.foot_radius_m[l])
            : terrain_contact(plan.terrain_y_m, plan.terrain_z_m, centre_W, model.foot_radius_m[l]);
    c.normals[l] = c.geometry[l].normal_W;
  }
  foot_jacobians_at_poses(model, data, s.base, &c.normals);
  for (int l = 0; l < c.legs; ++l) c.J[l] = data.J_foot_W[l];
  const DofVector nu = s.nu();
  for (int l = 0; l < c.legs; ++l) {
    const Vec3 v_point = foot_velocity(model.leg(l), c.J[l], nu);
    c.law[l] = foot_contact_force(params, c.geometry[l].penetration_m, c.normals[l], v_point);
    c.force_W[l] = c.law[l].force_W;
  }
}

/// With stick–slip (contact.friction_law), replaces the tangential forces in `c` by those of
/// the feet's stick–slip states, and clears the state of a foot out of contact.
void apply_stick_slip(const ContactParams& params, LegArray<TangentialContact>& state,
                      Contacts& c) {
  if (params.friction_law != FrictionLaw::kStickSlip) return;
  for (int l = 0; l < c.legs; ++l) {
    FootContactForce& f = c.law[l];
    if (!(c.geometry[l].penetration_m > 0.0) || !(f.normal_N > 0.0)) state[l] = {};
    f.tangential_W =
        stick_slip_force(params, state[l], c.normals[l], f.normal_N, f.slip_velocity_W);
    f.force_W = f.normal_N * c.normals[l] + f.tangential_W;
    f.slip_power_W = -f.tangential_W.dot(f.slip_velocity_W);
    c.force_W[l] = f.force_W;
  }
}

/// Energy stored in a contact's spring at penetration δ: ∫ K δ^e dδ = K δ^(e+1)/(e+1) [J].
double spring_energy(const ContactParams& c, double delta_m) {
  return delta_m > 0.0 ? c.stiffness * std::pow(delta_m, c.exponent + 1.0) / (c.exponent + 1.0)
                       : 0.0;
}

/// Everything the replay carries from step to step besides the state.
struct Integrator {
  const RobotModel& model;
  const ContactParams& contact;
  const ReplayParams& gains;
  const ReplayPlan& plan;
  RobotData data;
  Contacts contacts;
  StepSolver solver{};  ///< the step's factorisations (step_system.hpp)
  // cumulative since the start
  double actuator_energy_J = 0.0;
  double actuator_work_J = 0.0;  ///< ∫ τ·q̇ dt, signed
  /// Work the normal forces took from the robot; minus the energy stored in the contact
  /// springs (spring_energy), the energy the normal damping dissipated.
  LegArray<double> normal_work_J{}, spring_at_start_J{}, slip_J{}, slip_distance_m{};
  LegArray<Vec3> slip_displacement_m = zero_vectors();
  /// Stick–slip (contact.friction_law): each foot's spring deflection and mode.
  LegArray<TangentialContact> tangential{};
  DriveSpending spent{};        ///< with actuators: what the drives spent
  JointVector armature_kgm2{};  ///< with actuators: each joint's J_a (joint_armatures)
  long steps = 0, forced = 0;
  double max_step_s = 0.0;
  double h_next = 0.0;  ///< the next step to try [s]
  /// Per plan instant: the planned centre of mass's height and the terrain's under it [m]
  /// (the fall test, fall_reason).
  std::vector<double> plan_com_z_m{}, plan_ground_z_m{};
};

/// replay.early_contact: hold (docs/theory/replay.md#early-contact). For each leg whose foot
/// touches the terrain (c) while the plan swings it at its instant k (the step's start, or the
/// sample), on a face it could stand on (tilted from the horizontal by at most atan μ_s: a
/// tread, not a riser it stubs), sets that leg's damping reference in `qd_ref` to the joint
/// rates that hold the foot still under the trunk's twist at state s (step_system.hpp
/// holding_rates).
void hold_early_contacts(const Integrator& it, const Contacts& c, const SimState& s, std::size_t k,
                         JointVector& qd_ref) {
  if (it.gains.early_contact != EarlyContact::kHold) return;
  const auto row = static_cast<Eigen::Index>(k);
  const Vec3 up_W = -it.model.gravity_W.normalized();
  const double mu = it.contact.static_friction, min_cos = 1.0 / std::sqrt(1.0 + mu * mu);
  for (int l = 0; l < c.legs; ++l) {
    if (it.plan.contact_phase(row, l) != static_cast<std::int8_t>(ContactPhase::kSwing) ||
        !(c.geometry[l].penetration_m > 0.0) || c.normals[l].dot(up_W) < min_cos)
      continue;
    const LegInfo& leg = it.model.leg(l);
    qd_ref.segment(leg.first_joint, leg.n_joints) = holding_rates(leg, c.J[l], s.base);
  }
}

/// The error control halves a step at most this many times below replay.step: a step of
/// replay.step / 64 is accepted as it is (counted in ReplayResult::forced_steps).
constexpr double kMinStepFraction = 1.0 / 64.0;

/// Advances the trunk pose and joint angles by h at the new velocities (symplectic Euler).
void advance_positions(SimState& s, double h) {
  s.q += h * s.qd;
  s.base.p_W += h * s.base.v_W;
  const double angle = h * s.base.omega_W.norm();
  if (angle > 0.0) {
    const Mat3 dR = Eigen::AngleAxisd(angle, s.base.omega_W.normalized()).toRotationMatrix();
    s.base.W_R_B = dR * s.base.W_R_B;
  }
  // Keep the rotation orthonormal against rounding (a polar step: R (RᵀR)^(-1/2) ≈ ...).
  const Mat3& R = s.base.W_R_B;
  s.base.W_R_B = 1.5 * R - 0.5 * R * R.transpose() * R;
}

std::string stop_reason(const SimState& s, double t);

/// What one step proposes: the next state, the torques and the contact forces that acted
/// in it (linearised about the start, at the new velocities).
struct Step {
  SimState next;
  JointVector tau;
  LegArray<Vec3> force_W = zero_vectors();
  DrivenJoints drive;  ///< with actuators (then tau is drive.u)
  /// Stick–slip: the feet that slid in the step, and their tangential force's direction.
  LegArray<bool> slid{};
  LegArray<Vec3> slip_force_direction_W = zero_vectors();
};

/// Stick–slip: marks as sliding the feet not yet sliding in `out` whose tangential force at
/// the step's end, F(ν_new) of `force`, exceeds their cap (friction_cap at its normal part),
/// with their force's direction. Returns whether any foot was marked.
bool capped_feet(const Integrator& it, const Contacts& c, const LegArray<AffineForce>& force,
                 const DofVector& nu_new, Step& out) {
  if (it.contact.friction_law != FrictionLaw::kStickSlip) return false;
  bool marked = false;
  for (int l = 0; l < c.legs; ++l) {
    if (!(c.geometry[l].penetration_m > 0.0) || out.slid[l]) continue;
    const Vec3& n = c.normals[l];
    const Vec3 F = force[l].a + force[l].B * foot_velocity(it.model.leg(l), c.J[l], nu_new);
    const Vec3 Ft = F - n.dot(F) * n;
    if (Ft.norm() <= friction_cap(it.contact, it.tangential[l], n.dot(F))) continue;
    out.slid[l] = true;
    out.slip_force_direction_W[l] = Ft.normalized();
    marked = true;
  }
  return marked;
}

/// One linearly implicit Euler step of length h from s (contacts evaluated at s in
/// it.contacts), towards the plan point p (file comment of replay.hpp):
///   (M + h (h k_p + k_d) S Sᵀ − h Σ J_lᵀ B_l J_l) Δν = h (f₀ + Σ J_lᵀ (a_l + B_l J_l ν₀)),
/// f₀ the gravity, velocity terms, feedforward and PD at the start.
void implicit_step(Integrator& it, const SimState& s, const PlanPoint& p, double h, Step& out) {
  RobotData& data = it.data;
  const Contacts& c = it.contacts;
  BaseState rest = s.base;
  rest.a_W.setZero();
  rest.omegadot_W.setZero();
  const Eigen::Index n = s.q.size();
  DofVector f = -rnea(it.model, data, rest, s.q, s.qd, JointVector::Zero(n), nullptr, nullptr);
  DofMatrix A = crba(it.model, data, s.base, s.q);
  const double kp = it.gains.kp_Nmprad, kd = it.gains.kd_Nmsprad;
  const bool driven = it.model.drive.present;
  if (driven) {
    add_driven_joint_rows(it.model.drive, it.gains, s.q, s.qd, p.q, p.qd, p.tau, h, f, A,
                          out.drive);
  } else {
    f.tail(n) += p.tau + kp * (p.q - s.q - h * s.qd) + kd * (p.qd - s.qd);
    A.diagonal().tail(n).array() += h * (h * kp + kd);
  }
  const DofVector nu = s.nu();
  LegArray<AffineForce> force;
  LegArray<Vec3> v_start = zero_vectors();
  for (int l = 0; l < c.legs; ++l) v_start[l] = foot_velocity(it.model.leg(l), c.J[l], nu);
  out.slid.fill(false);
  DofVector nu_new = nu;
  // Stick–slip's return mapping (contact/stick_slip.hpp): every foot sticks, then a foot whose
  // stick force exceeds its cap slides and the step is solved again, until none does.
  for (int pass = 0; pass <= c.legs; ++pass) {
    DofVector rhs = f;
    DofMatrix lhs = A;
    for (int l = 0; l < c.legs; ++l) {
      if (!(c.geometry[l].penetration_m > 0.0)) continue;
      force[l] =
          affine_contact(it.contact, c.geometry[l], c.law[l], it.tangential[l],
                         out.slid[l] ? &out.slip_force_direction_W[l] : nullptr, v_start[l], h);
      add_contact_rows(it.model.leg(l), c.J[l], force[l], v_start[l], h, lhs, rhs);
    }
    const bool symmetric = std::none_of(out.slid.begin(), out.slid.end(), [](bool b) { return b; });
    nu_new = nu + it.solver.solve(lhs, h * rhs, symmetric);
    if (!capped_feet(it, c, force, nu_new, out)) break;
  }
  out.next = s;
  out.next.base.v_W = nu_new.head<3>();
  out.next.base.omega_W = nu_new.segment<3>(3);
  out.next.qd = nu_new.tail(n);
  if (driven) {
    finish_driven_joints(it.gains, s.q, p.q, p.qd, p.tau, out.next.qd, h, out.drive);
    out.tau = out.drive.u;
  } else {
    out.tau = p.tau + kp * (p.q - s.q - h * out.next.qd) + kd * (p.qd - out.next.qd);
  }
  for (int l = 0; l < c.legs; ++l)
    out.force_W[l] =
        c.geometry[l].penetration_m > 0.0
            ? Vec3(force[l].a + force[l].B * foot_velocity(it.model.leg(l), c.J[l], nu_new))
            : Vec3::Zero();
  advance_positions(out.next, h);
}

/// The largest difference between the normal force of the contact law at the step's end and
/// the one the step applied, over the feet [N]. The friction is left out: its secant is
/// dissipative at any step, and within the stiction speed its law is a regularisation whose
/// shape the motion does not resolve (docs/theory/replay.md#integrator).
double force_mismatch(const Contacts& at_end, const Step& step) {
  double worst = 0.0;
  for (int l = 0; l < at_end.legs; ++l)
    worst =
        std::max(worst, std::abs(at_end.law[l].normal_N - at_end.normals[l].dot(step.force_W[l])));
  return worst;
}

/// Adds an accepted step's spending and dissipation, with the forces that acted in it: the
/// discrete balance of energy holds to the step's order. at_start, at_end: the contacts at
/// the step's start and end.
void account_step(Integrator& it, const Contacts& at_start, const Contacts& at_end,
                  const Step& step, double h) {
  it.actuator_energy_J += h * lane_abs_dot(step.tau, step.next.qd);
  it.actuator_work_J += h * lane_dot(step.tau, step.next.qd);
  if (it.model.drive.present)
    account_driven_step(it.model.drive, step.drive, step.next.qd, h, it.spent);
  const DofVector nu_new = step.next.nu();
  const bool stick_slip = it.contact.friction_law == FrictionLaw::kStickSlip;
  for (int l = 0; l < at_start.legs; ++l) {
    if (step.force_W[l].isZero(0.0)) {
      it.tangential[l] = {};
      continue;
    }
    const Vec3& n = at_start.normals[l];
    const Vec3 v_new = foot_velocity(it.model.leg(l), at_start.J[l], nu_new);
    const Vec3& F = step.force_W[l];
    const Vec3 vt = v_new - n.dot(v_new) * n;
    // The normal work over the step's displacement, to second order (the Jacobians of both
    // ends: the start's alone misses ½ h² J̇ν), as the spring's energy is taken at the ends'
    // penetrations (docs/theory/replay.md#balance-of-energy).
    const Vec3 v_mid = 0.5 * (v_new + foot_velocity(it.model.leg(l), at_end.J[l], nu_new));
    it.normal_work_J[l] -= h * n.dot(F) * n.dot(v_mid);
    it.slip_J[l] -= h * (F - n.dot(F) * n).dot(vt);
    // The slip: the foot's tangential motion, or with stick–slip its anchor's.
    Vec3 slip = h * vt;
    if (stick_slip) {
      const TangentialUpdate u =
          settle_stick_slip(it.contact, it.tangential[l], n, std::max(0.0, n.dot(F)), vt, h,
                            step.slid[l] ? &step.slip_force_direction_W[l] : nullptr);
      it.tangential[l] = u.next;
      slip = u.slip_W;
    }
    it.slip_displacement_m[l] += slip;
    it.slip_distance_m[l] += slip.norm();
  }
  ++it.steps;
  it.max_step_s = std::max(it.max_step_s, h);
}

/// Integrates from the plan's instant k to k + 1 (s holds the state at k, it.contacts its
/// contacts), halving a step whose applied contact forces differ from the law at its end by
/// more than replay.tolerance × the robot's weight, and growing it back towards replay.step.
/// Returns false (with `why`) when the state stops being finite.
bool integrate_interval(Integrator& it, SimState& s, std::size_t k, std::string& why) {
  const double t0 = it.plan.t_s[k], t1 = it.plan.t_s[k + 1];
  const double limit_N = it.gains.tolerance * it.model.total_mass_kg * kGravity;
  Step step;
  Contacts at_end;
  double t = t0;
  while (t1 - t > 1e-12 * std::max(1.0, std::abs(t1))) {
    double h = std::min(it.h_next, t1 - t);
    for (;;) {
      PlanPoint p = plan_at(it.plan, k, t, t + h);
      hold_early_contacts(it, it.contacts, s, k, p.qd);
      implicit_step(it, s, p, h, step);
      if (!step.next.finite()) break;
      evaluate_contacts(it.model, it.data, it.contact, it.plan, step.next, at_end);
      if (force_mismatch(at_end, step) <= limit_N) break;
      if (h <= kMinStepFraction * it.gains.step_s) {
        ++it.forced;
        break;
      }
      h *= 0.5;
    }
    account_step(it, it.contacts, at_end, step, h);
    s = step.next;
    std::swap(it.contacts, at_end);  // at_end is overwritten by the next step
    apply_stick_slip(it.contact, it.tangential, it.contacts);
    t += h;
    it.h_next = std::min(it.gains.step_s, 2.0 * h);
    why = stop_reason(s, t);
    if (!why.empty()) return false;
    report_progress("replay", t - it.plan.t_s.front(), it.plan.t_s.back() - it.plan.t_s.front(),
                    "s of motion");
  }
  return true;
}

/// A driven sample's forward dynamics (docs/theory/replay.md#driven-by-the-actuators): the
/// drive torque u (given in `tau`: feedforward and PD at the state) bounded by the envelope at
/// the state's rates, the joints' friction by the regularised law, and
/// (M + diag(0, J_a)) ν̇ = [0; u − τ_f] + Σ J_lᵀ F_l − h (data.M then holds M + diag(0, J_a)).
/// Appends u and the bound flags to `out`, returns ν̇ and leaves in `tau` the torque reaching
/// the links, u − τ_f − J_a q̈.
const DofVector& driven_sample(Integrator& it, const SimState& s, JointVector& tau,
                               ReplayResult& out) {
  const Eigen::Index n = s.q.size();
  JointVector u(n), flags(n), link(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const ActuatorParams& a = it.model.drive.joints[j];
    bool at_bound = false;
    u[j] = bounded_drive_torque(a, it.gains.saturate, tau[j], s.qd[j], at_bound);
    flags[j] = at_bound ? 1.0 : 0.0;
    link[j] = u[j] - joint_friction_torque(a, s.qd[j]);
  }
  const Contacts& c = it.contacts;
  const DofVector& nu_dot = forward_dynamics_joints(it.model, it.data, s.base, s.q, s.qd, link,
                                                    &c.force_W, &c.normals, &it.armature_kgm2);
  tau = link - it.armature_kgm2.cwiseProduct(nu_dot.tail(n));
  out.tau_drive.push_back(u);
  out.saturated.push_back(flags);
  out.electrical_J.push_back(it.spent.electrical_J);
  out.copper_loss_J.push_back(it.spent.copper_loss_J);
  out.joint_friction_J.push_back(it.spent.joint_friction_J);
  return nu_dot;
}

/// Appends the sample of state s at the plan's instant k: torques, forces and the forward
/// dynamics evaluated at s, the cumulative energies and slips.
/// it.contacts holds the contacts of s (integrate_interval leaves them so).
/// Returns the robot's centre of mass at s.
Vec3 record_sample(Integrator& it, const SimState& s, std::size_t k, ReplayResult& out) {
  RobotData& data = it.data;
  const Contacts& c = it.contacts;
  const ReplayPlan& plan = it.plan;
  const bool driven = it.model.drive.present;
  const JointVector& ff = driven ? plan.tau_drive_Nm[k] : plan.tau_Nm[k];
  JointVector qd_ref = plan.qd_radps[k];
  hold_early_contacts(it, c, s, k, qd_ref);
  JointVector tau =
      ff + it.gains.kp_Nmprad * (plan.q_rad[k] - s.q) + it.gains.kd_Nmsprad * (qd_ref - s.qd);
  // Driven: tau in is the drive torque, out the link torque; data.M holds the armature.
  const DofVector& nu_dot = driven ? driven_sample(it, s, tau, out)
                                   : forward_dynamics_joints(it.model, data, s.base, s.q, s.qd, tau,
                                                             &c.force_W, &c.normals);
  BaseState b = s.base;
  b.a_W = nu_dot.head<3>();
  b.omegadot_W = nu_dot.segment<3>(3);
  const DofVector nu = s.nu();
  const DofVector momentum = data.M * nu;
  out.kinetic_J.push_back(0.5 * lane_dot(nu, momentum));  // with the armature's
  const Momentum& m = robot_momentum(it.model, data, s.base, s.q, s.qd);
  out.potential_J.push_back(-m.mass_kg * it.model.gravity_W.dot(m.com_W));
  out.t_s.push_back(plan.t_s[k]);
  out.base.push_back(b);
  out.q.push_back(s.q);
  out.qd.push_back(s.qd);
  out.qdd.push_back(nu_dot.tail(s.q.size()));
  out.tau.push_back(tau);
  out.tau_ff.push_back(ff);
  out.tracking_error.push_back(s.q - plan.q_rad[k]);
  LegArray<Vec3> foot = zero_vectors(), slip_v = zero_vectors(), normal = zero_vectors();
  LegArray<double> fn{}, pen{};
  for (int l = 0; l < c.legs; ++l) {
    foot[l] = c.geometry[l].point_W;
    normal[l] = c.geometry[l].normal_W;
    slip_v[l] = c.law[l].slip_velocity_W;
    fn[l] = c.law[l].normal_N;
    pen[l] = std::max(0.0, c.geometry[l].penetration_m);
  }
  out.force_W.push_back(c.force_W);
  out.foot_W.push_back(foot);
  out.normal_W.push_back(normal);
  out.slip_velocity_W.push_back(slip_v);
  out.normal_N.push_back(fn);
  out.penetration_m.push_back(pen);
  out.slip_displacement_W.push_back(it.slip_displacement_m);
  out.slip_distance_m.push_back(it.slip_distance_m);
  LegArray<double> damping{};
  for (int l = 0; l < c.legs; ++l)
    damping[l] = it.normal_work_J[l] -
                 (spring_energy(it.contact, c.geometry[l].penetration_m) - it.spring_at_start_J[l]);
  if (out.t_s.size() == 1) {  // the first sample: the springs' energy at the start
    for (int l = 0; l < c.legs; ++l)
      it.spring_at_start_J[l] = spring_energy(it.contact, c.geometry[l].penetration_m);
    damping.fill(0.0);
  }
  out.damping_energy_J.push_back(damping);
  // With stick–slip, the tangential work includes what the tangential springs hold at the
  // instant (at most (μ F_n)² / (2 k_t) per foot).
  out.slip_energy_J.push_back(it.slip_J);
  out.actuator_energy_J.push_back(it.actuator_energy_J);
  return m.com_W;
}

/// Why the replay must stop at state s (no longer finite), or "".
std::string stop_reason(const SimState& s, double t) {
  if (!s.finite())
    return "the state is no longer finite at t = " + std::to_string(t) +
           " s (the integration diverged; a smaller replay.step may help)";
  return "";
}

/// Why the replayed robot has fallen at the plan's instant k (docs/theory/replay.md#falls),
/// or "": its centre of mass is below half the planned one's height above the terrain under
/// the planned one (com_W: the replay's), or its trunk is tilted more than kFallTilt_rad from
/// the planned trunk. The robot's own geometry decides, not where its URDF puts the trunk
/// frame's origin.
std::string fall_reason(const Integrator& it, const SimState& s, const Vec3& com_W, std::size_t k) {
  const double ground = it.plan_ground_z_m[k];
  const double planned = it.plan_com_z_m[k] - ground;
  const double height = com_W.z() - ground;
  const double t = it.plan.t_s[k];
  if (height < kFallHeightFraction * planned)
    return "the robot fell at t = " + format_number(t, 6) + " s: its centre of mass is " +
           format_number(height, 3) + " m above the terrain, below half the planned " +
           format_number(planned, 3) + " m";
  const double tilt =
      std::acos(std::clamp(s.base.W_R_B.col(2).dot(it.plan.base[k].W_R_B.col(2)), -1.0, 1.0));
  if (tilt > kFallTilt_rad)
    return "the robot fell at t = " + format_number(t, 6) + " s: its trunk is tilted " +
           format_number(tilt * 180.0 / M_PI, 3) + " degrees from the planned trunk (at most " +
           format_number(kFallTilt_rad * 180.0 / M_PI, 3) + ")";
  return "";
}

/// The planned centre of mass and the terrain under it at every plan instant.
void plan_com_heights(Integrator& it, const Terrain& terrain) {
  const ReplayPlan& p = it.plan;
  for (std::size_t k = 0; k < p.t_s.size(); ++k) {
    const Vec3 com = robot_momentum(it.model, it.data, p.base[k], p.q_rad[k], p.qd_radps[k]).com_W;
    it.plan_com_z_m.push_back(com.z());
    it.plan_ground_z_m.push_back(terrain.height(com.x(), com.y()));
  }
}

}  // namespace

double weight_moment_Nm(const RobotModel& model) {
  return model.total_mass_kg * model.gravity_W.norm() * longest_leg_reach_m(model);
}

bool weak_joint_pd(double kp_Nmprad, double weight_moment_Nm) {
  return 0.1 * kp_Nmprad < weight_moment_Nm / 50.0;
}

ReplayParams resolved_gains(const ReplayParams& replay, const RobotModel& model) {
  ReplayParams g = replay;
  if (g.kp_auto) {
    const double moment_Nm = weight_moment_Nm(model), light_Nmprad = ReplayParams{}.kp_Nmprad;
    g.kp_Nmprad = weak_joint_pd(light_Nmprad, moment_Nm) ? kAutoGainPerWeightMoment * moment_Nm
                                                         : light_Nmprad;
  }
  if (g.kd_auto) g.kd_Nmsprad = 0.01 * g.kp_Nmprad;
  return g;
}

ReplayResult replay_plan(const RobotModel& model, const ContactParams& contact,
                         const ReplayParams& replay, const TerrainParams& terrain_params,
                         const ReplayPlan& plan) {
  check_plan(model, plan);
  check_replay_work(plan, replay);
  const auto start = std::chrono::steady_clock::now();
  Integrator it{model, contact, replay, plan, RobotData(model), Contacts{}};
  if (model.drive.present) {
    it.armature_kgm2 = joint_armatures(model.drive);
    it.spent.saturated_s.assign(static_cast<std::size_t>(model.joints()), 0.0);
  }
  check_mass_matrix(model, it.data, plan);
  plan_com_heights(it, Terrain(terrain_params));
  SimState s;
  s.base = plan.base.front();
  s.q = plan.q_rad.front();
  s.qd = plan.qd_radps.front();
  ReplayResult r;
  evaluate_contacts(model, it.data, contact, plan, s, it.contacts);
  apply_stick_slip(contact, it.tangential, it.contacts);
  record_sample(it, s, 0, r);
  bool completed = true;
  it.h_next = replay.step_s;
  for (std::size_t k = 0; k + 1 < plan.t_s.size() && completed; ++k) {
    completed = integrate_interval(it, s, k, r.message);
    if (!completed) break;
    const Vec3 com_W = record_sample(it, s, k + 1, r);
    r.message = fall_reason(it, s, com_W, k + 1);
    completed = r.message.empty();
    r.fell = !completed;
  }
  finish_report(plan, terrain_params, model.drive, completed, r);
  r.saturation_time_s = it.spent.saturated_s;
  // The balance of energy over the replay: what the joints did, less what the robot gained
  // (kinetic, potential, the contact springs) and what the contacts dissipated.
  double stored =
      r.kinetic_J.back() - r.kinetic_J.front() + r.potential_J.back() - r.potential_J.front();
  for (int l = 0; l < model.legs(); ++l)
    stored += spring_energy(contact, it.contacts.geometry[l].penetration_m) -
              it.spring_at_start_J[l] + r.damping_energy_J.back()[l] + r.slip_energy_J.back()[l];
  stored += it.spent.joint_friction_J;  // 0 without actuators
  r.actuator_work_J = it.actuator_work_J;
  r.energy_residual_J = it.actuator_work_J - stored;
  r.steps = it.steps;
  r.forced_steps = it.forced;
  r.max_step_s = it.max_step_s;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace hexdyn
