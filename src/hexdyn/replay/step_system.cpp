#include "hexdyn/replay/step_system.hpp"

#include <Eigen/QR>
#include <array>

namespace hexdyn {
namespace {

/// The columns of a foot's Jacobian that can be non-zero: the trunk's six, then its leg's joints.
struct FootColumns {
  int count = 0;
  std::array<int, 6 + kMaxLegJoints> index{};
};

FootColumns foot_columns(const LegInfo& leg) {
  FootColumns c;
  c.count = 6 + leg.n_joints;
  for (int i = 0; i < c.count; ++i) c.index[i] = i < 6 ? i : 6 + leg.first_joint + (i - 6);
  return c;
}

}  // namespace

LegVector holding_rates(const LegInfo& leg, const DofJacobian& J, const BaseState& trunk) {
  const LegJacobian J_leg = J.middleCols(6 + leg.first_joint, leg.n_joints);
  const Vec3 v_trunk_W = J.leftCols<3>() * trunk.v_W + J.middleCols<3>(3) * trunk.omega_W;
  return Eigen::CompleteOrthogonalDecomposition<LegJacobian>(J_leg).solve(-v_trunk_W);
}

AffineForce affine_contact(const ContactParams& params, const TerrainContactPoint& g,
                           const FootContactForce& law, const TangentialContact& tangential,
                           const Vec3* slip_force_direction, const Vec3& v_old, double h) {
  AffineForce out;
  const Vec3& n = g.normal_W;
  const Mat3 N = n * n.transpose();
  if (params.friction_law == FrictionLaw::kStickSlip) {
    // The normal force F_n(v) = fn0 + g·v over the step, then the stick or slip force.
    const Vec3 grad = (law.dF_dv + h * law.dF_dp).transpose() * n;
    const double fn0 = law.normal_N - n.dot(law.dF_dv * v_old);
    const AffineTangentialForce t = slip_force_direction
                                        ? slip_affine(params, *slip_force_direction, fn0, grad)
                                        : stick_affine(params, tangential, n, h);
    out.B = n * grad.transpose() + t.B_Nspm;
    out.a = fn0 * n + t.a_N;
    return out;
  }
  const Mat3 P = Mat3::Identity() - N;
  const double s = law.slip_velocity_W.norm();
  const double c =
      law.normal_N * (s > 1e-12 * params.stiction_velocity_mps
                          ? sliding_friction_coefficient(params, s) / s
                          : 1.5 * params.static_friction / params.stiction_velocity_mps);
  out.B = N * (law.dF_dv + h * law.dF_dp) - c * P;
  out.a = law.normal_N * n - N * law.dF_dv * v_old;
  return out;
}

void add_contact_rows(const LegInfo& leg, const DofJacobian& J, const AffineForce& force,
                      const Vec3& v_start, double h, DofMatrix& lhs, DofVector& rhs) {
  const FootColumns cols = foot_columns(leg);
  const int m = cols.count;
  const auto& column = cols.index;
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6 + kMaxLegJoints> Jc(3, m);
  for (int i = 0; i < m; ++i) Jc.col(i) = J.col(column[i]);
  const Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 6 + kMaxLegJoints, 3> JtB =
      Jc.transpose() * force.B;
  const Vec3 r = force.a + force.B * v_start;
  for (int i = 0; i < m; ++i) {
    rhs[column[i]] += Jc.col(i).dot(r);
    for (int k = 0; k < m; ++k) lhs(column[i], column[k]) -= h * JtB.row(i).dot(Jc.col(k));
  }
}

DofVector StepSolver::solve(const DofMatrix& lhs, const DofVector& rhs, bool symmetric) {
  if (symmetric) {
    llt_.compute(lhs);
    if (llt_.info() == Eigen::Success) return llt_.solve(rhs);
  }
  lu_.compute(lhs);
  return lu_.solve(rhs);
}

}  // namespace hexdyn
