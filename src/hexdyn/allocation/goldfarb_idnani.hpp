#pragma once
/// \file allocation/goldfarb_idnani.hpp
/// DualActiveSetQp: a dual active-set solver for small dense strictly convex QPs, in the
/// Goldfarb–Idnani style, extended with bounded multipliers for the exact L1 penalty
/// (docs/theory/allocation.md#the-dual-active-set-solver). It is the numerical core of the
/// active-set back end (allocation/active_set_backend.hpp), which adds the attempt policy, warm
/// starts across samples and the outcome; it knows nothing of either.
///
///   minimise    ½ xᵀ H x + gᵀ x
///   subject to  A x = b,   lower ≤ C x ≤ upper                         (strict mode)
///   or          ½ xᵀ H x + gᵀ x + ρ Σ_i w_i dist(C_i x, [lower_i, upper_i]),  A x = b
///                                                                       (penalised mode)
///
/// Method (Goldfarb & Idnani, Math. Programming 27 (1983) 1–33, as in quadprog). With
/// H = L Lᵀ and the normals N of the active rows (each oriented to read nᵀx ≥ β), the
/// factorisation J = L⁻ᵀ Q, L⁻¹ N = Q [R; 0] gives the primal step z = J₂ J₂ᵀ n⁺ and the dual
/// step r = R⁻¹ J₁ᵀ n⁺ for adding a row n⁺; Givens rotations update J and R as rows enter
/// and leave. The iterates are optimal for the active rows (dual feasible) and add the
/// most violated other row (largest violation / ‖C_i‖) until none is violated.
///
/// Rows. Every row, equality or inequality, is one constraint with a side: +1 when its
/// lower bound is active, −1 when its upper bound is; its multiplier u ≥ 0 in that
/// orientation is λ = side·u in hexdyn's sign (allocation/qp.hpp). Rows with lower = upper
/// keep any sign of u and are never dropped.
///
/// Penalised mode. The penalty bounds each multiplier by ρ w_i. A row whose multiplier
/// reaches ρ w_i becomes elastic: it leaves the active set, its multiplier stays at ρ w_i
/// (a fixed term −ρ w_i·side·C_i in the gradient) and the row may stay violated. The ratio
/// test includes these bounds and the point where an elastic row would come to hold (it
/// then rejoins the active set), so the final point is the penalised optimum. Crossed
/// bounds (lower > upper) are exchanged. Equality rows are never relaxed.
///
/// Two factorisations of the active set are kept, each built only when needed: the direct
/// one (M = L⁻¹N and the Cholesky factor of NᵀH⁻¹N), built row by row by a warm start and
/// enough to certify a warm set that is already optimal; and the Goldfarb–Idnani factors J
/// and R, built when the iteration has to move. Both call a row dependent on the active
/// ones by one test (dependent_row).
///
/// Sizes: n ≤ kActiveSetMaxVariables, m_eq + m_in ≤ kActiveSetMaxRows (the caller checks;
/// beyond them the behaviour is undefined). Storage is fixed-size: nothing is allocated.
/// Call order: load, set_mode, start_cold or start_warm, run, polish, then the results.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>

#include "hexdyn/allocation/friction.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/allocation/small_dense.hpp"

namespace hexdyn {

/// Largest number of variables of the active-set solver: three force components per leg.
inline constexpr int kActiveSetMaxVariables = kSmallDenseMax;
/// Most friction rows one leg brings: a 16-gon, either the inscribed one of a leg in its
/// impact transient under the exact cone (allocation/friction.hpp kInscribedConeFaces) or
/// the outer one that stands in for a cone in the required friction's probes
/// (grip/required_friction_solver.hpp kConeFaces); the pyramids have 4 or 8 faces and the
/// cone back end 8 cuts per cone (each checked against this where it is defined).
inline constexpr int kActiveSetMaxLegFaces = kInscribedConeFaces;
/// Largest number of rows (equality plus inequality) it accepts: the allocation's six trunk
/// rows, then per leg one two-sided torque row per joint, a support leg's minimum normal
/// force and its friction faces (allocation/problem.hpp), at the capacities (core/sizes.hpp:
/// kMaxLegs legs of kMaxLegJoints joints): 6 + 8 × (6 + 1 + 16) = 190.
inline constexpr int kActiveSetMaxRows = 6 + kMaxLegs * (kMaxLegJoints + 1 + kActiveSetMaxLegFaces);
static_assert(kActiveSetMaxRows == 190, "the row budget of docs/theory/allocation.md");

/// How a run of the dual iteration ended.
enum class ActiveSetExit {
  kOptimal,         ///< every row holds (or is elastic, penalised mode)
  kInfeasible,      ///< no step can make the most violated row hold
  kIterationLimit,  ///< more active-set changes than allowed
  kNumerical,       ///< a row to add turned out dependent on the active ones
};

/// "optimal", "infeasible", "stopped at the iteration limit", "stopped by a numerically
/// dependent row".
const char* exit_name(ActiveSetExit exit);

/// A row in a working set: index (equality rows first, then inequality rows) and side.
struct ActiveRow {
  int row = 0;
  int side = 1;  ///< +1: lower bound active; −1: upper bound active
};

class DualActiveSetQp {
 public:
  /// A row's normal counts as dependent on the active normals when the squared norm of its
  /// part outside their span (in the metric H⁻¹) is at most kDependence² times its own.
  static constexpr double kDependence = 1e-10;
  /// The one dependence test: `outside_sq` the squared norm of the part outside the span,
  /// `total_sq` the squared norm of the whole.
  static bool dependent_row(double outside_sq, double total_sq) {
    return !(outside_sq > kDependence * kDependence * total_sq);
  }

