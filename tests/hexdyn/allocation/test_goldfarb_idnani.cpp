// Tests of the dual active-set solver on its own (src/hexdyn/allocation/goldfarb_idnani.hpp),
// through its own interface and exit status, without the back end's policy or warm-start
// bookkeeping. Answers are checked against second computations: the closed-form KKT
// system on the rows the solver reports active, the KKT conditions (kkt_check.hpp), and
// the dense kernels (small_dense.hpp) against Eigen's decompositions.
#include <Eigen/Dense>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "hexdyn/allocation/active_set_checks.hpp"
#include "hexdyn/allocation/goldfarb_idnani.hpp"
#include "hexdyn/allocation/kkt_check.hpp"
#include "hexdyn/allocation/small_dense.hpp"

using namespace hexdyn;
using namespace hexdyn::test;

namespace {

/// The solver's answer as an outcome, for the KKT check.
QpOutcome outcome_of(const DualActiveSetQp& s, const QpProblem& p) {
  QpOutcome out;
  out.x = s.x().head(s.n());
  std::array<double, kActiveSetMaxRows> lambda{};
  s.lambdas(lambda.data());
  out.lambda_eq.resize(p.equalities());
  out.lambda_ineq.resize(p.inequalities());
  for (int k = 0; k < p.equalities(); ++k) out.lambda_eq[k] = lambda[k];
  for (int i = 0; i < p.inequalities(); ++i) out.lambda_ineq[i] = lambda[p.equalities() + i];
  return out;
}

/// x and λ of the equality-constrained problem on the rows the solver reports active,
/// from the dense KKT system [H −Nᵀ; N 0] (a second computation).
Eigen::VectorXd kkt_solution_on_active_rows(const DualActiveSetQp& s, const QpProblem& p) {
  const int n = p.variables(), q = s.active_count();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + q, n + q);
  Eigen::VectorXd rhs(n + q);
  K.topLeftCorner(n, n) = p.H;
  rhs.head(n) = -p.g;
  for (int i = 0; i < q; ++i) {
    const ActiveRow r = s.active_row(i);
    const bool eq = r.row < p.equalities();
    const Eigen::RowVectorXd a = eq ? p.A.row(r.row) : p.C.row(r.row - p.equalities());
    const double bound =
        eq ? p.b[r.row]
           : (r.side > 0 ? p.lower[r.row - p.equalities()] : p.upper[r.row - p.equalities()]);
    K.block(0, n + i, n, 1) = -a.transpose();
    K.block(n + i, 0, 1, n) = a;
    rhs[n + i] = bound;
  }
  return K.fullPivLu().solve(rhs).head(n);
}

/// Runs the dual iteration on the loaded problem from a cold start, in the given mode, with
/// at most `max_changes` active-set changes (counted into *changes if given), and polishes
/// an optimal end.
ActiveSetExit run_cold(DualActiveSetQp& s, bool penalised, int max_changes = 500,
                       int* changes = nullptr) {
  s.set_mode(penalised);
  s.start_cold();
  int count = 0;
  const ActiveSetExit exit = s.run(max_changes, count);
  if (exit == ActiveSetExit::kOptimal) s.polish();
  if (changes) *changes = count;
  return exit;
}

}  // namespace

