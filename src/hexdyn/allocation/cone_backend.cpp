/// \file allocation/cone_backend.cpp
/// The exact friction cone by sequential outer approximation on the dual active-set QP
/// (allocation/cone_backend.hpp).
///
/// Working problem. The problem's rows, then eight half-spaces per cone k, read as rows
///     d_jᵀ t_k − μ_k n_k ≤ 0,
/// each weighted by the cone's penalty: slot 0 the tangent at the current direction d;
/// slots 1–4 a square around the apex (±e, ±e⊥, e the direction at the start of the
/// sample), which keeps t bounded where n is small; slots 5–7 the tangents of earlier
/// passes (a ring, filled from pass kMemoryFromPass on). Every half-space contains the
/// cone, so the rows are a relaxation of the cone. The Hessian gains, per cone that was
/// active in the previous pass (multiplier λ > 0 at tangential force t⁰ ≠ 0, d = t⁰/‖t⁰‖),
///     κ (I − d dᵀ) on (t1, t2),   κ = min(λ / ‖t⁰‖, kCurvatureCap·max H_ii),
/// the Hessian of λ‖t‖ at t⁰ (the cone's term in the Lagrangian). Since (I − d dᵀ) t⁰ = 0,
/// the gradient is unchanged and the pass is the SQP (Newton) step on the KKT conditions
/// of the cone problem from the previous answer: the tangent half-space is the cone's
/// linearisation there, the curvature term its second-order part.
///
/// Convergence test, per cone, after a pass with answer t:
///  - feasibility: gap = ‖t‖ − max_j d_jᵀ t ≤ cone_tolerance · max(1, ‖t‖) (the cone holds
///    to the half-spaces' accuracy; 0 at the apex t = 0, which the square enforces at n = 0);
///  - stationarity: the forces that the cone itself would not exert are negligible,
///        κ |(I − d dᵀ) t| + Σ_j u_j |d_j × t/‖t‖| ≤ kStationarityTolerance · (1 + λ)
///    (u_j the half-spaces' multipliers; the second term is skipped at the apex, where any
///    combination is a cone multiplier). Feasibility alone is not enough: an answer at the
///    vertex of two half-spaces θ apart violates the cone by ½θ²‖t‖ but is O(θ) from the
///    optimum, so a gap of 1e-12 would still allow ~1e-6 N of error.
/// When every cone passes both, the pass's KKT conditions are those of the cone problem
/// (the active half-space is the cone's gradient at t, the curvature term vanishes with
/// its gradient) and, the problem being convex, the answer is its optimum. Otherwise each
/// cone turns to d = t/‖t‖ and the next pass runs.
///
/// Why it terminates, and converges. Each pass is one exact QP solve (finite: the
/// active-set method ends on every problem), and the passes are bounded by max_passes.
/// Near the answer the passes are Newton's method on the smooth KKT system of the active
/// cones (t ≠ 0), so the angle between successive directions is squared at every pass:
/// two to four passes per sample on the paper run, warm-started from the previous sample's
/// directions and multipliers. Far from it the square keeps the iterates bounded, cones
/// that were inactive enter with a plain tangent half-space (Kelley's cutting plane), and
/// from pass kMemoryFromPass on the remembered tangents make the outer approximation
/// shrink monotonically, so that passes cannot cycle between a few directions (which they
/// do for μ = 0.001 when the curvature is capped). A remembered tangent that holds t at a
/// vertex once t is on the cone has done its work and is dropped, or the passes would
/// creep linearly. A sample that has not converged within max_passes is returned flagged
/// (status 1, "approximate: outer approximation of <cone> converged only to ..."); none on
/// the paper run and the smoke sweep.
///
/// Relaxation. The pass QPs are solved by the active-set back end with the problem's
/// slack semantics; a cone's half-spaces carry the cone's weight, so a cone that gives way
/// has its tangent half-space violated with multiplier ρ w, the exact L1 penalty of the
/// cone violation ‖t‖ − μ n (at convergence the tangent's violation is the cone's). That
/// is exact only if no other half-space of the same cone is violated at the answer (two
/// violated half-spaces count the penalty twice): a cone giving way remembers no tangents,
/// and any other half-space of it found violated in a penalised pass is dropped for the
/// rest of the sample. The status and message are computed on the posed problem
/// (describe_violations), so rows and cones carry the problem's names.
#include "hexdyn/allocation/cone_backend.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/friction.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

