// Tests of the allocation solver interface (src/hexdyn/allocation/qp.hpp), run on every back
// end: Ipopt, the dual active-set back end and the exact-cone back end (on problems without
// cones it is the active-set back end; with cones, Ipopt and the cone back end). Each
// answer is checked against a second computation: the closed-form KKT system of
// equality-only QPs, the KKT conditions (kkt_check.hpp) and random feasible points of
// inequality QPs, the closed-form projection onto a friction cone, and the inscribed
// pyramid of cone problems. Each back end is held to the accuracy it promises: Ipopt to
// its interior-point tolerance, the exact back ends to rounding.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/cone_backend.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/kkt_check.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/allocation/qp_test_problems.hpp"
#include "hexdyn/core/errors.hpp"

using namespace hexdyn;
using namespace hexdyn::test;

namespace {

using test::add_rows_around;
using test::kInf;
using test::random_matrix;
using test::random_vector;

/// Random strictly convex objective and full-rank equality rows.
QpProblem random_equality_qp(std::mt19937& rng, int n, int m_eq) {
  QpProblem p;
  p.resize(n, m_eq, 0);
  const Eigen::MatrixXd M = random_matrix(rng, n, n);
  p.H = M * M.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  p.g = random_vector(rng, n);
  p.constant = 1.5;
  p.A = random_matrix(rng, m_eq, n);
  p.b = random_vector(rng, m_eq);
  return p;
}

/// Adds inequality rows around a point x0 that satisfies A x0 = b: `boxes` box rows on
/// single variables and `general` dense rows; bounds keep x0 strictly inside, some rows
/// one-sided. The unconstrained minimiser is pushed outside so that rows become active.
void add_inequalities(std::mt19937& rng, QpProblem& p, const Eigen::VectorXd& x0, int boxes,
                      int general) {
  const int n = p.variables(), m_in = boxes + general;
  p.C = Eigen::MatrixXd::Zero(m_in, n);
  p.lower.resize(m_in);
  p.upper.resize(m_in);
  p.ineq_names.assign(static_cast<std::size_t>(m_in), std::string());
  add_rows_around(rng, p, x0, 0, boxes, general);
}

Eigen::VectorXd particular_solution(const QpProblem& p, std::mt19937& rng) {
  // x0 = least-squares solution plus a random null-space component.
  const Eigen::VectorXd ls = p.A.completeOrthogonalDecomposition().solve(p.b);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(p.A);
  const Eigen::MatrixXd Z = lu.kernel();
  return ls + Z * random_vector(rng, static_cast<int>(Z.cols()));
}

bool feasible(const QpProblem& p, const Eigen::VectorXd& x, double tol) {
  if (p.equalities() > 0 && (p.A * x - p.b).lpNorm<Eigen::Infinity>() > tol) return false;
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    if (c < p.lower[i] - tol || c > p.upper[i] + tol) return false;
  }
  return true;
}

/// Projection of (t1, t2, n) onto the cone √(t1² + t2²) ≤ μ n (closed form).
Eigen::Vector3d project_onto_cone(const Eigen::Vector3d& f, double mu) {
  const double t = std::hypot(f[0], f[1]), n = f[2];
  if (t <= mu * n) return f;
  if (mu * t <= -n) return Eigen::Vector3d::Zero();
  // Onto the generator of the cone in the plane of f and the cone axis.
  const Eigen::Vector3d d =
      Eigen::Vector3d(mu * f[0] / t, mu * f[1] / t, 1.0) / std::sqrt(1.0 + mu * mu);
  return f.dot(d) * d;
}

/// A back end under test and the accuracy it promises on x and λ (relative): Ipopt to its
/// interior-point tolerance (on penalised problems, whose multipliers ρ w reach 1e9, to
/// about 1e-6), the exact back ends to rounding.
struct BackendCase {
  const char* name;
  double tol;          ///< problems as posed
  double relaxed_tol;  ///< penalised problems
  bool cones;          ///< takes problems with friction cones
};
constexpr BackendCase kBackends[] = {
    {"ipopt", 1e-7, 1e-5, true}, {"active-set", 1e-10, 1e-12, false}, {"cone", 1e-10, 1e-12, true}};

