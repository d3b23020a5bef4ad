/// \file allocation/active_set.cpp
/// The dual active-set back end of the allocation (allocation/active_set.hpp).
///
/// Method. Goldfarb & Idnani, "A numerically stable dual method for solving strictly convex
/// quadratic programs", Math. Programming 27 (1983) 1–33, as in quadprog, extended with
/// bounded multipliers for the exact L1 penalty. With H = L Lᵀ and the normals of the
/// active rows N (oriented so that each reads nᵀx ≥ β), the factorisation
///     J = L⁻ᵀ Q,   L⁻¹ N = Q [R; 0]   (R upper triangular, q × q)
/// gives the primal step z = J₂ J₂ᵀ n⁺ and the dual step r = R⁻¹ J₁ᵀ n⁺ for adding a row
/// n⁺; adding and dropping rows updates J and R with Givens rotations. The iterates are
/// optimal for the rows in the active set (dual feasible) and add the most violated other
/// row (largest violation / ‖C_i‖) until none is violated.
///
/// Rows. Every row, equality or inequality, is one constraint with a side: +1 when its
/// lower bound is active (C_i x ≥ lower_i), −1 when its upper bound is (−C_i x ≥ −upper_i);
/// its multiplier u ≥ 0 in that orientation is λ_i = side·u in hexdyn's sign. Rows with
/// lower = upper (all equality rows, and inequality rows written as l = u, such as the trunk
/// equations) keep any sign of u and are never dropped.
///
/// Penalised problem. The L1 penalty ρ w_i dist(C_i x, [lower_i, upper_i]) bounds each
/// multiplier by ρ w_i (the dual of the penalised problem is the dual of the strict one
/// with the box |λ_i| ≤ ρ w_i). A row whose multiplier reaches ρ w_i becomes "elastic": it
/// leaves the active set and its multiplier stays at ρ w_i, a fixed linear term
/// −ρ w_i·side·C_i in the gradient, while the row may stay violated. The ratio test of each
/// step includes these bounds and the point where an elastic row would become satisfied
/// (it then rejoins the active set with multiplier ρ w_i), so that the final point is the
/// penalised optimum: inactive rows hold, active rows hold with equality and multipliers in
/// their box, elastic rows are violated (or exactly at their bound) with multipliers at
/// ρ w_i. A row with lower > upper is penalised by ρ w_i (upper − lower) plus the distance
/// to [upper, lower], so it is solved with its bounds exchanged. Equality rows (A x = b)
/// have no bound on their multipliers: an inconsistent set of them fails (status 2).
///
/// Attempts (as in the Ipopt back end): the problem as posed, then, if it is infeasible,
/// the penalised problem, started from the strict attempt's active set; after a relaxed
/// sample a problem of the same sizes goes to the penalised form directly. Warm starts
/// begin with the previous solve's active (and elastic) rows when the sizes and the
/// structural key (QpProblem::structure) match: the equality-constrained solution on those
/// rows is computed (Cholesky factor of NᵀH⁻¹N), rows with multipliers outside their box are dropped (or made elastic) and
/// elastic rows that hold are released until the set is dual feasible; the iteration then
/// proceeds as usual, and the Goldfarb–Idnani factors are only built if it has to move.
/// A final point reached by moving is recomputed from its active set with one step of
/// iterative refinement, so that active rows hold to rounding.
///
/// Storage is fixed-size (kActiveSetMaxVariables, kActiveSetMaxRows); a solve allocates
/// only in messages and in the fallback of a failed solve.
#include "hexdyn/allocation/active_set.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

constexpr int kN = kActiveSetMaxVariables;
constexpr int kM = kActiveSetMaxRows;
constexpr double kInf = std::numeric_limits<double>::infinity();
/// A row whose normal has a component below this fraction (in the metric H⁻¹) outside
/// the span of the active normals counts as linearly dependent on them.
constexpr double kDependence = 1e-10;

using MatN = Eigen::Matrix<double, kN, kN>;
using VecN = Eigen::Matrix<double, kN, 1>;
using RowNormals = Eigen::Matrix<double, kN, kM>;  ///< column k: the normal of row k

enum class RowState : std::int8_t { kInactive, kActive, kElastic };
enum class ActiveSetExit { kOptimal, kInfeasible, kIterationLimit, kNumerical };

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

/// A row in a working set: row index (equality rows first, then inequality rows) and side.
struct RowRef {
  int row = 0;
  int side = 1;
};

