// Tests of the dual active-set back end (src/hexdyn/allocation_active_set.hpp). Each answer
// is checked against a second computation: the closed-form KKT solve of equality-only QPs,
// Ipopt with a tight tolerance on random QPs, the KKT conditions of the problem (and of
// the L1-penalised problem for relaxed answers: an optimality certificate, the problem
// being convex), an extended-precision solve of the equality-constrained problem on the
// answer's active rows, and, on every sample of the paper run and of the smoke sweep, the
// Ipopt back end: same status, same rows named, the same forces.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/active_set.hpp"
#include "hexdyn/allocation/ipopt.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/io/config.hpp"
#include "hexdyn/pipeline/dynamics_stage.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/sweep.hpp"
#include "hexdyn/allocation/qp_test_problems.hpp"

using namespace hexdyn;

namespace {

using test::add_rows_around;
using test::kInf;
using test::random_matrix;
using test::random_vector;

double inf_norm(const Eigen::VectorXd& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

/// Ipopt as the reference: tight tolerance, cold starts.
IpoptOptions reference_ipopt(double slack_penalty = 1e6) {
  IpoptOptions o;
  o.tolerance = 1e-11;
  o.slack_penalty = slack_penalty;
  o.warm_start = false;
  return o;
}

ActiveSetOptions active_set(double slack_penalty = 1e6, bool warm = true) {
  ActiveSetOptions o;
  o.slack_penalty = slack_penalty;
  o.warm_start = warm;
  return o;
}

/// Random strictly convex QP around a point x0 that satisfies every row: m_eq equality
/// rows A x = b, `lu` rows written as lower = upper, `boxes` box rows on single variables
/// and `general` dense rows (some one-sided); the unconstrained minimiser is pushed away
/// from x0 so that rows bind. *x0_out (if given) receives x0.
QpProblem random_qp(std::mt19937& rng, int n, int m_eq, int lu, int boxes, int general,
                    Eigen::VectorXd* x0_out = nullptr) {
  const int m_in = lu + boxes + general;
  QpProblem p;
  p.resize(n, m_eq, m_in);
  const Eigen::MatrixXd M = random_matrix(rng, n, n);
  p.H = M * M.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd x0 = random_vector(rng, n);
  p.A = random_matrix(rng, m_eq, n);
  p.b = p.A * x0;
  for (int i = 0; i < m_eq; ++i) p.eq_names[i] = "eq " + std::to_string(i);
  for (int i = 0; i < lu; ++i) {
    p.C.row(i) = random_matrix(rng, 1, n);
    p.lower[i] = p.upper[i] = p.C.row(i).dot(x0);
    p.ineq_names[i] = "trunk " + std::to_string(i);
  }
  add_rows_around(rng, p, x0, lu, boxes, general);
  p.g = -p.H * (x0 + 3.0 * random_vector(rng, n));
  p.constant = 0.25;
  if (x0_out) *x0_out = x0;
  return p;
}

/// ½xᵀHx + gᵀx + c + ρ Σ w_i · (violation of row i), violations in row units; violations
/// within rounding (1e-12·(1 + |bound|)) count as 0, or ρ w_i (up to 1e9) would turn them
/// into differences far above those of the objective.
double penalised_objective(const QpProblem& p, const Eigen::VectorXd& x, double rho) {
  auto beyond = [](double v, double bound) {
    return v > 1e-12 * (1.0 + std::abs(bound)) ? v : 0.0;
  };
  double v = 0.0;
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    const double w = p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0;
    if (p.lower[i] > -kQpInfinity) v += w * beyond(p.lower[i] - c, p.lower[i]);
    if (p.upper[i] < kQpInfinity) v += w * beyond(c - p.upper[i], p.upper[i]);
  }
  return p.objective(x) + rho * v;
}

/// KKT conditions of the L1-penalised problem (allocation_qp.hpp) at (x, λ): stationarity
/// H x + g − Aᵀλ_eq − Cᵀλ = 0 (relative to the size of its terms), equality rows hold, and
/// per inequality row the subgradient condition: λ_i = ρw_i below the lower bound, −ρw_i
/// above the upper bound, 0 strictly inside, within [0, ρw_i] at the lower bound and
/// [−ρw_i, 0] at the upper one. With H positive definite these certify the unique optimum.
bool check_penalised_kkt(const QpProblem& p, const QpOutcome& out, double rho, double tol,
                         std::string* why) {
  std::ostringstream os;
  const Eigen::VectorXd& x = out.x;
  const Eigen::MatrixXd H = p.H.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd r = H * x + p.g;
  Eigen::VectorXd scale = (H * x).cwiseAbs() + p.g.cwiseAbs();
  if (p.equalities() > 0) {
    r -= p.A.transpose() * out.lambda_eq;
    scale += p.A.cwiseAbs().transpose() * out.lambda_eq.cwiseAbs();
  }
  if (p.inequalities() > 0) {
    r -= p.C.transpose() * out.lambda_ineq;
    scale += p.C.cwiseAbs().transpose() * out.lambda_ineq.cwiseAbs();
  }
  for (int j = 0; j < p.variables(); ++j) {
    if (std::abs(r[j]) > tol * (1.0 + scale[j])) {
      os << "stationarity residual " << r[j] << " in variable " << j;
      *why = os.str();
      return false;
    }
  }
  for (int i = 0; i < p.equalities(); ++i) {
    if (std::abs(p.A.row(i).dot(x) - p.b[i]) > tol * (1.0 + std::abs(p.b[i]))) {
      *why = "equality " + p.eq_name(i) + " violated";
      return false;
    }
  }
  for (int i = 0; i < p.inequalities(); ++i) {
    const double kappa = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
    const double c = p.C.row(i).dot(x), lam = out.lambda_ineq[i];
    const double lo = p.lower[i], hi = p.upper[i];
    const bool has_lo = lo > -kQpInfinity, has_hi = hi < kQpInfinity;
    const double dlo = tol * (1.0 + std::abs(lo)), dhi = tol * (1.0 + std::abs(hi));
    // λ is minus the slope of the penalty: ρw below the lower bound, −ρw above the upper one
    // (both, cancelling, between crossed bounds); at a kink (within the tolerance d) any
    // value between the slopes on either side.
    auto minus_slope = [&](double at) {
      return (has_lo && at < lo ? kappa : 0.0) - (has_hi && at > hi ? kappa : 0.0);
    };
    const double d = std::max(has_lo ? dlo : 0.0, has_hi ? dhi : 0.0);
    const double lmin = std::min(minus_slope(c - d), minus_slope(c + d));
    const double lmax = std::max(minus_slope(c - d), minus_slope(c + d));
    const double ltol = tol * (1.0 + kappa);
    if (lam < lmin - ltol || lam > lmax + ltol) {
      os << p.ineq_name(i) << ": C x = " << c << " in [" << lo << ", " << hi << "], λ = " << lam
         << " not in [" << lmin << ", " << lmax << "]";
      *why = os.str();
      return false;
    }
  }
  return true;
}

/// x of the equality-constrained problem that an answer's rows define, solved again in
/// extended precision: rows at a bound with λ ≠ 0 held with equality, violated rows as the
/// fixed linear term −λ_i C_i with λ_i = ±ρ w_i (the penalty's slope), the rest left out.
Eigen::VectorXd extended_precision_x(const QpProblem& p, const QpOutcome& out, double rho) {
  using LD = long double;
  using MatL = Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>;
  using VecL = Eigen::Matrix<LD, Eigen::Dynamic, 1>;
  const int n = p.variables();
  VecL g = p.g.cast<LD>();
  std::vector<VecL> rows;
  std::vector<LD> rhs;
  for (int i = 0; i < p.equalities(); ++i) {
    rows.emplace_back(p.A.row(i).transpose().cast<LD>());
    rhs.push_back(p.b[i]);
  }
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(out.x), lo = p.lower[i], hi = p.upper[i];
    const double kappa = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
    const double dlo = 1e-9 * (1.0 + std::abs(lo)), dhi = 1e-9 * (1.0 + std::abs(hi));
    const VecL a = p.C.row(i).transpose().cast<LD>();
    if (lo > -kQpInfinity && c < lo - dlo) {
      g -= LD(kappa) * a;
    } else if (hi < kQpInfinity && c > hi + dhi) {
      g += LD(kappa) * a;
    } else if (out.lambda_ineq[i] != 0.0 && lo > -kQpInfinity && std::abs(c - lo) <= dlo) {
      rows.push_back(a);
      rhs.push_back(lo);
    } else if (out.lambda_ineq[i] != 0.0 && hi < kQpInfinity && std::abs(c - hi) <= dhi) {
      rows.push_back(a);
      rhs.push_back(hi);
    }
  }
  const int q = static_cast<int>(rows.size());
  MatL K = MatL::Zero(n + q, n + q);
  VecL r(n + q);
  K.topLeftCorner(n, n) = p.H.cast<LD>().selfadjointView<Eigen::Lower>();
  r.head(n) = -g;
  for (int j = 0; j < q; ++j) {
    K.block(0, n + j, n, 1) = -rows[j];
    K.block(n + j, 0, 1, n) = rows[j].transpose();
    r[n + j] = rhs[j];
  }
  const VecL sol = K.completeOrthogonalDecomposition().solve(r);
  return sol.head(n).cast<double>();
}

