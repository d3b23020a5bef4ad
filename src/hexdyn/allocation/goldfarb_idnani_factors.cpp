/// \file allocation/goldfarb_idnani_factors.cpp
/// The factorisations under the Goldfarb–Idnani solver (allocation/goldfarb_idnani.hpp): the
/// Cholesky factor of H, the working sets with their two factorisations of the active rows
/// (the direct one, M = L⁻¹N and the Cholesky factor of NᵀH⁻¹N, and the Goldfarb–Idnani
/// factors J and R with their Givens updates), and the equality-constrained solutions on the
/// active set. The iteration that drives them is in allocation/goldfarb_idnani.cpp.
#include <algorithm>
#include <cmath>
#include <utility>

#include "hexdyn/allocation/goldfarb_idnani.hpp"

namespace hexdyn {

// --- H = L Lᵀ ---

/// Factorises H (regularised if singular); false when H is indefinite.
bool DualActiveSetQp::factorize() {
  double max_diag = 0.0;
  for (int i = 0; i < n_; ++i) max_diag = std::max(max_diag, std::abs(H_(i, i)));
  delta_ = 0.0;
  // A pivot below 1e-9 of the largest diagonal entry: H is singular to working accuracy
  // (the dual iteration would lose about as many digits as cond(H) has).
  const double scale = max_diag > 0.0 ? max_diag : 1.0;
  if (!cholesky(H_, n_, 1e-9 * scale, L_, linv_.data())) {
    delta_ = 1e-9 * scale;
    for (int i = 0; i < n_; ++i) H_(i, i) += delta_;
    if (!cholesky(H_, n_, 0.0, L_, linv_.data())) return false;  // indefinite: not a convex QP
  }
  j0_valid_ = false;
  return true;
}

/// J₀ = L⁻ᵀ, computed once per problem when the dual iteration first needs it.
void DualActiveSetQp::ensure_j0() {
  if (j0_valid_) return;
  inverse_transpose_of_lower(L_, linv_.data(), n_, J0_);
  j0_valid_ = true;
}

// --- working sets ---

void DualActiveSetQp::clear_sets() {
  q_ = 0;
  for (int k = 0; k < m_; ++k) state_[k] = RowState::kInactive;
  geff_.head(n_) = g_.head(n_);
  moved_ = false;
}

void DualActiveSetQp::make_elastic(int k, int side) {
  state_[k] = RowState::kElastic;
  side_[k] = static_cast<std::int8_t>(side);
  geff_.head(n_) -= (cap_[k] * side) * a_.col(k).head(n_);
}

void DualActiveSetQp::release_elastic(int k) {
  state_[k] = RowState::kInactive;
  geff_.head(n_) += (cap_[k] * side_[k]) * a_.col(k).head(n_);
}

/// Appends row k to the active set in the direct factorisation (multiplier 0 until
/// solve_eqp); false when it depends on the active rows.
bool DualActiveSetQp::direct_add(int k, int side) {
  if (q_ >= n_) return false;
  double* m = M_.col(q_).data();
  for (int j = 0; j < n_; ++j) m[j] = side * a_(j, k);
  lower_solve(L_, linv_.data(), n_, m);
  double dn = 0.0;
  for (int j = 0; j < n_; ++j) dn += m[j] * m[j];
  // Row q of S_L: S_L y = (M_iᵀ m)_i, pivot² = mᵀm − yᵀy.
  double yy = 0.0;
  for (int i = 0; i < q_; ++i) {
    double s = M_.col(i).head(n_).dot(M_.col(q_).head(n_));
    for (int j = 0; j < i; ++j) s -= S_(i, j) * S_(q_, j);
    S_(q_, i) = s * sinv_[i];
    yy += S_(q_, i) * S_(q_, i);
  }
  const double pivot2 = dn - yy;
  if (dependent_row(pivot2, dn)) return false;
  S_(q_, q_) = std::sqrt(pivot2);
  sinv_[q_] = 1.0 / S_(q_, q_);
  act_[q_] = k;
  u_[q_] = 0.0;
  state_[k] = RowState::kActive;
  side_[k] = static_cast<std::int8_t>(side);
  ++q_;
  return true;
}

/// Builds J and R for the current active set (multipliers kept); false if a row turns
/// out dependent.
bool DualActiveSetQp::build_gi() {
  ensure_j0();
  J_.topLeftCorner(n_, n_) = J0_.topLeftCorner(n_, n_);
  const int q = q_;
  q_ = 0;
  for (int i = 0; i < q; ++i) {
    if (!gi_append(act_[i], side_[act_[i]])) {
      q_ = q;
      return false;
    }
    ++q_;
  }
  gi_valid_ = true;
  return true;
}

/// d_ = Jᵀ(side·a_k), the row's normal in the coordinates of J. Returns the squared norm of
/// its part outside the span of the active rows (entries q_ … n−1); `dependent` receives
/// dependent_row's verdict on it.
double DualActiveSetQp::project_row(int k, int side, bool& dependent) {
  for (int i = 0; i < n_; ++i) d_[i] = side * J_.col(i).head(n_).dot(a_.col(k).head(n_));
  double d2 = 0.0, dn = 0.0;
  for (int i = 0; i < n_; ++i) dn += d_[i] * d_[i];
  for (int i = q_; i < n_; ++i) d2 += d_[i] * d_[i];
  dependent = dependent_row(d2, dn);
  return d2;
}

/// Givens update of J and R for row k as active row number q_ (q_ not changed); false
/// when it depends on the active rows.
bool DualActiveSetQp::gi_append(int k, int side) {
  if (q_ >= n_) return false;
  bool dependent = false;
  project_row(k, side, dependent);
  if (dependent) return false;
  for (int i = n_ - 1; i > q_; --i) {
    if (d_[i] == 0.0) continue;
    double c, s, rho;
    givens(d_[i - 1], d_[i], c, s, rho);
    d_[i - 1] = rho;
    d_[i] = 0.0;
    rotate_columns(J_, n_, i - 1, i, c, s);
  }
  for (int i = 0; i <= q_; ++i) R_(i, q_) = d_[i];
  return true;
}

/// Whether row k's normal is independent of the active normals (the test of gi_append;
/// overwrites d_).
bool DualActiveSetQp::independent(int k) {
  bool dependent = false;
  project_row(k, side_[k], dependent);
  return q_ < n_ && !dependent;
}

/// Adds row k on `side` with multiplier u to the active set (Givens update of J and R).
/// False, with nothing changed, when its normal depends on the active normals.
bool DualActiveSetQp::add_row(int k, int side, double u) {
  if (!gi_append(k, side)) return false;
  act_[q_] = k;
  u_[q_] = u;
  ++q_;
  state_[k] = RowState::kActive;
  side_[k] = static_cast<std::int8_t>(side);
  return true;
}

/// Removes the active row at position `pos` (its row becomes inactive).
void DualActiveSetQp::drop_position(int pos) {
  state_[act_[pos]] = RowState::kInactive;
  for (int j = pos; j + 1 < q_; ++j) {
    for (int i = 0; i <= j + 1; ++i) R_(i, j) = R_(i, j + 1);
    act_[j] = act_[j + 1];
    u_[j] = u_[j + 1];
  }
  --q_;
  for (int j = pos; j < q_; ++j) {
    double c, s, rho;
    givens(R_(j, j), R_(j + 1, j), c, s, rho);
    R_(j, j) = rho;
    R_(j + 1, j) = 0.0;
    for (int col = j + 1; col < q_; ++col) {
      const double a = R_(j, col), b = R_(j + 1, col);
      R_(j, col) = c * a + s * b;
      R_(j + 1, col) = -s * a + c * b;
    }
    rotate_columns(J_, n_, j, j + 1, c, s);
  }
}

// --- equality-constrained solutions on the active set ---

/// Minimiser of ½xᵀHx + gradᵀx on the active rows side·a_kᵀx = rhs_k and its
/// multipliers u, with the Goldfarb–Idnani factors: x₀ = −J Jᵀ grad,
/// v = R⁻ᵀ(rhs − Nᵀx₀), x = x₀ + J₁ v, u = R⁻¹ v.
void DualActiveSetQp::eqp_gi(const SmallVector& grad, const double* rhs, SmallVector& x,
                             double* u) {
  for (int i = 0; i < n_; ++i) w_[i] = J_.col(i).head(n_).dot(grad.head(n_));
  x.head(n_).setZero();
  for (int i = 0; i < n_; ++i) x.head(n_) -= w_[i] * J_.col(i).head(n_);
  for (int i = 0; i < q_; ++i) {
    const int k = act_[i];
    t_[i] = rhs[i] - side_[k] * a_.col(k).head(n_).dot(x.head(n_));
  }
  upper_transpose_solve(R_, q_, t_.data(), v_.data(), rinv_.data());
  for (int i = 0; i < q_; ++i) x.head(n_) += v_[i] * J_.col(i).head(n_);
  upper_solve(R_, q_, v_.data(), u, rinv_.data());
}

/// The same with the direct factors: y = L⁻¹ grad, S u = rhs + Mᵀy,
/// x = L⁻ᵀ(M u − y).
void DualActiveSetQp::eqp_direct(const SmallVector& grad, const double* rhs, SmallVector& x,
                                 double* u) {
  double* y = w_.data();
  for (int j = 0; j < n_; ++j) y[j] = grad[j];
  lower_solve(L_, linv_.data(), n_, y);
  // S_L S_Lᵀ u = t.
  for (int i = 0; i < q_; ++i) {
    double s = rhs[i];
    for (int j = 0; j < n_; ++j) s += M_(j, i) * y[j];
    for (int j = 0; j < i; ++j) s -= S_(i, j) * v_[j];
    v_[i] = s * sinv_[i];
  }
  for (int i = q_ - 1; i >= 0; --i) {
    double s = v_[i];
    for (int j = i + 1; j < q_; ++j) s -= S_(j, i) * u[j];
    u[i] = s * sinv_[i];
  }
  for (int j = 0; j < n_; ++j) x[j] = -y[j];
  for (int i = 0; i < q_; ++i) x.head(n_) += u[i] * M_.col(i).head(n_);
  lower_transpose_solve(L_, linv_.data(), n_, x.data());
}

void DualActiveSetQp::eqp(const SmallVector& grad, const double* rhs, SmallVector& x, double* u) {
  if (gi_valid_)
    eqp_gi(grad, rhs, x, u);
  else
    eqp_direct(grad, rhs, x, u);
}

/// x and u on the working sets, with one step of iterative refinement (the gradient
/// holds ±ρ w terms of elastic rows, much larger than the answer).
void DualActiveSetQp::solve_eqp() {
  moved_ = false;
  for (int i = 0; i < q_; ++i) rhs_[i] = beta(act_[i], side_[act_[i]]);
  eqp(geff_, rhs_.data(), x_, u_.data());
  // Residuals: stationarity H x + g_eff − N u, rows rhs − Nᵀx.
  res_.head(n_) = H_.topLeftCorner(n_, n_) * x_.head(n_) + geff_.head(n_);
  for (int i = 0; i < q_; ++i) {
    const int k = act_[i];
    res_.head(n_) -= (side_[k] * u_[i]) * a_.col(k).head(n_);
    rhs_[i] -= side_[k] * a_.col(k).head(n_).dot(x_.head(n_));
  }
  eqp(res_, rhs_.data(), dx_, du_.data());
  x_.head(n_) += dx_.head(n_);
  for (int i = 0; i < q_; ++i) u_[i] += du_[i];
}

}  // namespace hexdyn