/// Half-spaces per cone: the current tangent (slot 0), a fixed square around the apex
/// (slots 1–4) and the last three tangents (slots 5–7, a ring).
constexpr int kCutsPerCone = 8;
constexpr int kFirstMemory = 5;
/// Tangents are remembered from this pass on: the Newton passes alone converge in two or
/// three passes where they converge; remembering earlier would pin the iterates to vertices
/// of old half-spaces (a bisection, linear), later lets a cycle run too long.
constexpr int kMemoryFromPass = 4;
/// κ ≤ kCurvatureCap · max H_ii: at a cone that gives way λ = ρ w (up to 1e9), and the
/// uncapped term would make H ill-conditioned; a capped κ only slows the Newton step there.
constexpr double kCurvatureCap = 1e8;
constexpr double kInf = std::numeric_limits<double>::infinity();
/// A pass has converged at a cone with curvature κ when κ |(I − d dᵀ) t| ≤ this times
/// (1 + λ), λ the multiplier κ was built from.
constexpr double kStationarityTolerance = 1e-10;
/// ‖t‖ at or below this times max(1, μ n) counts as the apex.
constexpr double kApex = 1e-12;

class ConeBackend final : public AllocationBackend {
 public:
  explicit ConeBackend(const ConeOptions& options)
      : opt_(options), qp_(make_active_set_backend(options.qp)) {
    if (!(opt_.cone_tolerance > 0.0) || opt_.max_passes < 1) {
      std::ostringstream os;
      os << "cone options: cone_tolerance must be > 0 and max_passes >= 1, got "
         << opt_.cone_tolerance << ", " << opt_.max_passes;
      throw ConfigError(os.str());
    }
  }

 private:
  double feasibility_tol() const { return qp_feasibility_tolerance(opt_.qp.tolerance); }

  /// Same sizes, names and cone indices as the previous problem. A query.
  bool same_structure(const QpProblem& p) const {
    const int n_cones = static_cast<int>(p.cones.size());
    bool same = n_ == p.variables() && m_eq_ == p.equalities() && m_in_ == p.inequalities() &&
                n_cones == static_cast<int>(dir_.size()) && p.eq_names == eq_names_ &&
                p.ineq_names == ineq_names_;
    for (int k = 0; same && k < n_cones; ++k) {
      const SecondOrderCone& c = p.cones[k];
      same = c.tangent1 == cone_index_[3 * k] && c.tangent2 == cone_index_[3 * k + 1] &&
             c.normal == cone_index_[3 * k + 2];
    }
    return same;
  }

  /// Takes p's structure as the current one, with fresh per-cone state.
  void remember_structure(const QpProblem& p) {
    const int n_cones = static_cast<int>(p.cones.size());
    n_ = p.variables(), m_eq_ = p.equalities(), m_in_ = p.inequalities();
    eq_names_ = p.eq_names;
    ineq_names_ = p.ineq_names;
    cone_index_.resize(static_cast<std::size_t>(3 * n_cones));
    for (int k = 0; k < n_cones; ++k) {
      cone_index_[3 * k] = p.cones[k].tangent1;
      cone_index_[3 * k + 1] = p.cones[k].tangent2;
      cone_index_[3 * k + 2] = p.cones[k].normal;
    }
    dir_.assign(static_cast<std::size_t>(n_cones), Eigen::Vector2d::UnitX());
    lambda_.assign(static_cast<std::size_t>(n_cones), 0.0);
    norm_.assign(static_cast<std::size_t>(n_cones), 0.0);
    kappa_.assign(static_cast<std::size_t>(n_cones), 0.0);
    cut_.assign(static_cast<std::size_t>(n_cones), {});
    on_.assign(static_cast<std::size_t>(n_cones), {});
    next_memory_.assign(static_cast<std::size_t>(n_cones), kFirstMemory);
  }

  /// Copies the posed problem into the working one (sizes set once per structure; its row
  /// names are not read, messages being built on the posed problem; structural key 0, so that
  /// the pass solver's warm start goes by the sizes), the cones' rows appended.
  void load_working(const QpProblem& p) {
    copy_problem_values(p, w_, kCutsPerCone * static_cast<int>(p.cones.size()), 0);
    max_diag_ = 0.0;
    for (int i = 0; i < p.variables(); ++i) max_diag_ = std::max(max_diag_, std::abs(p.H(i, i)));
  }