/// Rows named in a "relaxed: a by 1, b by 2" message, sorted.
std::vector<std::string> named_rows(const std::string& message) {
  std::vector<std::string> names;
  const std::string prefix = "relaxed: ";
  if (message.rfind(prefix, 0) != 0) return names;
  std::size_t pos = prefix.size();
  while (pos < message.size()) {
    const std::size_t by = message.find(" by ", pos);
    if (by == std::string::npos) break;
    names.push_back(message.substr(pos, by - pos));
    const std::size_t comma = message.find(", ", by);
    if (comma == std::string::npos) break;
    pos = comma + 2;
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// Violation of every row at x (row units; 0 where it holds).
Eigen::VectorXd row_violations(const QpProblem& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(p.inequalities());
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    if (p.lower[i] > -kQpInfinity) v[i] += std::max(0.0, p.lower[i] - c);
    if (p.upper[i] < kQpInfinity) v[i] += std::max(0.0, c - p.upper[i]);
  }
  return v;
}

/// Makes a random_qp infeasible: its l = u rows ask for 50, 60, ... while every variable
/// is boxed in [−0.5, 0.5] (rows lu .. lu + n − 1 are the boxes).
void make_infeasible(QpProblem& p, int lu) {
  const int n = p.variables();
  for (int i = 0; i < lu; ++i) p.lower[i] = p.upper[i] = 50.0 + 10.0 * i;
  for (int i = lu; i < lu + n; ++i) p.lower[i] = -0.5, p.upper[i] = 0.5;
}

}  // namespace