TEST_CASE("dual active set: the small dense kernels agree with Eigen", "[allocation][dual]") {
  std::mt19937 rng(5);
  const int n = 11;
  const Eigen::MatrixXd M = random_matrix(rng, n, n);
  SmallMatrix H = SmallMatrix::Zero();
  H.topLeftCorner(n, n) = M * M.transpose() + Eigen::MatrixXd::Identity(n, n);
  SmallMatrix L = SmallMatrix::Zero();
  std::array<double, kSmallDenseMax> linv{};
  REQUIRE(cholesky(H, n, 0.0, L, linv.data()));
  const Eigen::MatrixXd L_eigen = H.topLeftCorner(n, n).llt().matrixL();
  CHECK((L.topLeftCorner(n, n).triangularView<Eigen::Lower>().toDenseMatrix() - L_eigen)
            .cwiseAbs()
            .maxCoeff() < 1e-12);
  // L⁻¹ v, L⁻ᵀ v and J = L⁻ᵀ.
  const Eigen::VectorXd v = random_vector(rng, n);
  Eigen::VectorXd w = v;
  lower_solve(L, linv.data(), n, w.data());
  CHECK((L_eigen * w - v).cwiseAbs().maxCoeff() < 1e-12);
  w = v;
  lower_transpose_solve(L, linv.data(), n, w.data());
  CHECK((L_eigen.transpose() * w - v).cwiseAbs().maxCoeff() < 1e-12);
  SmallMatrix J = SmallMatrix::Zero();
  inverse_transpose_of_lower(L, linv.data(), n, J);
  CHECK((L_eigen.transpose() * J.topLeftCorner(n, n) - Eigen::MatrixXd::Identity(n, n))
            .cwiseAbs()
            .maxCoeff() < 1e-12);
  // R⁻¹ and R⁻ᵀ on an upper triangular R.
  SmallMatrix R = SmallMatrix::Zero();
  R.topLeftCorner(n, n) = L_eigen.transpose();
  std::array<double, kSmallDenseMax> out{}, rinv{};
  upper_solve(R, n, v.data(), out.data(), rinv.data());
  CHECK(
      (L_eigen.transpose() * Eigen::Map<Eigen::VectorXd>(out.data(), n) - v).cwiseAbs().maxCoeff() <
      1e-12);
  upper_transpose_solve(R, n, v.data(), out.data(), rinv.data());
  CHECK((L_eigen * Eigen::Map<Eigen::VectorXd>(out.data(), n) - v).cwiseAbs().maxCoeff() < 1e-12);
  // A Givens rotation zeroes the second entry and keeps the norm.
  double c, s, rho;
  givens(3.0, -4.0, c, s, rho);
  CHECK(std::abs(c * 3.0 + s * -4.0 - rho) < 1e-15);
  CHECK(std::abs(-s * 3.0 + c * -4.0) < 1e-15);
  CHECK(std::abs(std::abs(rho) - 5.0) < 1e-15);
  // An indefinite matrix has no Cholesky factor.
  H(0, 0) = -1.0;
  CHECK_FALSE(cholesky(H, n, 0.0, L, linv.data()));
}

TEST_CASE("dual active set: cold runs end optimal on the KKT solution of their active rows",
          "[allocation][dual]") {
  std::mt19937 rng(31);
  DualActiveSetQp s;
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 5 + trial % 10;
    CAPTURE(trial, n);
    const QpProblem p = random_qp(rng, n, trial % 3, trial % 2, n, 8 + trial);
    REQUIRE(s.load(p, 1e6, 1e-9));
    REQUIRE(s.convex());
    CHECK(s.crossed_row() == -1);
    CHECK(s.regularisation() == 0.0);
    int changes = 0;
    REQUIRE(run_cold(s, false, 500, &changes) == ActiveSetExit::kOptimal);
    CHECK(changes >= s.active_count());
    const QpOutcome out = outcome_of(s, p);
    CHECK(check_kkt(p, out, 1e-10));
    const Eigen::VectorXd x_kkt = kkt_solution_on_active_rows(s, p);
    CHECK(inf_norm(out.x - x_kkt) < 1e-9 * (1.0 + inf_norm(x_kkt)));
    CHECK(s.objective(p.constant) == Approx(p.objective(out.x)).epsilon(1e-12));
    bool beyond = true;
    CHECK(s.max_violation(1e-9, beyond) <= 1e-9);
    CHECK_FALSE(beyond);
  }
}

TEST_CASE("dual active set: a warm start from the answer's own rows needs no change",
          "[allocation][dual]") {
  std::mt19937 rng(8);
  const QpProblem p = random_qp(rng, 10, 2, 1, 10, 14);
  DualActiveSetQp s;
  REQUIRE(s.load(p, 1e6, 1e-9));
  REQUIRE(run_cold(s, false) == ActiveSetExit::kOptimal);
  const Eigen::VectorXd x_cold = s.x().head(10);
  std::vector<ActiveRow> rows;
  for (int i = 0; i < s.active_count(); ++i) rows.push_back(s.active_row(i));

  int dropped = 0;
  REQUIRE(s.start_warm(rows.data(), static_cast<int>(rows.size()), nullptr, 0, dropped));
  CHECK(dropped == 0);
  int warm_changes = 0;
  REQUIRE(s.run(500, warm_changes) == ActiveSetExit::kOptimal);
  CHECK(warm_changes == 0);
  s.polish();
  CHECK(inf_norm(Eigen::VectorXd(s.x().head(10)) - x_cold) < 1e-12 * (1.0 + inf_norm(x_cold)));
}

