// Tests of the attempt policy shared by the back ends
// (src/hexdyn/allocation/strict_then_penalised.hpp), on a scripted back end that records
// which attempts the policy asks for: strict first, penalised after a failed strict
// attempt, straight to penalised after a relaxed sample of the same sizes, the failure
// message of a sample that fails both, and what is forgotten when.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/allocation/strict_then_penalised.hpp"

using namespace hexdyn;

namespace {

/// A back end whose attempts end as scripted; it records the calls.
class ScriptedBackend final : public StrictThenPenalisedBackend {
 public:
  /// What the next solve's attempts return: strict solved?, penalised outcome.
  bool strict_solves = true;
  enum class Penalised { kOptimal, kRelaxed, kFails } penalised = Penalised::kRelaxed;

  std::vector<std::string> calls;  ///< "strict", "strict warm", "penalised ...", "drop"
  bool stored = false;             ///< the back end's own warm start

 private:
  double feasibility_tol() const override { return 1e-6; }
  bool can_warm_start(const ProblemShape& shape) const override {
    return stored && shape == stored_shape_;
  }
  void drop_warm_start() override {
    stored = false;
    calls.push_back("drop");
  }
  Attempt solve_strict(const QpProblem& p, bool warm) override {
    calls.push_back(warm ? "strict warm" : "strict");
    Attempt a;
    a.left_state = true;
    if (!strict_solves) {
      a.note = "infeasible";
      return a;
    }
    fill(p, SolverStatus::kOptimal);
    a.solved = true;
    return a;
  }
  Attempt solve_penalised(const QpProblem& p, const AttemptPlan& plan, bool after_strict) override {
    calls.push_back(std::string("penalised") + (plan.strict ? "" : " direct") +
                    (plan.warm ? " warm" : "") + (after_strict ? " after strict" : ""));
    Attempt a;
    if (penalised == Penalised::kFails) {
      a.note = "penalised solve infeasible (equality rows)";
      return a;
    }
    fill(p, penalised == Penalised::kOptimal ? SolverStatus::kOptimal : SolverStatus::kRelaxed);
    a.solved = true;
    return a;
  }
  void fill(const QpProblem& p, SolverStatus status) {
    out_.status = status;
    out_.x = Eigen::VectorXd::Zero(p.variables());
    out_.lambda_eq = Eigen::VectorXd::Zero(p.equalities());
    out_.lambda_ineq = Eigen::VectorXd::Zero(p.inequalities());
    out_.message = status == SolverStatus::kRelaxed ? "relaxed: row by 1" : "";
    stored = true;
    stored_shape_ = ProblemShape::of(p);
  }
  ProblemShape stored_shape_;
};

QpProblem problem(int n, int m_in, std::uint64_t structure = 0) {
  QpProblem p;
  p.resize(n, 0, m_in);
  p.H.setIdentity();
  p.structure = structure;
  return p;
}

}  // namespace

TEST_CASE("attempt policy: the plan is a function of the last shape and status",
          "[allocation][policy]") {
  const ProblemShape a = ProblemShape::of(problem(3, 4, 1));
  const ProblemShape b = ProblemShape::of(problem(3, 4, 2));  // same sizes, other rows
  const ProblemShape c = ProblemShape::of(problem(5, 4, 1));  // other sizes
  CHECK(a.same_sizes(b));
  CHECK_FALSE(a == b);
  CHECK_FALSE(a.same_sizes(c));
  CHECK(plan_attempts(a, false, a, false).strict);
  CHECK_FALSE(plan_attempts(a, true, a, false).strict);
  CHECK_FALSE(plan_attempts(a, true, b, false).strict);  // sizes decide, as documented
  CHECK(plan_attempts(a, true, c, false).strict);
  CHECK(plan_attempts(a, false, a, true).warm);
  CHECK_FALSE(plan_attempts(a, false, a, false).warm);
}

