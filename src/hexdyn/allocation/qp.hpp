#pragma once
/// \file allocation/qp.hpp
/// The solver side of the foot-force allocation (docs/theory/allocation.md#rows,
/// docs/theory/allocation.md#exact-l1-penalty): a small dense
/// QP (optionally with second-order friction cones, then an NLP), one solver interface
/// behind which back ends are swapped.
///
///   minimise    ½ xᵀ H x + gᵀ x + constant
///   subject to  A x = b                                  (equality rows, "eq")
///               lower ≤ C x ≤ upper                      (inequality rows, "ineq")
///               √(x[t1]² + x[t2]²) ≤ μ x[n]              (cones, optional)
///
/// Multiplier sign convention (Lagrangian L = f − λ_eqᵀ(A x − b) − λ_inᵀ(C x − ·)):
///   stationarity   H x + g − Aᵀ λ_eq − Cᵀ λ_in (− cone terms) = 0,
///   λ_in[i] ≥ 0 when the lower bound of row i is active, ≤ 0 when its upper bound is,
///   0 when the row is inactive. λ is the sensitivity of the optimal objective:
///   raising lower[i] (or b[i]) by ε changes it by about +λ[i]·ε.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// The fixed physical threshold of a violated constraint, independent of any solver
/// tolerance: a row or cone counts as violated when it misses its bound by more than
/// kViolationThreshold · max(1, |bound|) in its own units — N for the trunk force rows,
/// normal-force rows and friction faces or cones (|F_t| − μ F_n), N·m for the trunk
/// moment rows and the joint torque limits. 1e-6 N is about 1.5e-8 of the paper robot's
/// weight (65.7 N) and 1e-6 N·m about 2e-7 of its torque limit: far below anything
/// physical, far above the rounding of the rows (about 1e-13 relative). After every
/// solve the pipeline measures the solution against it (describe_violations) and flags
/// the sample relaxed when any row is beyond it, whatever the back end reported.
inline constexpr double kViolationThreshold = 1e-6;

/// A bound at or beyond this magnitude, or ±infinity, means "no bound".
inline constexpr double kQpInfinity = 1e19;

/// √(x[t1]² + x[t2]²) ≤ mu · x[normal]: the exact friction cone of one foot.
struct SecondOrderCone {
  int tangent1 = 0;      ///< index of f_t1 in x
  int tangent2 = 1;      ///< index of f_t2 in x
  int normal = 2;        ///< index of f_n in x
  double mu = 0.3;       ///< friction coefficient, ≥ 0
  std::string name;      ///< e.g. "cone L3"
  double penalty = 1.0;  ///< relative weight of this cone's slack when relaxed, > 0
};

/// Dense QP of n ≤ ~18 variables. Sizes: H n×n (symmetric; only its lower triangle is
/// read), g n, A m_eq×n, b m_eq, C m_in×n, lower/upper m_in. Names: empty, or one per
/// row (used in messages only; empty names become "eq[i]" / "ineq[i]").
///
/// When the rows cannot all hold, a back end relaxes inequality rows and cones with slacks
/// s ≥ 0 measured in the row's own units (N, N·m) under the L1 penalty ρ Σ w_i s_i; the
/// weights w (ineq_penalty, SecondOrderCone::penalty, default 1) set which rows give way
/// first: a row that must hold unless nothing else helps (e.g. a trunk equation written as
/// an l = u row) gets a large weight such as 1e3. Equality rows are never relaxed.
struct QpProblem {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  double constant = 0.0;
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  Eigen::MatrixXd C;
  Eigen::VectorXd lower;  ///< −infinity (or ≤ −kQpInfinity) for none
  Eigen::VectorXd upper;  ///< +infinity (or ≥ kQpInfinity) for none
  std::vector<std::string> eq_names;
  std::vector<std::string> ineq_names;
  std::vector<SecondOrderCone> cones;
  Eigen::VectorXd ineq_penalty;  ///< m_in weights w_i > 0, or empty for all 1
  /// Structural key, set by the problem's builder: two problems of the same sizes and the
  /// same key have rows of the same kind at every index, so that a back end may start one
  /// from the other's working set (the active-set back end's warm start). 0 when the
  /// builder sets none: then the sizes alone decide. build_allocation_problem encodes the
  /// friction model and each leg's contact phase.
  std::uint64_t structure = 0;

  int variables() const { return static_cast<int>(g.size()); }
  int equalities() const { return static_cast<int>(b.size()); }
  int inequalities() const { return static_cast<int>(lower.size()); }

  /// Sets every size (H, A, C zero; g, b zero; bounds unbounded; names cleared to
  /// the right count of empty strings; penalty weights 1; cones cleared; structure 0).
  void resize(int n, int m_eq, int m_in);
  /// Name of an equality / inequality row for messages.
  std::string eq_name(int i) const;
  std::string ineq_name(int i) const;
  /// ½ xᵀ H x + gᵀ x + constant (H read as symmetric from its lower triangle).
  double objective(const Eigen::VectorXd& x) const;
};

/// Throws SolverError naming the first inconsistent size or index (expected vs got).
void validate_qp_sizes(const QpProblem& p);

/// Copies `from` into the working problem `to`: its objective, equality rows and inequality
/// rows, then `extra_rows` more inequality rows (C zero, unbounded, weight 1) for the caller to
/// fill, no cones, and the structural key `structure`. The sizes, the row names (the extra rows
/// unnamed) and the key are set only when `to` differs from them in a size or the key (at a
/// contact event), so that copying problems of one structure allocates nothing. Returns
/// whether they were set.
bool copy_problem_values(const QpProblem& from, QpProblem& to, int extra_rows,
                         std::uint64_t structure);

