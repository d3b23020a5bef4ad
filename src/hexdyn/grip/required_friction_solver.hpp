#pragma once
/// \file grip/required_friction_solver.hpp
/// The internals of RequiredFrictionSolver (grip/required_friction.hpp), shared by its
/// two sources: required_friction.cpp (Newton on an active set, the choice of its rows,
/// bisection) and required_friction_cone.cpp (the exact cone's outer polygons). Not a public
/// interface. Sizes: at most kMaxLegs support legs of 3 forces, so the Newton system is at
/// most kMaxUnknowns = 25 square (19 for a hexapod), of which the leading block is used.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/allocation/goldfarb_idnani.hpp"
#include "hexdyn/core/sizes.hpp"
#include "hexdyn/grip/internal_forces.hpp"
#include "hexdyn/grip/required_friction.hpp"

namespace hexdyn {

inline constexpr int kMaxUnknowns = kMaxLegForces + 1;  ///< n forces and μ
using MuMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxUnknowns, kMaxUnknowns>;
using MuVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxUnknowns, 1>;

/// Faces of the outer polygon that stands in for an exact cone, and the bit that marks the
/// polygon problem's structural key.
inline constexpr int kConeFaces = 16;
static_assert(kConeFaces <= kActiveSetMaxLegFaces, "the active-set row budget holds the polygon");
/// A probe is feasible when its solution holds every row to this, relative to max(1, |bound|):
/// the back end's own tolerance (1e-9) with a margin, far tighter than the allocation's
/// verdict (kViolationThreshold), so that a probe's friction use is μ* to about 1e-8.
inline constexpr double kProbeThreshold = 1e-8;
inline constexpr std::uint64_t kConePolygonKey = std::uint64_t{1} << 62;

/// LU factorisation with partial pivoting of a Newton matrix J (at most kMaxUnknowns square,
/// in a buffer of fixed capacity), unblocked: at this size Eigen's PartialPivLU takes its
/// blocked path (above 16 columns), and the Newton attempts of a sample factor J ten times or
/// so (bench/RESULTS.md, "Required friction on the stairs range").
class MuLu {
 public:
  /// P J = L U; false when a pivot is zero or not finite (J singular to the working precision).
  bool compute(const MuMatrix& J) {
    n_ = static_cast<int>(J.rows());
    a_.topLeftCorner(n_, n_) = J;
    for (int k = 0; k < n_; ++k) {
      int p = k;
      double best = std::abs(a_(k, k));
      for (int i = k + 1; i < n_; ++i)
        if (std::abs(a_(i, k)) > best) best = std::abs(a_(p = i, k));
      if (!(best > 0.0) || !std::isfinite(best)) return false;
      perm_[static_cast<std::size_t>(k)] = p;
      if (p != k) a_.row(k).head(n_).swap(a_.row(p).head(n_));
      const double inv = 1.0 / a_(k, k);
      for (int i = k + 1; i < n_; ++i) {
        const double l = a_(i, k) * inv;
        a_(i, k) = l;
        if (l != 0.0)
          for (int j = k + 1; j < n_; ++j) a_(i, j) -= l * a_(k, j);
      }
    }
    return true;
  }
  /// The solution of J v = b.
  MuVector solve(const MuVector& b) const {
    MuVector v = b;
    for (int k = 0; k < n_; ++k) std::swap(v[k], v[perm_[static_cast<std::size_t>(k)]]);
    for (int i = 1; i < n_; ++i)
      for (int j = 0; j < i; ++j) v[i] -= a_(i, j) * v[j];
    for (int i = n_ - 1; i >= 0; --i) {
      for (int j = i + 1; j < n_; ++j) v[i] -= a_(i, j) * v[j];
      v[i] /= a_(i, i);
    }
    return v;
  }
  /// The solution of Jᵀ v = b.
  MuVector solve_transpose(const MuVector& b) const {
    MuVector v = b;
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < i; ++j) v[i] -= a_(j, i) * v[j];
      v[i] /= a_(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i)
      for (int j = i + 1; j < n_; ++j) v[i] -= a_(j, i) * v[j];
    for (int k = n_ - 1; k >= 0; --k) std::swap(v[k], v[perm_[static_cast<std::size_t>(k)]]);
    return v;
  }

