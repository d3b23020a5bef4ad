/// \file allocation/goldfarb_idnani.cpp
/// The dual active-set QP solver (allocation/goldfarb_idnani.hpp): loading, the dual iteration
/// and the results; the factorisations it updates are in allocation/goldfarb_idnani_factors.cpp.
///
/// Warm starts begin with the rows of an earlier solve: the equality-constrained solution
/// on those rows is computed with the direct factors (Cholesky factor of NᵀH⁻¹N), rows with
/// multipliers outside their box are dropped (or made elastic) and elastic rows that hold
/// are released until the set is dual feasible; the iteration then proceeds as usual, and
/// the Goldfarb–Idnani factors are only built if it has to move. A final point reached by
/// moving is recomputed from its active set with one step of iterative refinement, so
/// that active rows hold to rounding.
#include "hexdyn/allocation/goldfarb_idnani.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace hexdyn {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

const char* exit_name(ActiveSetExit r) {
  switch (r) {
    case ActiveSetExit::kOptimal:
      return "optimal";
    case ActiveSetExit::kInfeasible:
      return "infeasible";
    case ActiveSetExit::kIterationLimit:
      return "stopped at the iteration limit";
    case ActiveSetExit::kNumerical:
      return "stopped by a numerically dependent row";
  }
  return "unknown";
}

/// Copies the problem (sizes checked by the caller, n ≥ 1) and factorises H. Returns
/// false, without factorising, when an entry is not finite (or a bound is NaN).
bool DualActiveSetQp::load(const QpProblem& p, double rho, double tolerance) {
  n_ = p.variables();
  m_eq_ = p.equalities();
  m_ = m_eq_ + p.inequalities();
  tolerance_ = tolerance;
  // Σ 0·v is 0 exactly when every v is finite.
  double nonfinite = 0.0 * p.constant;
  // The factors of H are kept when H is the one last factorised (the required friction's
  // probes of one sample change only rows): same_h stays true while every entry is equal.
  bool same_h = factorized_ && n_ == factorized_n_;
  for (int j = 0; j < n_; ++j) {
    for (int i = 0; i < j; ++i) nonfinite += 0.0 * p.H(i, j);  // upper triangle: checked only
    for (int i = j; i < n_; ++i) {
      same_h = same_h && h_in_(i, j) == p.H(i, j);
      h_in_(i, j) = p.H(i, j);
      nonfinite += 0.0 * p.H(i, j);
    }
    g_[j] = p.g[j];
    nonfinite += 0.0 * g_[j];
  }
  any_crossed_ = -1;
  for (int k = 0; k < m_; ++k) {
    double lo, hi;
    if (k < m_eq_) {
      for (int j = 0; j < n_; ++j) a_(j, k) = p.A(k, j);
      lo = hi = p.b[k];
      nonfinite += 0.0 * lo;
      cap_[k] = kInf;
    } else {
      const int i = k - m_eq_;
      for (int j = 0; j < n_; ++j) a_(j, k) = p.C(i, j);
      lo = p.lower[i] > -kQpInfinity ? p.lower[i] : -kInf;
      hi = p.upper[i] < kQpInfinity ? p.upper[i] : kInf;
      if (std::isnan(p.lower[i]) || std::isnan(p.upper[i])) nonfinite = kInf;
      cap_[k] = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
    }
    for (int j = 0; j < n_; ++j) nonfinite += 0.0 * a_(j, k);
    lo0_[k] = lo;
    hi0_[k] = hi;
    if (lo > hi && any_crossed_ < 0) any_crossed_ = k;
  }
  if (nonfinite != 0.0) {
    factorized_ = false;
    return false;
  }
  if (same_h) return true;
  for (int j = 0; j < n_; ++j)
    for (int i = j; i < n_; ++i) H_(i, j) = H_(j, i) = h_in_(i, j);
  convex_ = factorize();
  factorized_ = true;
  factorized_n_ = n_;
  return true;
}

/// False when H is indefinite (after load).

/// First row with lower > upper, or −1.
/// δ added to H's diagonal (0 when H was positive definite).

