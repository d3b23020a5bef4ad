/// \file allocation/active_set_backend.cpp
/// The active-set back end of the allocation (allocation/active_set_backend.hpp): the dual
/// active-set solver (allocation/goldfarb_idnani.hpp) under the strict-then-penalised
/// policy (allocation/strict_then_penalised.hpp), with warm starts across samples.
///
/// Warm start. After each solve the final working sets (active rows with their sides, and
/// in penalised mode the elastic rows) are kept with the problem's shape. The next problem
/// of the same shape (sizes and structural key: rows of the same kind at every index)
/// starts from them; the solver verifies them (DualActiveSetQp::start_warm), so a stale
/// set costs iterations, never accuracy. An exact method reaches the same verdict from any
/// start: a warm attempt is retried cold only after an iteration limit or numerical
/// trouble. The penalised attempt starts from the strict attempt's final active set, or,
/// after a skipped strict attempt, from the stored sets.
///
/// A final point is polished (recomputed from its active set with one step of iterative
/// refinement) before the outcome is filled, so that active rows hold to rounding.
#include "hexdyn/allocation/active_set_backend.hpp"

#include <array>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

#include "hexdyn/allocation/goldfarb_idnani.hpp"
#include "hexdyn/allocation/strict_then_penalised.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

constexpr int kN = kActiveSetMaxVariables;
constexpr int kM = kActiveSetMaxRows;

/// The working sets a solve ended with, and the shape of its problem.
struct WorkingSetStart {
  ProblemShape shape;
  std::array<ActiveRow, kN> active{};
  int active_count = 0;
  std::array<ActiveRow, kM> elastic{};
  int elastic_count = 0;
};

class ActiveSetBackend final : public StrictThenPenalisedBackend {
 public:
  explicit ActiveSetBackend(const ActiveSetOptions& options) : opt_(options) {
    if (!(opt_.tolerance > 0.0) || !(opt_.slack_penalty > 0.0) || opt_.max_iterations < 1) {
      std::ostringstream os;
      os << "active-set options: tolerance and slack_penalty must be > 0 and max_iterations "
            ">= 1, got "
         << opt_.tolerance << ", " << opt_.slack_penalty << ", " << opt_.max_iterations;
      throw ConfigError(os.str());
    }
    core_ = std::make_unique<DualActiveSetQp>();
  }

 private:
  double feasibility_tol() const override { return qp_feasibility_tolerance(opt_.tolerance); }

  void check_supported(const QpProblem& p) const override {
    if (!p.cones.empty())
      throw SolverError("active-set back end: cones need the ipopt back end (got " +
                        std::to_string(p.cones.size()) +
                        " cones; use allocation.solver: ipopt or a friction pyramid)");
    if (p.variables() > kN) {
      std::ostringstream os;
      os << "active-set back end: variables: expected at most " << kN << ", got " << p.variables();
      throw SolverError(os.str());
    }
    if (p.equalities() + p.inequalities() > kM) {
      std::ostringstream os;
      os << "active-set back end: rows (equality + inequality): expected at most " << kM << ", got "
         << p.equalities() + p.inequalities();
      throw SolverError(os.str());
    }
  }

  std::string load(const QpProblem& p) override {
    if (!core_->load(p, opt_.slack_penalty, opt_.tolerance))
      return "non-finite entries in " + qp_first_non_finite(p);
    if (!core_->convex()) return "the objective Hessian H is indefinite (not a convex QP)";
    return {};
  }

  bool load_checks_finite() const override { return true; }

  bool can_warm_start(const ProblemShape& shape) const override {
    return opt_.warm_start && have_start_ && start_.shape == shape;
  }

  void drop_warm_start() override { have_start_ = false; }

  /// Keeps the final working sets for the next solve.
  void store_start(const QpProblem& p) {
    const DualActiveSetQp& s = *core_;
    start_.shape = ProblemShape::of(p);
    start_.active_count = s.active_count();
    for (int i = 0; i < start_.active_count; ++i) start_.active[i] = s.active_row(i);
    start_.elastic_count = s.elastic_rows(start_.elastic.data());
    have_start_ = true;
  }

  /// Runs the dual iteration from a warm start (if `warm` says so and one is given), then
  /// cold if the warm run ended neither optimal nor infeasible.
  ActiveSetExit run_attempt(bool warm, const ActiveRow* active, int n_active,
                            const ActiveRow* elastic, int n_elastic) {
    DualActiveSetQp& s = *core_;
    ActiveSetExit exit = ActiveSetExit::kNumerical;
    for (const bool use_warm : {true, false}) {
      if (use_warm && !warm) continue;
      int dropped = 0;
      if (use_warm)
        s.start_warm(active, n_active, elastic, n_elastic, dropped);
      else
        s.start_cold();
      int changes = dropped;
      exit = s.run(opt_.max_iterations, changes);
      out_.iterations += changes;
      if (exit == ActiveSetExit::kOptimal || exit == ActiveSetExit::kInfeasible) break;
    }
    return exit;
  }