 private:
  Eigen::Matrix<double, kMaxUnknowns, kMaxUnknowns, Eigen::RowMajor> a_;
  std::array<int, kMaxUnknowns> perm_{};
  int n_ = 0;
};

/// An active row: `side` +1 at its upper bound, −1 at its lower bound, 0 both (a trunk row).
struct MuRow {
  int row = 0;
  int side = 0;
};

/// Rows of a face with its μ dependence: the derivative of the row's value C x − bound with
/// respect to μ at x.
inline double row_mu_derivative(const AllocationLayout& layout, const Eigen::VectorXd& x, int row,
                                int side) {
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    if (leg.offset < 0 || row < leg.friction_row || row >= leg.friction_row + leg.friction_faces)
      continue;
    if (leg.count == 3) return -leg.face_reach * x[leg.offset + 2];
    return side > 0 ? -leg.face_reach * leg.known_normal_force_N : 0.0;
  }
  return 0.0;
}

/// How a Newton attempt on an active set ended.
enum class NewtonEnd {
  kCertified,    ///< the answer: every row holds, the multipliers have their signs
  kRowViolated,  ///< converged, but an inactive row is violated (NewtonState::row)
  kWrongSign,    ///< converged and feasible, but an active row's multiplier has the wrong sign
  kFailed,       ///< singular, not converged, or not finite
};

struct RequiredFrictionSolver::Impl {
  RequiredFrictionOptions opt;
  std::unique_ptr<AllocationBackend> backend;
  QpProblem work;
  ViolationWorkspace violations;
  RequiredFriction out;
  // The last certified active set, for problems of the same structure and sizes.
  bool has_warm = false;
  std::uint64_t warm_structure = 0;
  int warm_n = -1, warm_m = -1;
  std::vector<MuRow> warm_set;
  MuVector warm_z;
  // Newton's workspace and the state of its last attempt.
  std::vector<MuRow> candidate, trial;
  std::vector<std::pair<double, int>> slack;
  MuVector z;  ///< (x, μ) of the Newton iterate
  Eigen::VectorXd x;
  MuVector lambda;
  MuMatrix J;
  MuLu lu;      ///< of J at the last Newton iterate
  MuLu farkas;  ///< of J at μ − tolerance (infeasible_below)
  int newton_leg = -1;
  bool negative_mu = false;  ///< a Newton attempt of this sample ended at μ < 0
  double last_mu = -1.0;     ///< the previous sample's μ*, −1 before the first
  /// The caller's `enough` for this sample (RequiredFrictionSolver::solve), and whether the
  /// probe just below it has been found infeasible for this sample.
  double enough = -std::numeric_limits<double>::infinity();
  bool enough_infeasible = false;
  /// The probe's μ just below `enough`.
  double below_enough() const { return enough * (1.0 - 1e-9); }
  /// Ends the sample with method kBelow: μ* ≤ mu < enough, mu the friction the forces x use
  /// (leg: the leg that uses it).
  void settle_below(double mu, const Eigen::VectorXd& x, int leg) {
    out.mu = mu;
    out.leg = leg;
    out.method = RequiredFrictionMethod::kBelow;
    answer_x = x;
  }
  bool probe_below_enough(const AllocationLayout& layout);
  InternalForceWorkspace internal;  ///< internal_force_use's scratch
  bool last_nan = false;            ///< the previous polygon problem had no μ* ≤ mu_max
  int bad_row = -1;  ///< kRowViolated: the violated row; kWrongSign: the index in the set
  int bad_side = 0;  ///< kRowViolated: the violated side

  Impl(std::unique_ptr<AllocationBackend> b, const RequiredFrictionOptions& o)
      : opt(o), backend(std::move(b)) {
    for (int l = 0; l < kMaxLegs; ++l)  // every leg a robot may have
      for (int f = 0; f < kConeFaces; ++f) cone_angle[l][f] = 2.0 * M_PI * f / kConeFaces;
  }

