#include "hexdyn/replay/joint_drive.hpp"

#include <algorithm>
#include <cmath>

#include "hexdyn/drive/drive.hpp"

namespace hexdyn {

double joint_friction_torque(const ActuatorParams& a, double qd_radps) {
  return a.coulomb_friction_Nm * std::tanh(qd_radps / kJointStictionSpeed_radps) +
         a.viscous_friction_Nmsprad * qd_radps;
}

double joint_friction_secant(const ActuatorParams& a, double qd_radps) {
  const double r = std::abs(qd_radps);
  const double coulomb = r > 1e-12 * kJointStictionSpeed_radps
                             ? a.coulomb_friction_Nm * std::tanh(r / kJointStictionSpeed_radps) / r
                             : a.coulomb_friction_Nm / kJointStictionSpeed_radps;
  return coulomb + a.viscous_friction_Nmsprad;
}

double bounded_drive_torque(const ActuatorParams& a, bool saturate, double command_Nm,
                            double qd_radps, bool& at_bound) {
  at_bound = false;
  if (!saturate) return command_Nm;
  const DriveLimit lim = drive_torque_limit(a, qd_radps);
  if (command_Nm > lim.limit_Nm || command_Nm < lim.lower_Nm) {
    at_bound = true;
    return std::clamp(command_Nm, lim.lower_Nm, lim.limit_Nm);
  }
  return command_Nm;
}

void add_driven_joint_rows(const DriveTrainParams& drive, const ReplayParams& gains,
                           const JointVector& q, const JointVector& qd, const JointVector& q_plan,
                           const JointVector& qd_plan, const JointVector& tau_plan, double h,
                           DofVector& f, DofMatrix& A, DrivenJoints& out) {
  const Eigen::Index n = q.size();
  const double kp = gains.kp_Nmprad, kd = gains.kd_Nmsprad;
  out.u.resize(n);
  out.friction_secant.resize(n);
  out.saturated.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const ActuatorParams& a = drive.joints[j];
    const double command =
        tau_plan[j] + kp * (q_plan[j] - q[j] - h * qd[j]) + kd * (qd_plan[j] - qd[j]);
    bool at_bound = false;
    const double u = bounded_drive_torque(a, gains.saturate, command, qd[j], at_bound);
    const double c = joint_friction_secant(a, qd[j]);
    const Eigen::Index r = 6 + j;
    f[r] += (at_bound ? u : command) - c * qd[j];
    A(r, r) += a.armature_kgm2 + h * c + (at_bound ? 0.0 : h * (h * kp + kd));
    out.u[j] = u;
    out.friction_secant[j] = c;
    out.saturated[j] = at_bound ? 1.0 : 0.0;
  }
}

void finish_driven_joints(const ReplayParams& gains, const JointVector& q,
                          const JointVector& q_plan, const JointVector& qd_plan,
                          const JointVector& tau_plan, const JointVector& qd_new, double h,
                          DrivenJoints& out) {
  for (Eigen::Index j = 0; j < q.size(); ++j)
    if (out.saturated[j] == 0.0)
      out.u[j] = tau_plan[j] + gains.kp_Nmprad * (q_plan[j] - q[j] - h * qd_new[j]) +
                 gains.kd_Nmsprad * (qd_plan[j] - qd_new[j]);
}

void account_driven_step(const DriveTrainParams& drive, const DrivenJoints& step,
                         const JointVector& qd_new, double h, DriveSpending& spent) {
  for (Eigen::Index j = 0; j < step.u.size(); ++j) {
    const ActuatorParams& a = drive.joints[j];
    const double u = step.u[j], w = qd_new[j];
    spent.joint_friction_J += h * step.friction_secant[j] * w * w;
    spent.copper_loss_J += h * copper_loss(a, motor_current(a, u, w));
    spent.electrical_J += h * electrical_power(a, u, w);
    spent.saturated_s[j] += h * step.saturated[j];
  }
}

JointVector joint_armatures(const DriveTrainParams& drive) {
  JointVector J(static_cast<Eigen::Index>(drive.joints.size()));
  for (Eigen::Index j = 0; j < J.size(); ++j) J[j] = drive.joints[j].armature_kgm2;
  return J;
}

double electrical_power_total(const DriveTrainParams& drive, const JointVector& u,
                              const JointVector& qd) {
  double p = 0.0;
  for (Eigen::Index j = 0; j < u.size(); ++j) p += electrical_power(drive.joints[j], u[j], qd[j]);
  return p;
}

}  // namespace hexdyn
