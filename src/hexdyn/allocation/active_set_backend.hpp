#pragma once
/// \file allocation/active_set_backend.hpp
/// An exact dense QP back end of the allocation (docs/theory/allocation.md#back-ends,
/// `allocation.solver: active-set`): a dual active-set method in the Goldfarb–Idnani style
/// for the small problems of allocation/qp.hpp without cones,
///
///   minimise    ½ xᵀ H x + gᵀ x + constant
///   subject to  A x = b,   lower ≤ C x ≤ upper,
///
/// with the same problem semantics as the Ipopt back end (allocation/ipopt_backend.cpp): the
/// problem as posed first; when it is infeasible, the exact L1-penalised problem
///
///   minimise    ½ xᵀ H x + gᵀ x + ρ Σ_i w_i · dist(C_i x, [lower_i, upper_i])
///   subject to  A x = b
///
/// (ρ = slack_penalty, w_i = ineq_penalty, violations in row units; equality rows stay hard),
/// solved exactly and reported as status 1 with the message of describe_violations; after a
/// relaxed sample, a problem of the same sizes goes to the penalised form directly (as the
/// Ipopt back end does), whose solution is the strict optimum when no slack is needed.
///
/// Sizes and preconditions:
///  - n ≤ kActiveSetMaxVariables variables, m_eq + m_in ≤ kActiveSetMaxRows rows; beyond
///    these `solve` throws SolverError (expected vs got). The allocation has n ≤ 18 and at
///    most 6 + 6·19 = 120 inequality rows.
///  - H symmetric (its lower triangle is read) and positive definite. A Hessian that is not
///    numerically so (a Cholesky pivot below 1e-9·max H_ii) is regularised by δ I with
///    δ = 1e-9·max H_ii (1e-9 if H = 0), and the message says so (also for status 0); the
///    answer is then exact only where the constraints determine it. The allocation's
///    H = 2GᵀG has condition numbers below ~20 on the paper's runs.
///  - No cones: `solve` throws SolverError ("cones need the ipopt back end") for a problem
///    with cones, since that is a configuration error rather than numerical trouble; the
///    pipeline selects this back end only with friction pyramids.
///
/// Outcome fields: x, λ (signs of allocation/qp.hpp; for a relaxed row whose slack is used,
/// λ_i = ±ρ w_i), iterations = active-set changes over all attempts (adding, dropping or
/// relaxing a row), objective without penalties, max_violation, seconds, message.
/// After the problem's sizes and structural key have been seen once, a solve that ends with
/// status 0 allocates no heap memory (status 1 builds its message).
#include <memory>

#include "hexdyn/allocation/goldfarb_idnani.hpp"  // kActiveSetMaxVariables, kActiveSetMaxRows
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

struct ActiveSetOptions {
  /// A row counts as violated, and is added to the active set, beyond
  /// tolerance·max(1, |bound|) (row units). As in the Ipopt back end, a solution is flagged
  /// (status 1) when a row is violated beyond max(1e-6, 1e3·tolerance)·max(1, |bound|).
  double tolerance = 1e-9;
  /// ρ of the L1 penalty ρ Σ w_i · violation_i of the relaxed problem (row units).
  double slack_penalty = 1e6;
  /// Active-set changes per attempt (strict, then penalised) before giving up.
  int max_iterations = 500;
  /// Start from the previous solve's active set when the sizes and the structural key
  /// (QpProblem::structure) match (verified: rows with multipliers of the wrong sign or
  /// dependent normals are dropped).
  bool warm_start = true;
};

/// Maps the scene's allocation settings (tolerance, slack_penalty) to the options.
ActiveSetOptions active_set_options_from(const AllocationParams& params);

/// The dual active-set back end (the solver: allocation/goldfarb_idnani.hpp; the attempt
/// policy: allocation/strict_then_penalised.hpp; warm starts: allocation/active_set_backend.cpp).
/// Throws ConfigError for non-positive tolerance or slack_penalty or max_iterations < 1.
std::unique_ptr<AllocationBackend> make_active_set_backend(const ActiveSetOptions& options = {});

}  // namespace hexdyn
