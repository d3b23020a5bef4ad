#pragma once
/// \file active_set_checks.hpp
/// Second computations shared by the active-set tests (test_active_set.cpp,
/// test_active_set_sequences.cpp, test_goldfarb_idnani.cpp): random convex QPs, the
/// L1-penalised objective, an extended-precision solve on an answer's active rows. The KKT
/// certificate is the one checker of kkt_check.hpp (included here).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/kkt_check.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/allocation/qp_test_problems.hpp"

namespace hexdyn::test {

inline double inf_norm(const Eigen::VectorXd& v) {
  return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0;
}

/// Ipopt as the reference: tight tolerance, cold starts.
inline IpoptOptions reference_ipopt(double slack_penalty = 1e6) {
  IpoptOptions o;
  o.tolerance = 1e-11;
  o.slack_penalty = slack_penalty;
  o.warm_start = false;
  return o;
}

inline ActiveSetOptions active_set(double slack_penalty = 1e6, bool warm = true) {
  ActiveSetOptions o;
  o.slack_penalty = slack_penalty;
  o.warm_start = warm;
  return o;
}

/// Random strictly convex QP around a point x0 that satisfies every row: m_eq equality
/// rows A x = b, `lu` rows written as lower = upper, `boxes` box rows on single variables
/// and `general` dense rows (some one-sided); the unconstrained minimiser is pushed away
/// from x0 so that rows bind. *x0_out (if given) receives x0.
inline QpProblem random_qp(std::mt19937& rng, int n, int m_eq, int lu, int boxes, int general,
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
inline double penalised_objective(const QpProblem& p, const Eigen::VectorXd& x, double rho) {
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

/// x of the equality-constrained problem that an answer's rows define, solved again in
/// extended precision: rows at a bound with λ ≠ 0 held with equality, violated rows as the
/// fixed linear term −λ_i C_i with λ_i = ±ρ w_i (the penalty's slope), the rest left out.
inline Eigen::VectorXd extended_precision_x(const QpProblem& p, const QpOutcome& out, double rho) {
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
inline std::vector<std::string> named_rows(const std::string& message) {
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
inline Eigen::VectorXd row_violations(const QpProblem& p, const Eigen::VectorXd& x) {
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
inline void make_infeasible(QpProblem& p, int lu) {
  const int n = p.variables();
  for (int i = 0; i < lu; ++i) p.lower[i] = p.upper[i] = 50.0 + 10.0 * i;
  for (int i = lu; i < lu + n; ++i) p.lower[i] = -0.5, p.upper[i] = 0.5;
}

}  // namespace hexdyn::test
