#include "hexdyn/model/leg_chain.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

namespace hexdyn {
namespace {

/// Eigen's AngleAxis rotation, term for term (rot_axis_cs, robot_model.hpp).
Mat3 rot_axis(const Vec3& axis, double angle) {
  return rot_axis_cs(axis, std::cos(angle), std::sin(angle));
}

/// Unit vector ⊥ a (a unit), the one closest to `hint` when hint is not along a.
Vec3 perpendicular(const Vec3& a, const Vec3& hint) {
  Vec3 v = hint - hint.dot(a) * a;
  if (v.norm() < 1e-9) {
    v = a.unitOrthogonal();
  }
  return v.normalized();
}

/// Shifts q by ±2π into [lo, hi] when that is possible; q itself otherwise.
double into_limits(double q, double lo, double hi) {
  if (q < lo && q + 2.0 * M_PI <= hi) return q + 2.0 * M_PI;
  if (q > hi && q - 2.0 * M_PI >= lo) return q - 2.0 * M_PI;
  return q;
}

/// Joint-limit check of a solution; sets r.reason and r.margin_m when a joint is outside.
bool within_limits(const RobotModel& m, int leg, LegIkResult& r) {
  for (int j = 0; j < m.leg(leg).n_joints; ++j) {
    const int k = m.joint(leg, j);
    const double lo = m.joint_lower_rad[k], hi = m.joint_upper_rad[k];
    r.q[j] = into_limits(r.q[j], lo, hi);
    if (r.q[j] < lo || r.q[j] > hi) {
      r.reason = "joint " + m.joint_source_names[k] + " outside its limits";
      r.margin_m = std::min(r.q[j] - lo, hi - r.q[j]);
      r.margin_unit = "rad";
      return false;
    }
  }
  return true;
}

/// The femur and tibia angles of a yaw–pitch–pitch leg for the coxa angle q0: the planar
/// two-link problem in the femur plane, knee-up branch: the knee on the trunk-normal side of
/// the femur-joint-to-foot chord.
LegIkResult ypp_femur_tibia(const RobotModel& m, int leg, const Vec3& p, double q0) {
  const LegIkData& d = m.leg_ik[leg];
  LegIkResult r;
  const Mat3 R0 = rot_axis(d.a0_H, q0);
  const Vec3 t = d.H_R_J1.transpose() * (R0.transpose() * p - d.o1_H);  // femur joint → foot, J1
  const double tx = t.dot(d.e1_J1), ty = t.dot(d.e2_J1);
  const double dist = std::hypot(tx, ty);
  const double l2 = d.l2_m, l3 = d.l3_m;
  if (!planar_reach_ok(dist, l2, l3, m.ik_min_margin_m, r)) return r;
  const double cos_delta = (dist * dist - l2 * l2 - l3 * l3) / (2.0 * l2 * l3);
  // Knee up: (chord × femur)·n > 0 with n = outward × up; the sign of that product is
  // −sign(δ)·sign(a1·n), so δ takes the sign of −a1·n.
  const Vec3 n_J1 = d.H_R_J1.transpose() * d.outward_H.cross(R0.transpose() * d.up_H);
  const double sigma = d.a1_J1.dot(n_J1) >= 0.0 ? -1.0 : 1.0;
  const double delta = sigma * std::acos(std::clamp(cos_delta, -1.0, 1.0));
  const double q1 = std::atan2(ty, tx) - d.alpha_rad -
                    std::atan2(l3 * std::sin(delta), l2 + l3 * std::cos(delta));
  const double q2 = d.axis_sign * (delta - d.gamma_rad + d.alpha_rad);
  r.q = Vec3(wrap_angle(q0), wrap_angle(q1), wrap_angle(q2));
  if (!within_limits(m, leg, r)) return r;
  r.ok = true;
  return r;
}

/// Closed form for a yaw–pitch–pitch leg (LegIkData comments). The coxa angle puts the
/// foot on the femur plane: w1(q0)·p = κ, i.e. A cos q0 + B sin q0 = C, two roots. Taken
/// first: for a yawing coxa, the root whose outward direction points further to the foot
/// (the foot outside the coxa axis); for a rolling hip (rolling_hip), whose outward
/// direction hardly tells the roots apart, the root nearer the middle of the hip's limits.
/// When a rolling hip's solution leaves a joint limit, the other root's is taken if it lies
/// within them. Femur and tibia: ypp_femur_tibia.
LegIkResult ik_yaw_pitch_pitch(const RobotModel& m, int leg, const Vec3& p) {
  const LegIkData& d = m.leg_ik[leg];
  LegIkResult r;
  const Vec3& a = d.a0_H;
  const Vec3& w = d.w1_H;
  const double wa = w.dot(a), ap = a.dot(p);
  const double A = w.dot(p) - wa * ap;
  const double B = -w.dot(a.cross(p));
  const double C = d.kappa_m - wa * ap;
  const double rad = std::hypot(A, B);
  if (rad <= std::abs(C) + 1e-12) {
    r.reason = "foot inside the lateral offset of the coxa axis";
    r.margin_m = rad - std::abs(C);
    return r;
  }
  const double phi = std::atan2(B, A), psi = std::acos(std::clamp(C / rad, -1.0, 1.0));
  double q0 = phi + psi, q0_other = phi - psi;
  if (rolling_hip(d)) {
    // The root nearer the middle of the hip's range: the leg hangs rather than folds over.
    const auto gap = [&](double q) { return std::abs(wrap_angle(q - d.q_start[0])); };
    if (gap(q0_other) < gap(q0)) std::swap(q0, q0_other);
  } else {
    const double reach_a = (rot_axis(a, q0) * d.outward_H).dot(p);
    const double reach_b = (rot_axis(a, q0_other) * d.outward_H).dot(p);
    if (reach_b > reach_a) std::swap(q0, q0_other);
  }
  r = ypp_femur_tibia(m, leg, p, q0);
  if (r.ok || !rolling_hip(d) || std::string(r.margin_unit) != "rad") return r;  // a limit
  LegIkResult other = ypp_femur_tibia(m, leg, p, q0_other);
  return other.ok ? other : r;
}

/// Levenberg–Marquardt on the FK with the analytic Jacobian, from a fixed list of starts
/// (the model's q_start first): the first start that converges to |p_foot − p| ≤ 1e-12 m
/// inside the joint limits wins. The margin reported is the smallest singular value of
/// the leg Jacobian [m/rad], the distance of the leg to a singular configuration. When no
/// start reaches the target, the margin is minus the smallest distance left between foot and
/// target over the starts [m]: how far beyond the leg's reach the target lies, as far as the
/// iteration found (a target within reach that no start converges to shows as a small miss).
LegIkResult ik_numeric(const RobotModel& m, int leg, const Vec3& p) {
  const LegIkData& d = m.leg_ik[leg];
  LegIkResult best;
  bool converged = false;  // some start reached the target, outside the limits or singular
  double nearest_m = std::numeric_limits<double>::infinity();
  std::array<Vec3, 9> starts;
  starts[0] = d.q_start;
  int n = 1;
  for (double s1 : {-0.8, 0.8})
    for (double s2 : {-1.2, 1.2}) starts[n++] = d.q_start + Vec3(0.0, s1, s2);
  for (double s0 : {-0.6, 0.6}) starts[n++] = d.q_start + Vec3(s0, 0.0, 0.0);
  starts[n++] = Vec3::Zero();
  for (int s = 0; s < n; ++s) {
    Vec3 q = starts[s];
    double lambda = 1e-3;
    Vec3 e = p - chain_foot_position_H(m, leg, q);
    for (int it = 0; it < 200 && e.norm() > 1e-14; ++it) {
      const Mat3 J = chain_jacobian_H(m, leg, q);
      const Mat3 JtJ = J.transpose() * J;
      const Vec3 dq = (JtJ + lambda * Mat3::Identity()).ldlt().solve(J.transpose() * e);
      const Vec3 q_new = q + dq;
      const Vec3 e_new = p - chain_foot_position_H(m, leg, q_new);
      if (e_new.norm() < e.norm()) {
        q = q_new;
        e = e_new;
        lambda = std::max(lambda * 0.1, 1e-15);
      } else {
        lambda *= 10.0;
        if (lambda > 1e12) break;
      }
    }
    if (!(e.norm() <= 1e-12)) {
      if (e.norm() < nearest_m) nearest_m = e.norm();
      continue;
    }
    converged = true;
    LegIkResult r;
    for (int j = 0; j < m.leg(leg).n_joints; ++j) q[j] = std::remainder(q[j], 2.0 * M_PI);
    r.q = q;
    if (!within_limits(m, leg, r)) {
      best = r;
      continue;
    }
    const Mat3 J = chain_jacobian_H(m, leg, r.q);
    const Vec3 ev = Eigen::SelfAdjointEigenSolver<Mat3>(J.transpose() * J, Eigen::EigenvaluesOnly)
                        .eigenvalues();
    r.margin_m = std::sqrt(std::max(ev[0], 0.0));  // smallest singular value of J
    if (r.margin_m < m.ik_min_margin_m) {
      r.reason = "within robot.ik_min_margin of a singular configuration";
      best = r;
      continue;
    }
    r.ok = true;
    return r;
  }
  // A start that converged outside the limits or near a singularity says more than a miss.
  if (converged) return best;
  std::ostringstream why;
  why << "no joint angles reach the foot target: the nearest foot position found is " << nearest_m
      << " m from it (Levenberg-Marquardt)";
  best.reason = why.str();
  best.margin_m = -nearest_m;
  return best;
}

}  // namespace

LegChainPose chain_pose(const RobotModel& m, int leg, const Vec3& q) {
  LegChainPose c;
  for (int k = 0; k < kChainJoints3; ++k) {
    c.sin_q[k] = std::sin(q[k]);
    c.cos_q[k] = std::cos(q[k]);
  }
  const int b0 = m.body(leg, 0), b1 = m.body(leg, 1), b2 = m.body(leg, 2);
  c.o_H[0].setZero();
  c.w_H[0] = m.axis[b0];
  c.R_H[0] = rot_axis_cs(m.axis[b0], c.cos_q[0], c.sin_q[0]);
  c.o_H[1] = c.R_H[0] * m.p_parent_joint[b1];
  const Mat3 Rj1 = c.R_H[0] * m.R_parent_joint[b1];
  c.w_H[1] = Rj1 * m.axis[b1];
  c.R_H[1] = Rj1 * rot_axis_cs(m.axis[b1], c.cos_q[1], c.sin_q[1]);
  c.o_H[2] = c.o_H[1] + c.R_H[1] * m.p_parent_joint[b2];
  const Mat3 Rj2 = c.R_H[1] * m.R_parent_joint[b2];
  c.w_H[2] = Rj2 * m.axis[b2];
  c.R_H[2] = Rj2 * rot_axis_cs(m.axis[b2], c.cos_q[2], c.sin_q[2]);
  c.p_foot_H = c.o_H[2] + c.R_H[2] * m.p_foot_last[leg];
  return c;
}

Vec3 chain_foot_position_H(const RobotModel& m, int leg, const Vec3& q) {
  return chain_pose(m, leg, q).p_foot_H;
}

Mat3 chain_jacobian_H(const RobotModel& m, int leg, const Vec3& q) {
  return chain_jacobian_H(chain_pose(m, leg, q));
}

Mat3 chain_jacobian_H(const LegChainPose& c) {
  Mat3 J;
  for (int k = 0; k < kChainJoints3; ++k) J.col(k) = c.w_H[k].cross(c.p_foot_H - c.o_H[k]);
  return J;
}

Mat3 chain_jacobian_dot_H(const RobotModel& m, int leg, const Vec3& q, const Vec3& qd) {
  return chain_jacobian_dot_H(chain_pose(m, leg, q), qd);
}

Mat3 chain_jacobian_dot_H(const LegChainPose& c, const Vec3& qd) {
  Mat3 J;
  for (int k = 0; k < kChainJoints3; ++k) J.col(k) = c.w_H[k].cross(c.p_foot_H - c.o_H[k]);
  const Vec3 p_dot = J * qd;
  // Angular velocity of the link carrying joint k's axis, and the velocity of its origin.
  std::array<Vec3, kChainJoints3> Omega, o_dot;
  Omega[0].setZero();
  o_dot[0].setZero();
  for (int k = 1; k < kChainJoints3; ++k) {
    Omega[k] = Omega[k - 1] + c.w_H[k - 1] * qd[k - 1];
    o_dot[k] = o_dot[k - 1] + Omega[k].cross(c.o_H[k] - c.o_H[k - 1]);
  }
  Mat3 Jd;
  for (int k = 0; k < kChainJoints3; ++k) {
    const Vec3 w_dot = Omega[k].cross(c.w_H[k]);
    Jd.col(k) = w_dot.cross(c.p_foot_H - c.o_H[k]) + c.w_H[k].cross(p_dot - o_dot[k]);
  }
  return Jd;
}

LegIkResult chain_inverse_kinematics(const RobotModel& m, int leg, const Vec3& p_H) {
  if (m.leg_ik[leg].method == LegIkMethod::kYawPitchPitch) return ik_yaw_pitch_pitch(m, leg, p_H);
  return ik_numeric(m, leg, p_H);
}

void prepare_leg_chains(RobotModel& m) {
  constexpr double kParallel = 1e-9;
  for (int leg = 0; leg < m.legs(); ++leg) {
    const int b0 = m.body(leg, 0), b1 = m.body(leg, 1), b2 = m.body(leg, 2);
    m.p_hip_B[leg] = m.p_parent_joint[b0];
    m.R_B_H[leg] = m.R_parent_joint[b0];
    LegIkData d;
    d.a0_H = m.axis[b0].normalized();
    d.H_R_J1 = m.R_parent_joint[b1];
    d.o1_H = m.p_parent_joint[b1];
    d.a1_J1 = m.axis[b1].normalized();
    d.w1_H = d.H_R_J1 * d.a1_J1;
    d.up_H = m.R_B_H[leg].transpose() * Vec3::UnitZ();
    for (int j = 0; j < 3; ++j) {  // the three-joint solvers' data; longer legs: leg_motion.cpp
      const int k = m.joint(leg, j);
      const double lo = m.joint_lower_rad[k], hi = m.joint_upper_rad[k];
      d.q_start[j] = (std::isfinite(lo) && std::isfinite(hi)) ? 0.5 * (lo + hi) : 0.0;
    }
    // Outward direction: the zero-pose foot (else the femur joint) seen from the coxa
    // joint, without its component along the trunk normal.
    m.leg_ik[leg] = d;  // chain_pose below reads nothing of leg_ik
    const Vec3 foot0 = chain_foot_position_H(m, leg, Vec3::Zero());
    Vec3 out = foot0 - foot0.dot(d.up_H) * d.up_H;
    if (out.norm() < 1e-9) out = d.o1_H - d.o1_H.dot(d.up_H) * d.up_H;
    const bool has_outward = out.norm() >= 1e-9;
    if (has_outward) d.outward_H = out.normalized();
    // Yaw–pitch–pitch: tibia axis parallel to the femur axis, coxa axis not.
    const Vec3 a2_J1 = m.R_parent_joint[b2] * m.axis[b2].normalized();
    const bool parallel = a2_J1.cross(d.a1_J1).norm() < kParallel;
    const bool coxa_apart = d.a0_H.cross(d.w1_H).norm() > 1e-6;
    d.axis_sign = a2_J1.dot(d.a1_J1) >= 0.0 ? 1.0 : -1.0;
    const Vec3 v = m.p_parent_joint[b2];
    const Vec3 f = m.R_parent_joint[b2] * m.p_foot_last[leg];
    d.e1_J1 = perpendicular(d.a1_J1, v);
    d.e2_J1 = d.a1_J1.cross(d.e1_J1);
    d.l2_m = std::hypot(v.dot(d.e1_J1), v.dot(d.e2_J1));
    d.alpha_rad = std::atan2(v.dot(d.e2_J1), v.dot(d.e1_J1));
    d.l3_m = std::hypot(f.dot(d.e1_J1), f.dot(d.e2_J1));
    d.gamma_rad = std::atan2(f.dot(d.e2_J1), f.dot(d.e1_J1));
    d.kappa_m = d.a1_J1.dot(v + f) + d.w1_H.dot(d.o1_H);
    const bool planar_ok = d.l2_m > 1e-9 && d.l3_m > 1e-9;
    d.method = (parallel && coxa_apart && planar_ok && has_outward) ? LegIkMethod::kYawPitchPitch
                                                                    : LegIkMethod::kNumeric;
    m.leg_ik[leg] = d;
  }
  prepare_serial_chains(m);
}

}  // namespace hexdyn
