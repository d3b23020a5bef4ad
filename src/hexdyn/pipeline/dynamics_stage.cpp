#include "hexdyn/pipeline/dynamics_stage.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

int friction_faces(FrictionModel m) {
  switch (m) {
    case FrictionModel::kPyramid4: return 4;
    case FrictionModel::kPyramid8: return 8;
    case FrictionModel::kCone: return 0;
  }
  return 4;
}

constexpr const char* kTrunkRowNames[6] = {"trunk force x",  "trunk force y",  "trunk force z",
                                           "trunk moment x", "trunk moment y", "trunk moment z"};
/// Slack weights (allocation_qp.hpp ineq_penalty) set which rows give way when the
/// constraints cannot all hold: torque limits first (weight 1: the actuators are too
/// weak), then the trunk rows (the prescribed motion cannot be produced, as during a
/// touchdown transient with no other foot on the ground), and the contact rows last
/// (the ground cannot pull; more friction than μ means slipping, which the model
/// excludes).
constexpr double kTrunkRowPenaltyWeight = 1e2;
constexpr double kContactRowPenaltyWeight = 1e3;
/// Impact legs keep a fixed normal force, so their friction limit is a polygon even in
/// the exact-cone model: an inscribed 16-gon (within 2% of the circle).
constexpr int kImpactConeFaces = 16;
/// How far before a contact event its left limit is evaluated [s].
constexpr double kEventLeftLimit_s = 1e-10;

/// Row names, built once: building them per sample would cost more than the solve.
struct RowNames {
  std::array<std::string, kJoints> torque;
  std::array<std::string, kLegs> normal;
  std::array<std::array<std::string, kImpactConeFaces>, kLegs> face;
  RowNames() {
    for (int l = 0; l < kLegs; ++l) {
      for (int j = 0; j < kJointsPerLeg; ++j) torque[joint_index(l, j)] = "torque " + joint_name(l, j);
      normal[l] = "normal " + leg_name(l);
      for (int f = 0; f < kImpactConeFaces; ++f)
        face[l][f] = "friction " + leg_name(l) + " face " + std::to_string(f + 1);
    }
  }
};
const RowNames& row_names() {
  static const RowNames names;
  return names;
}

}  // namespace

Mat3 contact_frame(const Vec3& n_W) {
  const Vec3 n = n_W.normalized();
  Vec3 t1 = Vec3::UnitX() - n.x() * n;
  if (t1.norm() < 1e-9) t1 = Vec3::UnitY() - n.y() * n;
  t1.normalize();
  Mat3 R;
  R.col(0) = t1;
  R.col(1) = n.cross(t1);
  R.col(2) = n;
  return R;
}

double foot_effective_mass(const RobotModel& model, RobotData& data, const BaseState& base, const VecJ& q,
                           int leg, const Vec3& n_W) {
  crba(model, data, base, q);
  foot_jacobians(model, data, base, q);
  const int c = 6 + joint_index(leg, 0);
  const Mat3 M_ll = data.M.block<3, 3>(c, c);
  const Mat3 J = data.J_foot_W[leg].block<3, 3>(0, c);
  const Mat3 Lambda_inv = J * M_ll.llt().solve(J.transpose());
  return 1.0 / (n_W.transpose() * Lambda_inv * n_W);
}

BaseState base_state_at(const KinematicsResult& kin, int i) {
  BaseState b;
  const auto o = kin.base_orientation_wxyz.row(i);
  b.W_R_B = Quat(o(0), o(1), o(2), o(3)).normalized().toRotationMatrix();
  b.p_W = kin.base_position.row(i).transpose();
  b.v_W = kin.base_linear_velocity.row(i).transpose();
  b.omega_W = kin.base_angular_velocity.row(i).transpose();
  b.a_W = kin.base_linear_acceleration.row(i).transpose();
  b.omegadot_W = kin.base_angular_acceleration.row(i).transpose();
  return b;
}