/// Selects the strict (multipliers unbounded) or penalised problem; the penalised one
/// exchanges crossed bounds.
void DualActiveSetQp::set_mode(bool relaxed) {
  relaxed_ = relaxed;
  for (int k = 0; k < m_; ++k) {
    lo_[k] = lo0_[k], hi_[k] = hi0_[k];
    if (relaxed && lo_[k] > hi_[k]) std::swap(lo_[k], hi_[k]);
    eqtype_[k] = lo_[k] == hi_[k];
  }
}

/// Unconstrained minimiser, empty working sets.
void DualActiveSetQp::start_cold() {
  clear_sets();
  ensure_j0();
  J_.topLeftCorner(n_, n_) = J0_.topLeftCorner(n_, n_);
  gi_valid_ = true;
  solve_eqp();
}

/// Starts from the rows `active` (and `elastic`, penalised mode only), made dual feasible
/// as described in the file comment. Returns false (and leaves a cold start) when that
/// does not settle. `dropped` counts the rows given up.
bool DualActiveSetQp::start_warm(const ActiveRow* active, int n_active, const ActiveRow* elastic,
                                 int n_elastic, int& dropped) {
  std::array<ActiveRow, kN> w;
  std::array<ActiveRow, kM> e;
  int nw = 0, ne = 0;
  for (int i = 0; i < n_active && nw < n_; ++i)
    if (active[i].row < m_ && finite_side(active[i].row, active[i].side)) w[nw++] = active[i];
  if (relaxed_)
    for (int i = 0; i < n_elastic && ne < m_; ++i)
      if (elastic[i].row < m_ && elastic[i].row >= m_eq_ && cap_[elastic[i].row] < kInf &&
          finite_side(elastic[i].row, elastic[i].side))
        e[ne++] = elastic[i];
  for (int round = 0; round <= 2 * (nw + ne) + 1; ++round) {
    clear_sets();
    gi_valid_ = false;
    for (int i = 0; i < ne; ++i)
      if (state_[e[i].row] == RowState::kInactive) make_elastic(e[i].row, e[i].side);
    for (int i = 0; i < nw; ++i) {
      const ActiveRow r = w[i];
      if (state_[r.row] != RowState::kInactive || !direct_add(r.row, r.side)) ++dropped;
    }
    solve_eqp();
    // Rows outside their multiplier box leave (or turn elastic); elastic rows that
    // hold are released.
    bool changed = false;
    nw = 0;
    for (int i = 0; i < q_; ++i) {
      const int k = act_[i];
      if (u_[i] < lower_multiplier(k)) {
        changed = true;
        ++dropped;
        if (eqtype_[k] && relaxed_ && ne < kM) e[ne++] = {k, -side_[k]};
      } else if (u_[i] > upper_multiplier(k)) {
        changed = true;
        ++dropped;
        if (ne < kM) e[ne++] = {k, side_[k]};
      } else {
        w[nw++] = {k, side_[k]};
      }
    }
    int kept = 0;
    for (int i = 0; i < ne; ++i) {
      const ActiveRow r = e[i];
      if (state_[r.row] == RowState::kElastic &&
          residual(r.row, r.side) > side_tol(r.row, r.side)) {
        changed = true;
        ++dropped;
        continue;
      }
      e[kept++] = r;
    }
    ne = kept;
    if (!changed) return true;
  }
  start_cold();
  return false;
}

/// The dual iteration from the current (dual feasible) state; `changes` counts the
/// active-set changes.
ActiveSetExit DualActiveSetQp::run(int max_changes, int& changes) {
  while (true) {
    int side = 0;
    const int p = most_violated(side);
    if (p < 0) return ActiveSetExit::kOptimal;
    if (!gi_valid_ && !build_gi()) {
      start_cold();  // the warm set did not factorise: start again from scratch
      continue;
    }
    moved_ = true;
    if (a_.col(p).head(n_).squaredNorm() == 0.0) {
      // A zero row whose bounds exclude 0: only relaxation helps.
      if (!(relaxed_ && cap_[p] < kInf)) return ActiveSetExit::kInfeasible;
      make_elastic(p, side);
      if (++changes > max_changes) return ActiveSetExit::kIterationLimit;
      continue;
    }
    if (const std::optional<ActiveSetExit> exit = add_violated_row(p, side, max_changes, changes))
      return *exit;
  }
}

