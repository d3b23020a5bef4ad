#pragma once
/// \file allocation/cone_backend.hpp
/// The exact friction cone on the dual active-set QP
/// (docs/theory/allocation.md#exact-friction-cone, `allocation.solver: active-set` or `auto` with
/// `allocation.friction: cone`): the problem of allocation/qp.hpp with second-order cones
///
///   minimise    ½ xᵀ H x + gᵀ x + constant
///   subject to  A x = b,   lower ≤ C x ≤ upper,   √(x_t1² + x_t2²) ≤ μ x_n  (per cone),
///
/// solved by sequential outer approximation on the active-set back end (active_set_backend.hpp),
/// through its public interface: each cone is replaced by half-spaces that contain it (its
/// supporting half-space at the current tangential direction d, a square around the apex,
/// the tangents of earlier passes) and, where the cone was active in the previous pass, by
/// the curvature term ½ λ/‖t‖ · |(I − d dᵀ) t|² of the cone's Lagrangian Hessian. Each
/// pass is one QP solve, warm-started; passes repeat, the tangent turning to the new
/// direction, until every cone holds to 1e-12 relative and the forces that the cone would
/// not exert vanish to 1e-10 relative (details and the termination argument in cone_backend.cpp).
///
/// Why this method and not an interior point: the dual active-set method adds violated
/// constraints one at a time, so a supporting half-space at the current direction is its
/// natural step, and with the curvature term each pass is a Newton (SQP) step on the
/// cone's KKT conditions: two to four passes per sample from the previous sample's
/// directions, each a warm active-set solve whose active set does not change. An
/// interior-point method takes 10–20 factorisations per sample and cannot be warm-started
/// across samples; its answer is also only as exact as its final barrier parameter, where
/// this one ends on an exact QP solve whose cone constraints are tangent at the answer.
///
/// Semantics are those of the other back ends: the problem as posed first, the exact L1
/// penalty ρ Σ w_i s_i (cones with their own weight, violation ‖t‖ − μ n in newtons) when
/// it is infeasible, status 0 / 1 / 2 and messages naming the rows and cones by the
/// problem's own names ("relaxed: torque L1_femur by 0.73, friction cone L3 by 0.02").
/// A problem without cones is handed to the active-set back end unchanged.
///
/// Sizes: n ≤ kActiveSetMaxVariables, m_eq + m_in + 8·cones ≤ kActiveSetMaxRows (the
/// allocation: n ≤ 18, at most 6 + 6·4 rows and 6 cones); beyond these `solve` throws
/// SolverError. After the problem's structure (sizes, row names, cone indices) has been
/// seen, a solve that ends with status 0 allocates no heap memory (the working problem is
/// resized, and names copied, when the structure changes: at contact events).
///
/// Outcome fields as in qp.hpp: λ_cone[k] ≥ 0 is the multiplier of μ x_n − ‖t‖ ≥ 0 (the
/// sum of the multipliers of cone k's half-spaces; ρ w at a cone that gave way);
/// iterations = active-set changes summed over the passes.
#include <memory>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

struct ConeOptions {
  /// The active-set back end that solves each pass (tolerance, slack_penalty, warm start).
  ActiveSetOptions qp;
  /// A cone counts as converged when ‖t‖ − max_j d_jᵀ t (the gap between the cone and its
  /// half-spaces at the answer) is at most this times max(1, ‖t‖).
  double cone_tolerance = 1e-12;
  /// Passes (QP solves) per attempt before the answer is returned as approximate
  /// (status 1, "approximate: cone ... holds only to ...").
  int max_passes = 200;
  /// Start each sample from the previous sample's tangential directions and cone
  /// multipliers when the problem's structure (sizes, names, cone indices) is the same.
  bool warm_start = true;
};

/// Maps the scene's allocation settings (tolerance, slack_penalty) to the options.
ConeOptions cone_options_from(const AllocationParams& params);

/// The outer-approximation cone back end. Throws ConfigError for non-positive
/// cone_tolerance or max_passes < 1 (and for bad ActiveSetOptions).
std::unique_ptr<AllocationBackend> make_cone_backend(const ConeOptions& options = {});

}  // namespace hexdyn
