#include "hexdyn/kinematics/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hexdyn/core/cancel.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {

namespace {

/// The IK target of a leg at t (the planned foot, a sphere foot's centre offset by r n)
/// relative to the trunk in trunk axes, and its first two derivatives as seen from the
/// (possibly rotating) trunk frame.
struct RelativeTarget {
  Vec3 r_B, rd_B, rdd_B;
};

RelativeTarget relative_target(const RobotModel& model, const MotionPlan& plan, int leg, double t,
                               RobotKinematicState& out) {
  const FootMotion f = leg_foot_motion(plan.gait.legs[leg], t);
  out.feet[leg] = f;
  FootMotion c = f;
  if (const double radius = model.foot_radius_m[leg]; radius > 0.0) {
    const FootNormal n = leg_foot_normal(plan.gait.legs[leg], plan.terrain, t);
    c.p_W += radius * n.n_W;
    c.v_W += radius * n.nd_W;
    c.a_W += radius * n.ndd_W;
  }
  out.foot_center_W[leg] = c.p_W;
  const Mat3& W_R_B = out.trunk.W_R_B;
  const Vec3 omega_B = W_R_B.transpose() * out.trunk.omega_W;
  const Vec3 omegadot_B = W_R_B.transpose() * out.trunk.omegadot_W;
  RelativeTarget r;
  r.r_B = W_R_B.transpose() * (c.p_W - out.trunk.p_W);
  r.rd_B = W_R_B.transpose() * (c.v_W - out.trunk.v_W) - omega_B.cross(r.r_B);
  r.rdd_B = W_R_B.transpose() * (c.a_W - out.trunk.a_W) - 2.0 * omega_B.cross(r.rd_B) -
            omegadot_B.cross(r.r_B) - omega_B.cross(omega_B.cross(r.r_B));
  return r;
}

}  // namespace

RobotKinematicState::RobotKinematicState(const RobotModel& model)
    : q(JointVector::Zero(model.joints())),
      qd(JointVector::Zero(model.joints())),
      qdd(JointVector::Zero(model.joints())),
      cos_q(JointVector::Ones(model.joints())),
      sin_q(JointVector::Zero(model.joints())) {}

namespace {

/// Throws ReachError: leg `leg`'s foot target f at t is not reachable (`why`).
[[noreturn]] void throw_unreachable(const RobotModel& model, int leg, double t, const FootMotion& f,
                                    const LegIkResult& ik) {
  std::ostringstream msg;
  msg << "leg " << model.leg(leg).name << " at t = " << t << " s: foot target (" << f.p_W.x()
      << ", " << f.p_W.y() << ", " << f.p_W.z() << ") m not reachable: " << ik.reason << " (margin "
      << ik.margin_m << " " << ik.margin_unit;
  if (std::string(ik.margin_unit) == "m") msg << ", required >= " << model.ik_min_margin_m << " m";
  msg << ")";
  throw ReachError(msg.str());
}

/// Throws ReachError: the leg Jacobian is singular at the IK's solution.
[[noreturn]] void throw_singular(const RobotModel& model, int leg, double t, const FootMotion& f,
                                 const LegIkResult& ik) {
  // IK accepted the target (robot.ik_min_margin = 0 allows a leg exactly at full
  // extension or fold) but the leg Jacobian is singular there: the joint rates that
  // would move the foot as planned do not exist. Without this check they would be
  // inf/NaN and poison every later dataset.
  std::ostringstream msg;
  msg << "leg " << model.leg(leg).name << " at t = " << t << " s: foot target (" << f.p_W.x()
      << ", " << f.p_W.y() << ", " << f.p_W.z()
      << ") m at a singular leg configuration (full extension or fold): "
      << "joint rates undefined (margin " << ik.margin_m
      << " m, required >= " << model.ik_min_margin_m << " m; raise robot.ik_min_margin)";
  throw ReachError(msg.str());
}

/// Joint positions, rates and accelerations of a leg for its target relative to the trunk,
/// by the model's leg solver (leg_motion: three-joint IK and J⁻¹, or the redundant
/// resolution of a leg on its chain); `motion` is the caller's scratch.
void leg_state(const RobotModel& model, int leg, double t, const RelativeTarget& target,
               LegMotion& motion, RobotKinematicState& out) {
  const FootMotion& f = out.feet[leg];
  const Mat3& B_R_H = model.R_B_H[leg];
  const Vec3 p_H = B_R_H.transpose() * (target.r_B - model.p_hip_B[leg]);
  leg_motion(model, leg, p_H, B_R_H, target.rd_B, target.rdd_B, motion);
  if (!motion.ik.ok) throw_unreachable(model, leg, t, f, motion.ik);
  if (!motion.qd.allFinite() || !motion.qdd.allFinite())
    throw_singular(model, leg, t, f, motion.ik);
  const int k0 = model.joint(leg, 0), n = model.leg(leg).n_joints;
  out.q.segment(k0, n) = motion.ik.q;
  out.cos_q.segment(k0, n) = motion.cos_q;
  out.sin_q.segment(k0, n) = motion.sin_q;
  out.qd.segment(k0, n) = motion.qd;
  out.qdd.segment(k0, n) = motion.qdd;
}

}  // namespace