std::unique_ptr<AllocationBackend> make_backend(const BackendCase& c, bool warm_start = true) {
  const std::string name = c.name;
  if (name == "ipopt") {
    IpoptOptions o;
    o.warm_start = warm_start;
    return make_ipopt_backend(o);
  }
  ActiveSetOptions a;
  a.warm_start = warm_start;
  if (name == "active-set") return make_active_set_backend(a);
  ConeOptions o;
  o.qp = a;
  o.warm_start = warm_start;
  return make_cone_backend(o);
}

/// kBackends[index], for one run of a test case per back end (index from Catch2's GENERATE).
const BackendCase& backend_case(int index) { return kBackends[static_cast<std::size_t>(index)]; }

}  // namespace

TEST_CASE("back ends: equality-constrained QPs match the closed-form KKT solve", "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  std::mt19937 rng(20240601);
  auto backend = make_backend(bc);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 6 + trial % 7;     // 6..12
    const int m_eq = 3 + trial % 4;  // 3..6
    CAPTURE(trial, n, m_eq);
    const QpProblem p = random_equality_qp(rng, n, m_eq);
    // [H  −Aᵀ; A  0] [x; λ] = [−g; b]  (stationarity H x + g − Aᵀ λ = 0).
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m_eq, n + m_eq);
    K.topLeftCorner(n, n) = p.H;
    K.topRightCorner(n, m_eq) = -p.A.transpose();
    K.bottomLeftCorner(m_eq, n) = p.A;
    Eigen::VectorXd rhs(n + m_eq);
    rhs << -p.g, p.b;
    const Eigen::VectorXd sol = K.fullPivLu().solve(rhs);
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK((out.x - sol.head(n)).lpNorm<Eigen::Infinity>() <
          bc.tol * (1.0 + sol.head(n).lpNorm<Eigen::Infinity>()));
    CHECK((out.lambda_eq - sol.tail(m_eq)).lpNorm<Eigen::Infinity>() <
          10.0 * bc.tol * (1.0 + sol.tail(m_eq).lpNorm<Eigen::Infinity>()));
    CHECK(out.objective == Approx(p.objective(sol.head(n))).epsilon(1e-9));
    CHECK(out.message.empty());
    CHECK(out.lambda_cone.size() == 0);
    CHECK(check_kkt(p, out, bc.tol));
  }
}

TEST_CASE("back ends: inequality QPs satisfy KKT and beat random feasible points", "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  std::mt19937 rng(7);
  auto backend = make_backend(bc);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const int n = 8 + trial % 5;
    const int m_eq = 3 + trial % 4;
    CAPTURE(trial, n, m_eq);
    QpProblem p = random_equality_qp(rng, n, m_eq);
    const Eigen::VectorXd x0 = particular_solution(p, rng);
    add_inequalities(rng, p, x0, n, 10 + trial);
    // Push the unconstrained optimum away from x0 so that some rows bind.
    p.g = -p.H * (x0 + 3.0 * random_vector(rng, n));
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(check_kkt(p, out, 1e-6));
    CHECK(feasible(p, out.x, 1e-7));
    CHECK(out.lambda_ineq.cwiseAbs().maxCoeff() > 1e-6);  // some rows are active
    // Random feasible points x0 + Z y (Z: null space of A), scaled down until feasible.
    const Eigen::MatrixXd Z = Eigen::FullPivLU<Eigen::MatrixXd>(p.A).kernel();
    int tried = 0;
    for (int k = 0; k < 400; ++k) {
      Eigen::VectorXd y = Eigen::VectorXd::NullaryExpr(Z.cols(), [&] { return U(rng); });
      for (double s = 1.0; s > 1e-3; s *= 0.5) {
        const Eigen::VectorXd x = x0 + s * Z * y;
        if (!feasible(p, x, 1e-9)) continue;
        ++tried;
        CHECK(out.objective <= p.objective(x) + 1e-8 * (1.0 + std::abs(out.objective)));
        break;
      }
    }
    CHECK(tried > 50);
  }
}

