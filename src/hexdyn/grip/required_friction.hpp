#pragma once
/// \file grip/required_friction.hpp
/// The least friction coefficient a sample needs (docs/theory/grip.md#required-friction): the
/// smallest μ for which the sample's allocation rows (trunk equations, torque or drive limits,
/// minimum normal forces, and the friction faces or cones of the scene's friction model at μ)
/// admit a force distribution,
///
///   μ* = min μ   subject to   the rows of build_allocation_problem with friction μ.
///
/// For each μ the rows are convex and a larger μ only widens them, so feasibility is monotone
/// in μ and the problem is quasi-convex. Two methods, the second a fallback of the first:
///  - Newton on an active set: at a vertex answer (the pyramids: n + 1 rows active for n
///    forces and μ), the active rows are a square system in (x, μ), bilinear in x_n·μ, solved
///    by Newton. The answer is certified: every row holds at it, and the multipliers of
///    min μ (Jᵀλ = e_μ) have the signs of the rows' active sides, which makes it the global
///    minimum (a local minimum of a quasi-convex problem with a convex feasible set for each μ
///    is global; docs/theory/grip.md#why-the-newton-answer-is-the-minimum). The active set of
///    the previous sample of the same row layout is tried first: consecutive samples usually
///    share it, and then one sample costs two or three 19×19 factorisations. When the answer
///    fails its check, rows are exchanged one at a time by the ratio tests of the simplex
///    method (docs/theory/grip.md#where-the-active-set-comes-from).
///  - Bisection on feasibility: each probe solves the allocation problem at μ with the
///    active-set back end given to the solver (its own instance and warm start), and holds
///    every row to 1e-8; a feasible probe also tightens the upper end to the μ its own forces
///    use. From the upper bound the allocation itself gives (the friction its forces use) down
///    to a bracket of `tolerance`, with a Newton attempt from the rows nearest to active (and
///    linearly independent) each time the bracket has narrowed fourfold. A Newton answer at a
///    degenerate vertex (a zero multiplier) counts only when μ − `tolerance` is infeasible: a
///    Farkas certificate from its own rows, else a probe there.
///  - The exact cone: its cones become outer polygons of 16 faces that gather around each
///    leg's force direction until the polygon's μ* (a lower bound) and the cone use of its
///    forces (an upper bound) meet within `tolerance` (docs/theory/grip.md#the-exact-cone).
/// μ* is NaN when no μ ≤ mu_max admits the rows (the message names what still fails there),
/// or when a constant row (a swing leg's torque) exceeds its limit.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/allocation/qp.hpp"

namespace hexdyn {

/// How μ* of a sample was found.
enum class RequiredFrictionMethod : int {
  kNewton = 0,               ///< Newton from the previous sample's active set
  kBisectionThenNewton = 1,  ///< bisection, then Newton inside its bracket
  kBisection = 2,            ///< bisection alone: within `tolerance` above μ*
  kNone = 3,                 ///< no μ* (NaN)
  /// Settled below the caller's `enough` (RequiredFrictionSolver::solve): `mu` is an upper
  /// bound, μ* ≤ mu < enough (the allocation's own friction use, or a feasible probe's); for a
  /// run computed for its summary only.
  kBelow = 4,
};

/// The answer for one sample.
struct RequiredFriction {
  double mu = 0.0;  ///< μ*, NaN where none ≤ mu_max suffices
  int leg = -1;     ///< the leg whose friction binds at μ* (0..5), −1 where none
  RequiredFrictionMethod method = RequiredFrictionMethod::kNone;
  std::string message;  ///< why μ* is NaN, empty otherwise
};

/// How hard the search for μ* tries.
struct RequiredFrictionOptions {
  /// Bisection stops when the bracket is at most this wide (absolute, in μ).
  double tolerance = 1e-7;
  /// The largest μ considered: beyond it a sample counts as needing no μ at all.
  double mu_max = 1e3;
  /// Newton iterations per attempt.
  int newton_iterations = 8;
  /// A sample without μ* has a message naming the rows that still fail at mu_max (from the
  /// back end's relaxed answer there); false: the message says only that none suffices, and
  /// the probe needs no relaxed answer (a run computed for a sweep's row alone).
  bool reasons = true;
};

/// Finds μ* of successive samples; keeps the last certified active set per row layout. One
/// per thread.
class RequiredFrictionSolver {
 public:
  /// `backend` solves the bisection's probes, problems without cones (the cones become outer
  /// polygons): the active-set back end (allocation/active_set_backend.hpp), an instance of its own
  /// besides the allocation's, so that each keeps its own warm start.
  explicit RequiredFrictionSolver(std::unique_ptr<AllocationBackend> backend,
                                  const RequiredFrictionOptions& options = {});
  ~RequiredFrictionSolver();
  RequiredFrictionSolver(const RequiredFrictionSolver&) = delete;
  RequiredFrictionSolver& operator=(const RequiredFrictionSolver&) = delete;

  /// μ* of the problem `qp` built by build_allocation_problem with layout `layout` (at any μ;
  /// not modified). `allocation`: the allocation's solution of `qp` (size n) when it holds
  /// every row within kViolationThreshold, else null; its friction use bounds μ* from above.
  /// `enough`: a caller that needs μ* only where it reaches `enough` (the largest μ* of a run
  /// so far, for the run's maximum) lets a sample end with method kBelow and an upper bound
  /// below `enough` as `mu`: a sample whose allocation holds, by its friction use or else one
  /// feasible probe just below `enough` (before any Newton attempt); any other, once the
  /// previous sample's active set has failed and the probe at mu_max has passed, by that probe
  /// (docs/theory/grip.md#in-a-sweep). The default asks for μ* itself. Cone problems
  /// (allocation.friction: cone) ignore it.
  const RequiredFriction& solve(const QpProblem& qp, const AllocationLayout& layout,
                                const Eigen::VectorXd* allocation,
                                double enough = -std::numeric_limits<double>::infinity());

  /// After solve: whether the last problem needs more friction than `mu` (its rows at `mu`
  /// admit no forces, by one probe). For a kBelow answer, whose μ* is bounded only from above.
  bool needs_more_than(const AllocationLayout& layout, double mu);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// qp's friction rows and cones set to friction coefficient mu (the layout's face rows and
/// cones; every other row unchanged).
void set_friction_coefficient(const AllocationLayout& layout, double mu, QpProblem& qp);

/// The least μ at which x (size layout.variables) holds the friction rows and cones of
/// `layout` in `qp` (the largest face or cone use over the legs), with the leg that uses it
/// in *leg (−1 when no leg has friction rows). +inf when a leg's use is unbounded (f_n ≤ 0).
double friction_use(const QpProblem& qp, const AllocationLayout& layout, const Eigen::VectorXd& x,
                    int* leg = nullptr);

/// The same for leg l alone; −1 when the leg has no friction rows.
double leg_friction_use(const QpProblem& qp, const AllocationLayout& layout,
                        const Eigen::VectorXd& x, int l);

/// Per leg: a friction face or cone of `layout` in `qp` that x violates by more than
/// kViolationThreshold (relative to max(1, |bound|)): the foot would slip at the problem's μ.
LegArray<bool> slipping_legs(const QpProblem& qp, const AllocationLayout& layout,
                             const Eigen::VectorXd& x);

}  // namespace hexdyn