  /// Polishes the final point of an attempt that ended optimal and fills the outcome from
  /// it; returns the rows it violates beyond the status threshold, as describe_violations
  /// words them (empty when none, without building any text).
  std::string finish_attempt(const QpProblem& p) {
    DualActiveSetQp& s = *core_;
    s.polish();
    const int n = s.n(), m_eq = s.m_eq(), m_in = s.rows() - m_eq;
    out_.x.resize(n);
    for (int i = 0; i < n; ++i) out_.x[i] = s.x()[i];
    out_.lambda_eq.resize(m_eq);
    out_.lambda_ineq.resize(m_in);
    out_.lambda_cone.resize(0);
    s.lambdas(lambda_all_.data());
    for (int k = 0; k < m_eq; ++k) out_.lambda_eq[k] = lambda_all_[k];
    for (int i = 0; i < m_in; ++i) out_.lambda_ineq[i] = lambda_all_[m_eq + i];
    out_.objective = s.objective(p.constant);
    bool beyond = false;
    out_.max_violation = s.max_violation(feasibility_tol(), beyond);
    if (!beyond) return {};
    return describe_violations(p, out_.x, feasibility_tol(), &out_.max_violation, violations_);
  }

  /// Status optimal, with a note when H had to be regularised.
  void mark_optimal() {
    out_.status = SolverStatus::kOptimal;
    if (core_->regularisation() > 0.0) out_.message = regularisation_note();
  }

  std::string regularisation_note() const {
    char buf[96];
    std::snprintf(buf, sizeof buf, "objective Hessian not positive definite: regularised by %.3g I",
                  core_->regularisation());
    return buf;
  }

  Attempt solve_strict(const QpProblem& p, bool warm) override {
    DualActiveSetQp& s = *core_;
    Attempt a;
    if (const int k = s.crossed_row(); k >= 0) {
      a.note = "infeasible (lower > upper on " +
               (k < p.equalities() ? p.eq_name(k) : p.ineq_name(k - p.equalities())) + ")";
      return a;
    }
    s.set_mode(false);
    const ActiveSetExit exit =
        run_attempt(warm, start_.active.data(), start_.active_count, nullptr, 0);
    a.left_state = true;
    if (exit != ActiveSetExit::kOptimal) {
      a.note = exit_name(exit);
      return a;
    }
    const std::string violated = finish_attempt(p);
    if (!violated.empty()) {  // not expected of an exact method: say so if it happens
      a.note = "optimal but violated " + violated;
      return a;
    }
    mark_optimal();
    store_start(p);
    a.solved = true;
    return a;
  }

  Attempt solve_penalised(const QpProblem& p, const AttemptPlan& plan, bool after_strict) override {
    DualActiveSetQp& s = *core_;
    // The start: the stored sets after a skipped strict attempt, else the strict attempt's
    // final active set (copied: the run overwrites it).
    const ActiveRow* active = nullptr;
    const ActiveRow* elastic = nullptr;
    int n_active = 0, n_elastic = 0;
    if (!plan.strict && plan.warm) {
      active = start_.active.data(), n_active = start_.active_count;
      elastic = start_.elastic.data(), n_elastic = start_.elastic_count;
    } else if (after_strict) {
      n_active = s.active_count();
      for (int i = 0; i < n_active; ++i) strict_rows_[i] = s.active_row(i);
      active = strict_rows_.data();
    }
    s.set_mode(true);
    const ActiveSetExit exit = run_attempt(active != nullptr, active, n_active, elastic, n_elastic);
    Attempt a;
    if (exit != ActiveSetExit::kOptimal) {
      a.note = std::string("penalised solve ") + exit_name(exit);
      if (exit == ActiveSetExit::kInfeasible) a.note += " (equality rows)";
      return a;
    }
    const std::string violated = finish_attempt(p);
    if (violated.empty()) {
      // No slack needed: by exactness of the penalty this is the strict optimum.
      mark_optimal();
    } else {
      out_.status = SolverStatus::kRelaxed;
      out_.message = "relaxed: " + violated;
      if (s.regularisation() > 0.0) out_.message += " (" + regularisation_note() + ")";
    }
    store_start(p);
    a.solved = true;
    return a;
  }

  ActiveSetOptions opt_;
  std::unique_ptr<DualActiveSetQp> core_;
  WorkingSetStart start_;  ///< valid when have_start_
  bool have_start_ = false;
  std::array<ActiveRow, kN> strict_rows_{};  ///< scratch: the strict attempt's active set
  std::array<double, kM> lambda_all_{};      ///< scratch: multipliers of all rows
  ViolationWorkspace violations_;            ///< scratch of describe_violations
};

}  // namespace

ActiveSetOptions active_set_options_from(const AllocationParams& params) {
  ActiveSetOptions o;
  o.tolerance = params.tolerance;
  o.slack_penalty = params.slack_penalty;
  return o;
}

std::unique_ptr<AllocationBackend> make_active_set_backend(const ActiveSetOptions& options) {
  return std::make_unique<ActiveSetBackend>(options);
}

}  // namespace hexdyn