TEST_CASE("back ends: an equality written as an l = u row gives the same solution",
          "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  std::mt19937 rng(11);
  auto backend = make_backend(bc);
  const QpProblem eq = random_equality_qp(rng, 9, 6);
  QpProblem rows;
  rows.resize(9, 0, 6);
  rows.H = eq.H;
  rows.g = eq.g;
  rows.constant = eq.constant;
  rows.C = eq.A;
  rows.lower = eq.b;
  rows.upper = eq.b;
  const Eigen::VectorXd x_eq = backend->solve(eq).x;
  const Eigen::VectorXd l_eq = backend->solve(eq).lambda_eq;
  const QpOutcome& out = backend->solve(rows);
  REQUIRE(out.status == SolverStatus::kOptimal);
  CHECK((out.x - x_eq).lpNorm<Eigen::Infinity>() < 1e-7 * (1.0 + x_eq.lpNorm<Eigen::Infinity>()));
  CHECK((out.lambda_ineq - l_eq).lpNorm<Eigen::Infinity>() <
        1e-6 * (1.0 + l_eq.lpNorm<Eigen::Infinity>()));
  CHECK(check_kkt(rows, out, 1e-7));
}

TEST_CASE("back ends: multiplier signs follow the documented convention", "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  QpProblem p = test::sign_convention_problem();  // x = (1, −2, 0), λ = (1, −2)
  auto backend = make_backend(bc);
  const QpOutcome& out = backend->solve(p);
  REQUIRE(out.status == SolverStatus::kOptimal);
  CHECK(out.x[0] == Approx(1.0).margin(bc.tol));
  CHECK(out.x[1] == Approx(-2.0).margin(bc.tol));
  CHECK(out.x[2] == Approx(0.0).margin(bc.tol));
  CHECK(out.lambda_ineq[0] == Approx(1.0).margin(bc.tol));
  CHECK(out.lambda_ineq[1] == Approx(-2.0).margin(bc.tol));
  CHECK(out.objective == Approx(2.5).epsilon(1e-9));
  CHECK(check_kkt(p, out, bc.tol));
  // A wrong multiplier sign is caught.
  QpOutcome bad = out;
  bad.lambda_ineq[0] = -1.0;
  const KktVerdict wrong_sign = check_kkt(p, bad, 1e-6);
  CHECK_FALSE(wrong_sign);
  CHECK_FALSE(wrong_sign.why.empty());
  // A point off the optimum is caught.
  bad = out;
  bad.x[2] = 0.1;
  CHECK_FALSE(check_kkt(p, bad, 1e-6));
}

TEST_CASE("back ends: an infeasible problem is relaxed and names the row that gave way",
          "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  auto backend = make_backend(bc);
  SECTION("a torque row against an equality") {
    // x0 + x1 = 10 and x1 = 8 (equalities), torque row x0 ≤ 1: violated by 1.
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
    CHECK(out.status == SolverStatus::kRelaxed);
    CHECK(out.x.allFinite());
    CHECK(out.message.find("torque L1_femur") != std::string::npos);
    CHECK(out.message.find("friction L3 +x") == std::string::npos);
    CHECK(out.message == "relaxed: torque L1_femur by 1");
    CHECK(out.x[0] == Approx(2.0).margin(bc.relaxed_tol));
    CHECK(out.max_violation == Approx(1.0).margin(bc.relaxed_tol));
    CHECK(out.lambda_ineq[0] == Approx(-1e6).epsilon(1e-6));  // the penalty's slope
    CHECK((p.A * out.x - p.b).norm() < 1e-7);                 // equalities stay hard
    CHECK_FALSE(check_kkt(p, out, 1e-6));                     // not primal feasible
  }
  SECTION("contradictory bounds on one row, largest violation first") {
    QpProblem p;
    p.resize(2, 0, 2);
    p.H.setIdentity();
    p.C << 1, 0, 0, 1;
    p.lower << 5.0, 3.0;
    p.upper << 4.0, 2.9;
    p.ineq_names = {"normal L2", "torque L4_tibia"};
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == SolverStatus::kRelaxed);
    CHECK(out.x.allFinite());
    // Each row sits at the end of [upper, lower] nearer the unconstrained optimum 0; the
    // larger violation is named first.
    CHECK((out.x - Eigen::Vector2d(4.0, 2.9)).lpNorm<Eigen::Infinity>() < bc.relaxed_tol);
    CHECK(out.message == "relaxed: normal L2 by 1, torque L4_tibia by 0.1");
  }
  SECTION("unsatisfiable equalities fail with a finite fallback") {
    QpProblem p;
    p.resize(2, 2, 1);
    p.H.setIdentity();
    p.A << 1, 0, 1, 0;
    p.b << 1, 2;
    p.C << 0, 1;
    p.lower << 0.0;
    p.upper << 1.0;
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == SolverStatus::kFailed);
    CHECK(out.x.allFinite());
    CHECK(out.x[0] == Approx(1.5).margin(1e-9));  // least squares of x0 = 1, x0 = 2
    CHECK_FALSE(out.message.empty());
  }
  SECTION("non-finite data fail with a finite fallback, never NaN; the next solve is normal") {
    std::mt19937 rng(3);
    QpProblem p = random_equality_qp(rng, 6, 3);
    p.g[2] = std::nan("");
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == SolverStatus::kFailed);
    CHECK(out.x.allFinite());
    CHECK(std::isfinite(out.objective));
    CHECK(out.message.find("non-finite") != std::string::npos);
    p.g[2] = 0.5;
    CHECK(backend->solve(p).status == SolverStatus::kOptimal);
  }
}