/// Steps towards making row p (from `side`) hold, each step as long as the first block
/// allows, until p holds or turns elastic (nullopt: select the next row) or the iteration
/// must stop (its exit). `changes` counts the active-set changes.
std::optional<ActiveSetExit> DualActiveSetQp::add_violated_row(int p, int side, int max_changes,
                                                               int& changes) {
  double u_plus = 0.0;  // multiplier of p
  for (;;) {
    if (++changes > max_changes) return ActiveSetExit::kIterationLimit;
    // d = Jᵀ n⁺ (n⁺ = side·a_p), z = J₂ d₂, r = R⁻¹ d₁.
    bool dependent = false;
    const double d2 = project_row(p, side, dependent);
    if (!dependent) {
      z_.head(n_).setZero();
      for (int i = q_; i < n_; ++i) z_.head(n_) += d_[i] * J_.col(i).head(n_);
    }
    upper_solve(R_, q_, d_.data(), r_.data(), rinv_.data());
    const Step step = step_length(p, side, dependent, d2, u_plus);
    if (!(step.t < kInf) || step.block == Block::kNone) return ActiveSetExit::kInfeasible;
    const double t = step.t;
    const int which = step.which;
    // Step.
    if (!dependent) x_.head(n_) += t * z_.head(n_);
    for (int i = 0; i < q_; ++i) u_[i] -= t * r_[i];
    u_plus += t;
    if (step.block == Block::kFull) {
      if (!add_row(p, side, u_plus)) return ActiveSetExit::kNumerical;
      return std::nullopt;  // p holds: select the next row
    }
    if (step.block == Block::kPlusCap) {
      make_elastic(p, side);
      return std::nullopt;
    }
    if (step.block == Block::kCross) {
      release_elastic(which);
      if (!add_row(which, side_[which], cap_[which])) return ActiveSetExit::kNumerical;
      continue;
    }
    const int k = act_[which];
    const int s = side_[k];
    drop_position(which);
    if (step.block == Block::kCap)
      make_elastic(k, s);
    else if (eqtype_[k])
      make_elastic(k, -s);  // an l = u row at −ρ w (penalised mode)
  }
}

/// Step lengths along (z, r) of adding row p with multiplier u_plus so far (d2 from
/// project_row): the full step (p holds), a multiplier reaching a bound of its box, p's
/// multiplier reaching its cap, an elastic row coming to hold. The shortest wins.
DualActiveSetQp::Step DualActiveSetQp::step_length(int p, int side, bool dependent, double d2,
                                                   double u_plus) {
  Step s{kInf, Block::kNone, -1};
  if (!dependent) {
    s.t = std::max(0.0, -residual(p, side) / d2);
    s.block = Block::kFull;
  }
  for (int i = 0; i < q_; ++i) {
    const int k = act_[i];
    if (r_[i] > 0.0) {
      const double lb = lower_multiplier(k);
      if (lb > -kInf) {
        const double ti = std::max(0.0, (u_[i] - lb) / r_[i]);
        if (ti < s.t) s.t = ti, s.block = Block::kDrop, s.which = i;
      }
    } else if (r_[i] < 0.0) {
      const double ub = upper_multiplier(k);
      if (ub < kInf) {
        const double ti = std::max(0.0, (ub - u_[i]) / -r_[i]);
        if (ti < s.t) s.t = ti, s.block = Block::kCap, s.which = i;
      }
    }
  }
  if (relaxed_ && cap_[p] < kInf) {
    const double ti = std::max(0.0, cap_[p] - u_plus);
    if (ti < s.t) s.t = ti, s.block = Block::kPlusCap;
  }
  if (relaxed_ && !dependent) {
    for (int k = m_eq_; k < m_; ++k) {
      if (state_[k] != RowState::kElastic) continue;
      const double slope = side_[k] * a_.col(k).head(n_).dot(z_.head(n_));
      if (!(slope > 0.0)) continue;
      const double ti = std::max(0.0, -residual(k, side_[k]) / slope);
      // A row that depends on the active rows keeps its value along z (the slope is
      // rounding): it cannot come to hold.
      if (ti < s.t && independent(k)) s.t = ti, s.block = Block::kCross, s.which = k;
    }
  }
  return s;
}

