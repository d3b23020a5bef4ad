#pragma once
/// \file problem.hpp
/// The allocation problem of one sample (DESIGN.md §3 "Allocation"): torque-optimal foot
/// forces under the trunk equations, torque limits, minimum normal forces and friction.
///
/// Variables, stacked by leg in the contact frame [t1 t2 n] of each foot
/// (contact/touchdowns.hpp): (f_t1, f_t2, f_n) [N] for a support leg, (f_t1, f_t2) for a
/// leg in its impact transient (f_n is the transient's force, a known input), nothing for
/// a swing leg (F = 0).
///
/// Rows, in order: the six trunk equations (lower = upper, so that they can be relaxed);
/// then per leg with variables its three torque rows, a support leg's minimum normal
/// force, and its friction faces (a pyramid, or for an impact leg under the exact cone the
/// inscribed 16-gon; a support leg under the exact cone gets a second-order cone instead).
#include <array>
#include <string>

#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/dynamics/rnea.hpp"

namespace hexdyn {

/// Builds the allocation problem of one sample into `qp` (resized). Legs in `phase`
/// kSwing carry no force, kImpact legs carry the known normal force `impact_force_N[l]`
/// [N] along the third column of W_R_contact[l] (the contact frames, world axes).
/// `layout_offset[l]` receives the index of the leg's first variable (−1 without
/// variables). Sets qp.structure to a key of the row layout (the friction model and each
/// leg's phase), so that back ends recognise problems built alike.
/// Returns the largest excess [N m] of a swing-leg torque over the limit (constant rows
/// that no force can change), 0 when none; `*constant_violation` (may be null) names it.
double build_allocation_problem(const AllocationParams& alloc, const ContactParams& contact,
                                const ContactSplit& split,
                                const std::array<ContactPhase, kLegs>& phase,
                                const std::array<double, kLegs>& impact_force_N,
                                const std::array<Mat3, kLegs>& W_R_contact, QpProblem& qp,
                                std::array<int, kLegs>& layout_offset,
                                std::string* constant_violation);

/// Foot forces F_W [N] (world axes, terrain on foot) and joint torques tau [N m] of a
/// solution x of build_allocation_problem with the same inputs: τ = τ₀ − Σ J_jᵀ F.
void forces_from_solution(const ContactSplit& split, const std::array<ContactPhase, kLegs>& phase,
                          const std::array<double, kLegs>& impact_force_N,
                          const std::array<Mat3, kLegs>& W_R_contact,
                          const std::array<int, kLegs>& layout_offset, const Eigen::VectorXd& x,
                          std::array<Vec3, kLegs>& F_W, VecJ& tau);

}  // namespace hexdyn