TEST_CASE("back ends: a feasible problem after a relaxed one is solved to optimality",
          "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  // Same sizes: the second solve goes to the penalised form first; with no slack needed
  // its answer must be the strict optimum.
  std::mt19937 rng(21);
  QpProblem feasible = random_equality_qp(rng, 9, 6);
  const Eigen::VectorXd x0 = particular_solution(feasible, rng);
  add_inequalities(rng, feasible, x0, 9, 21);
  feasible.g = -feasible.H * (x0 + 2.0 * random_vector(rng, 9));
  QpProblem infeasible = feasible;
  infeasible.lower[3] = infeasible.upper[3] + 1.0;  // crossed bounds on one row

  auto fresh = make_backend(bc);
  const QpOutcome reference = fresh->solve(feasible);
  REQUIRE(reference.status == SolverStatus::kOptimal);

  auto backend = make_backend(bc);
  REQUIRE(backend->solve(infeasible).status == SolverStatus::kRelaxed);
  const QpOutcome after = backend->solve(feasible);
  CHECK(after.status == SolverStatus::kOptimal);
  CHECK(after.message.empty());
  CHECK((after.x - reference.x).lpNorm<Eigen::Infinity>() <
        10.0 * bc.tol * (1.0 + reference.x.lpNorm<Eigen::Infinity>()));
  CHECK(check_kkt(feasible, after, 10.0 * bc.tol));
  // And the one after that is solved as posed again.
  const QpOutcome again = backend->solve(feasible);
  CHECK(again.status == SolverStatus::kOptimal);
  CHECK((again.x - reference.x).lpNorm<Eigen::Infinity>() <
        bc.tol * (1.0 + reference.x.lpNorm<Eigen::Infinity>()));
}

TEST_CASE("back ends: penalty weights choose the row that gives way", "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  // x0 + x1 = 10 written as an l = u row, against x0 ≤ 2 and x1 ≤ 3: 5 units must give.
  QpProblem p;
  p.resize(2, 0, 3);
  p.H.setIdentity();
  p.C << 1, 1, 1, 0, 0, 1;
  p.lower << 10.0, -kInf, -kInf;
  p.upper << 10.0, 2.0, 3.0;
  p.ineq_names = {"trunk force z", "torque L1_femur", "torque L2_femur"};
  auto backend = make_backend(bc);
  SECTION("a heavy trunk row holds and the torques give way") {
    p.ineq_penalty << 1e3, 1.0, 1.0;
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kRelaxed);
    CHECK(out.x.sum() == Approx(10.0).margin(1e-6));
    // Both torque rows give way; with the penalty the same for any split of the 5 units,
    // ½|x|² on x0 + x1 = 10 decides: x = (5, 5).
    CHECK(out.x[0] == Approx(5.0).margin(10.0 * bc.relaxed_tol));
    CHECK(out.x[1] == Approx(5.0).margin(10.0 * bc.relaxed_tol));
    CHECK(out.message == "relaxed: torque L1_femur by 3, torque L2_femur by 2");
    CHECK(out.max_violation < 5.0 + 1e-6);
  }
  SECTION("heavy torque rows hold and the trunk row gives way") {
    p.ineq_penalty << 1.0, 1e3, 1e3;
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kRelaxed);
    CHECK(out.x[0] == Approx(2.0).margin(bc.relaxed_tol));
    CHECK(out.x[1] == Approx(3.0).margin(bc.relaxed_tol));
    CHECK(out.message == "relaxed: trunk force z by 5");
    CHECK(out.lambda_ineq[0] == Approx(1e6).epsilon(1e-6));
  }
  SECTION("non-positive weights are rejected") {
    p.ineq_penalty << 1.0, 0.0, 1.0;
    CHECK_THROWS_AS(backend->solve(p), SolverError);
  }
}