std::vector<Touchdown> resolve_touchdowns(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                                          const ContactParams& contact) {
  std::vector<Touchdown> out;
  RobotKinematicState s;
  for (int leg = 0; leg < kLegs; ++leg) {
    for (const Swing& sw : plan.gait.legs[leg].swings) {
      Touchdown td;
      td.leg = leg;
      td.t_s = sw.t_touchdown_s;
      td.normal_W = plan.terrain.normal(sw.p_touchdown_W.x(), sw.p_touchdown_W.y());
      const FootMotion arrival = swing_foot_motion(sw, sw.t_touchdown_s);
      td.approach_speed_mps = -arrival.v_W.dot(td.normal_W);
      robot_state_at(model, plan, td.t_s, s);
      BaseState base;
      base.W_R_B = s.trunk.W_R_B;
      base.p_W = s.trunk.p_W;
      td.effective_mass_kg = foot_effective_mass(model, data, base, s.q, leg, td.normal_W);
      // Rigid contact: no transient (occurred = false), the foot supports from touchdown on.
      if (contact.model == ContactModel::kCompliant)
        td.transient = simulate_touchdown(contact, td.effective_mass_kg, td.approach_speed_mps, ImpactOptions{});
      out.push_back(std::move(td));
    }
  }
  std::sort(out.begin(), out.end(), [](const Touchdown& a, const Touchdown& b) {
    return a.t_s < b.t_s || (a.t_s == b.t_s && a.leg < b.leg);
  });
  return out;
}

void sample_contacts(const KinematicsResult& kin, int i, const Terrain& terrain,
                     const std::vector<Touchdown>& touchdowns, SampleContacts& out) {
  const double t = kin.time_s[i];
  out.impacting_legs = 0;
  for (int l = 0; l < kLegs; ++l) {
    out.phase[l] = kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kSwing) ? ContactPhase::kSwing
                                                                                           : ContactPhase::kSupport;
    out.impact_force_N[l] = 0.0;
    out.impact_penetration_m[l] = 0.0;
    const Vec3 p = kin.foot_position.row(i).segment<3>(3 * l).transpose();
    out.W_R_contact[l] = contact_frame(terrain.normal(p.x(), p.y()));
  }
  for (const Touchdown& td : touchdowns) {
    if (!td.transient.occurred || t < td.t_s || t >= td.t_s + td.transient.duration_s) continue;
    if (out.phase[td.leg] == ContactPhase::kSwing) continue;
    out.phase[td.leg] = ContactPhase::kImpact;
    out.impact_force_N[td.leg] = transient_force_at(td.transient, t - td.t_s);
    out.impact_penetration_m[td.leg] = transient_penetration_at(td.transient, t - td.t_s);
    ++out.impacting_legs;
  }
}

