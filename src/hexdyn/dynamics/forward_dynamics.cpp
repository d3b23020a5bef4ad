#include "hexdyn/dynamics/forward_dynamics.hpp"

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

DofVector generalised_velocity(const BaseState& state, const JointVector& qd) {
  DofVector nu(6 + qd.size());
  nu << state.v_W, state.omega_W, qd;
  return nu;
}

}  // namespace

const DofVector& forward_dynamics(const RobotModel& model, RobotData& data, const BaseState& state,
                                  const JointVector& q, const JointVector& qd,
                                  const DofVector& tau_gen, LegVectors foot_forces_W,
                                  LegVectors normals_W, const JointVector* armature_kgm2) {
  // h − Σ J_lᵀ F_l: the inverse dynamics at zero generalised acceleration.
  BaseState at_rest = state;
  at_rest.a_W.setZero();
  at_rest.omegadot_W.setZero();
  data.bias = rnea(model, data, at_rest, q, qd, JointVector::Zero(model.joints()), foot_forces_W,
                   normals_W);
  crba(model, data, state, q);
  if (armature_kgm2) data.M.diagonal().tail(model.joints()) += *armature_kgm2;
  data.M_llt.compute(data.M);
  if (data.M_llt.info() != Eigen::Success)
    throw SolverError("forward dynamics: the mass matrix is not positive definite");
  data.nu_dot = data.M_llt.solve(tau_gen - data.bias);
  if (!data.nu_dot.allFinite())
    throw SolverError("forward dynamics: the acceleration is not finite");
  return data.nu_dot;
}

const DofVector& forward_dynamics_joints(const RobotModel& model, RobotData& data,
                                         const BaseState& state, const JointVector& q,
                                         const JointVector& qd, const JointVector& tau_joints_Nm,
                                         LegVectors foot_forces_W, LegVectors normals_W,
                                         const JointVector* armature_kgm2) {
  DofVector tau_gen = DofVector::Zero(model.dofs());
  tau_gen.tail(model.joints()) = tau_joints_Nm;
  return forward_dynamics(model, data, state, q, qd, tau_gen, foot_forces_W, normals_W,
                          armature_kgm2);
}

double kinetic_energy(const RobotModel& model, RobotData& data, const BaseState& state,
                      const JointVector& q, const JointVector& qd) {
  const DofVector nu = generalised_velocity(state, qd);
  crba(model, data, state, q);
  return 0.5 * nu.dot(data.M * nu);
}

}  // namespace hexdyn
