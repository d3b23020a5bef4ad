#pragma once
/// \file step_system.hpp
/// The linear system of one replay step (docs/theory/replay.md#integrator): each foot's contact
/// force as an affine function of its velocity at the step's end, its rows in the step's
/// matrix over the columns its Jacobian can touch, and the factorisation that solves it.
/// Internal to the replay stage (replay.cpp). World axes; a foot's Jacobian J is
/// 3 × (6 + joints) (dynamics/rnea.hpp foot_jacobians), zero outside the trunk's six columns
/// and its own leg's joints.
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "hexdyn/contact/simulation_contact.hpp"
#include "hexdyn/contact/stick_slip.hpp"
#include "hexdyn/core/base_state.hpp"
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/core/sizes.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// J ν of a foot's Jacobian J on leg `leg`, over the columns where J can be non-zero [m/s].
/// Inline: the step calls it for every foot several times.
inline Vec3 foot_velocity(const LegInfo& leg, const DofJacobian& J, const DofVector& nu) {
  Vec3 v = J.leftCols<6>() * nu.head<6>();
  for (int j = 0; j < leg.n_joints; ++j) {
    const int k = 6 + leg.first_joint + j;
    v += J.col(k) * nu[k];
  }
  return v;
}

/// The contact force of a foot as an affine function of its velocity at the step's end,
/// F(v) = a + B v (file comment of replay.hpp): the normal force linearised about the start
/// (its stiffness over the step's displacement h v, its damping), the friction as the damper
/// −(μ(s)/s) F_n P v of the start's slip speed s (its secant: always dissipative, so a step
/// never reverses a slip the law would only slow down).
struct AffineForce {
  Vec3 a = Vec3::Zero();  ///< [N]
  Mat3 B = Mat3::Zero();  ///< [N s/m]
};

/// The rates of leg `leg`'s joints that hold its foot's contact point still while the trunk
/// moves with the twist (v_W, ω_W) of `trunk` (replay.early_contact: hold,
/// docs/theory/replay.md#early-contact): q̇ = −J_leg⁺ J_trunk ν_trunk [rad/s], J_leg the leg's
/// columns of the foot's Jacobian J and J_trunk its first six, the pseudo-inverse the
/// least-squares, least-norm solution (exact when J_leg has full row rank; a leg of more joints
/// moves with the least norm). No allocation.
LegVector holding_rates(const LegInfo& leg, const DofJacobian& J, const BaseState& trunk);

/// The affine force of a foot with contact geometry g and law (at the step's start, foot
/// velocity v_old) over a step of length h [s]. With stick–slip, the stick force of
/// `tangential`, or the slip force along *slip_force_direction when given.
AffineForce affine_contact(const ContactParams& params, const TerrainContactPoint& g,
                           const FootContactForce& law, const TangentialContact& tangential,
                           const Vec3* slip_force_direction, const Vec3& v_old, double h);

/// Adds a foot's contact to a step's system: −h Jᵀ B J to `lhs` and Jᵀ (a + B v₀) to `rhs`
/// ((6 + joints)² and 6 + joints), on the columns where J can be non-zero.
void add_contact_rows(const LegInfo& leg, const DofJacobian& J, const AffineForce& force,
                      const Vec3& v_start, double h, DofMatrix& lhs, DofVector& rhs);

/// Solves a step's system lhs Δν = rhs, keeping its factorisations from step to step (no
/// allocation): by Cholesky when the caller knows lhs to be symmetric (every contact's B is,
/// but a sliding stick–slip foot's, contact/stick_slip.hpp slip_affine) and it is positive
/// definite, else by LU with partial pivoting.
class StepSolver {
 public:
  DofVector solve(const DofMatrix& lhs, const DofVector& rhs, bool symmetric);

 private:
  Eigen::LLT<DofMatrix> llt_;
  Eigen::PartialPivLU<DofMatrix> lu_;
};

}  // namespace hexdyn