TEST_CASE("dual active set: exit statuses", "[allocation][dual]") {
  SECTION("inconsistent equality rows are infeasible, in either mode") {
    QpProblem p;
    p.resize(2, 2, 0);
    p.H.setIdentity();
    p.A << 1, 0, 1, 0;
    p.b << 1, 2;
    DualActiveSetQp s;
    REQUIRE(s.load(p, 1e6, 1e-9));
    for (const bool penalised : {false, true}) {
      CHECK(run_cold(s, penalised) == ActiveSetExit::kInfeasible);
    }
  }
  SECTION("crossed bounds: reported, infeasible as posed, elastic when penalised") {
    QpProblem p;
    p.resize(2, 0, 1);
    p.H.setIdentity();
    p.C << 1, 0;
    p.lower << 5.0;
    p.upper << 4.0;
    DualActiveSetQp s;
    REQUIRE(s.load(p, 10.0, 1e-9));
    CHECK(s.crossed_row() == 0);
    REQUIRE(run_cold(s, true) == ActiveSetExit::kOptimal);
    // Penalised optimum of ½x² + 10·dist(x, [4, 5]) + 10·(5 − 4): x = 4 with λ ∈ [0, 10].
    CHECK(s.x()[0] == Approx(4.0).margin(1e-12));
    CHECK(check_penalised_kkt(p, outcome_of(s, p), 10.0, 1e-10));
  }
  SECTION("the iteration limit stops a run") {
    std::mt19937 rng(2);
    const QpProblem p = random_qp(rng, 12, 0, 0, 12, 20);
    DualActiveSetQp s;
    REQUIRE(s.load(p, 1e6, 1e-9));
    CHECK(run_cold(s, false, 1) == ActiveSetExit::kIterationLimit);
    CHECK(std::string(exit_name(ActiveSetExit::kIterationLimit)) ==
          "stopped at the iteration limit");
  }
  SECTION("non-finite data and indefinite H are refused at load") {
    QpProblem p;
    p.resize(2, 0, 0);
    p.H.setIdentity();
    p.g << 1.0, std::nan("");
    DualActiveSetQp s;
    CHECK_FALSE(s.load(p, 1e6, 1e-9));
    p.g << 1.0, 0.0;
    p.H(1, 1) = -1.0;
    REQUIRE(s.load(p, 1e6, 1e-9));
    CHECK_FALSE(s.convex());
  }
}

TEST_CASE("dual active set: the dependence test", "[allocation][dual]") {
  CHECK(DualActiveSetQp::dependent_row(0.0, 1.0));
  CHECK(DualActiveSetQp::dependent_row(0.0, 0.0));  // a zero normal
  CHECK(DualActiveSetQp::dependent_row(0.5e-20, 1.0));
  CHECK_FALSE(DualActiveSetQp::dependent_row(2e-20, 1.0));
  // A row that duplicates an active one is not added twice: the answer has one of them
  // active (test_active_set.cpp checks the multipliers of such problems against Ipopt).
  QpProblem p;
  p.resize(2, 0, 2);
  p.H.setIdentity();
  p.g << -4.0, 0.0;
  p.C << 1, 0, 2, 0;
  p.lower << -kInf, -kInf;
  p.upper << 1.0, 2.0;
  DualActiveSetQp s;
  REQUIRE(s.load(p, 1e6, 1e-9));
  REQUIRE(run_cold(s, false) == ActiveSetExit::kOptimal);
  CHECK(s.active_count() == 1);
  CHECK(s.x()[0] == Approx(1.0).margin(1e-14));
  CHECK(check_kkt(p, outcome_of(s, p), 1e-12));
}