TEST_CASE("back ends: inconsistent sizes throw SolverError", "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1, 2));
  CAPTURE(bc.name);
  auto backend = make_backend(bc);
  QpProblem p;
  p.resize(3, 1, 1);
  p.A.resize(1, 2);
  CHECK_THROWS_AS(backend->solve(p), SolverError);
  p.resize(3, 1, 1);
  p.cones.push_back({0, 1, 3, 0.3, "cone"});
  CHECK_THROWS_AS(backend->solve(p), SolverError);
  p.resize(3, 1, 1);
  p.ineq_names = {"a", "b"};
  CHECK_THROWS_AS(backend->solve(p), SolverError);
}

TEST_CASE("back ends: a warm start does not cost iterations on a perturbed problem",
          "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 1));  // the cone back end adds no cones here
  CAPTURE(bc.name);
  std::mt19937 rng(99);
  QpProblem p = random_equality_qp(rng, 9, 6);
  const Eigen::VectorXd x0 = particular_solution(p, rng);
  add_inequalities(rng, p, x0, 9, 21);
  p.g = -p.H * (x0 + 2.0 * random_vector(rng, 9));
  QpProblem q = p;
  q.g += 1e-3 * random_vector(rng, 9);
  q.b += 1e-3 * random_vector(rng, 6);

  auto backend = make_backend(bc);
  const QpOutcome cold = backend->solve(q);
  REQUIRE(cold.status == SolverStatus::kOptimal);
  backend->reset_warm_start();
  REQUIRE(backend->solve(p).status == SolverStatus::kOptimal);
  const QpOutcome warm = backend->solve(q);
  REQUIRE(warm.status == SolverStatus::kOptimal);
  CHECK(warm.iterations <= cold.iterations);
  CHECK((warm.x - cold.x).lpNorm<Eigen::Infinity>() <
        10.0 * bc.tol * (1.0 + cold.x.lpNorm<Eigen::Infinity>()));
  CHECK(check_kkt(q, warm, 10.0 * bc.tol));
  // Without warm starts the iterations are those of the cold solve.
  auto cold_backend = make_backend(bc, false);
  cold_backend->solve(p);
  CHECK(cold_backend->solve(q).iterations == cold.iterations);
}

