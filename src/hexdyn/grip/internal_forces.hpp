/// \file grip/internal_forces.hpp
/// A bound on a held sample's required friction from its allocation's forces moved along the
/// trunk rows' null space, the feet's internal forces (docs/theory/grip.md#internal-forces):
/// a sweep's run settles a sample whose required friction stays below the run's largest so
/// far with it, instead of a probe.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/allocation/qp.hpp"

namespace hexdyn {

/// internal_force_use's scratch, kept from sample to sample (n variables, 6 trunk rows).
struct InternalForceWorkspace {
  Eigen::MatrixXd trunk_t;  ///< n × 6: the trunk rows Cᵀ
  Eigen::MatrixXd scaled;   ///< n × 6: D⁻¹ Cᵀ
  Eigen::MatrixXd schur;    ///< 6 × 6: C D⁻¹ Cᵀ, regularised
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::VectorXd inverse_weight, gradient, lambda, dx, x, trial;
  std::vector<char> face;  ///< per inequality row: a friction face
};

/// The friction the forces x_a + s dx use (friction_use). dx minimises ½ Σ over the loaded
/// feet of (|Δf_t + f_t|² + kNormalWeight² Δf_n²) / f_n² (f at x_a; a foot in its touchdown
/// transient has no normal variable and its known normal force) subject to C dx = 0, C the
/// trunk rows of `qp` (its first AllocationLayout::kTrunkRows inequality rows): the internal
/// forces that take the most tangential force off the feet for the normal force they move;
/// s is the largest step in [0, 1] that keeps each row but the friction faces within its
/// bounds, or half that step, or no step, whichever uses least (the move lowers the sum of the
/// feet's tangential forces, not always the largest ratio). x_a: n forces that hold every row
/// of `qp` (the allocation's answer). Returns that friction, at most x_a's, its forces in ws.x
/// and in `leg` the leg that uses it. Every row other than a friction face holds at ws.x as it
/// does at x_a: ws.x is feasible at μ equal to the returned friction.
double internal_force_use(const QpProblem& qp, const AllocationLayout& layout,
                          const Eigen::VectorXd& x_a, InternalForceWorkspace& ws, int& leg);

}  // namespace hexdyn