TEST_CASE("attempt policy: strict, penalised, and straight to penalised after a relaxed sample",
          "[allocation][policy]") {
  ScriptedBackend b;
  const QpProblem p = problem(3, 4);

  // A feasible sample: strict only, cold (nothing stored yet).
  CHECK(b.solve(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict"});

  // An infeasible one: strict, then penalised from the strict attempt's state.
  b.calls.clear();
  b.strict_solves = false;
  CHECK(b.solve(p).status == SolverStatus::kRelaxed);
  CHECK(b.calls == std::vector<std::string>{"strict warm", "penalised warm after strict"});

  // The next of the same sizes goes to the penalised form directly.
  b.calls.clear();
  b.penalised = ScriptedBackend::Penalised::kOptimal;
  CHECK(b.solve(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"penalised direct warm"});

  // It needed no slack: the one after is solved as posed again.
  b.calls.clear();
  b.strict_solves = true;
  CHECK(b.solve(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict warm"});

  // After a relaxed sample, a problem of other sizes is tried as posed first.
  b.calls.clear();
  b.strict_solves = false;
  b.penalised = ScriptedBackend::Penalised::kRelaxed;
  REQUIRE(b.solve(p).status == SolverStatus::kRelaxed);
  b.calls.clear();
  b.strict_solves = true;
  CHECK(b.solve(problem(5, 4)).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict"});
}

TEST_CASE("attempt policy: a verdict alone is the strict attempt, even after a relaxed sample",
          "[allocation][policy]") {
  ScriptedBackend b;
  const QpProblem p = problem(3, 4);
  // A relaxed sample first: a plain solve of the same sizes would go to the penalised form.
  b.strict_solves = false;
  REQUIRE(b.solve(p).status == SolverStatus::kRelaxed);
  // As posed, infeasible: the strict attempt only, status failed, the warm start kept.
  b.calls.clear();
  const QpOutcome& out = b.solve_as_posed(p);
  CHECK(out.status == SolverStatus::kFailed);
  CHECK(out.message == "infeasible");
  CHECK(b.calls == std::vector<std::string>{"strict warm"});
  CHECK(b.stored);
  // As posed, feasible: the strict attempt's answer.
  b.calls.clear();
  b.strict_solves = true;
  CHECK(b.solve_as_posed(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict warm"});
  // A plain solve after it follows the usual policy (no relaxed sample since).
  b.calls.clear();
  CHECK(b.solve(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict warm"});
}

TEST_CASE("attempt policy: a sample that fails both attempts", "[allocation][policy]") {
  ScriptedBackend b;
  const QpProblem p = problem(3, 4);
  REQUIRE(b.solve(p).status == SolverStatus::kOptimal);
  b.calls.clear();
  b.strict_solves = false;
  b.penalised = ScriptedBackend::Penalised::kFails;
  const QpOutcome& out = b.solve(p);
  CHECK(out.status == SolverStatus::kFailed);
  CHECK(out.x.allFinite());
  CHECK(out.message.rfind("failed: strict solve infeasible; penalised solve infeasible "
                          "(equality rows)",
                          0) == 0);
  // The warm start is dropped, and the next sample is tried as posed, cold.
  CHECK(b.calls.back() == "drop");
  b.calls.clear();
  b.strict_solves = true;
  CHECK(b.solve(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict"});
}

TEST_CASE("attempt policy: non-finite data, no variables, and reset", "[allocation][policy]") {
  ScriptedBackend b;
  QpProblem p = problem(3, 4);
  REQUIRE(b.solve(p).status == SolverStatus::kOptimal);
  b.calls.clear();

  p.g[1] = std::nan("");
  const QpOutcome& bad = b.solve(p);
  CHECK(bad.status == SolverStatus::kFailed);
  CHECK(bad.message.find("non-finite entries in g") != std::string::npos);
  CHECK(b.calls == std::vector<std::string>{"drop"});  // no attempt runs

  b.calls.clear();
  const QpProblem empty = problem(0, 0);
  CHECK(b.solve(empty).status == SolverStatus::kOptimal);
  CHECK(b.calls.empty());

  p.g[1] = 0.0;
  REQUIRE(b.solve(p).status == SolverStatus::kOptimal);
  b.calls.clear();
  b.reset_warm_start();
  CHECK(b.calls == std::vector<std::string>{"drop"});
  b.calls.clear();
  REQUIRE(b.solve(p).status == SolverStatus::kOptimal);
  CHECK(b.calls == std::vector<std::string>{"strict"});
}
