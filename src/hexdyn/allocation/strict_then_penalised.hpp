#pragma once
/// \file allocation/strict_then_penalised.hpp
/// The attempt policy of the allocation back ends, in one place
/// (docs/theory/allocation.md#the-attempt-policy):
///
///  1. the problem as posed ("strict");
///  2. if that fails, the exact L1-penalised problem, whose solution is the strict optimum
///     when no slack is needed and otherwise says which rows gave way;
///  3. after a relaxed sample, a problem of the same sizes goes to the penalised form
///     directly: infeasible samples come in runs (a touchdown transient), and proving
///     infeasibility first would cost a whole failed solve per sample.
///
/// Every back end that solves QPs itself (Ipopt, active-set) derives from
/// StrictThenPenalisedBackend and supplies the two attempts; the policy decides which run.
/// What carries from one solve to the next is explicit: the policy keeps the last
/// problem's shape and whether it was relaxed; each back end keeps its own warm start (a
/// point, a working set) together with the shape it belongs to, and says through a const
/// query whether it can start the next problem.
#include <cstdint>
#include <string>

#include "hexdyn/allocation/qp.hpp"

namespace hexdyn {

/// What a warm start must match: the sizes, the number of cones and the structural key
/// (QpProblem::structure) of a problem.
struct ProblemShape {
  int variables = -1;
  int equalities = -1;
  int inequalities = -1;
  int cones = -1;
  std::uint64_t structure = 0;

  static ProblemShape of(const QpProblem& p);
  /// Same sizes and cone count, whatever the structural key.
  bool same_sizes(const ProblemShape& other) const;
  bool operator==(const ProblemShape& other) const = default;
};

/// The attempts of one solve.
struct AttemptPlan {
  bool strict = true;  ///< try the problem as posed first
  bool warm = false;   ///< the back end may start from its stored warm start
};

/// The plan for a problem of shape `now` (a pure function): strict unless the last solve,
/// of a problem of the same sizes, was relaxed; warm as the back end says.
AttemptPlan plan_attempts(const ProblemShape& last, bool last_relaxed, const ProblemShape& now,
                          bool can_warm_start);

/// A back end under the policy. solve_impl runs it: the non-finite and no-variable cases,
/// then solve_strict and, if needed, solve_penalised; a solve that fails both gets the
/// finite fallback point and the message "failed: strict solve <why>; <penalised why>".
class StrictThenPenalisedBackend : public AllocationBackend {
 public:
  /// Forgets the last problem and the back end's warm start.
  void reset_warm_start() final;

 protected:
  /// The end of one attempt.
  struct Attempt {
    bool solved = false;  ///< out_ holds the answer (strict: status optimal)
    /// The attempt ran, and its final state may start the penalised attempt.
    bool left_state = false;
    /// Why not solved, in the words of the failure message: the strict attempt's reason
    /// ("infeasible", "Infeasible_Problem_Detected, then cold ..."), the penalised
    /// attempt's with its own name ("penalised solve infeasible (equality rows)").
    std::string note;
  };

  /// Throws SolverError for a problem the back end cannot take (cones, sizes). Default: none.
  virtual void check_supported(const QpProblem& p) const;
  /// Prepares a problem with variables and finite data; returns why it cannot be solved
  /// ("the objective Hessian H is indefinite"), empty when it can. Default: nothing to do.
  virtual std::string load(const QpProblem& p);
  /// Whether load() itself finds non-finite data, with the message "non-finite entries in "
  /// + qp_first_non_finite: then the problem is not checked twice. Default: false.
  virtual bool load_checks_finite() const { return false; }
  /// Whether the stored warm start belongs to a problem of this shape (and warm starts are
  /// enabled). A query: changes nothing.
  virtual bool can_warm_start(const ProblemShape& shape) const = 0;
  /// The problem as posed. When solved, out_ holds status kOptimal, x, λ, objective,
  /// max_violation and message (empty, or a note), and the back end stores its warm start.
  virtual Attempt solve_strict(const QpProblem& p, bool warm) = 0;
  /// The penalised problem: after a strict attempt that left its state (`after_strict`), or
  /// directly (plan.strict false), from the stored warm start if plan.warm. When solved,
  /// out_ holds status kOptimal (no slack needed) or kRelaxed, and the back end stores or
  /// drops its warm start as it sees fit.
  virtual Attempt solve_penalised(const QpProblem& p, const AttemptPlan& plan,
                                  bool after_strict) = 0;
  /// Drops the back end's warm start (after a failed solve, and on reset).
  virtual void drop_warm_start() = 0;
  /// The threshold for the status (qp_feasibility_tolerance of the back end's tolerance).
  virtual double feasibility_tol() const = 0;

 private:
  void solve_impl(const QpProblem& p) final;
  /// kFailed with the fallback point; the warm start and the relaxed mark are dropped.
  void fail(const QpProblem& p, const std::string& why);

  ProblemShape last_shape_;    ///< of the last problem loaded
  bool last_relaxed_ = false;  ///< the last solve ended relaxed
};

}  // namespace hexdyn
