#pragma once
/// \file model/redundant_leg.hpp
/// A leg of any number of joints as a serial chain in its hip frame H, and the motion of a
/// redundant leg (docs/theory/model.md#redundant-legs): the joint positions that put the foot
/// where the plan puts it and stay nearest the leg's nominal pose, with their rates and
/// accelerations.
///
/// Resolution. q(p) = argmin ½ (q − q_nom)ᵀ W (q − q_nom) subject to f(q) = p, f the foot
/// position in H [m], W diagonal and positive. Its optimality conditions
///   W (q − q_nom) + Jᵀ λ = 0,   f(q) = p                                   (J = ∂f/∂q, 3 × m)
/// define q and λ as smooth functions of p wherever J has full rank and the Lagrangian's
/// Hessian H = W + Σ_i λ_i ∇²f_i is positive definite on J's null space. Once differentiated:
///   K [q̇; λ̇] = [0; ṗ],   K = [H Jᵀ; J 0],
/// so q̇ is the W-weighted pseudo-inverse of J applied to ṗ plus the null-space motion that
/// keeps the optimum; twice:
///   K [q̈; λ̈] = [−(2 Σ_i λ̇_i ∇²f_i q̇ + Σ_i λ_i ∇³f_i[q̇, q̇, ·]); p̈ − ∇²f[q̇, q̇]].
/// Every derivative of f comes from the chain evaluated on nested dual numbers: exact to
/// rounding, no finite differences. For m = 3 the constraint fixes q (J square) and the same
/// equations give the usual q̇ = J⁻¹ṗ and q̈ = J⁻¹(p̈ − J̇q̇).
///
/// Sizes: 1 ≤ m ≤ kMaxChainJoints joints; storage of fixed capacity, so no call allocates.
#include <Eigen/Core>
#include <array>

#include "hexdyn/core/common.hpp"

namespace hexdyn {

/// Largest number of joints of one leg chain.
inline constexpr int kMaxChainJoints = 6;

/// One value per joint of a chain (m entries).
using ChainVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxChainJoints, 1>;
/// ∂f/∂q of a chain: 3 × m.
using ChainJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxChainJoints>;
/// An m × m matrix of a chain.
using ChainMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxChainJoints, kMaxChainJoints>;

enum class ChainJointType { kRevolute, kPrismatic };

/// Joint k of a chain: its frame placed in the previous link's frame (the hip frame H for
/// k = 0) by p_parent_m and R_parent, then moved by q_k about (revolute, [rad]) or along
/// (prismatic, [m]) the unit `axis` of that joint frame; the joint frame is link k's frame.
struct ChainJoint {
  Vec3 p_parent_m = Vec3::Zero();
  Mat3 R_parent = Mat3::Identity();
  Vec3 axis = Vec3::UnitZ();
  ChainJointType type = ChainJointType::kRevolute;
};

/// A leg as a serial chain: `count` joints from hip to foot, the foot point in the last
/// link's frame.
struct SerialChain {
  std::array<ChainJoint, kMaxChainJoints> joints{};
  int count = 0;
  Vec3 p_foot_m = Vec3::Zero();
};

/// f(q): the foot position in H [m]. q: count entries.
Vec3 chain_foot_position(const SerialChain& chain, const ChainVector& q);
/// J(q) = ∂f/∂q (3 × count).
ChainJacobian chain_jacobian(const SerialChain& chain, const ChainVector& q);
/// ∇²f_i(q), i = x, y, z (each count × count, symmetric).
std::array<ChainMatrix, 3> chain_hessians(const SerialChain& chain, const ChainVector& q);
/// ∇²f[u, v] = Σ_ab ∂²f/∂q_a∂q_b u_a v_b (for u = v = q̇: J̇ q̇).
Vec3 chain_second_derivative(const SerialChain& chain, const ChainVector& q, const ChainVector& u,
                             const ChainVector& v);
/// ∇³f[u, v, w] = Σ_abc ∂³f/∂q_a∂q_b∂q_c u_a v_b w_c.
Vec3 chain_third_derivative(const SerialChain& chain, const ChainVector& q, const ChainVector& u,
                            const ChainVector& v, const ChainVector& w);

/// The pose a redundant leg stays nearest: q_nominal and the diagonal of W (both count
/// entries, W > 0; for example 1 / range² of each joint).
struct RedundantResolution {
  ChainVector q_nominal;
  ChainVector weight;
};

/// The solution at one instant: q, q̇, q̈ (count entries each) and the multipliers λ, λ̇ of
/// the foot's three rows. converged: the optimality conditions hold to rounding and the
/// reduced Hessian is positive definite; otherwise the fields hold the last iterate.
struct RedundantLegMotion {
  ChainVector q, qd, qdd;
  Vec3 lambda = Vec3::Zero(), lambda_dot = Vec3::Zero();
  bool converged = false;
  double foot_error_m = 0.0;  ///< |f(q) − p|
  int iterations = 0;
};

/// The resolution's q, q̇, q̈ for the foot at p_H [m] moving at pd_H [m/s] and pdd_H [m/s²]
/// (hip frame), Newton on the optimality conditions from `q_start` (count entries; the
/// previous instant's q along a motion, else q_nominal) after damped least-squares steps
/// that reach the foot. Precondition: chain.count ≥ 3.
RedundantLegMotion redundant_leg_motion(const SerialChain& chain,
                                        const RedundantResolution& resolution, const Vec3& p_H,
                                        const Vec3& pd_H, const Vec3& pdd_H,
                                        const ChainVector& q_start);

}  // namespace hexdyn