double build_allocation_problem(const AllocationParams& alloc, const ContactParams& contact,
                                const ContactSplit& split, const std::array<ContactPhase, kLegs>& phase,
                                const std::array<double, kLegs>& impact_force_N,
                                const std::array<Mat3, kLegs>& W_R_c, QpProblem& qp,
                                std::array<int, kLegs>& offset, std::string* constant_violation) {
  const int faces = friction_faces(alloc.friction);
  const double mu = contact.friction_coefficient;
  // Layout and sizes.
  int n = 0, m_in = 6;  // six trunk rows (lower = upper, so that they can be relaxed)
  for (int l = 0; l < kLegs; ++l) {
    offset[l] = -1;
    if (phase[l] == ContactPhase::kSwing) continue;
    offset[l] = n;
    const bool support = phase[l] == ContactPhase::kSupport;
    n += support ? 3 : 2;
    m_in += kJointsPerLeg;                 // torque rows
    if (support) m_in += 1;                // normal force row
    m_in += support ? faces : (faces ? faces : kImpactConeFaces);
  }
  qp.resize(n, 0, m_in);
  // Known forces: the normal force of impact legs.
  VecJ tau_known = split.tau0;
  Vec6 trunk_rhs = split.trunk_rhs;
  for (int l = 0; l < kLegs; ++l) {
    if (phase[l] != ContactPhase::kImpact) continue;
    const Vec3 F_fixed = impact_force_N[l] * W_R_c[l].col(2);
    tau_known -= split.JjT[l] * F_fixed;
    trunk_rhs -= split.JbT[l] * F_fixed;
  }
  // Torques τ = tau_known − G x; trunk rows B x = trunk_rhs (at most 18 variables: on the stack).
  using GMatrix = Eigen::Matrix<double, kJoints, Eigen::Dynamic, Eigen::ColMajor, kJoints, 3 * kLegs>;
  using BMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, 3 * kLegs>;
  GMatrix G = GMatrix::Zero(kJoints, n);
  BMatrix B = BMatrix::Zero(6, n);
  for (int l = 0; l < kLegs; ++l) {
    if (offset[l] < 0) continue;
    const int k = phase[l] == ContactPhase::kSupport ? 3 : 2;
    G.middleCols(offset[l], k) = split.JjT[l] * W_R_c[l].leftCols(k);
    B.middleCols(offset[l], k) = split.JbT[l] * W_R_c[l].leftCols(k);
  }
  // Objective Σ τ² = |tau_known − G x|² = ½ xᵀ (2 GᵀG) x − 2 (Gᵀ tau_known)ᵀ x + |tau_known|².
  qp.H = 2.0 * G.transpose() * G;
  qp.g = -2.0 * G.transpose() * tau_known;
  qp.constant = tau_known.squaredNorm();
  int row = 0;
  for (int r = 0; r < 6; ++r, ++row) {
    qp.C.row(row) = B.row(r);
    qp.lower[row] = qp.upper[row] = trunk_rhs[r];
    qp.ineq_names[row] = kTrunkRowNames[r];
    qp.ineq_penalty[row] = kTrunkRowPenaltyWeight;
  }
  const double tmax = alloc.torque_limit_Nm;
  double worst_constant = 0.0;
  for (int l = 0; l < kLegs; ++l) {
    if (offset[l] < 0) {
      for (int j = 0; j < kJointsPerLeg; ++j) {
        const double excess = std::abs(tau_known[joint_index(l, j)]) - tmax;
        if (excess > worst_constant) {
          worst_constant = excess;
          if (constant_violation) {
            std::ostringstream os;
            os.precision(3);
            os << "torque " << joint_name(l, j) << " (swing leg) by " << excess;
            *constant_violation = os.str();
          }
        }
      }
      continue;
    }
    const int o = offset[l];
    for (int j = 0; j < kJointsPerLeg; ++j, ++row) {
      const int kk = joint_index(l, j);
      qp.C.row(row) = G.row(kk);
      qp.lower[row] = tau_known[kk] - tmax;
      qp.upper[row] = tau_known[kk] + tmax;
      qp.ineq_names[row] = row_names().torque[kk];
    }
    const bool support = phase[l] == ContactPhase::kSupport;
    if (support) {
      qp.C(row, o + 2) = 1.0;
      qp.lower[row] = alloc.min_normal_force_N;
      qp.upper[row] = std::numeric_limits<double>::infinity();
      qp.ineq_penalty[row] = kContactRowPenaltyWeight;
      qp.ineq_names[row++] = row_names().normal[l];
    }
    const int nf = faces ? faces : (support ? 0 : kImpactConeFaces);
    // Inscribed N-gon: face normals at 2πk/N, at distance μ f_n cos(π/N).
    for (int f = 0; f < nf; ++f, ++row) {
      const double a = 2.0 * M_PI * f / nf;
      const double reach = mu * std::cos(M_PI / nf);
      qp.C(row, o) = std::cos(a);
      qp.C(row, o + 1) = std::sin(a);
      qp.lower[row] = -std::numeric_limits<double>::infinity();
      if (support) {
        qp.C(row, o + 2) = -reach;
        qp.upper[row] = 0.0;
      } else {
        qp.upper[row] = reach * impact_force_N[l];
      }
      qp.ineq_penalty[row] = kContactRowPenaltyWeight;
      qp.ineq_names[row] = row_names().face[l][f];
    }
    if (!faces && support)
      qp.cones.push_back({o, o + 1, o + 2, mu, "friction cone " + leg_name(l), kContactRowPenaltyWeight});
  }
  return worst_constant;
}

