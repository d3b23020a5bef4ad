/// \file allocation/ipopt_backend.cpp
/// The Ipopt back end of the allocation (allocation/qp.hpp); the TNLP adapter that poses
/// the problem to Ipopt is in allocation/ipopt_nlp.cpp.
///
/// The attempts follow the policy of allocation/strict_then_penalised.hpp. The strict
/// attempt is warm-started from the last strict solution (point and multipliers) when the
/// problem's shape matches, and retried cold if that fails. If Ipopt does not converge, or
/// its answer violates a row, the problem is solved again with penalised slack variables
/// (docs/theory/allocation.md#exact-l1-penalty): each inequality row gets s⁺_i ≥ 0 if its lower
/// bound is finite and s⁻_i ≥ 0 if its upper bound is,
///     lower_i ≤ C_i x + s⁺_i − s⁻_i ≤ upper_i,
/// each cone k gets s_k ≥ 0 with √(t1² + t2²) ≤ μ n + s_k, and the objective gains the
/// exact L1 penalty ρ (Σ w_i (s⁺_i + s⁻_i) + Σ w_k s_k) (weights from the problem, slacks
/// in row units). Equality rows stay hard. One constraint per row with two slacks keeps
/// the constraint gradients independent where an l = u row holds exactly; two one-sided
/// rows sharing a slack do not, and Ipopt then stalls near the solution. (A row with
/// lower > upper does become two one-sided rows: Ipopt rejects crossed bounds.)
/// After a relaxed solve, the next problem of the same sizes goes to the penalised form
/// directly (the policy): Ipopt spends many iterations before it declares a problem
/// infeasible.
/// With cones, the penalised problem is first solved with each cone replaced by its
/// inscribed 16-gon (a QP), whose solution starts the penalised cone NLP and stands in for
/// it (flagged) if that fails. A run that stalls (e.g. Restoration_Failed) is accepted when
/// Ipopt's optimality error at its last point is within the acceptable tolerance.
///
/// Ipopt form. Variables (x, s). Constraints, in order: equality rows; the inequality rows
/// (with their slacks in the penalised form, rows without a finite bound left out); one
/// row per cone,
///     μ n (+ s) − (√(t1² + t2² + ε²) − ε) ≥ 0,
/// a smooth form of the cone (ε = IpoptOptions::cone_smoothing_N). It implies μ n (+ s) ≥ 0,
/// is exact at the apex, admits at most ε of tangential excess elsewhere, and its gradient
/// never vanishes (∂/∂n = μ), so a solution at the apex (an unloaded foot) has multipliers;
/// the squared form μ²n² − t² ≥ 0 has none there.
/// Ipopt's Lagrangian is f + λᵀ g, so hexdyn's multipliers are −λ_ipopt.
#include "hexdyn/allocation/ipopt_backend.hpp"

#include <Eigen/Dense>
#include <IpIpoptApplication.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hexdyn/allocation/friction.hpp"
#include "hexdyn/allocation/ipopt_nlp.hpp"
#include "hexdyn/allocation/strict_then_penalised.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

using ipopt_nlp::Mode;
using ipopt_nlp::QpTnlp;
using ipopt_nlp::RelaxedRow;

const char* return_status_name(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
      return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates:
      return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop:
      return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found:
      return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed:
      return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation:
      return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option:
      return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected:
      return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception:
      return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory:
      return "Insufficient_Memory";
    case Ipopt::Internal_Error:
      return "Internal_Error";
  }
  return "unknown Ipopt status";
}

bool succeeded(Ipopt::ApplicationReturnStatus s) {
  return s == Ipopt::Solve_Succeeded || s == Ipopt::Solved_To_Acceptable_Level;
}

/// Statuses after which the returned point may still be optimal to a looser tolerance:
/// near a degenerate optimum Ipopt sometimes stalls after it has converged in practice.
bool stalled(Ipopt::ApplicationReturnStatus s) {
  return s == Ipopt::Search_Direction_Becomes_Too_Small || s == Ipopt::Restoration_Failed ||
         s == Ipopt::Maximum_Iterations_Exceeded || s == Ipopt::Error_In_Step_Computation ||
         s == Ipopt::Maximum_CpuTime_Exceeded;
}