TEST_CASE("active-set back end: equality-constrained QPs match the closed-form KKT solve",
          "[allocation][active_set]") {
  std::mt19937 rng(20240601);
  auto backend = make_active_set_backend();
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 6 + trial % 7, m_eq = 3 + trial % 4;
    CAPTURE(trial, n, m_eq);
    QpProblem p = random_qp(rng, n, m_eq, 0, 0, 0);
    // [H  −Aᵀ; A  0] [x; λ] = [−g; b].
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m_eq, n + m_eq);
    K.topLeftCorner(n, n) = p.H;
    K.topRightCorner(n, m_eq) = -p.A.transpose();
    K.bottomLeftCorner(m_eq, n) = p.A;
    Eigen::VectorXd rhs(n + m_eq);
    rhs << -p.g, p.b;
    const Eigen::VectorXd sol = K.fullPivLu().solve(rhs);
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == 0);
    CHECK(inf_norm(out.x - sol.head(n)) < 1e-10 * (1.0 + inf_norm(sol.head(n))));
    CHECK(inf_norm(out.lambda_eq - sol.tail(m_eq)) < 1e-9 * (1.0 + inf_norm(sol.tail(m_eq))));
    CHECK(out.objective == Approx(p.objective(sol.head(n))).epsilon(1e-12));
    CHECK(out.message.empty());
    CHECK(out.lambda_cone.size() == 0);
    CHECK(check_kkt(p, out, 1e-10));
  }
}

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
    REQUIRE(ref.status == 0);
    REQUIRE(out.status == 0);
    std::string why;
    const bool kkt = check_kkt(p, out, 1e-9, &why);
    INFO(why);
    CHECK(kkt);
    CHECK(inf_norm(out.x - ref.x) < 1e-7 * (1.0 + inf_norm(ref.x)));
    CHECK(out.objective == Approx(ref.objective).epsilon(1e-10));
    CHECK(out.objective == Approx(p.objective(out.x)).epsilon(1e-13));
    CHECK(out.max_violation < 1e-9 * (1.0 + inf_norm(p.C * out.x)));
    // Multipliers are unique at these (non-degenerate) optima.
    CHECK(inf_norm(out.lambda_ineq - ref.lambda_ineq) < 1e-5 * (1.0 + inf_norm(ref.lambda_ineq)));
    CHECK(inf_norm(out.lambda_eq - ref.lambda_eq) < 1e-5 * (1.0 + inf_norm(ref.lambda_eq)));
    CHECK(out.iterations > 0);
    CHECK(out.seconds >= 0.0);
    binding += (out.lambda_ineq.array().abs() > 1e-6).count() > lu;
  }
  CHECK(binding > 30);  // inequality rows were active, not only the l = u rows
}