  /// Half-spaces and curvature of every cone for the next pass, from dir_, lambda_, norm_.
  void set_cones(const QpProblem& p) {
    const int m_in = p.inequalities();
    w_.H = p.H;
    for (std::size_t k = 0; k < p.cones.size(); ++k) {
      const SecondOrderCone& c = p.cones[k];
      const Eigen::Vector2d& d = dir_[k];
      cut_[k][0] = d;
      const int first = m_in + kCutsPerCone * static_cast<int>(k);
      const auto cut = [&](int j) { return FrictionFace{cut_[k][j].x(), cut_[k][j].y(), c.mu}; };
      write_cone_faces(c, first, kCutsPerCone, cut, nullptr, w_);
      for (int j = 1; j < kCutsPerCone; ++j)
        if (!on_[k][j]) w_.upper[first + j] = kInf;
      double kappa = 0.0;
      if (lambda_[k] > 0.0 && norm_[k] > 0.0)
        kappa = std::min(lambda_[k] / norm_[k], kCurvatureCap * std::max(max_diag_, 1e-12));
      kappa_[k] = kappa;
      if (kappa > 0.0) {
        // κ (I − d dᵀ) on (t1, t2), both triangles (the back end reads the lower one).
        const double a = kappa * (1.0 - d.x() * d.x()), b = -kappa * d.x() * d.y(),
                     e = kappa * (1.0 - d.y() * d.y());
        w_.H(c.tangent1, c.tangent1) += a;
        w_.H(c.tangent2, c.tangent2) += e;
        w_.H(c.tangent1, c.tangent2) += b;
        w_.H(c.tangent2, c.tangent1) += b;
      }
    }
  }

  void fail(const QpProblem& p, const std::string& why) {
    qp_fail_with_fallback(p, feasibility_tol(), why, out_);
    have_directions_ = false;
  }

  /// Refuses a problem too large for the active-set back end once the cones' half-spaces
  /// are added.
  static void check_sizes(const QpProblem& p) {
    const int n = p.variables();
    const int rows =
        p.equalities() + p.inequalities() + kCutsPerCone * static_cast<int>(p.cones.size());
    if (n > kActiveSetMaxVariables || rows > kActiveSetMaxRows) {
      std::ostringstream os;
      os << "cone back end: variables (at most " << kActiveSetMaxVariables << ") and rows + "
         << kCutsPerCone << " per cone (at most " << kActiveSetMaxRows << "): got " << n << " and "
         << rows;
      throw SolverError(os.str());
    }
  }

  /// The sample's starting point: the structure taken (fresh per-cone state when it
  /// changed), the directions of the previous sample kept as a warm start or reset to the
  /// t1 axis, the square around the apex around them, and the posed problem loaded.
  void start_sample(const QpProblem& p) {
    const int n_cones = static_cast<int>(p.cones.size());
    const bool same = same_structure(p);
    if (!same) remember_structure(p);
    if (!same || !have_directions_ || !opt_.warm_start) {
      qp_->reset_warm_start();
      for (int k = 0; k < n_cones; ++k) {
        dir_[k] = Eigen::Vector2d::UnitX();
        lambda_[k] = norm_[k] = 0.0;
      }
    }
    for (int k = 0; k < n_cones; ++k) {
      // The square around the apex, fixed for this sample; no remembered tangents yet.
      const Eigen::Vector2d d = dir_[k];
      cut_[k][1] = -d;
      cut_[k][2] = Eigen::Vector2d(-d.y(), d.x());
      cut_[k][3] = Eigen::Vector2d(d.y(), -d.x());
      cut_[k][4] = d;
      for (int j = 0; j < kCutsPerCone; ++j) on_[k][j] = j < kFirstMemory;
      next_memory_[k] = kFirstMemory;
    }
    load_working(p);
  }

  /// What the convergence test of the passes found.
  struct PassReview {
    bool converged = false;  ///< every cone passed (last pass)
    double worst_gap = 0.0;  ///< the largest miss of the last pass, relative
    int worst_cone = 0;      ///< whose (kept from an earlier pass when none missed)
    /// ½ Σ κ |(I − d dᵀ) t|² of the last pass: not in the posed objective.
    double curvature_term = 0.0;
  };

  /// Multiplier of cone k's half-spaces together (≥ 0 when they push) in a pass's answer.
  static double cone_multiplier(const QpOutcome& r, int m_in, int k) {
    double lam = 0.0;
    for (int j = 0; j < kCutsPerCone; ++j) lam -= r.lambda_ineq[m_in + kCutsPerCone * k + j];
    return lam;
  }