class IpoptBackend final : public StrictThenPenalisedBackend {
 public:
  explicit IpoptBackend(const IpoptOptions& options) : opt_(options) {
    if (!(opt_.tolerance > 0.0) || !(opt_.slack_penalty > 0.0) || opt_.max_iterations < 1 ||
        !(opt_.max_cpu_seconds > 0.0) || !(opt_.cone_smoothing_N > 0.0) ||
        !(opt_.dual_inf_tol > 0.0)) {
      std::ostringstream os;
      os << "Ipopt options: tolerance, slack_penalty, max_cpu_seconds, cone_smoothing_N, "
            "dual_inf_tol must be > 0 and max_iterations >= 1, got "
         << opt_.tolerance << ", " << opt_.slack_penalty << ", " << opt_.max_cpu_seconds << ", "
         << opt_.cone_smoothing_N << ", " << opt_.dual_inf_tol << ", " << opt_.max_iterations;
      throw ConfigError(os.str());
    }
    app_ = IpoptApplicationFactory();
    Ipopt::OptionsList& o = *app_->Options();
    o.SetIntegerValue("print_level", 0);
    o.SetStringValue("sb", "yes");
    o.SetStringValue("hessian_approximation", "exact");
    o.SetNumericValue("acceptable_tol", acceptable_tol());
    o.SetNumericValue("acceptable_constr_viol_tol", acceptable_tol());
    o.SetIntegerValue("max_iter", opt_.max_iterations);
    o.SetNumericValue("max_cpu_time", opt_.max_cpu_seconds);
    o.SetStringValue("linear_solver", opt_.linear_solver);
    o.SetStringValue("jac_c_constant", "yes");
    // Rows are limits such as ±6 N·m: keep them exact rather than relaxed by 1e-8 relative.
    o.SetNumericValue("bound_relax_factor", 0.0);
    // The empty parameter-file name keeps a stray ipopt.opt in the working directory out.
    const Ipopt::ApplicationReturnStatus st = app_->Initialize("");
    if (st != Ipopt::Solve_Succeeded)
      throw SolverError(std::string("Ipopt initialisation failed: ") + return_status_name(st));
    tnlp_ = new QpTnlp();
  }

 private:
  /// Feasibility threshold of a row for the status (allocation/qp.hpp).
  double feasibility_tol() const override { return qp_feasibility_tolerance(opt_.tolerance); }

  bool can_warm_start(const ProblemShape& shape) const override {
    return opt_.warm_start && start_.valid && start_.shape == shape;
  }
  void drop_warm_start() override { start_.valid = false; }
  /// Keeps x and the TNLP's multipliers as the warm start of the next problem of p's shape.
  void store_start(const QpProblem& p, const Eigen::VectorXd& x) {
    start_.valid = true;
    start_.shape = ProblemShape::of(p);
    start_.x = x;
    start_.lambda = tnlp_->lambda_out;
  }

  /// Options that differ between runs. Penalised runs have multipliers ρ w up to 1e9, to
  /// which Ipopt scales its optimality test, and their optima are often degenerate (rows
  /// that hold with a zero multiplier at an impact foot's friction polygon): an interior
  /// point then sits ~√(complementarity) inside such a row. They therefore also get an
  /// absolute complementarity tolerance of 1e-3·tolerance, which brings their forces to
  /// within ~2e-6 N of the exact penalised optimum on the paper run
  /// (docs/validation/allocation.md#active-set-against-ipopt-friction-pyramids).
  void set_per_solve_options(bool linear_constraints, bool warm, bool penalised) {
    Ipopt::OptionsList& o = *app_->Options();
    const double tol = opt_.tolerance;
    o.SetNumericValue("tol", tol);
    o.SetNumericValue("constr_viol_tol", tol);
    o.SetNumericValue("compl_inf_tol", penalised ? 1e-3 * tol : 1e-4);
    o.SetNumericValue("dual_inf_tol", opt_.dual_inf_tol);
    o.SetStringValue("jac_d_constant", linear_constraints ? "yes" : "no");
    o.SetStringValue("hessian_constant", linear_constraints ? "yes" : "no");
    if (warm) {
      o.SetStringValue("warm_start_init_point", "yes");
      o.SetNumericValue("warm_start_bound_push", 1e-9);
      o.SetNumericValue("warm_start_bound_frac", 1e-9);
      o.SetNumericValue("warm_start_slack_bound_push", 1e-9);
      o.SetNumericValue("warm_start_slack_bound_frac", 1e-9);
      o.SetNumericValue("warm_start_mult_bound_push", 1e-9);
      o.SetNumericValue("mu_init", 1e-6);
    } else {
      o.SetStringValue("warm_start_init_point", "no");
      o.SetNumericValue("mu_init", 0.1);
    }
  }