TEST_CASE("active-set back end: multiplier signs follow the documented convention",
          "[allocation][active_set]") {
  const QpProblem p = test::sign_convention_problem();  // λ = (1, −2)
  auto backend = make_active_set_backend();
  const QpOutcome& out = backend->solve(p);
  REQUIRE(out.status == 0);
  CHECK(out.x[0] == Approx(1.0).margin(1e-14));
  CHECK(out.x[1] == Approx(-2.0).margin(1e-14));
  CHECK(out.x[2] == Approx(0.0).margin(1e-14));
  CHECK(out.lambda_ineq[0] == Approx(1.0).margin(1e-14));
  CHECK(out.lambda_ineq[1] == Approx(-2.0).margin(1e-14));
  CHECK(out.objective == Approx(2.5).epsilon(1e-14));
  CHECK(out.iterations == 2);
  CHECK(check_kkt(p, out, 1e-12));
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
    REQUIRE(out.status == 0);
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
    REQUIRE(out.status == 0);
    CHECK(inf_norm(out.x) < 1e-14);
    std::string why;
    CHECK(check_kkt(p, out, 1e-12, &why));
    INFO(why);
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
    REQUIRE(out.status == 0);
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
    REQUIRE(ref.status == 0);
    REQUIRE(out.status == 0);
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
    CHECK(out.status == 1);
    CHECK(out.message == "relaxed: zero row by 1");
    CHECK(out.max_violation == Approx(1.0));
    CHECK(inf_norm(out.x - ref.x) < 1e-12 * (1.0 + inf_norm(ref.x)));
    const QpOutcome& by_ipopt = ipopt->solve(q);
    CHECK(by_ipopt.status == 1);
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
    REQUIRE(out.status == 0);
    CHECK(out.message.find("regularised") != std::string::npos);
    const QpOutcome& ref = ipopt->solve(p);
    REQUIRE(ref.status == 0);
    CHECK(inf_norm(out.x - ref.x) < 1e-6);
    CHECK(check_kkt(p, out, 1e-8));
  }
}