TEST_CASE("back ends: the exact friction cone", "[allocation]") {
  const BackendCase& bc = backend_case(GENERATE(0, 2));  // the back ends that take cones
  CAPTURE(bc.name);
  REQUIRE(bc.cones);
  auto backend = make_backend(bc);
  const double mu = 0.3;
  SECTION("projection onto one cone matches the closed form") {
    const Eigen::Vector3d targets[] = {
        {5.0, -2.0, 4.0}, {0.5, 0.2, 10.0}, {3.0, 4.0, -1.0}, {1.0, 1.0, -20.0}, {0.0, 2.0, 1.0}};
    for (const Eigen::Vector3d& f_hat : targets) {
      CAPTURE(f_hat.transpose());
      // min ½|f − f̂|² = ½ fᵀ f − f̂ᵀ f + ½|f̂|².
      QpProblem p;
      p.resize(3, 0, 0);
      p.H.setIdentity();
      p.g = -f_hat;
      p.constant = 0.5 * f_hat.squaredNorm();
      p.cones.push_back({0, 1, 2, mu, "cone L1"});
      const QpOutcome& out = backend->solve(p);
      REQUIRE(out.status == SolverStatus::kOptimal);
      const Eigen::Vector3d want = project_onto_cone(f_hat, mu);
      CHECK((out.x - want).norm() < 1e-6 * (1.0 + want.norm()));
      CHECK(std::hypot(out.x[0], out.x[1]) <= mu * out.x[2] + 1e-7);
    }
  }
  SECTION("two feet sharing a load: cone no worse than the inscribed pyramid") {
    // Variables (t1, t2, n) per foot; Σ n = 20 N, Σ t1 = 4 N, Σ t2 = −1 N; the objective
    // prefers large tangential forces on foot 1.
    QpProblem cone;
    cone.resize(6, 3, 0);
    cone.H = Eigen::MatrixXd::Identity(6, 6);
    cone.H(0, 0) = 0.2;
    cone.g << -3.0, 1.0, -1.0, 0.5, 0.0, -2.0;
    cone.A << 1, 0, 0, 1, 0, 0,  //
        0, 1, 0, 0, 1, 0,        //
        0, 0, 1, 0, 0, 1;
    cone.b << 4.0, -1.0, 20.0;
    cone.eq_names = {"trunk Fx", "trunk Fy", "trunk Fz"};
    cone.cones.push_back({0, 1, 2, mu, "cone L1"});
    cone.cones.push_back({3, 4, 5, mu, "cone L2"});
    const QpOutcome out_cone = backend->solve(cone);
    REQUIRE(out_cone.status == SolverStatus::kOptimal);
    for (int foot = 0; foot < 2; ++foot)
      CHECK(std::hypot(out_cone.x[3 * foot], out_cone.x[3 * foot + 1]) <=
            mu * out_cone.x[3 * foot + 2] + 1e-7);
    CHECK((cone.A * out_cone.x - cone.b).norm() < 1e-7);

    // The inscribed pyramid: |t_k| ≤ (μ/√2) n, four rows per foot.
    QpProblem pyr = cone;
    pyr.cones.clear();
    pyr.C = Eigen::MatrixXd::Zero(8, 6);
    pyr.lower = Eigen::VectorXd::Constant(8, -kInf);
    pyr.upper = Eigen::VectorXd::Zero(8);
    pyr.ineq_names.assign(8, std::string());
    const double a = mu / std::sqrt(2.0);
    int row = 0;
    for (int foot = 0; foot < 2; ++foot)
      for (int axis = 0; axis < 2; ++axis)
        for (double sign : {1.0, -1.0}) {
          pyr.C(row, 3 * foot + axis) = sign;
          pyr.C(row, 3 * foot + 2) = -a;
          ++row;
        }
    const QpOutcome& out_pyr = backend->solve(pyr);
    REQUIRE(out_pyr.status == SolverStatus::kOptimal);
    CHECK(check_kkt(pyr, out_pyr, 1e-6));
    CHECK(out_cone.objective <= out_pyr.objective + 1e-7);
    // The cone was binding somewhere, otherwise the comparison says nothing.
    CHECK(out_cone.objective < out_pyr.objective - 1e-3);
    CHECK(check_kkt(cone, out_cone, 1e-6));
  }
  SECTION("an infeasible cone is relaxed and named") {
    // Tangential force fixed at 5 N, normal force at most 10 N: the cone needs 5 ≤ 3.
    QpProblem p;
    p.resize(3, 1, 1);
    p.H.setIdentity();
    p.A << 1, 0, 0;
    p.b << 5.0;
    p.C << 0, 0, 1;
    p.lower << 0.0;
    p.upper << 10.0;
    p.ineq_names = {"normal L3"};
    p.cones.push_back({0, 1, 2, mu, "friction cone L3"});
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == SolverStatus::kRelaxed);
    CHECK(out.x.allFinite());
    CHECK(out.message.find("friction cone L3") != std::string::npos);
  }
}

TEST_CASE("describe_violations and the fallback point", "[allocation]") {
  QpProblem p;
  p.resize(2, 1, 2);
  p.A << 1, 1;
  p.b << 1;
  p.C << 1, 0, 0, 1;
  p.lower << 0.0, -kInf;
  p.upper << kInf, 0.5;
  p.ineq_names = {"normal L1", "torque L2_coxa"};
  double worst = 0.0;
  CHECK(describe_violations(p, Eigen::Vector2d(0.5, 0.5), 1e-9, &worst).empty());
  CHECK(worst == 0.0);
  // x = (−0.25, 1.25): eq residual 0, normal L1 by 0.25, torque L2_coxa by 0.75.
  CHECK(describe_violations(p, Eigen::Vector2d(-0.25, 1.25), 1e-9, &worst) ==
        "torque L2_coxa by 0.75, normal L1 by 0.25");
  CHECK(worst == Approx(0.75));
  CHECK(describe_violations(p, Eigen::Vector2d(0.0, 0.0), 1e-9) == "eq[0] by 1");
  const Eigen::VectorXd x = qp_fallback_point(p);
  CHECK(x[0] == Approx(0.5));
  CHECK(x[1] == Approx(0.5));
}