/// The solver's answer, a value recorded per sample.
struct QpOutcome {
  /// kOptimal; kRelaxed (penalised slack was needed: some rows or cones do not hold; or an
  /// approximate answer, see message); kFailed (x is a finite fallback: the least-squares
  /// solution of A x = b, or zeros).
  SolverStatus status = SolverStatus::kFailed;
  Eigen::VectorXd x;            ///< n
  Eigen::VectorXd lambda_eq;    ///< m_eq, sign convention in the file comment
  Eigen::VectorXd lambda_ineq;  ///< m_in, ≥ 0 at an active lower bound, ≤ 0 at an upper
  /// Per cone, multiplier of μ x_n − √(x_t1² + x_t2²) ≥ 0 (≥ 0, positive when active;
  /// 0 when the cones were replaced by polygons).
  Eigen::VectorXd lambda_cone;
  int iterations = 0;          ///< interior-point iterations, all attempts
  double objective = 0.0;      ///< ½ xᵀHx + gᵀx + constant at x (without penalties)
  double seconds = 0.0;        ///< wall time of the call
  double max_violation = 0.0;  ///< largest violation of a row or cone at x (row units)
  /// kOptimal: empty, or a note that Ipopt reached only its acceptable tolerance.
  /// kRelaxed: "relaxed: " and what gave way, largest violation first, e.g.
  /// "relaxed: torque L1_femur by 0.73, friction L3 +y by 0.02", with a note in
  /// parentheses if the cones were replaced by inscribed polygons; "approximate: ..." when
  /// that replacement was needed although nothing gave way. kFailed: "failed: " and why.
  std::string message;
};

/// A QP/NLP back end. `solve` never throws for numerical trouble (that is the outcome's
/// status); it throws SolverError only for inconsistent sizes (or a problem the back end
/// does not support). The reference stays valid until the next call. A back end may carry
/// a warm start from one solve to the next (each back end says what it keeps); it is not
/// thread-safe: one back end per thread.
class AllocationBackend {
 public:
  virtual ~AllocationBackend();
  /// Checks the sizes (validate_qp_sizes), solves (solve_impl) and records the time taken
  /// in the outcome's `seconds`.
  const QpOutcome& solve(const QpProblem& problem);
  /// solve for a feasibility verdict alone: a problem infeasible as posed may end at once
  /// with status kFailed, without the relaxed answer `solve` would give (the strict-then-
  /// penalised back ends skip the penalised attempt); a feasible one ends as with `solve`.
  /// Back ends without such a shortcut solve as `solve` does.
  const QpOutcome& solve_as_posed(const QpProblem& problem);
  /// Forget everything carried from earlier solves: the next solve starts cold.
  virtual void reset_warm_start() = 0;

 protected:
  bool as_posed_ = false;  ///< solve_as_posed is running
  /// Fills out_ (all but `seconds`) for a problem of consistent sizes.
  virtual void solve_impl(const QpProblem& problem) = 0;

  QpOutcome out_;
};

/// Rows and cones that x violates by more than tol·max(1, |bound|), largest first, as
/// "torque L1_femur by 0.73, friction L3 +y by 0.02" (empty when none). Violations are in
/// row units (equalities |A_i x − b_i|; cones √(t1² + t2²) − μ n). *max_violation (if
/// given) receives the largest violation of any row or cone, whatever its size.
std::string describe_violations(const QpProblem& problem, const Eigen::VectorXd& x, double tol,
                                double* max_violation = nullptr);

/// Workspace of describe_violations for a caller that measures every sample: its buffers
/// keep their capacity from one call to the next, so that a call without a violation
/// allocates nothing (a violation allocates its text).
struct ViolationWorkspace {
  std::vector<double> row_value;  ///< A x, then C x [row units]
  /// (violation, row) of the rows beyond the threshold; row = i for equality i,
  /// m_eq + i for inequality i, m_eq + m_in + k for cone k.
  std::vector<std::pair<double, int>> violated;
};

/// describe_violations with the caller's workspace: the same text and *max_violation, bit
/// for bit.
std::string describe_violations(const QpProblem& problem, const Eigen::VectorXd& x, double tol,
                                double* max_violation, ViolationWorkspace& workspace);

/// A finite point for a failed solve: the minimum-norm least-squares solution of A x = b
/// (zeros without equality rows or with non-finite data).
Eigen::VectorXd qp_fallback_point(const QpProblem& problem);

// --- outcome bookkeeping shared by the back ends ---

/// Threshold beyond which a row counts as violated in an outcome's status, relative to
/// max(1, |bound|), for a back end run at `tolerance`: max(1e-6, 1e3·tolerance).
double qp_feasibility_tolerance(double tolerance);

/// Name of the first non-finite part of the problem ("H", "g", ..., "bounds of <row>"),
/// empty when every entry is finite (infinite bounds are allowed).
std::string qp_first_non_finite(const QpProblem& problem);

/// Fills `out` (all but iterations and seconds) for a failed solve: kFailed, x =
/// qp_fallback_point, zero multipliers, finite objective and max_violation, and the
/// message "failed: <why>; fallback x = ...; violated: ...".
void qp_fail_with_fallback(const QpProblem& problem, double feasibility_tol, const std::string& why,
                           QpOutcome& out);

/// Fills `out` (all but iterations and seconds) for a problem without variables: kOptimal
/// when its constant rows hold, kFailed naming them otherwise.
void qp_solve_without_variables(const QpProblem& problem, double feasibility_tol, QpOutcome& out);

}  // namespace hexdyn