  /// Runs Ipopt on the configured TNLP (the application and its options persist; the
  /// algorithm objects are rebuilt, which costs little next to the factorisations).
  Ipopt::ApplicationReturnStatus run(int& iterations) {
    Ipopt::ApplicationReturnStatus st = Ipopt::Internal_Error;
    try {
      st = app_->OptimizeTNLP(tnlp_);
    } catch (...) {
      st = Ipopt::NonIpopt_Exception_Thrown;
    }
    iterations += tnlp_->finalized ? tnlp_->iterations_out : 0;
    return st;
  }

  /// Multipliers of the first m_in inequality rows and of the cones of the configured
  /// problem, in hexdyn's sign (rows beyond m_in, the polygon faces, are dropped).
  void fill_multipliers(int m_in, bool with_cones) {
    QpTnlp& t = *tnlp_;
    const Eigen::VectorXd& lam = t.lambda_out;
    out_.lambda_eq = -lam.head(t.m_eq);
    out_.lambda_ineq.setZero(m_in);
    if (t.mode == Mode::kStrict) {
      out_.lambda_ineq = -lam.segment(t.m_eq, m_in);
    } else {
      for (std::size_t q = 0; q < t.relaxed.size(); ++q)
        if (t.relaxed[q].row < m_in)
          out_.lambda_ineq[t.relaxed[q].row] -= lam[t.m_eq + static_cast<int>(q)];
    }
    out_.lambda_cone.setZero(static_cast<int>(t.p->cones.size()));
    if (with_cones)
      for (int k = 0; k < t.n_cones; ++k) out_.lambda_cone[k] = -lam[t.first_cone_row() + k];
  }

  Attempt solve_strict(const QpProblem& p, bool warm) override {
    const int n = p.variables(), m_in = p.inequalities();
    const bool linear = p.cones.empty();
    QpTnlp& t = *tnlp_;
    t.finalized = false;
    Attempt a;
    // Warm if possible; a failed warm start is retried cold.
    for (const bool use_warm : {true, false}) {
      if (use_warm && !warm) continue;
      t.setup(p, Mode::kStrict, opt_.slack_penalty, opt_.cone_smoothing_N);
      if (use_warm) {
        t.start_x = start_.x;
        t.start_multipliers = true;
        t.start_lambda = start_.lambda;
        t.start_z_lower.setZero(n);
      } else {
        t.start_x = qp_fallback_point(p);
        t.start_multipliers = false;
      }
      set_per_solve_options(linear, use_warm, false);
      const Ipopt::ApplicationReturnStatus st = run(out_.iterations);
      if (!a.note.empty()) a.note += ", then cold ";
      a.note += return_status_name(st);
      if (!run_usable(st)) {
        // Linear constraints that Ipopt finds infeasible are infeasible from any start.
        if (linear && st == Ipopt::Infeasible_Problem_Detected) break;
        continue;
      }
      const Eigen::VectorXd x = t.x_out.head(n);
      double viol = 0.0;
      const std::string v = describe_violations(p, x, feasibility_tol(), &viol);
      if (!v.empty()) {
        a.note += " but violated " + v;
        continue;
      }
      out_.status = SolverStatus::kOptimal;
      out_.x = x;
      fill_multipliers(m_in, true);
      out_.objective = p.objective(x);
      out_.max_violation = viol;
      if (!succeeded(st) || st == Ipopt::Solved_To_Acceptable_Level)
        out_.message = acceptable_note(st);
      store_start(p, x);
      a.solved = true;
      return a;
    }
    drop_warm_start();
    a.left_state = t.finalized;
    return a;
  }