void robot_state_at(const RobotModel& model, const MotionPlan& plan, double t,
                    RobotKinematicState& out) {
  if (out.q.size() != model.joints()) out = RobotKinematicState(model);
  out.trunk = plan.trunk.at(t);
  LegMotion motion;
  for (int leg = 0; leg < model.legs(); ++leg) {
    const RelativeTarget target = relative_target(model, plan, leg, t, out);
    leg_state(model, leg, t, target, motion, out);
  }
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

KinematicsResult sample_kinematics(const RobotModel& model, const MotionPlan& plan,
                                   const std::vector<double>& times) {
  KinematicsResult k;
  const int T = static_cast<int>(times.size());
  k.resize(T, model.legs(), model.joints(), false);  // every row is written below
  RobotKinematicState s(model);
  BodyPoses poses;
  const bool prismatic = has_prismatic_joints(model);
  for (int i = 0; i < T; ++i) {
    if (i % 64 == 0) check_cancelled();
    const double t = times[i];
    robot_state_at(model, plan, t, s);
    k.time_s[i] = t;
    k.base_position.row(i) = s.trunk.p_W.transpose();
    const Quat q(s.trunk.W_R_B);
    k.base_orientation_wxyz.row(i) << q.w(), q.x(), q.y(), q.z();
    k.base_linear_velocity.row(i) = s.trunk.v_W.transpose();
    k.base_angular_velocity.row(i) = s.trunk.omega_W.transpose();
    k.base_linear_acceleration.row(i) = s.trunk.a_W.transpose();
    k.base_angular_acceleration.row(i) = s.trunk.omegadot_W.transpose();
    k.joint_position.row(i) = s.q.transpose();
    k.joint_velocity.row(i) = s.qd.transpose();
    k.joint_acceleration.row(i) = s.qdd.transpose();
    for (int leg = 0; leg < model.legs(); ++leg) {
      k.foot_position.row(i).segment<3>(3 * leg) = s.feet[leg].p_W.transpose();
      k.foot_velocity.row(i).segment<3>(3 * leg) = s.feet[leg].v_W.transpose();
      k.foot_center.row(i).segment<3>(3 * leg) = s.foot_center_W[leg].transpose();
      k.contact_phase(i, leg) = static_cast<std::int8_t>(
          s.feet[leg].in_swing ? ContactPhase::kSwing : ContactPhase::kSupport);
    }
    if (prismatic)
      forward_kinematics_tree(model, s.q, poses);  // a slide moves its body along the axis
    else
      forward_kinematics_tree(model, s.cos_q, s.sin_q, poses);
    k.com_position.row(i) =
        (s.trunk.p_W + s.trunk.W_R_B * center_of_mass_B(model, poses)).transpose();
  }
  return k;
}

}  // namespace hexdyn
