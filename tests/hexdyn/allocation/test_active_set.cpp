// Tests of the dual active-set back end (src/hexdyn/allocation/active_set_backend.hpp) on single
// problems. Each answer is checked against a second computation: the closed-form KKT solve
// of equality-only QPs, Ipopt with a tight tolerance on random QPs, the KKT conditions of
// the problem (and of the L1-penalised problem for relaxed answers: an optimality
// certificate, the problem being convex) and an extended-precision solve of the
// equality-constrained problem on the answer's active rows. Sequences of problems (warm
// starts, whole runs) are in test_active_set_sequences.cpp.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/active_set_checks.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/errors.hpp"

using namespace hexdyn;
using namespace hexdyn::test;

TEST_CASE(
    "active-set back end: random QPs with equalities, l = u rows, boxes and general rows "
    "match Ipopt",
    "[allocation][active_set]") {
  std::mt19937 rng(7);
  auto backend = make_active_set_backend();
  auto ipopt = make_ipopt_backend(reference_ipopt());
  int binding = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 4 + trial % 15;  // 4..18
    const int m_eq = trial % 3;
    const int lu = std::min(n - m_eq - 1, trial % 7);
    const int general = 5 + trial % 13;
    CAPTURE(trial, n, m_eq, lu, general);
    const QpProblem p = random_qp(rng, n, m_eq, lu, n, general);
    const QpOutcome ref = ipopt->solve(p);
    const QpOutcome& out = backend->solve(p);
    REQUIRE(ref.status == SolverStatus::kOptimal);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(check_kkt(p, out, 1e-9));
    CHECK(inf_norm(out.x - ref.x) < 1e-7 * (1.0 + inf_norm(ref.x)));
    CHECK(out.objective == Approx(ref.objective).epsilon(1e-10));
    CHECK(out.objective == Approx(p.objective(out.x)).epsilon(1e-13));
    CHECK(out.max_violation < 1e-9 * (1.0 + inf_norm(p.C * out.x)));
    // Multipliers are unique at these (non-degenerate) optima.
    CHECK(inf_norm(out.lambda_ineq - ref.lambda_ineq) < 1e-5 * (1.0 + inf_norm(ref.lambda_ineq)));
    CHECK(inf_norm(out.lambda_eq - ref.lambda_eq) < 1e-5 * (1.0 + inf_norm(ref.lambda_eq)));
    CHECK(out.iterations > 0);
    binding += (out.lambda_ineq.array().abs() > 1e-6).count() > lu;
  }
  CHECK(binding > 30);  // inequality rows were active, not only the l = u rows
}

TEST_CASE("active-set back end: the sign-convention problem takes two active-set changes",
          "[allocation][active_set]") {
  // Its answers and multipliers are checked on every back end in test_backends.cpp; an
  // exact method gets them to rounding, in exactly the two changes its two active rows need.
  const QpProblem p = test::sign_convention_problem();  // x = (1, −2, 0), λ = (1, −2)
  auto backend = make_active_set_backend();
  const QpOutcome& out = backend->solve(p);
  REQUIRE(out.status == SolverStatus::kOptimal);
  CHECK(out.x[0] == Approx(1.0).margin(1e-14));
  CHECK(out.x[1] == Approx(-2.0).margin(1e-14));
  CHECK(out.lambda_ineq[0] == Approx(1.0).margin(1e-14));
  CHECK(out.lambda_ineq[1] == Approx(-2.0).margin(1e-14));
  CHECK(out.iterations == 2);
}