/// Recomputes x and the multipliers from the working sets (with one refinement step)
/// after the iteration moved; a warm start that needed no iteration is already refined.
void DualActiveSetQp::polish() {
  if (moved_) solve_eqp();
}

// --- results ---
/// Multipliers of all rows into `out` (size rows()), hexdyn's sign.
void DualActiveSetQp::lambdas(double* out) const {
  for (int k = 0; k < m_; ++k) out[k] = state_[k] == RowState::kElastic ? side_[k] * cap_[k] : 0.0;
  for (int i = 0; i < q_; ++i) out[act_[i]] = side_[act_[i]] * u_[i];
}
/// Largest violation of any row at x (row units, as describe_violations), and whether a
/// row is violated beyond tol·max(1, |bound|).
double DualActiveSetQp::max_violation(double tol, bool& beyond) const {
  double worst = 0.0;
  beyond = false;
  for (int k = 0; k < m_; ++k) {
    const double c = a_.col(k).head(n_).dot(x_.head(n_));
    const double lo = lo0_[k], hi = hi0_[k];
    const double below = lo > -kInf ? lo - c : -1.0;
    const double above = hi < kInf ? c - hi : -1.0;
    const bool use_lo = below >= above && lo > -kInf;
    const double v = use_lo ? below : above;
    const double bound = use_lo ? lo : hi;
    if (!(v <= 0.0)) {
      worst = std::max(worst, v);
      if (!(v <= tol * std::max(1.0, std::abs(bound)))) beyond = true;
    }
  }
  return worst;
}
double DualActiveSetQp::objective(double constant) const {
  const auto x = x_.head(n_);
  return 0.5 * (x.dot(H_.topLeftCorner(n_, n_) * x) - delta_ * x.squaredNorm()) +
         g_.head(n_).dot(x) + constant;
}
/// Elastic rows into `out` (capacity kM); returns their number.
int DualActiveSetQp::elastic_rows(ActiveRow* out) const {
  int ne = 0;
  for (int k = 0; k < m_; ++k)
    if (state_[k] == RowState::kElastic) out[ne++] = {k, side_[k]};
  return ne;
}

// --- rows ---

bool DualActiveSetQp::finite_side(int k, int side) const {
  return side > 0 ? lo_[k] > -kInf : hi_[k] < kInf;
}
/// β of row k on a side: the row reads side·a_kᵀx ≥ β.
double DualActiveSetQp::beta(int k, int side) const { return side > 0 ? lo_[k] : -hi_[k]; }
/// side·a_kᵀx − β (≥ 0 when that side holds).
double DualActiveSetQp::residual(int k, int side) const {
  return side * a_.col(k).head(n_).dot(x_.head(n_)) - beta(k, side);
}
double DualActiveSetQp::side_tol(int k, int side) const {
  return tolerance_ * std::max(1.0, std::abs(side > 0 ? lo_[k] : hi_[k]));
}
double DualActiveSetQp::lower_multiplier(int k) const {
  if (!eqtype_[k]) return 0.0;
  return relaxed_ ? -cap_[k] : -kInf;
}
double DualActiveSetQp::upper_multiplier(int k) const { return relaxed_ ? cap_[k] : kInf; }

/// The row with the largest violation / ‖a_k‖ among inactive rows, or −1.
int DualActiveSetQp::most_violated(int& side) const {
  int best = -1;
  double best_score = 0.0;
  for (int k = 0; k < m_; ++k) {
    if (state_[k] != RowState::kInactive) continue;
    const bool lo = lo_[k] > -kInf, hi = hi_[k] < kInf;
    if (!lo && !hi) continue;
    const double c = a_.col(k).head(n_).dot(x_.head(n_));
    double v = 0.0;
    int s = 0;
    if (lo && lo_[k] - c > side_tol(k, 1)) {
      v = lo_[k] - c, s = 1;
    } else if (hi && c - hi_[k] > side_tol(k, -1)) {
      v = c - hi_[k], s = -1;
    } else {
      continue;
    }
    const double norm = a_.col(k).head(n_).norm();
    const double score = norm > 0.0 ? v / norm : kInf;
    if (best < 0 || score > best_score) best = k, best_score = score, side = s;
  }
  return best;
}

}  // namespace hexdyn