void forces_from_solution(const ContactSplit& split, const std::array<ContactPhase, kLegs>& phase,
                          const std::array<double, kLegs>& impact_force_N, const std::array<Mat3, kLegs>& W_R_c,
                          const std::array<int, kLegs>& offset, const Eigen::VectorXd& x,
                          std::array<Vec3, kLegs>& F_W, VecJ& tau) {
  tau = split.tau0;
  for (int l = 0; l < kLegs; ++l) {
    F_W[l].setZero();
    if (phase[l] == ContactPhase::kSupport) {
      F_W[l] = W_R_c[l] * x.segment<3>(offset[l]);
    } else if (phase[l] == ContactPhase::kImpact) {
      F_W[l] = W_R_c[l].leftCols<2>() * x.segment<2>(offset[l]) + impact_force_N[l] * W_R_c[l].col(2);
    }
    tau -= split.JjT[l] * F_W[l];
  }
}

double integrate_series(const std::vector<double>& t, const double* y, int stride) {
  return integrate_pieces(t, y, stride, {}, {});
}

namespace {

/// ∫ over points (t_k, y_k), k < n (integrate_pieces explains the rule).
double integrate_piece(const double* t, const double* y, std::size_t n) {
  if (n < 2) return 0.0;
  if (n == 2) return 0.5 * (t[1] - t[0]) * (y[0] + y[1]);
  gsl_interp* interp = gsl_interp_alloc(gsl_interp_steffen, n);
  gsl_interp_accel* acc = gsl_interp_accel_alloc();
  gsl_interp_init(interp, t, y, n);
  const double value = gsl_interp_eval_integ(interp, t, y, t[0], t[n - 1], acc);
  gsl_interp_accel_free(acc);
  gsl_interp_free(interp);
  return value;
}

}  // namespace

double integrate_pieces(const std::vector<double>& t, const double* y, int stride,
                        const std::vector<int>& break_index, const std::vector<double>& left_value) {
  const std::size_t n = t.size();
  if (n < 2) return 0.0;
  std::vector<double> ys;
  ys.reserve(n);
  double total = 0.0;
  std::size_t a = 0;  // first sample of the current piece
  auto close_piece = [&](std::size_t b, double y_end) {
    ys.clear();
    for (std::size_t k = a; k < b; ++k) ys.push_back(y[k * stride]);
    ys.push_back(y_end);
    total += integrate_piece(t.data() + a, ys.data(), b - a + 1);
    a = b;
  };
  for (std::size_t k = 0; k < break_index.size(); ++k) {
    const auto b = static_cast<std::size_t>(break_index[k]);
    if (b <= a || b >= n) continue;
    close_piece(b, left_value[k]);
  }
  close_piece(n - 1, y[(n - 1) * stride]);
  return total;
}

void compute_power(const KinematicsResult& kin, double total_mass_kg, double distance_m,
                   const std::vector<PowerJump>& jumps, DynamicsResult& dyn) {
  const int T = kin.samples();
  dyn.joint_power = dyn.joint_torque.cwiseProduct(kin.joint_velocity);
  dyn.total_power_W.assign(T, 0.0);
  RowMatrix abs_power = dyn.joint_power.cwiseAbs();
  for (int i = 0; i < T; ++i) dyn.total_power_W[i] = abs_power.row(i).sum();
  std::vector<int> breaks;
  for (const PowerJump& j : jumps) breaks.push_back(j.index);
  std::vector<double> left(jumps.size());
  dyn.energy_joint_J.assign(kJoints, 0.0);
  dyn.energy_total_J = 0.0;
  for (int j = 0; j < kJoints; ++j) {
    for (std::size_t k = 0; k < jumps.size(); ++k) left[k] = jumps[k].abs_power_left_W(j);
    dyn.energy_joint_J[j] = integrate_pieces(kin.time_s, abs_power.data() + j, kJoints, breaks, left);
    dyn.energy_total_J += dyn.energy_joint_J[j];
  }
  dyn.distance_m = distance_m;
  dyn.cost_of_transport = dyn.energy_total_J / (total_mass_kg * kGravity * distance_m);
}