TEST_CASE("active-set back end: degenerate problems", "[allocation][active_set]") {
  auto backend = make_active_set_backend();
  auto ipopt = make_ipopt_backend(reference_ipopt());

  SECTION("redundant active rows: duplicates and linear combinations") {
    // Target (3, 3, 3); x0 ≤ 1 twice, x1 ≤ 1, x0 + x1 ≤ 2 and 2x0 + 2x1 ≤ 4 all active at
    // x = (1, 1, 3): five active rows, rank 2.
    QpProblem p;
    p.resize(3, 0, 5);
    p.H.setIdentity();
    p.g << -3, -3, -3;
    p.C << 1, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 2, 0;
    p.upper << 1, 1, 1, 2, 4;
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(inf_norm(out.x - Eigen::Vector3d(1, 1, 3)) < 1e-14);
    CHECK(check_kkt(p, out, 1e-12));
  }
  SECTION("an unloaded foot: more active rows than variables at the apex of a pyramid") {
    // (t1, t2, n) pulled towards (1, −0.5, −1): f_n ≥ 0 and the four faces ±t − μ' n ≤ 0
    // all hold with equality at 0.
    QpProblem p;
    p.resize(3, 0, 5);
    p.H.setIdentity();
    p.g << -1.0, 0.5, 1.0;
    const double mu = 0.3 / std::sqrt(2.0);
    p.C << 0, 0, 1,  //
        1, 0, -mu,   //
        -1, 0, -mu,  //
        0, 1, -mu,   //
        0, -1, -mu;
    p.lower << 0, -kInf, -kInf, -kInf, -kInf;
    p.upper << kInf, 0, 0, 0, 0;
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(inf_norm(out.x) < 1e-14);
    CHECK(check_kkt(p, out, 1e-12));
    CHECK(inf_norm(out.x - ipopt->solve(p).x) < 1e-7);
  }
  SECTION("l = u rows give the equality-row solution and multipliers") {
    std::mt19937 rng(11);
    const QpProblem eq = random_qp(rng, 9, 6, 0, 0, 0);
    QpProblem rows;
    rows.resize(9, 0, 6);
    rows.H = eq.H;
    rows.g = eq.g;
    rows.C = eq.A;
    rows.lower = eq.b;
    rows.upper = eq.b;
    const QpOutcome by_eq = backend->solve(eq);
    const QpOutcome& out = backend->solve(rows);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(inf_norm(out.x - by_eq.x) < 1e-12 * (1.0 + inf_norm(by_eq.x)));
    CHECK(inf_norm(out.lambda_ineq - by_eq.lambda_eq) < 1e-10 * (1.0 + inf_norm(by_eq.lambda_eq)));
  }
  SECTION("rows without bounds and zero rows that hold change nothing") {
    std::mt19937 rng(5);
    const QpProblem p = random_qp(rng, 8, 2, 3, 8, 6);
    QpProblem q = p;
    const int m = p.inequalities();
    q.C.conservativeResize(m + 4, Eigen::NoChange);
    q.lower.conservativeResize(m + 4);
    q.upper.conservativeResize(m + 4);
    q.C.bottomRows(4).setZero();
    q.C.row(m) = random_matrix(rng, 1, 8);
    q.lower[m] = -kInf, q.upper[m] = kInf;  // no bounds
    q.C.row(m + 1) = random_matrix(rng, 1, 8);
    q.lower[m + 1] = -2e19, q.upper[m + 1] = 1e19;  // "no bound" by magnitude
    q.lower[m + 2] = -1.0, q.upper[m + 2] = 1.0;    // zero row, holds
    q.lower[m + 3] = q.upper[m + 3] = 0.0;          // zero row, l = u = 0
    q.ineq_names.resize(static_cast<std::size_t>(m + 4), "extra");
    q.ineq_penalty.setOnes(m + 4);
    const QpOutcome ref = backend->solve(p);
    const QpOutcome& out = backend->solve(q);
    REQUIRE(ref.status == SolverStatus::kOptimal);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(inf_norm(out.x - ref.x) < 1e-12 * (1.0 + inf_norm(ref.x)));
    CHECK(out.lambda_ineq.tail(4).cwiseAbs().maxCoeff() == 0.0);
    CHECK(check_kkt(q, out, 1e-10));
  }
  SECTION("a zero row whose bounds exclude 0 is relaxed and named, like Ipopt does") {
    std::mt19937 rng(6);
    const QpProblem p = random_qp(rng, 6, 1, 2, 6, 4);
    QpProblem q = p;
    const int m = p.inequalities();
    q.C.conservativeResize(m + 1, Eigen::NoChange);
    q.C.row(m).setZero();
    q.lower.conservativeResize(m + 1);
    q.upper.conservativeResize(m + 1);
    q.lower[m] = 1.0, q.upper[m] = 2.0;
    q.ineq_names.push_back("zero row");
    q.ineq_penalty.setOnes(m + 1);
    const QpOutcome ref = backend->solve(p);
    const QpOutcome& out = backend->solve(q);
    CHECK(out.status == SolverStatus::kRelaxed);
    CHECK(out.message == "relaxed: zero row by 1");
    CHECK(out.max_violation == Approx(1.0));
    CHECK(inf_norm(out.x - ref.x) < 1e-12 * (1.0 + inf_norm(ref.x)));
    const QpOutcome& by_ipopt = ipopt->solve(q);
    CHECK(by_ipopt.status == SolverStatus::kRelaxed);
    CHECK(by_ipopt.message == out.message);
  }
  SECTION("a singular H whose null direction the rows fix") {
    // ½(x0² + x1²) − x2, x2 free in the objective, held by x0 + x2 ≤ 3 and x1 − x2 ≥ −5.
    QpProblem p;
    p.resize(3, 0, 2);
    p.H.diagonal() << 1.0, 1.0, 0.0;
    p.g << 0.0, 0.0, -1.0;
    p.C << 1, 0, 1, 0, 1, -1;
    p.lower << -kInf, -5.0;
    p.upper << 3.0, kInf;
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(out.message.find("regularised") != std::string::npos);
    const QpOutcome& ref = ipopt->solve(p);
    REQUIRE(ref.status == SolverStatus::kOptimal);
    CHECK(inf_norm(out.x - ref.x) < 1e-6);
    CHECK(check_kkt(p, out, 1e-8));
  }
}