  /// Copies the problem (sizes checked by the caller, n ≥ 1; ρ the penalty, `tolerance`
  /// the relative violation beyond which a row is added) and factorises H, regularised by
  /// δ I (δ = 1e-9·max H_ii) when a pivot falls below δ; an H equal entry for entry to the
  /// last one factorised keeps its factors. False, without factorising, when an entry is not
  /// finite (or a bound is NaN).
  bool load(const QpProblem& p, double rho, double tolerance);
  /// False when H is indefinite even after regularisation (after load).
  bool convex() const { return convex_; }
  /// First row with lower > upper, or −1.
  int crossed_row() const { return any_crossed_; }
  /// δ added to H's diagonal (0 when H was positive definite).
  double regularisation() const { return delta_; }

  /// Selects the strict (multipliers unbounded) or penalised problem.
  void set_mode(bool penalised);
  /// Unconstrained minimiser, empty working sets.
  void start_cold();
  /// Starts from the rows `active` (and `elastic`, penalised mode only): the
  /// equality-constrained solution on them, then rows whose multipliers leave their box
  /// are dropped (or made elastic) and elastic rows that hold are released until the set is
  /// dual feasible. False (with a cold start) when that does not settle. `dropped` counts
  /// the rows given up.
  bool start_warm(const ActiveRow* active, int n_active, const ActiveRow* elastic, int n_elastic,
                  int& dropped);
  /// The dual iteration from the current (dual feasible) state; `changes` counts the
  /// active-set changes, stopping beyond `max_changes`.
  ActiveSetExit run(int max_changes, int& changes);
  /// Recomputes x and the multipliers from the working sets with one step of iterative
  /// refinement, if the iteration moved since they were last computed.
  void polish();

  // --- results ---
  int n() const { return n_; }
  int rows() const { return m_; }
  int m_eq() const { return m_eq_; }
  /// The current point (first n entries).
  const SmallVector& x() const { return x_; }
  /// Multipliers of all rows in hexdyn's sign into out[0 .. rows()).
  void lambdas(double* out) const;
  /// Largest violation of any row at x (row units), and whether a row is violated beyond
  /// tol·max(1, |bound|).
  double max_violation(double tol, bool& beyond) const;
  /// ½ xᵀ H x + gᵀ x + constant with the unregularised H.
  double objective(double constant) const;
  int active_count() const { return q_; }
  ActiveRow active_row(int i) const { return {act_[i], side_[act_[i]]}; }
  /// Elastic rows into out (capacity kActiveSetMaxRows); returns their number.
  int elastic_rows(ActiveRow* out) const;

 private:
  static constexpr int kN = kActiveSetMaxVariables;
  static constexpr int kM = kActiveSetMaxRows;
  using RowNormals = Eigen::Matrix<double, kN, kM>;  ///< column k: the normal of row k
  enum class RowState : std::int8_t { kInactive, kActive, kElastic };
  /// What ends a step of adding a row: the row holds (full step), an active multiplier
  /// reaches the bound of its box (drop) or its cap (elastic), the added row's multiplier
  /// reaches its cap, an elastic row comes to hold (cross).
  enum class Block : std::int8_t { kNone, kFull, kDrop, kCap, kPlusCap, kCross };
  struct Step {
    double t;     ///< step length
    Block block;  ///< what ends it
    int which;    ///< kDrop, kCap: position in the active set; kCross: the row
  };

  bool factorize();
  void ensure_j0();
  bool finite_side(int k, int side) const;
  double beta(int k, int side) const;
  double residual(int k, int side) const;
  double side_tol(int k, int side) const;
  double lower_multiplier(int k) const;
  double upper_multiplier(int k) const;
  int most_violated(int& side) const;
  void clear_sets();
  void make_elastic(int k, int side);
  void release_elastic(int k);
  bool direct_add(int k, int side);
  bool build_gi();
  double project_row(int k, int side, bool& dependent);
  bool gi_append(int k, int side);
  bool independent(int k);
  bool add_row(int k, int side, double u);
  void drop_position(int pos);
  std::optional<ActiveSetExit> add_violated_row(int p, int side, int max_changes, int& changes);
  Step step_length(int p, int side, bool dependent, double d2, double u_plus);
  void eqp_gi(const SmallVector& grad, const double* rhs, SmallVector& x, double* u);
  void eqp_direct(const SmallVector& grad, const double* rhs, SmallVector& x, double* u);
  void eqp(const SmallVector& grad, const double* rhs, SmallVector& x, double* u);
  void solve_eqp();

  // Problem.
  int n_ = 0, m_ = 0, m_eq_ = 0;
  double tolerance_ = 1e-9;
  bool relaxed_ = false;
  int any_crossed_ = -1;
  double delta_ = 0.0;  ///< regularisation added to H's diagonal
  bool convex_ = true;
  SmallMatrix H_, L_, J0_;   ///< H (regularised if needed), its Cholesky factor, L⁻ᵀ
  SmallMatrix h_in_;         ///< lower triangle of H as last loaded (unregularised)
  bool factorized_ = false;  ///< H_, L_, delta_ and convex_ describe h_in_
  int factorized_n_ = 0;
  SmallVector g_;
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
  SmallVector x_, geff_;
  bool moved_ = false;  ///< the iteration moved since the last solve_eqp
  // Factorisations of the active set.
  SmallMatrix M_, S_;              ///< direct: L⁻¹N and the Cholesky factor of MᵀM
  std::array<double, kN> sinv_{};  ///< 1 / S_ii
  bool gi_valid_ = false;          ///< J_ and R_ describe the active set
  SmallMatrix J_, R_;
  // Scratch.
  SmallVector z_, res_, dx_;
  std::array<double, kN> d_{}, r_{}, w_{}, t_{}, v_{}, rhs_{}, du_{}, rinv_{};
};

}  // namespace hexdyn