  /// Cone k's spurious stationarity force at tangential force t = (t1, t2) of norm `norm`:
  /// the curvature term's κ |(I − d dᵀ) t| (across) and, away from the apex, each active
  /// half-space's Σ u_j |d_j × t/‖t‖|. Drops the remembered half-spaces that hold t at a
  /// vertex once t is on the cone.
  double spurious_force(const QpProblem& p, const QpOutcome& r, int k, double t1, double t2,
                        double norm, double gap, double across) {
    const SecondOrderCone& c = p.cones[k];
    const int m_in = p.inequalities();
    // The curvature term's gradient κ (I − d dᵀ) t is a spurious force in the pass's
    // stationarity: negligible only once t has turned onto d (to ~1e-10 rad), which is
    // stricter than the gap (½‖t‖·angle²) where κ > 0.
    double spurious = kappa_[k] * std::abs(across);
    // Likewise each active half-space whose normal is not the cone's gradient at t
    // (an answer at the vertex of two half-spaces a small angle θ apart violates the
    // cone by only ½θ²‖t‖ but is off the optimum by O(θ)): Σ u_j |d_j × t/‖t‖|. At the
    // apex any combination of half-spaces is a valid cone multiplier.
    if (norm > kApex * std::max(1.0, std::abs(c.mu * r.x[c.normal]))) {
      const bool on_cone = gap <= opt_.cone_tolerance * std::max(1.0, norm);
      for (int j = 0; j < kCutsPerCone; ++j) {
        const double u = -r.lambda_ineq[m_in + kCutsPerCone * k + j];
        if (!(u > 0.0)) continue;
        const double off = u * std::abs(cut_[k][j].x() * t2 - cut_[k][j].y() * t1) / norm;
        spurious += off;
        // t sits on the cone at a vertex of the current tangent and an older half-space,
        // which holds it there (the passes would creep, linearly): the older one has
        // done its work (bounding the iterates) and is dropped for this sample.
        if (j >= kFirstMemory && on_cone && off > kStationarityTolerance * (1.0 + lambda_[k]))
          on_[k][j] = false;
      }
    }
    return spurious;
  }

  /// Cone k after pass number `passes` with answer r: its convergence test (into review),
  /// the half-spaces dropped or remembered, and its direction, multiplier and ‖t‖ for the
  /// next pass.
  void review_cone(const QpProblem& p, const QpOutcome& r, int k, int passes, PassReview& review) {
    const SecondOrderCone& c = p.cones[k];
    const int m_in = p.inequalities();
    const double t1 = r.x[c.tangent1], t2 = r.x[c.tangent2];
    const double norm = std::hypot(t1, t2);
    const Eigen::Vector2d& d = dir_[k];
    double support = -kInf;
    for (int j = 0; j < kCutsPerCone; ++j)
      if (j == 0 || on_[k][j])
        support = std::max(support, cut_[k][j].x() * t1 + cut_[k][j].y() * t2);
    const double gap = norm - support;
    const double across = d.x() * t2 - d.y() * t1;  // |(I − d dᵀ) t|, signed
    review.curvature_term += 0.5 * kappa_[k] * across * across;
    const double lam = cone_multiplier(r, m_in, k);
    // Another half-space of this cone violated at a penalised answer would count the
    // cone's penalty twice: it is dropped for the rest of the sample.
    if (r.status == SolverStatus::kRelaxed) {
      for (int j = 1; j < kCutsPerCone; ++j) {
        if (on_[k][j] &&
            cut_[k][j].x() * t1 + cut_[k][j].y() * t2 - c.mu * r.x[c.normal] > feasibility_tol()) {
          on_[k][j] = false;
          review.converged = false;
        }
      }
    }
    const double spurious = spurious_force(p, r, k, t1, t2, norm, gap, across);
    if (gap > opt_.cone_tolerance * std::max(1.0, norm) ||
        spurious > kStationarityTolerance * (1.0 + lambda_[k])) {
      review.converged = false;
      const double miss = std::max(gap / std::max(1.0, norm), spurious / (1.0 + lambda_[k]));
      if (miss > review.worst_gap) review.worst_gap = miss, review.worst_cone = k;
    }
    // A cone giving way (its tangent half-space violated, penalised) is followed by the
    // Newton passes alone: remembered tangents near its direction would be violated too.
    const bool giving_way = d.x() * t1 + d.y() * t2 - c.mu * r.x[c.normal] > feasibility_tol();
    if (passes >= kMemoryFromPass && norm > 0.0 && !giving_way &&
        !(gap <= opt_.cone_tolerance * std::max(1.0, norm))) {
      // Remember this pass's tangent (Kelley's cutting plane: the half-spaces only
      // accumulate, so the passes cannot cycle between the same few), then turn.
      int& m = next_memory_[k];
      cut_[k][m] = d;
      on_[k][m] = true;
      m = m + 1 < kCutsPerCone ? m + 1 : kFirstMemory;
    }
    if (norm > 0.0) dir_[k] = Eigen::Vector2d(t1 / norm, t2 / norm);
    lambda_[k] = std::max(lam, 0.0);
    norm_[k] = norm;
  }