TEST_CASE("active-set back end: infeasible problems are relaxed as Ipopt relaxes them",
          "[allocation][active_set]") {
  auto backend = make_active_set_backend();
  auto ipopt = make_ipopt_backend(reference_ipopt());

  // The small infeasible problems of the interface (a torque row against equalities,
  // crossed bounds, penalty weights) are in test_backends.cpp, on every back end.
  SECTION("two l = u rows that contradict each other") {
    // x0 + x1 = 1 and x0 + x1 = 2: the penalty is flat between, ½|x|² picks x0 + x1 = 1.
    // A moderate ρ keeps Ipopt's penalised solve accurate to compare with.
    auto backend_rho = make_active_set_backend(active_set(10.0));
    auto ipopt_rho = make_ipopt_backend(reference_ipopt(10.0));
    QpProblem p;
    p.resize(2, 0, 2);
    p.H.setIdentity();
    p.C << 1, 1, 1, 1;
    p.lower << 1.0, 2.0;
    p.upper << 1.0, 2.0;
    p.ineq_names = {"trunk a", "trunk b"};
    const QpOutcome& out = backend_rho->solve(p);
    REQUIRE(out.status == SolverStatus::kRelaxed);
    CHECK(inf_norm(out.x - Eigen::Vector2d(0.5, 0.5)) < 1e-13);
    CHECK(out.message == "relaxed: trunk b by 1");
    // Row b is below its bound: λ_b = +ρ; stationarity x = (λ_a + λ_b)(1, 1) gives λ_a.
    CHECK(out.lambda_ineq[1] == Approx(10.0));
    CHECK(out.lambda_ineq[0] == Approx(-9.5));
    CHECK(backend->solve(p).message == out.message);  // the same with ρ = 1e6
    const QpOutcome& ref = ipopt_rho->solve(p);
    CHECK(ref.message == out.message);
    CHECK(inf_norm(ref.x - out.x) < 1e-6);
  }
  SECTION("random infeasible problems: same rows, same violations, same forces") {
    // Trunk-like l = u rows that boxes on the variables forbid; moderate ρ and weights, so
    // that Ipopt's penalised solve is accurate too.
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> W(1.0, 5.0);
    const double rho = 10.0;
    auto backend_rho = make_active_set_backend(active_set(rho));
    auto ipopt_rho = make_ipopt_backend(reference_ipopt(rho));
    for (int trial = 0; trial < 12; ++trial) {
      const int n = 6 + trial % 10, lu = 2 + trial % 4;
      CAPTURE(trial, n, lu);
      QpProblem p = random_qp(rng, n, 0, lu, n, 4);
      make_infeasible(p, lu);
      for (int i = 0; i < p.inequalities(); ++i) p.ineq_penalty[i] = W(rng);
      const QpOutcome ref = ipopt_rho->solve(p);
      const QpOutcome& out = backend_rho->solve(p);
      REQUIRE(ref.status == SolverStatus::kRelaxed);
      REQUIRE(out.status == SolverStatus::kRelaxed);
      CHECK(check_penalised_kkt(p, out, rho, 1e-9));
      CHECK(named_rows(out.message) == named_rows(ref.message));
      CHECK(inf_norm(row_violations(p, out.x) - row_violations(p, ref.x)) < 1e-6);
      CHECK(out.max_violation == Approx(ref.max_violation).margin(1e-6));
      CHECK(inf_norm(out.x - ref.x) < 1e-6 * (1.0 + inf_norm(ref.x)));
      CHECK(penalised_objective(p, out.x, rho) <=
            penalised_objective(p, ref.x, rho) + 1e-12 * (1.0 + std::abs(ref.objective)));
      CHECK(inf_norm(extended_precision_x(p, out, rho) - out.x) < 1e-10 * (1.0 + inf_norm(out.x)));
    }
  }
}

TEST_CASE("active-set back end: unsupported problems and options are rejected",
          "[allocation][active_set]") {
  auto backend = make_active_set_backend();
  QpProblem p;
  p.resize(3, 0, 1);
  p.H.setIdentity();
  p.cones.push_back({0, 1, 2, 0.3, "friction cone L1"});
  CHECK_THROWS_AS(backend->solve(p), SolverError);
  try {
    backend->solve(p);
  } catch (const SolverError& e) {
    CHECK(std::string(e.what()).find("cones need the ipopt back end") != std::string::npos);
  }
  QpProblem big;
  big.resize(kActiveSetMaxVariables + 1, 0, 2);
  big.H.setIdentity();
  CHECK_THROWS_AS(backend->solve(big), SolverError);
  big.resize(4, 10, kActiveSetMaxRows);
  big.H.setIdentity();
  CHECK_THROWS_AS(backend->solve(big), SolverError);
  QpProblem bad;
  bad.resize(3, 1, 1);
  bad.A.resize(1, 2);
  CHECK_THROWS_AS(backend->solve(bad), SolverError);
  ActiveSetOptions o;
  o.tolerance = 0.0;
  CHECK_THROWS_AS(make_active_set_backend(o), ConfigError);
  o = ActiveSetOptions{};
  o.max_iterations = 0;
  CHECK_THROWS_AS(make_active_set_backend(o), ConfigError);
  AllocationParams params;
  params.tolerance = 1e-8;
  params.slack_penalty = 123.0;
  const ActiveSetOptions from = active_set_options_from(params);
  CHECK(from.tolerance == 1e-8);
  CHECK(from.slack_penalty == 123.0);
}
