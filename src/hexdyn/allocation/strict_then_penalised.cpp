#include "hexdyn/allocation/strict_then_penalised.hpp"

namespace hexdyn {

ProblemShape ProblemShape::of(const QpProblem& p) {
  return {p.variables(), p.equalities(), p.inequalities(), static_cast<int>(p.cones.size()),
          p.structure};
}

bool ProblemShape::same_sizes(const ProblemShape& o) const {
  return variables == o.variables && equalities == o.equalities && inequalities == o.inequalities &&
         cones == o.cones;
}

AttemptPlan plan_attempts(const ProblemShape& last, bool last_relaxed, const ProblemShape& now,
                          bool can_warm_start) {
  AttemptPlan plan;
  plan.strict = !(last_relaxed && now.same_sizes(last));
  plan.warm = can_warm_start;
  return plan;
}

void StrictThenPenalisedBackend::reset_warm_start() {
  last_shape_ = ProblemShape{};
  last_relaxed_ = false;
  drop_warm_start();
}

void StrictThenPenalisedBackend::check_supported(const QpProblem&) const {}

std::string StrictThenPenalisedBackend::load(const QpProblem&) { return {}; }

void StrictThenPenalisedBackend::fail(const QpProblem& p, const std::string& why) {
  qp_fail_with_fallback(p, feasibility_tol(), why, out_);
  last_relaxed_ = false;
  drop_warm_start();
}

void StrictThenPenalisedBackend::solve_impl(const QpProblem& p) {
  check_supported(p);
  out_.iterations = 0;
  out_.message.clear();
  if (p.variables() == 0 || !load_checks_finite()) {
    if (const std::string bad = qp_first_non_finite(p); !bad.empty()) {
      fail(p, "non-finite entries in " + bad);
      return;
    }
  }
  if (p.variables() == 0) {
    qp_solve_without_variables(p, feasibility_tol(), out_);
    return;
  }
  if (const std::string why = load(p); !why.empty()) {
    fail(p, why);
    return;
  }
  const ProblemShape shape = ProblemShape::of(p);
  const AttemptPlan plan = plan_attempts(last_shape_, last_relaxed_, shape, can_warm_start(shape));
  last_shape_ = shape;
  last_relaxed_ = false;

  // Notes are text only on the failure path: a solve that succeeds builds no string.
  if (as_posed_) {  // a feasibility verdict: the problem as posed, nothing relaxed
    const Attempt strict = solve_strict(p, plan.warm);
    if (!strict.solved) {
      out_.status = SolverStatus::kFailed;
      out_.message = strict.note;
    }
    return;
  }
  Attempt strict;
  if (plan.strict) {
    strict = solve_strict(p, plan.warm);
    if (strict.solved) return;
  }
  const Attempt penalised = solve_penalised(p, plan, strict.left_state);
  if (!penalised.solved) {
    fail(p, "strict solve " + (plan.strict ? strict.note : "skipped after a relaxed sample") +
                "; " + penalised.note);
    return;
  }
  last_relaxed_ = out_.status != SolverStatus::kOptimal;
}

}  // namespace hexdyn
