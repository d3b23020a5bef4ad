#pragma once
/// \file qp_test_problems.hpp
/// Random QP ingredients shared by the allocation back-end tests
/// (test_allocation_qp.cpp, test_allocation_active_set.cpp).
#include <Eigen/Dense>
#include <limits>
#include <random>
#include <string>

#include "hexdyn/allocation/qp.hpp"

namespace hexdyn::test {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// rows × cols standard-normal entries.
inline Eigen::MatrixXd random_matrix(std::mt19937& rng, int rows, int cols) {
  std::normal_distribution<double> N(0.0, 1.0);
  return Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return N(rng); });
}

inline Eigen::VectorXd random_vector(std::mt19937& rng, int n) { return random_matrix(rng, n, 1); }

/// Fills inequality rows first .. first + boxes + general − 1 of p (already sized, C zero
/// there) around a point x0: `boxes` box rows on single variables, then `general` dense
/// rows; bounds keep x0 strictly inside by 0.05–0.6, and rows i with i % 4 == 1 (== 2) have
/// no lower (upper) bound.
inline void add_rows_around(std::mt19937& rng, QpProblem& p, const Eigen::VectorXd& x0, int first,
                            int boxes, int general) {
  std::uniform_real_distribution<double> U(0.05, 0.6);
  const int n = p.variables();
  for (int k = 0; k < boxes + general; ++k) {
    const int i = first + k;
    if (k < boxes) {
      p.C(i, k % n) = 1.0;
      p.ineq_names[i] = "box x" + std::to_string(k % n);
    } else {
      p.C.row(i) = random_matrix(rng, 1, n);
      p.ineq_names[i] = "row " + std::to_string(i);
    }
    const double c = p.C.row(i).dot(x0);
    p.lower[i] = (i % 4 == 1) ? -kInf : c - U(rng);
    p.upper[i] = (i % 4 == 2) ? kInf : c + U(rng);
  }
}

/// min ½|x|² s.t. x0 ≥ 1 (lower active) and x1 ≤ −2 (upper active), x2 free: x = (1, −2, 0),
/// stationarity x − Cᵀλ = 0 gives λ = (1, −2), objective 2.5. Checks the sign convention of
/// the multipliers.
inline QpProblem sign_convention_problem() {
  QpProblem p;
  p.resize(3, 0, 2);
  p.H.setIdentity();
  p.C << 1, 0, 0, 0, 1, 0;
  p.lower << 1.0, -kInf;
  p.upper << kInf, -2.0;
  return p;
}

}  // namespace hexdyn::test