TEST_CASE("active-set back end: infeasible problems are relaxed as Ipopt relaxes them",
          "[allocation][active_set]") {
  auto backend = make_active_set_backend();
  auto ipopt = make_ipopt_backend(reference_ipopt());

  SECTION("a torque row against equalities") {
    // x0 + x1 = 10 and x1 = 8 (equality rows), torque row x0 ≤ 1: violated by 1.
    QpProblem p;
    p.resize(3, 2, 2);
    p.H.setIdentity();
    p.A << 1, 1, 0, 0, 1, 0;
    p.b << 10, 8;
    p.C << 1, 0, 0, 0, 0, 1;
    p.lower << -kInf, -1.0;
    p.upper << 1.0, 1.0;
    p.eq_names = {"trunk Fz", "trunk Mx"};
    p.ineq_names = {"torque L1_femur", "friction L3 +x"};
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == 1);
    CHECK(out.message == "relaxed: torque L1_femur by 1");
    CHECK(out.x[0] == Approx(2.0).margin(1e-14));
    CHECK(out.max_violation == Approx(1.0).margin(1e-14));
    CHECK(out.lambda_ineq[0] == Approx(-1e6));   // the penalty's slope
    CHECK(inf_norm(p.A * out.x - p.b) < 1e-13);  // equalities stay hard
    const QpOutcome& ref = ipopt->solve(p);
    CHECK(ref.status == 1);
    CHECK(ref.message == out.message);
  }
  SECTION("crossed bounds on a row, largest violation first") {
    QpProblem p;
    p.resize(2, 0, 2);
    p.H.setIdentity();
    p.C << 1, 0, 0, 1;
    p.lower << 5.0, 3.0;
    p.upper << 4.0, 2.9;
    p.ineq_names = {"normal L2", "torque L4_tibia"};
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == 1);
    // Each row sits at the end of [upper, lower] nearer the unconstrained optimum 0.
    CHECK(inf_norm(out.x - Eigen::Vector2d(4.0, 2.9)) < 1e-14);
    CHECK(out.message == "relaxed: normal L2 by 1, torque L4_tibia by 0.1");
    CHECK(ipopt->solve(p).message == out.message);
  }
  SECTION("penalty weights choose the row that gives way") {
    // x0 + x1 = 10 as an l = u row against x0 ≤ 2 and x1 ≤ 3: 5 units must give.
    QpProblem p;
    p.resize(2, 0, 3);
    p.H.setIdentity();
    p.C << 1, 1, 1, 0, 0, 1;
    p.lower << 10.0, -kInf, -kInf;
    p.upper << 10.0, 2.0, 3.0;
    p.ineq_names = {"trunk force z", "torque L1_femur", "torque L2_femur"};
    p.ineq_penalty << 1.0, 1e3, 1e3;
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == 1);
    CHECK(out.x[0] == Approx(2.0).margin(1e-13));
    CHECK(out.x[1] == Approx(3.0).margin(1e-13));
    CHECK(out.message == "relaxed: trunk force z by 5");
    CHECK(out.lambda_ineq[0] == Approx(1e6));
    p.ineq_penalty << 1e3, 1.0, 1.0;
    const QpOutcome& other = backend->solve(p);
    REQUIRE(other.status == 1);
    // Both torque rows give way; with the penalty the same for any split of the 5 units,
    // ½|x|² on x0 + x1 = 10 decides: x = (5, 5).
    CHECK(other.x[0] == Approx(5.0).margin(1e-12));
    CHECK(other.x[1] == Approx(5.0).margin(1e-12));
    CHECK(other.message == "relaxed: torque L1_femur by 3, torque L2_femur by 2");
    const QpOutcome& ref = ipopt->solve(p);
    CHECK(ref.message == other.message);
    // Ipopt's penalised solves stop at a tolerance relative to multipliers ρ w = 1e9.
    CHECK(inf_norm(ref.x - other.x) < 1e-5);
  }
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
    REQUIRE(out.status == 1);
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
  SECTION("unsatisfiable equality rows fail with the least-squares fallback") {
    QpProblem p;
    p.resize(2, 2, 1);
    p.H.setIdentity();
    p.A << 1, 0, 1, 0;
    p.b << 1, 2;
    p.C << 0, 1;
    p.lower << 0.0;
    p.upper << 1.0;
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == 2);
    CHECK(out.x.allFinite());
    CHECK(out.x[0] == Approx(1.5).margin(1e-12));
    CHECK(out.message.rfind("failed: ", 0) == 0);
    CHECK(ipopt->solve(p).status == 2);
  }
  SECTION("non-finite data fail with a finite fallback; the next solve is normal") {
    std::mt19937 rng(3);
    QpProblem p = random_qp(rng, 6, 3, 0, 0, 0);
    for (int where = 0; where < 4; ++where) {
      QpProblem q = p;
      if (where == 0) q.g[2] = std::nan("");
      if (where == 1) q.H(0, 4) = kInf;  // upper triangle: not read, still rejected
      if (where == 2) q.A(1, 1) = -kInf;
      if (where == 3) q.constant = std::nan("");
      CAPTURE(where);
      const QpOutcome& out = backend->solve(q);
      CHECK(out.status == 2);
      CHECK(out.x.allFinite());
      CHECK(std::isfinite(out.objective));
      CHECK(out.message.find("non-finite") != std::string::npos);
    }
    CHECK(backend->solve(p).status == 0);
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
      REQUIRE(ref.status == 1);
      REQUIRE(out.status == 1);
      std::string why;
      const bool kkt = check_penalised_kkt(p, out, rho, 1e-9, &why);
      INFO(why);
      CHECK(kkt);
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

TEST_CASE("active-set back end: random degenerate problems are solved to certified optimality",
          "[allocation][active_set]") {
  // Duplicated and scaled rows, zero rows, l = u rows, crossed bounds, infeasible shifts,
  // and slowly changing sequences (warm starts), up to the size limits. Every answer is
  // certified by the KKT conditions of the problem (status 0) or of the penalised problem
  // (status 1), and the warm-started back end agrees with a cold one.
  std::mt19937 rng(12345);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto warm = make_active_set_backend();
  auto cold = make_active_set_backend(active_set(1e6, false));
  QpProblem previous;
  int counts[3] = {0, 0, 0}, certified = 0, agreed = 0, trials = 0;
  std::string first_failure;
  for (int t = 0; t < 1500; ++t) {
    QpProblem p;
    if (t > 0 && U(rng) < 0.4) {
      p = previous;  // the next sample of a slowly changing sequence
      p.g += 0.01 * Eigen::VectorXd::NullaryExpr(p.variables(), [&] { return N(rng); });
    } else {
      const int n = 1 + static_cast<int>(rng() % kActiveSetMaxVariables);
      const int m_eq = n > 3 ? static_cast<int>(rng() % 3) : 0;
      const int m_in = static_cast<int>(rng() % 60);
      p.resize(n, m_eq, m_in);
      const Eigen::MatrixXd M = random_matrix(rng, n, n);
      p.H = M * M.transpose() + 0.01 * Eigen::MatrixXd::Identity(n, n);
      p.g = 3.0 * random_vector(rng, n);
      const Eigen::VectorXd x0 = random_vector(rng, n);
      p.A = random_matrix(rng, m_eq, n);
      p.b = p.A * x0;
      const bool infeasible = U(rng) < 0.3;
      for (int i = 0; i < m_in; ++i) {
        const double kind = U(rng);
        if (kind < 0.2) {
          p.C(i, static_cast<int>(rng() % n)) = 1.0;  // a box
        } else if (kind < 0.25 && i > 0) {
          p.C.row(i) = p.C.row(static_cast<int>(rng() % i)) * (U(rng) < 0.5 ? 1.0 : 2.0);
        } else if (kind >= 0.28) {  // else a zero row
          p.C.row(i) = random_matrix(rng, 1, n);
        }
        const double c = p.C.row(i).dot(x0), bounds = U(rng);
        if (bounds < 0.2) {
          p.lower[i] = p.upper[i] = c;
        } else if (bounds < 0.4) {
          p.lower[i] = c - U(rng);
        } else if (bounds < 0.6) {
          p.upper[i] = c + U(rng);
        } else if (bounds < 0.97) {
          p.lower[i] = c - U(rng), p.upper[i] = c + U(rng);
        }
        if (infeasible && U(rng) < 0.15) {  // may cross the bounds
          if (p.lower[i] > -kQpInfinity)
            p.lower[i] += 3.0 + 5.0 * U(rng);
          else if (p.upper[i] < kQpInfinity)
            p.upper[i] -= 3.0 + 5.0 * U(rng);
        }
        p.ineq_penalty[i] = U(rng) < 0.5 ? 1.0 : 1.0 + 100.0 * U(rng);
        p.ineq_names[i] = "row " + std::to_string(i);
      }
    }
    previous = p;
    const QpOutcome a = warm->solve(p);
    const QpOutcome& b = cold->solve(p);
    ++trials;
    ++counts[a.status];
    std::string why;
    const bool ok = a.status == 0   ? check_kkt(p, a, 1e-8, &why)
                    : a.status == 1 ? check_penalised_kkt(p, a, 1e6, 1e-8, &why)
                                    : false;
    certified += ok;
    if (!ok && first_failure.empty())
      first_failure = std::to_string(t) + ": " + a.message + " " + why;
    agreed += a.status == b.status && inf_norm(a.x - b.x) <= 1e-6 * (1.0 + inf_norm(b.x));
  }
  INFO("statuses " << counts[0] << "/" << counts[1] << "/" << counts[2] << "; " << first_failure);
  CHECK(certified == trials);
  CHECK(agreed == trials);
  CHECK(counts[1] > 200);  // relaxed answers were exercised
}

TEST_CASE("active-set back end: a feasible problem after a relaxed one is solved to optimality",
          "[allocation][active_set]") {
  std::mt19937 rng(21);
  const QpProblem feasible = random_qp(rng, 9, 0, 6, 9, 15);
  QpProblem infeasible = feasible;
  infeasible.lower[8] = infeasible.upper[8] + 1.0;  // crossed bounds on one row
  auto fresh = make_active_set_backend();
  const QpOutcome reference = fresh->solve(feasible);
  REQUIRE(reference.status == 0);
  auto backend = make_active_set_backend();
  REQUIRE(backend->solve(infeasible).status == 1);
  const QpOutcome after = backend->solve(feasible);  // goes to the penalised form first
  CHECK(after.status == 0);
  CHECK(after.message.empty());
  CHECK(inf_norm(after.x - reference.x) < 1e-10 * (1.0 + inf_norm(reference.x)));
  CHECK(check_kkt(feasible, after, 1e-9));
  const QpOutcome again = backend->solve(feasible);
  CHECK(again.status == 0);
  CHECK(inf_norm(again.x - reference.x) < 1e-10 * (1.0 + inf_norm(reference.x)));
  CHECK(again.iterations == 0);  // warm: the previous active set is the answer
}

TEST_CASE("active-set back end: warm starts give the cold answers with fewer changes",
          "[allocation][active_set]") {
  std::mt19937 rng(99);
  auto warm = make_active_set_backend(active_set(1e6, true));
  auto cold = make_active_set_backend(active_set(1e6, false));
  for (const bool relaxed : {false, true}) {
    CAPTURE(relaxed);
    Eigen::VectorXd x0;
    QpProblem p = random_qp(rng, 12, 0, 6, 12, 20, &x0);
    if (relaxed) make_infeasible(p, 6);  // the trunk-like rows cannot hold within the boxes
    const Eigen::VectorXd dg = random_vector(rng, 12);
    const Eigen::MatrixXd dC = random_matrix(rng, p.inequalities(), 12);
    const Eigen::VectorXd db = random_vector(rng, p.inequalities());
    long warm_changes = 0, cold_changes = 0;
    int samples = 0, matched = 0;
    for (int k = 0; k < 60; ++k) {
      QpProblem q = p;
      const double s = 0.002 * k;
      q.g += s * dg;
      q.C += 0.1 * s * dC;
      // Bounds move with the rows (x0 stays feasible) and by a little more.
      const Eigen::VectorXd shift = 0.1 * s * dC * x0 + 0.1 * s * db;
      for (int i = 0; i < q.inequalities(); ++i) {
        if (q.lower[i] > -kQpInfinity) q.lower[i] += shift[i];
        if (q.upper[i] < kQpInfinity) q.upper[i] += shift[i];
      }
      const QpOutcome a = warm->solve(q);
      const QpOutcome& b = cold->solve(q);
      REQUIRE(a.status == b.status);
      CHECK(a.status == (relaxed ? 1 : 0));
      matched += inf_norm(a.x - b.x) < 1e-9 * (1.0 + inf_norm(b.x));
      warm_changes += a.iterations;
      cold_changes += b.iterations;
      ++samples;
    }
    CHECK(matched == samples);
    INFO("active-set changes: warm " << warm_changes << ", cold " << cold_changes);
    CHECK(warm_changes * 3 < cold_changes);
  }
  // reset_warm_start: the next solve starts cold.
  QpProblem p = random_qp(rng, 10, 1, 4, 10, 10);
  const int cold_iterations = cold->solve(p).iterations;
  warm->solve(p);
  CHECK(warm->solve(p).iterations == 0);
  warm->reset_warm_start();
  CHECK(warm->solve(p).iterations == cold_iterations);
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

namespace {

/// Agreement of the two back ends over every sample of a scene, solved in order as a run
/// solves them (warm starts, relaxed runs): worst figures and counts.
struct RunComparison {
  int samples = 0, relaxed = 0;
  int status_mismatches = 0;
  int name_mismatches = 0;
  int kkt_failures = 0;
  int objective_failures = 0;  ///< active-set penalised objective above Ipopt's
  double max_dx_optimal = 0.0;
  double max_dx_relaxed = 0.0;
  double max_violation_diff = 0.0;
  double max_dx_extended = 0.0;  ///< against the extended-precision solve
  std::string first_problem;
};

RunComparison compare_backends(const Scene& scene) {
  const PreparedScene prep = prepare_scene(scene);
  const KinematicsResult kin = sample_kinematics(prep.model, prep.plan, prep.grid);
  RobotData data(prep.model);
  const double rho = scene.allocation.slack_penalty;
  IpoptOptions io = ipopt_options_from(scene.allocation);
  io.tolerance = 1e-12;  // the reference: strict solves to the last digits
  auto ipopt = make_ipopt_backend(io);
  auto active = make_active_set_backend(active_set_options_from(scene.allocation));
  QpProblem qp;
  std::array<int, kLegs> offset{};
  SampleContacts contacts;
  RunComparison r;
  auto note = [&](int i, const std::string& what) {
    if (r.first_problem.empty())
      r.first_problem =
          "sample " + std::to_string(i) + " t = " + std::to_string(kin.time_s[i]) + ": " + what;
  };
  for (int i = 0; i < kin.samples(); ++i) {
    const ContactSplit& split = contact_split(
        prep.model, data, base_state_at(kin, i), kin.joint_position.row(i).transpose(),
        kin.joint_velocity.row(i).transpose(), kin.joint_acceleration.row(i).transpose());
    sample_contacts(kin, i, prep.plan.terrain, prep.touchdowns, contacts);
    build_allocation_problem(scene.allocation, scene.contact, split, contacts.phase,
                             contacts.impact_force_N, contacts.W_R_contact, qp, offset, nullptr);
    const QpOutcome ref = ipopt->solve(qp);
    const QpOutcome& out = active->solve(qp);
    ++r.samples;
    const double dx = inf_norm(out.x - ref.x);
    if (out.status != ref.status) {
      ++r.status_mismatches;
      note(i, "status " + std::to_string(out.status) + " vs Ipopt " + std::to_string(ref.status));
    }
    std::string why;
    if (out.status == 0) {
      r.max_dx_optimal = std::max(r.max_dx_optimal, dx);
      if (!check_kkt(qp, out, 1e-9, &why)) ++r.kkt_failures, note(i, why);
    } else {
      ++r.relaxed;
      r.max_dx_relaxed = std::max(r.max_dx_relaxed, dx);
      if (named_rows(out.message) != named_rows(ref.message)) {
        ++r.name_mismatches;
        note(i, out.message + " vs Ipopt " + ref.message);
      }
      r.max_violation_diff = std::max(
          r.max_violation_diff, inf_norm(row_violations(qp, out.x) - row_violations(qp, ref.x)));
    }
    if (!check_penalised_kkt(qp, out, rho, 1e-9, &why)) ++r.kkt_failures, note(i, why);
    // The active-set answer is the exact penalised optimum: Ipopt's penalised objective is
    // not below it (to rounding of F, which holds ρ w times the violations).
    const double gap = penalised_objective(qp, ref.x, rho) - penalised_objective(qp, out.x, rho);
    const double scale = 1.0 + std::abs(penalised_objective(qp, ref.x, rho));
    if (gap < -1e-10 * scale) ++r.objective_failures, note(i, "penalised objective above Ipopt's");
    r.max_dx_extended =
        std::max(r.max_dx_extended, inf_norm(extended_precision_x(qp, out, rho) - out.x));
  }
  return r;
}

void check_comparison(const RunComparison& r) {
  INFO(r.samples << " samples, " << r.relaxed << " relaxed; max |Δx| optimal " << r.max_dx_optimal
                 << " N, relaxed " << r.max_dx_relaxed << " N; violations " << r.max_violation_diff
                 << "; extended precision " << r.max_dx_extended << " N. " << r.first_problem);
  CHECK(r.status_mismatches == 0);
  CHECK(r.name_mismatches == 0);
  CHECK(r.kkt_failures == 0);
  CHECK(r.objective_failures == 0);
  CHECK(r.max_dx_optimal < 1e-6);
  CHECK(r.max_dx_relaxed < 1e-6);
  CHECK(r.max_violation_diff < 1e-6);
  CHECK(r.max_dx_extended < 1e-6);
}

}  // namespace

TEST_CASE("active-set back end: every sample of the paper run agrees with Ipopt",
          "[allocation][active_set][paper]") {
  // Every sample: the same status, the same rows giving way by the same amounts, forces
  // within 1e-6 N. Relaxed samples also: the active-set forces are the exact penalised
  // optimum (KKT certificate, extended-precision re-solve).
  SECTION("the paper's grid: 1e-6 N on every sample") {
    const RunComparison r = compare_backends(load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml"));
    CHECK(r.samples > 500);
    CHECK(r.relaxed > 100);  // touchdown transients
    check_comparison(r);
    WARN("paper run: " << r.samples << " samples (" << r.relaxed << " relaxed): max |Δx| vs Ipopt "
                       << r.max_dx_optimal << " N optimal, " << r.max_dx_relaxed
                       << " N relaxed; vs extended precision " << r.max_dx_extended << " N");
  }
  SECTION("the denser grid of 40 samples per transient and 1 ms event steps: 1e-6 N too") {
    // 648 relaxed samples. Degenerate penalised optima (rows that hold with zero
    // multipliers next to ρ w up to 1e9) are where Ipopt's own inexactness would show;
    // the KKT certificate and the extended-precision re-solve check our side of them.
    const RunComparison r = compare_backends(
        load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml", {{"output.impact_samples", "40"}, {"output.event_step", "1e-3"}}));
    CHECK(r.samples > 1000);
    CHECK(r.relaxed > 500);
    check_comparison(r);
    WARN("paper run, 40 samples per transient: " << r.samples << " samples (" << r.relaxed
                                                 << " relaxed): max |Δx| vs Ipopt " << r.max_dx_optimal
                                                 << " N optimal, " << r.max_dx_relaxed << " N relaxed");
  }
}

TEST_CASE("active-set back end: every sample of the smoke sweep agrees with Ipopt",
          "[allocation][active_set][sweep]") {
  const SweepSpec spec = load_sweep(HEXDYN_SOURCE_DIR "/configs/sweeps/smoke.yaml");
  REQUIRE(spec.scenario_count() == 8);
  for (std::size_t k = 0; k < spec.scenario_count(); ++k) {
    const ScenarioInput in = scenario_input(spec, k);
    CAPTURE(in.id);
    const RunComparison r = compare_backends(load_scene_from_string(in.yaml, in.id));
    CHECK(r.samples > 30);
    check_comparison(r);
  }
}