  Attempt solve_penalised(const QpProblem& p, const AttemptPlan& plan, bool after_strict) override {
    const int n = p.variables();
    QpTnlp& t = *tnlp_;
    // Start from the strict run's last point, or after a skipped strict run from the
    // previous (relaxed) sample's solution.
    const Eigen::VectorXd x0 = after_strict && t.x_out.allFinite() && t.x_out.size() >= n
                                   ? Eigen::VectorXd(t.x_out.head(n))
                               : !plan.strict && out_.x.size() == n && out_.x.allFinite()
                                   ? out_.x
                                   : qp_fallback_point(p);
    Attempt a;
    if (p.cones.empty()) {
      const Ipopt::ApplicationReturnStatus st = run_slack(p, x0);
      if (!run_usable(st)) {
        a.note = std::string("penalised solve ") + return_status_name(st);
        return a;
      }
      finish_relaxed(p, true, "");
      a.solved = true;
      return a;
    }
    // With cones the penalised NLP is hard for Ipopt from a poor start (iterates stall near
    // the apex of cones of unloaded feet). First solve the penalised QP with every cone
    // replaced by an inscribed polygon, then the penalised cone NLP from its solution; if
    // the latter fails, the polygon solution (inside the cones) is the answer.
    build_polygon_problem(p, poly_);
    const Ipopt::ApplicationReturnStatus st_poly = run_slack(poly_, x0);
    const bool poly_ok = run_usable(st_poly);
    if (poly_ok) poly_x_ = t.x_out.head(n);
    const Ipopt::ApplicationReturnStatus st_cone = run_slack(p, poly_ok ? poly_x_ : x0);
    if (run_usable(st_cone)) {
      finish_relaxed(p, true, "");
      a.solved = true;
      return a;
    }
    if (!poly_ok) {
      a.note = std::string("penalised polygon solve ") + return_status_name(st_poly) +
               "; penalised cone solve " + return_status_name(st_cone);
      return a;
    }
    run_slack(poly_, poly_x_);  // restores the polygon solution and its multipliers
    finish_relaxed(p, false,
                   std::string("cones replaced by inscribed ") + std::to_string(kPolygonFaces) +
                       "-gons, the penalised cone solve ended with " + return_status_name(st_cone));
    a.solved = true;
    return a;
  }

  /// Ipopt's point is an answer: converged, or stalled with its optimality error within the
  /// acceptable tolerance.
  bool run_usable(Ipopt::ApplicationReturnStatus st) const {
    const QpTnlp& t = *tnlp_;
    if (!(t.finalized && t.x_out.allFinite() && t.lambda_out.allFinite())) return false;
    return succeeded(st) || (stalled(st) && t.nlp_error_out <= acceptable_tol());
  }
  double acceptable_tol() const { return std::max(1e-6, 1e3 * opt_.tolerance); }

  std::string acceptable_note(Ipopt::ApplicationReturnStatus st) const {
    std::ostringstream os;
    os.precision(2);
    os << "solved to Ipopt's acceptable level only (" << return_status_name(st)
       << ", optimality error " << tnlp_->nlp_error_out << ")";
    return os.str();
  }

  /// Configures and runs the penalised problem q from x_start (slacks start just above
  /// the violations there).
  Ipopt::ApplicationReturnStatus run_slack(const QpProblem& q, const Eigen::VectorXd& x_start) {
    QpTnlp& t = *tnlp_;
    const int n = q.variables();
    t.setup(q, Mode::kSlack, opt_.slack_penalty, opt_.cone_smoothing_N);
    t.start_x.resize(t.nv());
    t.start_x.head(n) = x_start;
    for (const RelaxedRow& rr : t.relaxed) {
      const double c = q.C.row(rr.row).dot(x_start);
      if (rr.plus >= 0) t.start_x[n + rr.plus] = std::max(0.0, q.lower[rr.row] - c) + 1e-2;
      if (rr.minus >= 0) t.start_x[n + rr.minus] = std::max(0.0, c - q.upper[rr.row]) + 1e-2;
    }
    for (int k = 0; k < t.n_cones; ++k) {
      const SecondOrderCone& c = q.cones[k];
      const double v =
          std::hypot(x_start[c.tangent1], x_start[c.tangent2]) - c.mu * x_start[c.normal];
      t.start_x[n + t.cone_slack(k)] = std::max(v, 0.0) + 1e-2;
    }
    t.start_multipliers = false;
    set_per_solve_options(q.cones.empty(), false, true);
    return run(out_.iterations);
  }