  /// The answer of the last pass r (after `passes` passes), on the posed problem: solution,
  /// multipliers (one per cone), objective without the curvature term, status and message.
  void answer(const QpProblem& p, const QpOutcome& r, const PassReview& review, int passes) {
    const int m_in = p.inequalities();
    const int n_cones = static_cast<int>(p.cones.size());
    out_.x = r.x;
    out_.lambda_eq = r.lambda_eq;
    out_.lambda_ineq = r.lambda_ineq.head(m_in);
    out_.lambda_cone.resize(n_cones);
    for (int k = 0; k < n_cones; ++k) out_.lambda_cone[k] = cone_multiplier(r, m_in, k);
    out_.objective = r.objective - review.curvature_term;
    const std::string v = describe_violations(p, out_.x, feasibility_tol(), &out_.max_violation);
    have_directions_ = true;
    if (!review.converged) {
      const SecondOrderCone& worst = p.cones[review.worst_cone];
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "outer approximation of %s converged only to %.3g after %d passes",
                    worst.name.empty() ? "a cone" : worst.name.c_str(), review.worst_gap, passes);
      out_.status = SolverStatus::kRelaxed;
      out_.message =
          v.empty() ? std::string("approximate: ") + buf : "relaxed: " + v + " (" + buf + ")";
      return;
    }
    if (v.empty()) {
      out_.status = SolverStatus::kOptimal;
      if (r.status == SolverStatus::kOptimal)
        out_.message = r.message;  // e.g. a regularisation note
    } else {
      out_.status = SolverStatus::kRelaxed;
      out_.message = "relaxed: " + v;
    }
  }

 public:
  void reset_warm_start() override {
    have_directions_ = false;
    qp_->reset_warm_start();
  }

 private:
  void solve_impl(const QpProblem& p) override {
    if (p.cones.empty()) {
      out_ = qp_->solve(p);
      return;
    }
    check_sizes(p);
    out_.iterations = 0;
    out_.message.clear();
    if (const std::string bad = qp_first_non_finite(p); !bad.empty()) {
      fail(p, "non-finite entries in " + bad);
      return;
    }
    start_sample(p);
    const QpOutcome* r = nullptr;
    PassReview review;
    int passes = 0;
    while (!review.converged && passes < opt_.max_passes) {
      set_cones(p);
      r = &qp_->solve(w_);
      ++passes;
      out_.iterations += r->iterations;
      if (r->status == SolverStatus::kFailed) {
        fail(p, "pass " + std::to_string(passes) + " of the outer approximation: " + r->message);
        return;
      }
      review.converged = true;
      review.worst_gap = 0.0;
      review.curvature_term = 0.0;
      for (int k = 0; k < static_cast<int>(p.cones.size()); ++k)
        review_cone(p, *r, k, passes, review);
    }
    answer(p, *r, review, passes);
  }

  ConeOptions opt_;
  std::unique_ptr<AllocationBackend> qp_;
  QpProblem w_;  ///< working problem: the posed rows, then kCutsPerCone rows per cone
  double max_diag_ = 0.0;
  // Structure of the previous problem.
  int n_ = -1, m_eq_ = -1, m_in_ = -1;
  std::vector<std::string> eq_names_, ineq_names_;
  std::vector<int> cone_index_;
  // Per cone: tangential direction, multiplier and ‖t‖ of the last pass, curvature used,
  // whether the frame half-spaces are on.
  std::vector<Eigen::Vector2d> dir_;
  std::vector<double> lambda_, norm_, kappa_;
  std::vector<std::array<Eigen::Vector2d, kCutsPerCone>> cut_;  ///< half-space directions
  std::vector<std::array<bool, kCutsPerCone>> on_;              ///< which are in force
  std::vector<int> next_memory_;                                ///< next ring slot
  /// The warm start of the next sample of the same structure: dir_, lambda_ and norm_ hold
  /// the last sample's answer.
  bool have_directions_ = false;
};

}  // namespace

ConeOptions cone_options_from(const AllocationParams& params) {
  ConeOptions o;
  o.qp = active_set_options_from(params);
  return o;
}

std::unique_ptr<AllocationBackend> make_cone_backend(const ConeOptions& options) {
  return std::make_unique<ConeBackend>(options);
}

}  // namespace hexdyn