  /// work = qp (a problem without cones); the row names copied only when the layout changed.
  void load(const QpProblem& qp) { copy_problem_values(qp, work, 0, qp.structure); }

  /// Feasibility of the rows at mu: the back end's solve at mu, every row and cone held to
  /// kViolationThreshold. The forces in *x_out.
  bool feasible_at(const AllocationLayout& layout, double mu, Eigen::VectorXd& x_out,
                   std::string* why = nullptr) {
    set_friction_coefficient(layout, mu, work);
    // A verdict alone needs the problem as posed; the reason for an infeasible one needs the
    // back end's relaxed answer, whose violated rows the message names.
    const QpOutcome& o = why ? backend->solve(work) : backend->solve_as_posed(work);
    x_out = o.x;
    if (o.status != SolverStatus::kOptimal && !why) return false;
    double worst = 0.0;
    const std::string text = describe_violations(work, o.x, kProbeThreshold, &worst, violations);
    x_out = o.x;
    if (why) *why = text;
    return o.status == SolverStatus::kOptimal && text.empty();
  }

  NewtonEnd newton(const AllocationLayout& layout, const std::vector<MuRow>& set,
                   const MuVector& z0);
  NewtonEnd check(const AllocationLayout& layout, const std::vector<MuRow>& set);
  /// The row of J for inequality row `row` at its side `side` (at z, work set to z's μ).
  MuVector gradient(const AllocationLayout& layout, int row, int side) const {
    const int n = work.variables();
    MuVector a(n + 1);
    a.head(n) = work.C.row(row).transpose();
    a[n] = row_mu_derivative(layout, x, row, side);
    return a;
  }
  bool infeasible_below(const AllocationLayout& layout, const std::vector<MuRow>& set,
                        double mu_low);
  int dual_ratio_leaving(const AllocationLayout& layout, const std::vector<MuRow>& set);
  bool primal_ratio_entering(const AllocationLayout& layout, const std::vector<MuRow>& set,
                             MuRow& enter);
  bool solve_from(const AllocationLayout& layout, std::vector<MuRow> set, const MuVector& z0);
  Eigen::VectorXd x_scratch;  ///< the forces of check()'s probe of a degenerate vertex
  MuMatrix basis;  ///< active_set_at: orthonormal rows of J of the candidate rows, as columns
  void add_if_independent(const AllocationLayout& layout, MuRow a);
  bool active_set_at(const AllocationLayout& layout, const Eigen::Ref<const Eigen::VectorXd>& x_at,
                     double mu);
  bool upper_end(const AllocationLayout& layout, const Eigen::VectorXd* allocation, double& hi,
                 Eigen::VectorXd& x_hi);
  bool newton_in_bracket(const AllocationLayout& layout, const Eigen::VectorXd& x_hi, double lo,
                         double hi);
  void bisect(const AllocationLayout& layout, const Eigen::VectorXd* allocation, double guess);
  void solve_polygonal(const AllocationLayout& layout, const Eigen::VectorXd* allocation);
  void load_cone_polygon(const QpProblem& qp, const AllocationLayout& layout);
  void solve_cone(const QpProblem& qp, const AllocationLayout& layout,
                  const Eigen::VectorXd* allocation);

  // The exact cone's outer polygons: per leg, the directions of its faces [rad], kept from one
  // sample to the next; the polygon problem's layout.
  LegArray<std::array<double, kConeFaces>> cone_angle;
  LegArray<double> cone_center{};   ///< the direction the faces gather around [rad]
  LegArray<double> cone_spacing{};  ///< their spacing δ [rad]
  void cluster_faces(int l, double a, double delta);
  AllocationLayout cone_layout;
  Eigen::VectorXd answer_x;  ///< the forces of the last answer
  void remember(const std::vector<MuRow>& set);
};

}  // namespace hexdyn