  /// Outcome of a successful penalised run on p (or on its polygon version).
  void finish_relaxed(const QpProblem& p, bool with_cones, const std::string& note) {
    const QpTnlp& t = *tnlp_;
    out_.x = t.x_out.head(p.variables());
    fill_multipliers(p.inequalities(), with_cones);
    out_.objective = p.objective(out_.x);
    const std::string v = describe_violations(p, out_.x, feasibility_tol(), &out_.max_violation);
    // The slack problem's iterate does not warm-start the next strict problem.
    drop_warm_start();
    if (v.empty() && note.empty()) {
      // No slack needed: by exactness of the penalty this is the strict optimum, but only
      // to the penalised run's tolerance, which Ipopt scales by its multipliers (up to ρ w).
      // Polish it by the problem as posed, warm-started from here.
      out_.status = SolverStatus::kOptimal;
      out_.message = "optimal to the penalised solve's tolerance only";
      polish_strict(p);
      return;
    }
    out_.status = SolverStatus::kRelaxed;
    out_.message = v.empty() ? "approximate: " + note
                             : "relaxed: " + v + (note.empty() ? "" : " (" + note + ")");
  }

  /// Solves p as posed, warm-started from the penalised run in the TNLP (point and
  /// multipliers); on success the outcome becomes that solution.
  void polish_strict(const QpProblem& p) {
    QpTnlp& t = *tnlp_;
    const int n = p.variables(), m_eq = p.equalities(), m_in = p.inequalities();
    const int n_cones = static_cast<int>(p.cones.size());
    polish_x_ = t.x_out.head(n);
    polish_lambda_.setZero(m_eq + m_in + n_cones);
    polish_lambda_.head(m_eq) = t.lambda_out.head(m_eq);
    for (std::size_t q = 0; q < t.relaxed.size(); ++q)
      polish_lambda_[m_eq + t.relaxed[q].row] += t.lambda_out[m_eq + static_cast<int>(q)];
    for (int k = 0; k < n_cones; ++k)
      polish_lambda_[m_eq + m_in + k] = t.lambda_out[t.first_cone_row() + k];
    t.setup(p, Mode::kStrict, opt_.slack_penalty, opt_.cone_smoothing_N);
    t.start_x = polish_x_;
    t.start_multipliers = true;
    t.start_lambda = polish_lambda_;
    t.start_z_lower.setZero(n);
    set_per_solve_options(p.cones.empty(), true, false);
    const Ipopt::ApplicationReturnStatus st = run(out_.iterations);
    if (!run_usable(st)) return;
    const Eigen::VectorXd x = t.x_out.head(n);
    double viol = 0.0;
    if (!describe_violations(p, x, feasibility_tol(), &viol).empty()) return;
    out_.x = x;
    fill_multipliers(m_in, true);
    out_.objective = p.objective(x);
    out_.max_violation = viol;
    out_.message = succeeded(st) && st != Ipopt::Solved_To_Acceptable_Level ? std::string()
                                                                            : acceptable_note(st);
    store_start(p, x);
  }

  /// p with every cone replaced by the kPolygonFaces rows of its inscribed polygon
  /// (allocation/friction.hpp), (t1, t2)·(cos a, sin a) − μ cos(π/N) n ≤ 0.
  static void build_polygon_problem(const QpProblem& p, QpProblem& poly) {
    const bool named =
        copy_problem_values(p, poly, kPolygonFaces * static_cast<int>(p.cones.size()), p.structure);
    int r = p.inequalities();
    for (std::size_t k = 0; k < p.cones.size(); ++k) {
      const SecondOrderCone& c = p.cones[k];
      const std::string name = c.name.empty() ? "cone[" + std::to_string(k) + "]" : c.name;
      const auto face = [&](int f) { return inscribed_friction_face(f, kPolygonFaces, c.mu); };
      r = write_cone_faces(c, r, kPolygonFaces, face, named ? &name : nullptr, poly);
    }
  }

  static constexpr int kPolygonFaces = kInscribedConeFaces;

  IpoptOptions opt_;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
  Ipopt::SmartPtr<QpTnlp> tnlp_;
  QpProblem poly_;          ///< penalised polygon version of a cone problem (workspace)
  Eigen::VectorXd poly_x_;  ///< its solution
  Eigen::VectorXd polish_x_, polish_lambda_;  ///< start of a polishing strict run
  /// The warm start: the last strict solution with its multipliers, and its problem's shape.
  struct {
    bool valid = false;
    ProblemShape shape;
    Eigen::VectorXd x, lambda;
  } start_;
};

}  // namespace

std::unique_ptr<AllocationBackend> make_ipopt_backend(const IpoptOptions& options) {
  return std::make_unique<IpoptBackend>(options);
}

IpoptOptions ipopt_options_from(const AllocationParams& params) {
  IpoptOptions o;
  o.tolerance = params.tolerance;
  o.slack_penalty = params.slack_penalty;
  return o;
}

}  // namespace hexdyn
