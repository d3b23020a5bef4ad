#pragma once
/// \file allocation/small_dense.hpp
/// The dense linear algebra under the dual active-set QP (allocation/goldfarb_idnani.hpp):
/// Cholesky factor, triangular solves and Givens rotations on matrices of fixed capacity
/// kSmallDenseMax × kSmallDenseMax whose leading n × n (or q × q) block is in use.
///
/// Written out rather than taken from Eigen's decompositions because the QP updates its
/// factors in place, one row at a time (Givens updates of J and R as rows enter and leave
/// the active set), reuses them across solves, and must allocate nothing: Eigen's
/// LLT/HouseholderQR recompute from scratch and size themselves dynamically. Every routine
/// reads and writes only the leading block and is exact in its operation order, so a
/// solve is reproducible bit for bit.
#include <Eigen/Core>
#include <cmath>

#include "hexdyn/core/sizes.hpp"

namespace hexdyn {

/// Capacity of the small dense matrices: the allocation's largest number of variables
/// (kMaxLegs support legs of three force components). A problem of n variables uses the
/// leading n × n block only, so its arithmetic does not depend on the capacity.
inline constexpr int kSmallDenseMax = kMaxLegForces;

using SmallMatrix = Eigen::Matrix<double, kSmallDenseMax, kSmallDenseMax>;
using SmallVector = Eigen::Matrix<double, kSmallDenseMax, 1>;

/// Givens rotation (c, s) with c a + s b = ρ and −s a + c b = 0.
inline void givens(double a, double b, double& c, double& s, double& rho) {
  if (b == 0.0) {
    c = 1.0, s = 0.0, rho = a;
    return;
  }
  rho = std::sqrt(a * a + b * b);
  c = a / rho;
  s = b / rho;
}

/// Columns (i, j) of the leading n rows of M ← (c·col_i + s·col_j, −s·col_i + c·col_j).
inline void rotate_columns(SmallMatrix& M, int n, int i, int j, double c, double s) {
  for (int r = 0; r < n; ++r) {
    const double a = M(r, i), b = M(r, j);
    M(r, i) = c * a + s * b;
    M(r, j) = -s * a + c * b;
  }
}

/// H = L Lᵀ on the leading n × n block (lower triangle of H read), with linv[i] = 1 / L_ii.
/// False when a pivot is not above `min_pivot` (L is then partly written).
inline bool cholesky(const SmallMatrix& H, int n, double min_pivot, SmallMatrix& L, double* linv) {
  for (int j = 0; j < n; ++j) {
    double s = H(j, j);
    for (int k = 0; k < j; ++k) s -= L(j, k) * L(j, k);
    if (!(s > min_pivot)) return false;
    L(j, j) = std::sqrt(s);
    linv[j] = 1.0 / L(j, j);
    for (int i = j + 1; i < n; ++i) {
      double t = H(i, j);
      for (int k = 0; k < j; ++k) t -= L(i, k) * L(j, k);
      L(i, j) = t * linv[j];
    }
  }
  return true;
}

/// v ← L⁻¹ v (n entries), L lower triangular with linv[i] = 1 / L_ii.
inline void lower_solve(const SmallMatrix& L, const double* linv, int n, double* v) {
  for (int i = 0; i < n; ++i) {
    double s = v[i];
    for (int k = 0; k < i; ++k) s -= L(i, k) * v[k];
    v[i] = s * linv[i];
  }
}

/// v ← L⁻ᵀ v (n entries).
inline void lower_transpose_solve(const SmallMatrix& L, const double* linv, int n, double* v) {
  for (int i = n - 1; i >= 0; --i) {
    double s = v[i];
    for (int k = i + 1; k < n; ++k) s -= L(k, i) * v[k];
    v[i] = s * linv[i];
  }
}

/// J = L⁻ᵀ on the leading n × n block (upper triangular; row c of J is (L⁻¹ e_c)ᵀ).
inline void inverse_transpose_of_lower(const SmallMatrix& L, const double* linv, int n,
                                       SmallMatrix& J) {
  J.topLeftCorner(n, n).setZero();
  for (int c = 0; c < n; ++c) {
    J(c, c) = linv[c];
    for (int i = c + 1; i < n; ++i) {
      double s = 0.0;
      for (int k = c; k < i; ++k) s += L(i, k) * J(c, k);
      J(c, i) = -s * linv[i];
    }
  }
}

/// out = R⁻¹ in (q entries), R upper triangular; rinv (q entries) receives 1 / R_ii.
inline void upper_solve(const SmallMatrix& R, int q, const double* in, double* out, double* rinv) {
  for (int i = 0; i < q; ++i) rinv[i] = 1.0 / R(i, i);
  for (int i = q - 1; i >= 0; --i) {
    double s = in[i];
    for (int j = i + 1; j < q; ++j) s -= R(i, j) * out[j];
    out[i] = s * rinv[i];
  }
}

/// out = R⁻ᵀ in (q entries); rinv (q entries) receives 1 / R_ii.
inline void upper_transpose_solve(const SmallMatrix& R, int q, const double* in, double* out,
                                  double* rinv) {
  for (int i = 0; i < q; ++i) rinv[i] = 1.0 / R(i, i);
  for (int i = 0; i < q; ++i) {
    double s = in[i];
    for (int j = 0; j < i; ++j) s -= R(j, i) * out[j];
    out[i] = s * rinv[i];
  }
}

}  // namespace hexdyn