DynamicsResult solve_dynamics(const Scene& scene, const RobotModel& model, const MotionPlan& plan,
                              KinematicsResult& kin, const std::vector<Touchdown>& touchdowns, std::ostream* log) {
  const int T = kin.samples();
  DynamicsResult dyn;
  dyn.present = true;
  dyn.joint_torque.setZero(T, kJoints);
  dyn.contact_force.setZero(T, 3 * kLegs);
  dyn.penetration.setZero(T, kLegs);
  dyn.solver_status.assign(T, 0);
  dyn.solver_iterations.assign(T, 0.0);
  dyn.solver_objective.assign(T, 0.0);
  dyn.solver_seconds.assign(T, 0.0);
  dyn.solver_messages.assign(T, std::string());
  for (const Touchdown& td : touchdowns) {
    if (td.transient.truncated && log)
      *log << "hexdyn: touchdown of " << leg_name(td.leg) << " at t = " << td.t_s
           << " s: transient " << td.transient.message << "\n";
    ImpactRecord r;
    r.leg = td.leg;
    r.t_start_s = td.t_s;
    r.duration_s = td.transient.duration_s;
    r.peak_force_N = td.transient.peak_force_N;
    r.impulse_Ns = td.transient.impulse_Ns;
    r.effective_mass_kg = td.effective_mass_kg;
    r.approach_speed_mps = td.approach_speed_mps;
    if (td.transient.occurred) dyn.impacts.push_back(r);
  }

  RobotData data(model);
  auto backend = make_allocation_backend(scene.allocation);
  QpProblem qp;
  std::array<int, kLegs> offset{};
  SampleContacts c;
  std::array<Vec3, kLegs> F_W;
  VecJ tau;
  // Episode of consecutive non-optimal samples, for the log.
  int episode_count = 0, episode_status = 0;
  double episode_start = 0.0, episode_end = 0.0, episode_worst = -1.0;
  std::string episode_message;
  auto flush_episode = [&]() {
    if (episode_count > 0 && log) {
      *log << "hexdyn: t = [" << episode_start << ", " << episode_end << "] s: " << episode_count
           << (episode_status == 1 ? " sample(s) relaxed: " : " sample(s) failed: ") << episode_message << "\n";
    }
    episode_count = 0;
    episode_status = 0;
    episode_worst = -1.0;
  };

  // One sample of `k`: contacts into `cs`, forces and torques into F_out, tau_out; the
  // excess of constant rows over their limits (build_allocation_problem) into `excess`
  // and `violation`.
  auto solve_sample = [&](const KinematicsResult& k, int i, AllocationBackend& be, SampleContacts& cs,
                          std::array<Vec3, kLegs>& F_out, VecJ& tau_out, double& excess,
                          std::string& violation) -> const QpOutcome& {
    const BaseState base = base_state_at(k, i);
    const VecJ q = k.joint_position.row(i).transpose();
    const VecJ qd = k.joint_velocity.row(i).transpose();
    const VecJ qdd = k.joint_acceleration.row(i).transpose();
    const ContactSplit& split = contact_split(model, data, base, q, qd, qdd);
    sample_contacts(k, i, plan.terrain, touchdowns, cs);
    violation.clear();
    excess = build_allocation_problem(scene.allocation, scene.contact, split, cs.phase, cs.impact_force_N,
                                      cs.W_R_contact, qp, offset, &violation);
    const QpOutcome& outcome = be.solve(qp);
    forces_from_solution(split, cs.phase, cs.impact_force_N, cs.W_R_contact, offset, outcome.x, F_out, tau_out);
    return outcome;
  };

  // Left limits at contact events (compute_power): the sample solved again an instant
  // before, by a back end of its own so that the run's warm starts stay as they are.
  std::vector<PowerJump> jumps;
  std::unique_ptr<AllocationBackend> left_backend;
  SampleContacts c_left;
  std::array<Vec3, kLegs> F_left;
  VecJ tau_left;
  std::array<ContactPhase, kLegs> previous_phase{};
  double constant_excess = 0.0, left_excess = 0.0;
  std::string constant_violation, left_violation;

  for (int i = 0; i < T; ++i) {
    const double t = kin.time_s[i];
    const QpOutcome& outcome =
        solve_sample(kin, i, *backend, c, F_W, tau, constant_excess, constant_violation);
    if (i > 0 && c.phase != previous_phase) {
      // The instant before: far below any grid step (merged at 1e-9 s), far above the
      // rounding of t.
      const double t_left = t - kEventLeftLimit_s;
      if (!left_backend) left_backend = make_allocation_backend(scene.allocation);
      const KinematicsResult k_left = sample_kinematics(model, plan, {t_left});
      solve_sample(k_left, 0, *left_backend, c_left, F_left, tau_left, left_excess, left_violation);
      // A proper left limit only when the event is at this sample (adaptive grid); on a
      // grid that steps over the event the series is integrated across the jump.
      if (c_left.phase == previous_phase) {
        PowerJump jump;
        jump.index = i;
        jump.abs_power_left_W = tau_left.cwiseProduct(k_left.joint_velocity.row(0).transpose()).cwiseAbs();
        jumps.push_back(jump);
      }
    }
    previous_phase = c.phase;
    int status = outcome.status;
    std::string message = outcome.message;
    if (constant_excess > scene.allocation.tolerance && status == 0) {
      status = 1;
      message = "relaxed: " + constant_violation;
    } else if (constant_excess > scene.allocation.tolerance) {
      message += ", " + constant_violation;
    }
    dyn.solver_status[i] = static_cast<std::int8_t>(status);
    dyn.solver_iterations[i] = outcome.iterations;
    dyn.solver_objective[i] = tau.squaredNorm();
    dyn.solver_seconds[i] = outcome.seconds;
    dyn.joint_torque.row(i) = tau.transpose();
    for (int l = 0; l < kLegs; ++l) {
      dyn.contact_force.row(i).segment<3>(3 * l) = F_W[l].transpose();
      double delta = c.impact_penetration_m[l];
      if (c.phase[l] == ContactPhase::kSupport && scene.contact.model == ContactModel::kCompliant)
        delta = static_penetration(scene.contact, std::max(0.0, F_W[l].dot(c.W_R_contact[l].col(2))));
      dyn.penetration(i, l) = delta;
      kin.contact_phase(i, l) = static_cast<std::int8_t>(c.phase[l]);
    }
    if (status != 0) {
      std::string legs;
      for (int l = 0; l < kLegs; ++l)
        if (c.phase[l] == ContactPhase::kImpact) legs += " " + leg_name(l);
      if (!legs.empty()) message += " (impact" + legs + ")";
      dyn.solver_messages[i] = message;
      if (episode_count == 0) episode_start = t;
      episode_end = t;
      ++episode_count;
      episode_status = std::max(episode_status, status);
      if (outcome.max_violation > episode_worst) {
        episode_worst = outcome.max_violation;
        episode_message = message;
      }
    } else {
      flush_episode();
    }
  }
  flush_episode();
  compute_power(kin, model.total_mass_kg, plan.trunk.total_travel_m(), jumps, dyn);
  return dyn;
}

}  // namespace hexdyn