/// Givens rotation (c, s) with c a + s b = ρ, −s a + c b = 0.
inline void givens(double a, double b, double& c, double& s, double& rho) {
  if (b == 0.0) {
    c = 1.0, s = 0.0, rho = a;
    return;
  }
  rho = std::sqrt(a * a + b * b);
  c = a / rho;
  s = b / rho;
}

/// The dual active-set solver on one problem: data, factorisations and working sets, all
/// in fixed-size storage.
///
/// Two factorisations of the active set are kept, each built only when needed:
///  - direct: M = L⁻¹N and the Cholesky factor S_L of S = MᵀM = NᵀH⁻¹N, built row by row
///    by a warm start; it gives the equality-constrained solution cheaply, and when that
///    solution is already optimal nothing else is computed;
///  - Goldfarb–Idnani: J = L⁻ᵀQ and R, built (from J₀ = L⁻ᵀ) when the dual iteration
///    has to move, and updated by Givens rotations as rows are added and dropped.
/// Both declare a row dependent on the active ones by the same test: the squared norm of
/// the part of L⁻¹n outside the span of the active rows' L⁻¹n_i is at most
/// kDependence²·‖L⁻¹n‖².
class DualActiveSet {
 public:
  /// Copies the problem (sizes checked by the caller, n ≥ 1) and factorises H. Returns
  /// false, without factorising, when an entry is not finite (or a bound is NaN).
  bool load(const QpProblem& p, double rho, double tolerance) {
    n_ = p.variables();
    m_eq_ = p.equalities();
    m_ = m_eq_ + p.inequalities();
    tolerance_ = tolerance;
    // Σ 0·v is 0 exactly when every v is finite.
    double nonfinite = 0.0 * p.constant;
    for (int j = 0; j < n_; ++j) {
      for (int i = 0; i < j; ++i) nonfinite += 0.0 * p.H(i, j);  // upper triangle: checked only
      for (int i = j; i < n_; ++i) {
        H_(i, j) = H_(j, i) = p.H(i, j);
        nonfinite += 0.0 * H_(i, j);
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
    if (nonfinite != 0.0) return false;
    convex_ = factorize();
    return true;
  }

  /// False when H is indefinite (after load).
  bool convex() const { return convex_; }

  /// First row with lower > upper, or −1.
  int crossed_row() const { return any_crossed_; }
  /// δ added to H's diagonal (0 when H was positive definite).
  double regularisation() const { return delta_; }

  /// Selects the strict (multipliers unbounded) or penalised problem; the penalised one
  /// exchanges crossed bounds.
  void set_mode(bool relaxed) {
    relaxed_ = relaxed;
    for (int k = 0; k < m_; ++k) {
      lo_[k] = lo0_[k], hi_[k] = hi0_[k];
      if (relaxed && lo_[k] > hi_[k]) std::swap(lo_[k], hi_[k]);
      eqtype_[k] = lo_[k] == hi_[k];
    }
  }

  /// Unconstrained minimiser, empty working sets.
  void start_cold() {
    clear_sets();
    ensure_j0();
    J_.topLeftCorner(n_, n_) = J0_.topLeftCorner(n_, n_);
    gi_valid_ = true;
    solve_eqp();
  }

  /// Starts from the rows `active` (and `elastic`, penalised mode only), made dual feasible
  /// as described in the file comment. Returns false (and leaves a cold start) when that
  /// does not settle. `dropped` counts the rows given up.
  bool start_warm(const RowRef* active, int n_active, const RowRef* elastic, int n_elastic,
                  int& dropped) {
    std::array<RowRef, kN> w;
    std::array<RowRef, kM> e;
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
        const RowRef r = w[i];
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
        const RowRef r = e[i];
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
  ActiveSetExit run(int max_changes, int& changes) {
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
      double u_plus = 0.0;  // multiplier of p
      for (;;) {
        if (++changes > max_changes) return ActiveSetExit::kIterationLimit;
        // d = Jᵀ n⁺ (n⁺ = side·a_p), z = J₂ d₂, r = R⁻¹ d₁.
        for (int i = 0; i < n_; ++i) d_[i] = side * J_.col(i).head(n_).dot(a_.col(p).head(n_));
        double d2 = 0.0, dn = 0.0;
        for (int i = 0; i < n_; ++i) dn += d_[i] * d_[i];
        for (int i = q_; i < n_; ++i) d2 += d_[i] * d_[i];
        const bool dependent = !(d2 > kDependence * kDependence * dn);
        if (!dependent) {
          z_.head(n_).setZero();
          for (int i = q_; i < n_; ++i) z_.head(n_) += d_[i] * J_.col(i).head(n_);
        }
        r_back_substitute(d_.data(), r_.data());
        // Step lengths: full step (p holds), a multiplier reaching a bound of its box,
        // p's multiplier reaching its cap, an elastic row coming to hold.
        enum class Block { kNone, kFull, kDrop, kCap, kPlusCap, kCross };
        Block block = Block::kNone;
        double t = kInf;
        int which = -1;
        if (!dependent) {
          t = std::max(0.0, -residual(p, side) / d2);
          block = Block::kFull;
        }
        for (int i = 0; i < q_; ++i) {
          const int k = act_[i];
          if (r_[i] > 0.0) {
            const double lb = lower_multiplier(k);
            if (lb > -kInf) {
              const double ti = std::max(0.0, (u_[i] - lb) / r_[i]);
              if (ti < t) t = ti, block = Block::kDrop, which = i;
            }
          } else if (r_[i] < 0.0) {
            const double ub = upper_multiplier(k);
            if (ub < kInf) {
              const double ti = std::max(0.0, (ub - u_[i]) / -r_[i]);
              if (ti < t) t = ti, block = Block::kCap, which = i;
            }
          }
        }
        if (relaxed_ && cap_[p] < kInf) {
          const double ti = std::max(0.0, cap_[p] - u_plus);
          if (ti < t) t = ti, block = Block::kPlusCap;
        }
        if (relaxed_ && !dependent) {
          for (int k = m_eq_; k < m_; ++k) {
            if (state_[k] != RowState::kElastic) continue;
            const double slope = side_[k] * a_.col(k).head(n_).dot(z_.head(n_));
            if (!(slope > 0.0)) continue;
            const double ti = std::max(0.0, -residual(k, side_[k]) / slope);
            // A row that depends on the active rows keeps its value along z (the slope is
            // rounding): it cannot come to hold.
            if (ti < t && independent(k)) t = ti, block = Block::kCross, which = k;
          }
        }
        if (!(t < kInf) || block == Block::kNone) return ActiveSetExit::kInfeasible;
        // Step.
        if (!dependent) x_.head(n_) += t * z_.head(n_);
        for (int i = 0; i < q_; ++i) u_[i] -= t * r_[i];
        u_plus += t;
        if (block == Block::kFull) {
          if (!add_row(p, side, u_plus)) return ActiveSetExit::kNumerical;
          break;  // p holds: select the next row
        }
        if (block == Block::kPlusCap) {
          make_elastic(p, side);
          break;
        }
        if (block == Block::kCross) {
          release_elastic(which);
          if (!add_row(which, side_[which], cap_[which])) return ActiveSetExit::kNumerical;
          continue;
        }
        const int k = act_[which];
        const int s = side_[k];
        drop_position(which);
        if (block == Block::kCap)
          make_elastic(k, s);
        else if (eqtype_[k])
          make_elastic(k, -s);  // an l = u row at −ρ w (penalised mode)
      }
    }
  }

  /// Recomputes x and the multipliers from the working sets (with one refinement step)
  /// after the iteration moved; a warm start that needed no iteration is already refined.
  void polish() {
    if (moved_) solve_eqp();
  }

  // --- results ---
  int n() const { return n_; }
  int rows() const { return m_; }
  int m_eq() const { return m_eq_; }
  const VecN& x() const { return x_; }
  /// Multipliers of all rows into `out` (size rows()), hexdyn's sign.
  template <class Vec>
  void lambdas(Vec& out) const {
    for (int k = 0; k < m_; ++k)
      out[k] = state_[k] == RowState::kElastic ? side_[k] * cap_[k] : 0.0;
    for (int i = 0; i < q_; ++i) out[act_[i]] = side_[act_[i]] * u_[i];
  }
  /// Largest violation of any row at x (row units, as describe_violations), and whether a
  /// row is violated beyond tol·max(1, |bound|).
  double max_violation(double tol, bool& beyond) const {
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
  double objective(double constant) const {
    const auto x = x_.head(n_);
    return 0.5 * (x.dot(H_.topLeftCorner(n_, n_) * x) - delta_ * x.squaredNorm()) +
           g_.head(n_).dot(x) + constant;
  }
  int active_count() const { return q_; }
  RowRef active_row(int i) const { return {act_[i], side_[act_[i]]}; }
  /// Elastic rows into `out` (capacity kM); returns their number.
  int elastic_rows(RowRef* out) const {
    int ne = 0;
    for (int k = 0; k < m_; ++k)
      if (state_[k] == RowState::kElastic) out[ne++] = {k, side_[k]};
    return ne;
  }

 private:
  // --- H = L Lᵀ ---

  /// Factorises H (regularised if singular); false when H is indefinite.
  bool factorize() {
    double max_diag = 0.0;
    for (int i = 0; i < n_; ++i) max_diag = std::max(max_diag, std::abs(H_(i, i)));
    delta_ = 0.0;
    // A pivot below 1e-9 of the largest diagonal entry: H is singular to working accuracy
    // (the dual iteration would lose about as many digits as cond(H) has).
    const double scale = max_diag > 0.0 ? max_diag : 1.0;
    if (!cholesky(1e-9 * scale)) {
      delta_ = 1e-9 * scale;
      for (int i = 0; i < n_; ++i) H_(i, i) += delta_;
      if (!cholesky(0.0)) return false;  // indefinite: not a convex QP
    }
    j0_valid_ = false;
    return true;
  }

  /// H = L Lᵀ (and 1/L_ii); false when a pivot is not above `min_pivot`.
  bool cholesky(double min_pivot) {
    for (int j = 0; j < n_; ++j) {
      double s = H_(j, j);
      for (int k = 0; k < j; ++k) s -= L_(j, k) * L_(j, k);
      if (!(s > min_pivot)) return false;
      L_(j, j) = std::sqrt(s);
      linv_[j] = 1.0 / L_(j, j);
      for (int i = j + 1; i < n_; ++i) {
        double t = H_(i, j);
        for (int k = 0; k < j; ++k) t -= L_(i, k) * L_(j, k);
        L_(i, j) = t * linv_[j];
      }
    }
    return true;
  }

  /// v ← L⁻¹ v.
  void l_solve(double* v) const {
    for (int i = 0; i < n_; ++i) {
      double s = v[i];
      for (int k = 0; k < i; ++k) s -= L_(i, k) * v[k];
      v[i] = s * linv_[i];
    }
  }
  /// v ← L⁻ᵀ v.
  void lt_solve(double* v) const {
    for (int i = n_ - 1; i >= 0; --i) {
      double s = v[i];
      for (int k = i + 1; k < n_; ++k) s -= L_(k, i) * v[k];
      v[i] = s * linv_[i];
    }
  }

  /// J₀ = L⁻ᵀ, computed once per problem when the dual iteration first needs it.
  void ensure_j0() {
    if (j0_valid_) return;
    // Row c of J₀ is (L⁻¹ e_c)ᵀ.
    J0_.topLeftCorner(n_, n_).setZero();
    for (int c = 0; c < n_; ++c) {
      J0_(c, c) = linv_[c];
      for (int i = c + 1; i < n_; ++i) {
        double s = 0.0;
        for (int k = c; k < i; ++k) s += L_(i, k) * J0_(c, k);
        J0_(c, i) = -s * linv_[i];
      }
    }
    j0_valid_ = true;
  }

  // --- rows ---

  bool finite_side(int k, int side) const { return side > 0 ? lo_[k] > -kInf : hi_[k] < kInf; }
  /// β of row k on a side: the row reads side·a_kᵀx ≥ β.
  double beta(int k, int side) const { return side > 0 ? lo_[k] : -hi_[k]; }
  /// side·a_kᵀx − β (≥ 0 when that side holds).
  double residual(int k, int side) const {
    return side * a_.col(k).head(n_).dot(x_.head(n_)) - beta(k, side);
  }
  double side_tol(int k, int side) const {
    return tolerance_ * std::max(1.0, std::abs(side > 0 ? lo_[k] : hi_[k]));
  }
  double lower_multiplier(int k) const {
    if (!eqtype_[k]) return 0.0;
    return relaxed_ ? -cap_[k] : -kInf;
  }
  double upper_multiplier(int k) const { return relaxed_ ? cap_[k] : kInf; }

  /// The row with the largest violation / ‖a_k‖ among inactive rows, or −1.
  int most_violated(int& side) const {
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

  // --- working sets ---

  void clear_sets() {
    q_ = 0;
    for (int k = 0; k < m_; ++k) state_[k] = RowState::kInactive;
    geff_.head(n_) = g_.head(n_);
    moved_ = false;
  }

  void make_elastic(int k, int side) {
    state_[k] = RowState::kElastic;
    side_[k] = static_cast<std::int8_t>(side);
    geff_.head(n_) -= (cap_[k] * side) * a_.col(k).head(n_);
  }

  void release_elastic(int k) {
    state_[k] = RowState::kInactive;
    geff_.head(n_) += (cap_[k] * side_[k]) * a_.col(k).head(n_);
  }

  /// Appends row k to the active set in the direct factorisation (multiplier 0 until
  /// solve_eqp); false when it depends on the active rows.
  bool direct_add(int k, int side) {
    if (q_ >= n_) return false;
    double* m = M_.col(q_).data();
    for (int j = 0; j < n_; ++j) m[j] = side * a_(j, k);
    l_solve(m);
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
    if (!(pivot2 > kDependence * kDependence * dn)) return false;
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
  bool build_gi() {
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

  /// Givens update of J and R for row k as active row number q_ (q_ not changed); false
  /// when it depends on the active rows.
  bool gi_append(int k, int side) {
    if (q_ >= n_) return false;
    for (int i = 0; i < n_; ++i) d_[i] = side * J_.col(i).head(n_).dot(a_.col(k).head(n_));
    double d2 = 0.0, dn = 0.0;
    for (int i = 0; i < n_; ++i) dn += d_[i] * d_[i];
    for (int i = q_; i < n_; ++i) d2 += d_[i] * d_[i];
    if (!(d2 > kDependence * kDependence * dn)) return false;
    for (int i = n_ - 1; i > q_; --i) {
      if (d_[i] == 0.0) continue;
      double c, s, rho;
      givens(d_[i - 1], d_[i], c, s, rho);
      d_[i - 1] = rho;
      d_[i] = 0.0;
      rotate_columns(J_, i - 1, i, c, s);
    }
    for (int i = 0; i <= q_; ++i) R_(i, q_) = d_[i];
    return true;
  }

  /// Whether row k's normal is independent of the active normals (the test of gi_append).
  bool independent(int k) {
    double d2 = 0.0, dn = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double d = J_.col(i).head(n_).dot(a_.col(k).head(n_));
      dn += d * d;
      if (i >= q_) d2 += d * d;
    }
    return q_ < n_ && d2 > kDependence * kDependence * dn;
  }

  /// Adds row k on `side` with multiplier u to the active set (Givens update of J and R).
  /// False, with nothing changed, when its normal depends on the active normals.
  bool add_row(int k, int side, double u) {
    if (!gi_append(k, side)) return false;
    act_[q_] = k;
    u_[q_] = u;
    ++q_;
    state_[k] = RowState::kActive;
    side_[k] = static_cast<std::int8_t>(side);
    return true;
  }

  /// Removes the active row at position `pos` (its row becomes inactive).
  void drop_position(int pos) {
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
      rotate_columns(J_, j, j + 1, c, s);
    }
  }

  /// Columns (i, j) ← (c·col_i + s·col_j, −s·col_i + c·col_j).
  void rotate_columns(MatN& M, int i, int j, double c, double s) const {
    for (int r = 0; r < n_; ++r) {
      const double a = M(r, i), b = M(r, j);
      M(r, i) = c * a + s * b;
      M(r, j) = -s * a + c * b;
    }
  }

  /// out = R⁻¹ in (first q entries).
  void r_back_substitute(const double* in, double* out) {
    for (int i = 0; i < q_; ++i) rinv_[i] = 1.0 / R_(i, i);
    for (int i = q_ - 1; i >= 0; --i) {
      double s = in[i];
      for (int j = i + 1; j < q_; ++j) s -= R_(i, j) * out[j];
      out[i] = s * rinv_[i];
    }
  }
  /// out = R⁻ᵀ in (first q entries); rinv_ from the last r_back_substitute or set here.
  void r_forward_substitute(const double* in, double* out) {
    for (int i = 0; i < q_; ++i) rinv_[i] = 1.0 / R_(i, i);
    for (int i = 0; i < q_; ++i) {
      double s = in[i];
      for (int j = 0; j < i; ++j) s -= R_(j, i) * out[j];
      out[i] = s * rinv_[i];
    }
  }

  // --- equality-constrained solutions on the active set ---

  /// Minimiser of ½xᵀHx + gradᵀx on the active rows side·a_kᵀx = rhs_k and its
  /// multipliers u, with the Goldfarb–Idnani factors: x₀ = −J Jᵀ grad,
  /// v = R⁻ᵀ(rhs − Nᵀx₀), x = x₀ + J₁ v, u = R⁻¹ v.
  void eqp_gi(const VecN& grad, const double* rhs, VecN& x, double* u) {
    for (int i = 0; i < n_; ++i) w_[i] = J_.col(i).head(n_).dot(grad.head(n_));
    x.head(n_).setZero();
    for (int i = 0; i < n_; ++i) x.head(n_) -= w_[i] * J_.col(i).head(n_);
    for (int i = 0; i < q_; ++i) {
      const int k = act_[i];
      t_[i] = rhs[i] - side_[k] * a_.col(k).head(n_).dot(x.head(n_));
    }
    r_forward_substitute(t_.data(), v_.data());
    for (int i = 0; i < q_; ++i) x.head(n_) += v_[i] * J_.col(i).head(n_);
    r_back_substitute(v_.data(), u);
  }

  /// The same with the direct factors: y = L⁻¹ grad, S u = rhs + Mᵀy,
  /// x = L⁻ᵀ(M u − y).
  void eqp_direct(const VecN& grad, const double* rhs, VecN& x, double* u) {
    double* y = w_.data();
    for (int j = 0; j < n_; ++j) y[j] = grad[j];
    l_solve(y);
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
    lt_solve(x.data());
  }

  void eqp(const VecN& grad, const double* rhs, VecN& x, double* u) {
    if (gi_valid_)
      eqp_gi(grad, rhs, x, u);
    else
      eqp_direct(grad, rhs, x, u);
  }

  /// x and u on the working sets, with one step of iterative refinement (the gradient
  /// holds ±ρ w terms of elastic rows, much larger than the answer).
  void solve_eqp() {
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

  // Problem.
  int n_ = 0, m_ = 0, m_eq_ = 0;
  double tolerance_ = 1e-9;
  bool relaxed_ = false;
  int any_crossed_ = -1;
  double delta_ = 0.0;  ///< regularisation added to H's diagonal
  bool convex_ = true;
  MatN H_, L_, J0_;  ///< H (regularised if needed), its Cholesky factor, L⁻ᵀ
  VecN g_;
  RowNormals a_;
  std::array<double, kM> lo0_{}, hi0_{};  ///< bounds as posed (±inf for none)
  std::array<double, kM> lo_{}, hi_{};    ///< bounds of the current mode
  std::array<double, kM> cap_{};          ///< ρ w_k, or inf for equality rows
  std::array<bool, kM> eqtype_{};
  std::array<double, kN> linv_{};  ///< 1 / L_ii
  bool j0_valid_ = false;
  // Working sets.
  std::array<RowState, kM> state_{};
  std::array<std::int8_t, kM> side_{};
  int q_ = 0;
  std::array<int, kN> act_{};
  std::array<double, kN> u_{};
  VecN x_, geff_;
  bool moved_ = false;  ///< the iteration moved since the last solve_eqp
  // Factorisations of the active set.
  MatN M_, S_;                     ///< direct: L⁻¹N and the Cholesky factor of MᵀM
  std::array<double, kN> sinv_{};  ///< 1 / S_ii
  bool gi_valid_ = false;          ///< J_ and R_ describe the active set
  MatN J_, R_;
  // Scratch.
  VecN z_, res_, dx_;
  std::array<double, kN> d_{}, r_{}, w_{}, t_{}, v_{}, rhs_{}, du_{}, rinv_{};
};

class ActiveSetBackend final : public AllocationBackend {
 public:
  explicit ActiveSetBackend(const ActiveSetOptions& options) : opt_(options) {
    if (!(opt_.tolerance > 0.0) || !(opt_.slack_penalty > 0.0) || opt_.max_iterations < 1) {
      std::ostringstream os;
      os << "active-set options: tolerance and slack_penalty must be > 0 and max_iterations "
            ">= 1, got "
         << opt_.tolerance << ", " << opt_.slack_penalty << ", " << opt_.max_iterations;
      throw ConfigError(os.str());
    }
    core_ = std::make_unique<DualActiveSet>();
  }

 private:
  /// Feasibility threshold of a row for the status (allocation/qp.hpp).
  double feasibility_tol() const { return qp_feasibility_tolerance(opt_.tolerance); }

  static void check_supported(const QpProblem& p) {
    if (!p.cones.empty())
      throw SolverError("active-set back end: cones need the ipopt back end (got " +
                        std::to_string(p.cones.size()) +
                        " cones; use allocation.solver: ipopt or a friction pyramid)");
    if (p.variables() > kN) {
      std::ostringstream os;
      os << "active-set back end: variables: expected at most " << kN << ", got " << p.variables();
      throw SolverError(os.str());
    }
    if (p.equalities() + p.inequalities() > kM) {
      std::ostringstream os;
      os << "active-set back end: rows (equality + inequality): expected at most " << kM << ", got "
         << p.equalities() + p.inequalities();
      throw SolverError(os.str());
    }
  }

  void fail_with_fallback(const QpProblem& p, const std::string& why) {
    qp_fail_with_fallback(p, feasibility_tol(), why, out_);
    have_warm_ = false;
    last_relaxed_ = false;
  }

  /// x, multipliers and objective from the solver's final state.
  void fill_solution(const QpProblem& p) {
    const DualActiveSet& s = *core_;
    const int n = s.n(), m_eq = s.m_eq(), m_in = s.rows() - m_eq;
    out_.x.resize(n);
    for (int i = 0; i < n; ++i) out_.x[i] = s.x()[i];
    out_.lambda_eq.resize(m_eq);
    out_.lambda_ineq.resize(m_in);
    out_.lambda_cone.resize(0);
    s.lambdas(lambda_all_);
    for (int k = 0; k < m_eq; ++k) out_.lambda_eq[k] = lambda_all_[k];
    for (int i = 0; i < m_in; ++i) out_.lambda_ineq[i] = lambda_all_[m_eq + i];
    out_.objective = s.objective(p.constant);
  }

  /// Rows that x violates beyond the status threshold, as describe_violations words them
  /// (empty when none); sets out_.max_violation. The scan is done here first, so that a
  /// feasible answer builds no text.
  std::string violations(const QpProblem& p) {
    bool beyond = false;
    out_.max_violation = core_->max_violation(feasibility_tol(), beyond);
    if (!beyond) return {};
    return describe_violations(p, out_.x, feasibility_tol(), &out_.max_violation);
  }

  /// Remembers the final working sets for the next solve.
  void store_warm() {
    const DualActiveSet& s = *core_;
    warm_active_n_ = s.active_count();
    for (int i = 0; i < warm_active_n_; ++i) warm_active_[i] = s.active_row(i);
    warm_elastic_n_ = s.elastic_rows(warm_elastic_.data());
    have_warm_ = true;
  }

  /// Same sizes and structural key (QpProblem::structure) as the last problem (and
  /// remembers the key).
  bool same_structure(const QpProblem& p, bool same_sizes) {
    const bool same = same_sizes && p.structure == warm_structure_;
    warm_structure_ = p.structure;
    return same;
  }

  /// Polishes the final point of an attempt that ended optimal and fills the outcome from
  /// it; returns the rows it violates (violations()).
  std::string finish_attempt(const QpProblem& p) {
    core_->polish();
    fill_solution(p);
    return violations(p);
  }

  /// Status optimal, with a note when H had to be regularised.
  void mark_optimal() {
    out_.status = SolverStatus::kOptimal;
    if (core_->regularisation() > 0.0) out_.message = regularisation_note();
  }

  std::string regularisation_note() const {
    char buf[96];
    std::snprintf(buf, sizeof buf, "objective Hessian not positive definite: regularised by %.3g I",
                  core_->regularisation());
    return buf;
  }

  void solve_impl(const QpProblem& p) override {
    check_supported(p);
    const int n = p.variables(), m_eq = p.equalities(), m_in = p.inequalities();
    out_.iterations = 0;
    out_.message.clear();
    if (n == 0) {
      if (const std::string bad = qp_first_non_finite(p); !bad.empty())
        fail_with_fallback(p, "non-finite entries in " + bad);
      else
        qp_solve_without_variables(p, feasibility_tol(), out_);
      return;
    }
    DualActiveSet& s = *core_;
    if (!s.load(p, opt_.slack_penalty, opt_.tolerance)) {
      fail_with_fallback(p, "non-finite entries in " + qp_first_non_finite(p));
      return;
    }
    if (!s.convex()) {
      fail_with_fallback(p, "the objective Hessian H is indefinite (not a convex QP)");
      return;
    }

    const bool same_sizes = warm_n_ == n && warm_m_eq_ == m_eq && warm_m_in_ == m_in;
    const bool structure = same_structure(p, same_sizes);
    const bool skip_strict = last_relaxed_ && same_sizes;
    const bool warm = opt_.warm_start && have_warm_ && structure;
    warm_n_ = n, warm_m_eq_ = m_eq, warm_m_in_ = m_in;
    last_relaxed_ = false;
    const int max_changes = opt_.max_iterations;

    // --- strict attempt ---
    ActiveSetExit strict_res = ActiveSetExit::kInfeasible;
    std::string strict_violated;  // an optimal strict answer that violates rows (not expected)
    bool strict_ran = false;
    if (!skip_strict) {
      if (s.crossed_row() < 0) {
        s.set_mode(false);
        ActiveSetExit res = ActiveSetExit::kNumerical;
        for (const bool use_warm : {true, false}) {
          if (use_warm && !warm) continue;
          int dropped = 0;
          if (use_warm)
            s.start_warm(warm_active_.data(), warm_active_n_, nullptr, 0, dropped);
          else
            s.start_cold();
          int changes = dropped;
          res = s.run(max_changes, changes);
          out_.iterations += changes;
          // An exact method reaches the same verdict from any start: retry cold only
          // after an iteration limit or numerical trouble.
          if (res == ActiveSetExit::kOptimal || res == ActiveSetExit::kInfeasible) break;
        }
        strict_ran = true;
        strict_res = res;
        if (res == ActiveSetExit::kOptimal) {
          const std::string v = finish_attempt(p);
          if (v.empty()) {
            mark_optimal();
            store_warm();
            return;
          }
          strict_violated = v;
        }
      }
    }

    // --- penalised attempt ---
    s.set_mode(true);
    ActiveSetExit res = ActiveSetExit::kNumerical;
    for (const bool use_warm : {true, false}) {
      int dropped = 0;
      if (use_warm) {
        if (skip_strict && warm) {
          s.start_warm(warm_active_.data(), warm_active_n_, warm_elastic_.data(), warm_elastic_n_,
                       dropped);
        } else if (strict_ran) {
          // The strict attempt's final active set.
          std::array<RowRef, kN> rows;
          const int q = s.active_count();
          for (int i = 0; i < q; ++i) rows[i] = s.active_row(i);
          s.start_warm(rows.data(), q, nullptr, 0, dropped);
        } else {
          continue;
        }
      } else {
        s.start_cold();
      }
      int changes = dropped;
      res = s.run(max_changes, changes);
      out_.iterations += changes;
      if (res == ActiveSetExit::kOptimal || res == ActiveSetExit::kInfeasible) break;
    }
    if (res != ActiveSetExit::kOptimal) {
      std::string note = "strict solve ";
      if (skip_strict) {
        note += "skipped after a relaxed sample";
      } else if (s.crossed_row() >= 0) {
        const int k = s.crossed_row();
        note += "infeasible (lower > upper on " +
                (k < m_eq ? p.eq_name(k) : p.ineq_name(k - m_eq)) + ")";
      } else if (!strict_violated.empty()) {
        note += "optimal but violated " + strict_violated;
      } else {
        note += exit_name(strict_res);
      }
      note += "; penalised solve ";
      note += exit_name(res);
      if (res == ActiveSetExit::kInfeasible) note += " (equality rows)";
      fail_with_fallback(p, note);
      return;
    }
    const std::string v = finish_attempt(p);
    if (v.empty()) {
      // No slack needed: by exactness of the penalty this is the strict optimum.
      mark_optimal();
    } else {
      out_.status = SolverStatus::kRelaxed;
      out_.message = "relaxed: " + v;
      if (s.regularisation() > 0.0) out_.message += " (" + regularisation_note() + ")";
    }
    store_warm();
    last_relaxed_ = out_.status != SolverStatus::kOptimal;
  }

  ActiveSetOptions opt_;
  std::unique_ptr<DualActiveSet> core_;
  int warm_n_ = -1, warm_m_eq_ = -1, warm_m_in_ = -1;
  std::uint64_t warm_structure_ = 0;  ///< QpProblem::structure of the last problem
  std::array<RowRef, kN> warm_active_{};
  int warm_active_n_ = 0;
  std::array<RowRef, kM> warm_elastic_{};
  int warm_elastic_n_ = 0;
  std::array<double, kM> lambda_all_{};  ///< scratch: multipliers of all rows
};

}  // namespace

ActiveSetOptions active_set_options_from(const AllocationParams& params) {
  ActiveSetOptions o;
  o.tolerance = params.tolerance;
  o.slack_penalty = params.slack_penalty;
  return o;
}

std::unique_ptr<AllocationBackend> make_active_set_backend(const ActiveSetOptions& options) {
  return std::make_unique<ActiveSetBackend>(options);
}

}  // namespace hexdyn
