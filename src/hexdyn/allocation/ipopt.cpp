/// \file allocation_ipopt.cpp
/// The Ipopt back end of the allocation (allocation_qp.hpp).
///
/// Each solve tries the problem as posed ("strict"), warm-started from the previous
/// solution when the sizes match (and cold if that fails). If Ipopt does not converge, or
/// its answer violates a row, the problem is solved again with penalised slack variables
/// (DESIGN.md §3): each inequality row gets s⁺_i ≥ 0 if its lower bound is finite and
/// s⁻_i ≥ 0 if its upper bound is,
///     lower_i ≤ C_i x + s⁺_i − s⁻_i ≤ upper_i,
/// each cone k gets s_k ≥ 0 with √(t1² + t2²) ≤ μ n + s_k, and the objective gains the
/// exact L1 penalty ρ (Σ w_i (s⁺_i + s⁻_i) + Σ w_k s_k) (weights from the problem, slacks
/// in row units). Equality rows stay hard. One constraint per row with two slacks keeps
/// the constraint gradients independent where an l = u row holds exactly; two one-sided
/// rows sharing a slack do not, and Ipopt then stalls near the solution. (A row with
/// lower > upper does become two one-sided rows: Ipopt rejects crossed bounds.)
/// After a relaxed solve, the next problem of the same sizes goes to the penalised form
/// directly: infeasible samples come in runs, and Ipopt spends many iterations before it
/// declares a problem infeasible.
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
#include <Eigen/Dense>
#include <IpIpoptApplication.hpp>
#include <IpIpoptCalculatedQuantities.hpp>
#include <IpIpoptData.hpp>
#include <IpTNLP.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "hexdyn/allocation/ipopt.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr double kIpoptInf = 2e19;  // beyond Ipopt's nlp_{lower,upper}_bound_inf (±1e19)

enum class Mode { kStrict, kSlack };

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

double clamp_bound(double v) {
  if (!(v > -kQpInfinity)) return -kIpoptInf;
  if (!(v < kQpInfinity)) return kIpoptInf;
  return v;
}

/// An inequality row with its slacks (slack mode): lower ≤ C x + s⁺ − s⁻ ≤ upper.
struct RelaxedRow {
  int row = 0;
  int plus = -1;   ///< index of s⁺ among the slack variables, −1 without a lower bound
  int minus = -1;  ///< index of s⁻, −1 without an upper bound
  int slacks() const { return (plus >= 0) + (minus >= 0); }
};

/// The QP (strict or with slacks) in Ipopt's TNLP form. Reconfigured by `setup` before
/// every solve; the object itself lives as long as the backend.
class QpTnlp : public Ipopt::TNLP {
 public:
  // --- input, set by the backend before OptimizeTNLP ---
  const QpProblem* p = nullptr;
  Eigen::MatrixXd H;  ///< full symmetric H
  Mode mode = Mode::kStrict;
  std::vector<RelaxedRow> relaxed;   ///< slack mode: the rows with a finite bound
  int relaxed_slacks = 0;            ///< Σ slacks() over `relaxed`
  std::vector<double> slack_weight;  ///< ρ per slack variable
  int n = 0, n_slack = 0, m_eq = 0, m_in = 0, n_cones = 0;
  double eps = 1e-9;        ///< cone smoothing [N]
  Eigen::VectorXd start_x;  ///< n + n_slack
  bool start_multipliers = false;
  Eigen::VectorXd start_lambda;   ///< Ipopt multipliers of all constraints
  Eigen::VectorXd start_z_lower;  ///< n + n_slack

  // --- output, written by finalize_solution ---
  bool finalized = false;
  Eigen::VectorXd x_out;       ///< n + n_slack
  Eigen::VectorXd lambda_out;  ///< Ipopt sign
  Eigen::VectorXd z_lower_out;
  int iterations_out = 0;
  double nlp_error_out = 0.0;  ///< Ipopt's scaled optimality error at the returned point

  void setup(const QpProblem& problem, Mode m, double rho, double cone_eps) {
    p = &problem;
    eps = cone_eps;
    mode = m;
    n = problem.variables();
    m_eq = problem.equalities();
    m_in = problem.inequalities();
    n_cones = static_cast<int>(problem.cones.size());
    H = problem.H.selfadjointView<Eigen::Lower>();
    relaxed.clear();
    relaxed_slacks = 0;
    slack_weight.clear();
    n_slack = 0;
    if (mode == Mode::kSlack) {
      for (int i = 0; i < m_in; ++i) {
        const bool lo = problem.lower[i] > -kQpInfinity, up = problem.upper[i] < kQpInfinity;
        if (!lo && !up) continue;
        const double w = rho * (problem.ineq_penalty.size() ? problem.ineq_penalty[i] : 1.0);
        RelaxedRow rr;
        rr.row = i;
        if (lo) rr.plus = n_slack++, slack_weight.push_back(w);
        if (up) rr.minus = n_slack++, slack_weight.push_back(w);
        if (lo && up && problem.lower[i] > problem.upper[i]) {
          // Contradictory bounds: one constraint per side, or Ipopt rejects the bounds.
          relaxed.push_back({i, rr.plus, -1});
          relaxed.push_back({i, -1, rr.minus});
        } else {
          relaxed.push_back(rr);
        }
        relaxed_slacks += rr.slacks();
      }
      for (const SecondOrderCone& c : problem.cones) {
        slack_weight.push_back(rho * c.penalty);
        ++n_slack;
      }
    }
    finalized = false;
  }

  int cone_slack(int k) const { return n_slack - n_cones + k; }  // slack mode only
  int first_cone_row() const {
    return m_eq + (mode == Mode::kStrict ? m_in : static_cast<int>(relaxed.size()));
  }
  int constraints() const { return first_cone_row() + n_cones; }
  int nv() const { return n + n_slack; }
  int hess_x_entries() const { return n * (n + 1) / 2; }
  static int tri(int i, int j) { return i * (i + 1) / 2 + j; }  // i ≥ j

  bool get_nlp_info(Index& nv_out, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    nv_out = nv();
    m = constraints();
    const bool slack = mode == Mode::kSlack;
    nnz_jac_g = m_eq * n +
                (slack ? static_cast<int>(relaxed.size()) * n + relaxed_slacks : m_in * n) +
                n_cones * (slack ? 4 : 3);
    nnz_h_lag = hess_x_entries();
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index nv_in, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (Index j = 0; j < nv_in; ++j) {
      x_l[j] = j < n ? -kIpoptInf : 0.0;
      x_u[j] = kIpoptInf;
    }
    for (int i = 0; i < m_eq; ++i) g_l[i] = g_u[i] = p->b[i];
    int r = m_eq;
    if (mode == Mode::kStrict) {
      for (int i = 0; i < m_in; ++i, ++r) {
        g_l[r] = clamp_bound(p->lower[i]);
        g_u[r] = clamp_bound(p->upper[i]);
      }
    } else {
      for (const RelaxedRow& rr : relaxed) {
        g_l[r] = rr.plus >= 0 ? p->lower[rr.row] : -kIpoptInf;
        g_u[r] = rr.minus >= 0 ? p->upper[rr.row] : kIpoptInf;
        ++r;
      }
    }
    for (int k = 0; k < n_cones; ++k) {
      g_l[r] = 0.0;
      g_u[r++] = kIpoptInf;
    }
    return r == m;
  }

  bool get_starting_point(Index nv_in, bool init_x, Number* x, bool init_z, Number* z_L,
                          Number* z_U, Index m, bool init_lambda, Number* lambda) override {
    if (init_x) {
      if (start_x.size() != nv_in) return false;
      std::copy(start_x.data(), start_x.data() + nv_in, x);
    }
    if (init_z) {
      if (!start_multipliers || start_z_lower.size() != nv_in) return false;
      std::copy(start_z_lower.data(), start_z_lower.data() + nv_in, z_L);
      std::fill(z_U, z_U + nv_in, 0.0);
    }
    if (init_lambda) {
      if (!start_multipliers || start_lambda.size() != m) return false;
      std::copy(start_lambda.data(), start_lambda.data() + m, lambda);
    }
    return true;
  }

  /// √(t1² + t2² + ε²) of cone k.
  double smooth_norm(const Number* x, int k) const {
    const SecondOrderCone& c = p->cones[k];
    return std::sqrt(x[c.tangent1] * x[c.tangent1] + x[c.tangent2] * x[c.tangent2] + eps * eps);
  }

  double mu_n_plus_slack(const Number* x, int k) const {
    const SecondOrderCone& c = p->cones[k];
    double v = c.mu * x[c.normal];
    if (mode == Mode::kSlack) v += x[n + cone_slack(k)];
    return v;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj) override {
    Eigen::Map<const Eigen::VectorXd> xv(x, n);
    obj = 0.5 * xv.dot(H * xv) + p->g.dot(xv) + p->constant;
    for (int j = 0; j < n_slack; ++j) obj += slack_weight[j] * x[n + j];
    return true;
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override {
    Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::Map<Eigen::VectorXd>(grad, n) = H * xv + p->g;
    for (int j = 0; j < n_slack; ++j) grad[n + j] = slack_weight[j];
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    Eigen::Map<const Eigen::VectorXd> xv(x, n);
    int r = 0;
    for (int i = 0; i < m_eq; ++i) g[r++] = p->A.row(i).dot(xv);
    if (mode == Mode::kStrict) {
      for (int i = 0; i < m_in; ++i) g[r++] = p->C.row(i).dot(xv);
    } else {
      for (const RelaxedRow& rr : relaxed) {
        double v = p->C.row(rr.row).dot(xv);
        if (rr.plus >= 0) v += x[n + rr.plus];
        if (rr.minus >= 0) v -= x[n + rr.minus];
        g[r++] = v;
      }
    }
    for (int k = 0; k < n_cones; ++k) g[r++] = mu_n_plus_slack(x, k) - (smooth_norm(x, k) - eps);
    return r == m;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index nele, Index* iRow, Index* jCol,
                  Number* values) override {
    const bool slack = mode == Mode::kSlack;
    int e = 0, r = 0;
    if (values == nullptr) {
      for (int i = 0; i < m_eq; ++i, ++r)
        for (int j = 0; j < n; ++j, ++e) iRow[e] = r, jCol[e] = j;
      if (!slack) {
        for (int i = 0; i < m_in; ++i, ++r)
          for (int j = 0; j < n; ++j, ++e) iRow[e] = r, jCol[e] = j;
      } else {
        for (const RelaxedRow& rr : relaxed) {
          for (int j = 0; j < n; ++j, ++e) iRow[e] = r, jCol[e] = j;
          if (rr.plus >= 0) iRow[e] = r, jCol[e] = n + rr.plus, ++e;
          if (rr.minus >= 0) iRow[e] = r, jCol[e] = n + rr.minus, ++e;
          ++r;
        }
      }
      for (int k = 0; k < n_cones; ++k) {
        const SecondOrderCone& c = p->cones[k];
        iRow[e] = r, jCol[e] = c.tangent1, ++e;
        iRow[e] = r, jCol[e] = c.tangent2, ++e;
        iRow[e] = r, jCol[e] = c.normal, ++e;
        if (slack) iRow[e] = r, jCol[e] = n + cone_slack(k), ++e;
        ++r;
      }
      return e == nele;
    }
    for (int i = 0; i < m_eq; ++i)
      for (int j = 0; j < n; ++j) values[e++] = p->A(i, j);
    if (!slack) {
      for (int i = 0; i < m_in; ++i)
        for (int j = 0; j < n; ++j) values[e++] = p->C(i, j);
    } else {
      for (const RelaxedRow& rr : relaxed) {
        for (int j = 0; j < n; ++j) values[e++] = p->C(rr.row, j);
        if (rr.plus >= 0) values[e++] = 1.0;
        if (rr.minus >= 0) values[e++] = -1.0;
      }
    }
    for (int k = 0; k < n_cones; ++k) {
      const SecondOrderCone& c = p->cones[k];
      const double r = smooth_norm(x, k);
      values[e++] = -x[c.tangent1] / r;
      values[e++] = -x[c.tangent2] / r;
      values[e++] = c.mu;
      if (slack) values[e++] = 1.0;
    }
    return e == nele;
  }

  bool eval_h(Index, const Number* x, bool, Number obj_factor, Index, const Number* lambda, bool,
              Index nele, Index* iRow, Index* jCol, Number* values) override {
    if (values == nullptr) {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j <= i; ++j) iRow[tri(i, j)] = i, jCol[tri(i, j)] = j;
      return hess_x_entries() == nele;
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j <= i; ++j) values[tri(i, j)] = obj_factor * H(i, j);
    const int r0 = first_cone_row();
    for (int k = 0; k < n_cones; ++k) {
      // ∇²(−√(t1² + t2² + ε²)) = −(r² I − t tᵀ)/r³ on (t1, t2).
      const SecondOrderCone& c = p->cones[k];
      const double t1 = x[c.tangent1], t2 = x[c.tangent2];
      const double r = smooth_norm(x, k);
      const double w = lambda[r0 + k] / (r * r * r);
      values[tri(c.tangent1, c.tangent1)] -= w * (t2 * t2 + eps * eps);
      values[tri(c.tangent2, c.tangent2)] -= w * (t1 * t1 + eps * eps);
      const int hi = std::max(c.tangent1, c.tangent2), lo = std::min(c.tangent1, c.tangent2);
      values[tri(hi, lo)] += w * t1 * t2;
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index nv_in, const Number* x, const Number* z_L,
                         const Number*, Index m, const Number*, const Number* lambda, Number,
                         const Ipopt::IpoptData* ip_data,
                         Ipopt::IpoptCalculatedQuantities* ip_cq) override {
    finalized = true;
    x_out = Eigen::Map<const Eigen::VectorXd>(x, nv_in);
    z_lower_out = Eigen::Map<const Eigen::VectorXd>(z_L, nv_in);
    lambda_out = Eigen::Map<const Eigen::VectorXd>(lambda, m);
    iterations_out = ip_data ? static_cast<int>(ip_data->iter_count()) : 0;
    nlp_error_out = std::numeric_limits<double>::infinity();
    if (ip_cq) {
      try {
        nlp_error_out = ip_cq->curr_nlp_error();
      } catch (...) {
      }
    }
  }
};

class IpoptBackend final : public AllocationBackend {
 public:
  explicit IpoptBackend(const IpoptOptions& options) : opt_(options) {
    if (!(opt_.tolerance > 0.0) || !(opt_.slack_penalty > 0.0) || opt_.max_iterations < 1 ||
        !(opt_.max_cpu_seconds > 0.0) || !(opt_.cone_smoothing_N > 0.0)) {
      std::ostringstream os;
      os << "Ipopt options: tolerance, slack_penalty, max_cpu_seconds, cone_smoothing_N must "
            "be > 0 and max_iterations >= 1, got "
         << opt_.tolerance << ", " << opt_.slack_penalty << ", " << opt_.max_cpu_seconds << ", "
         << opt_.cone_smoothing_N << ", " << opt_.max_iterations;
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
  /// Feasibility threshold of a row for the status (allocation_qp.hpp).
  double feasibility_tol() const { return qp_feasibility_tolerance(opt_.tolerance); }

  /// Options that differ between runs. Penalised runs have multipliers ρ w up to 1e9, to
  /// which Ipopt scales its optimality test, and their optima are often degenerate (rows
  /// that hold with a zero multiplier at an impact foot's friction polygon): an interior
  /// point then sits ~√(complementarity) inside such a row. They therefore also get an
  /// absolute complementarity tolerance of 1e-3·tolerance, which brings their forces to
  /// within ~2e-6 N of the exact penalised optimum on the paper run (README "Allocation").
  void set_per_solve_options(bool linear_constraints, bool warm, bool penalised) {
    Ipopt::OptionsList& o = *app_->Options();
    const double tol = opt_.tolerance;
    o.SetNumericValue("tol", tol);
    o.SetNumericValue("constr_viol_tol", tol);
    o.SetNumericValue("compl_inf_tol", penalised ? 1e-3 * tol : 1e-4);
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

  void fail_with_fallback(const QpProblem& p, const std::string& why) {
    qp_fail_with_fallback(p, feasibility_tol(), why, out_);
    have_warm_ = false;
  }

  void solve_impl(const QpProblem& p) override {
    const int n = p.variables(), m_eq = p.equalities(), m_in = p.inequalities();
    const int n_cones = static_cast<int>(p.cones.size());
    out_.iterations = 0;
    out_.message.clear();
    if (const std::string bad = qp_first_non_finite(p); !bad.empty()) {
      fail_with_fallback(p, "non-finite entries in " + bad);
      return;
    }
    if (n == 0) {
      qp_solve_without_variables(p, feasibility_tol(), out_);
      return;
    }
    const bool linear = n_cones == 0;

    // --- strict attempt (warm if possible; a failed warm start is retried cold) ---
    // Infeasible samples come in runs, and Ipopt needs many iterations to declare a
    // problem infeasible: after a relaxed sample of the same sizes the penalised problem
    // is solved directly (its solution is the strict optimum when no slack is needed).
    QpTnlp& t = *tnlp_;
    const bool same_sizes =
        warm_n_ == n && warm_m_eq_ == m_eq && warm_m_in_ == m_in && warm_cones_ == n_cones;
    const bool skip_strict = last_relaxed_ && same_sizes;
    const bool warm = opt_.warm_start && have_warm_ && same_sizes;
    warm_n_ = n, warm_m_eq_ = m_eq, warm_m_in_ = m_in, warm_cones_ = n_cones;
    last_relaxed_ = false;
    t.finalized = false;
    std::string strict_note = skip_strict ? "skipped after a relaxed sample" : "";
    for (const bool use_warm : {true, false}) {
      if (skip_strict) break;
      if (use_warm && !warm) continue;
      t.setup(p, Mode::kStrict, opt_.slack_penalty, opt_.cone_smoothing_N);
      if (use_warm) {
        t.start_x = warm_x_;
        t.start_multipliers = true;
        t.start_lambda = warm_lambda_;
        t.start_z_lower.setZero(n);
      } else {
        t.start_x = qp_fallback_point(p);
        t.start_multipliers = false;
      }
      set_per_solve_options(linear, use_warm, false);
      const Ipopt::ApplicationReturnStatus st = run(out_.iterations);
      if (!strict_note.empty()) strict_note += ", then cold ";
      strict_note += return_status_name(st);
      if (!run_usable(st)) {
        // Linear constraints that Ipopt finds infeasible are infeasible from any start.
        if (linear && st == Ipopt::Infeasible_Problem_Detected) break;
        continue;
      }
      const Eigen::VectorXd x = t.x_out.head(n);
      double viol = 0.0;
      const std::string v = describe_violations(p, x, feasibility_tol(), &viol);
      if (!v.empty()) {
        strict_note += " but violated " + v;
        continue;
      }
      out_.status = 0;
      out_.x = x;
      fill_multipliers(m_in, true);
      out_.objective = p.objective(x);
      out_.max_violation = viol;
      if (!succeeded(st) || st == Ipopt::Solved_To_Acceptable_Level)
        out_.message = acceptable_note(st);
      have_warm_ = true;
      warm_x_ = x;
      warm_lambda_ = t.lambda_out;
      return;
    }
    have_warm_ = false;

    // --- penalised slack attempts ---
    // Start from the strict run's last point, or after a skipped strict run from the
    // previous (relaxed) sample's solution.
    const Eigen::VectorXd x0 =
        t.finalized && t.x_out.allFinite() && t.x_out.size() >= n ? Eigen::VectorXd(t.x_out.head(n))
        : skip_strict && out_.x.size() == n && out_.x.allFinite() ? out_.x
                                                                  : qp_fallback_point(p);
    const std::string strict_part = "strict solve " + strict_note;
    if (n_cones == 0) {
      const Ipopt::ApplicationReturnStatus st = run_slack(p, x0);
      if (!run_usable(st)) {
        fail_with_fallback(p, strict_part + "; penalised solve " + return_status_name(st));
        return;
      }
      finish_relaxed(p, true, "");
      return;
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
      return;
    }
    if (!poly_ok) {
      fail_with_fallback(p, strict_part + "; penalised polygon solve " +
                                return_status_name(st_poly) + "; penalised cone solve " +
                                return_status_name(st_cone));
      return;
    }
    run_slack(poly_, poly_x_);  // restores the polygon solution and its multipliers
    finish_relaxed(p, false,
                   std::string("cones replaced by inscribed ") + std::to_string(kPolygonFaces) +
                       "-gons, the penalised cone solve ended with " + return_status_name(st_cone));
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
    have_warm_ = false;
    if (v.empty() && note.empty()) {
      // No slack needed: by exactness of the penalty this is the strict optimum, but only
      // to the penalised run's tolerance, which Ipopt scales by its multipliers (up to ρ w).
      // Polish it by the problem as posed, warm-started from here.
      out_.status = 0;
      out_.message = "optimal to the penalised solve's tolerance only";
      last_relaxed_ = false;
      polish_strict(p);
      return;
    }
    out_.status = 1;
    out_.message = v.empty() ? "approximate: " + note
                             : "relaxed: " + v + (note.empty() ? "" : " (" + note + ")");
    last_relaxed_ = true;
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
    have_warm_ = true;
    warm_x_ = x;
    warm_lambda_ = t.lambda_out;
  }

  /// p with every cone replaced by kPolygonFaces rows (t1, t2)·(cos a, sin a) − μ cos(π/N) n ≤ 0,
  /// the inscribed polygon.
  static void build_polygon_problem(const QpProblem& p, QpProblem& poly) {
    const int n = p.variables(), m_in = p.inequalities();
    const int rows = m_in + kPolygonFaces * static_cast<int>(p.cones.size());
    poly.H = p.H;
    poly.g = p.g;
    poly.constant = p.constant;
    poly.A = p.A;
    poly.b = p.b;
    poly.eq_names = p.eq_names;
    poly.C.setZero(rows, n);
    poly.lower.resize(rows);
    poly.upper.resize(rows);
    poly.C.topRows(m_in) = p.C;
    poly.lower.head(m_in) = p.lower;
    poly.upper.head(m_in) = p.upper;
    poly.ineq_names.resize(static_cast<std::size_t>(rows));
    for (int i = 0; i < m_in; ++i) poly.ineq_names[i] = p.ineq_name(i);
    poly.ineq_penalty.resize(rows);
    for (int i = 0; i < m_in; ++i)
      poly.ineq_penalty[i] = p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0;
    poly.cones.clear();
    int r = m_in;
    for (std::size_t k = 0; k < p.cones.size(); ++k) {
      const SecondOrderCone& c = p.cones[k];
      for (int f = 0; f < kPolygonFaces; ++f, ++r) {
        const double a = 2.0 * M_PI * f / kPolygonFaces;
        poly.C(r, c.tangent1) = std::cos(a);
        poly.C(r, c.tangent2) = std::sin(a);
        poly.C(r, c.normal) = -c.mu * std::cos(M_PI / kPolygonFaces);
        poly.lower[r] = -std::numeric_limits<double>::infinity();
        poly.upper[r] = 0.0;
        poly.ineq_penalty[r] = c.penalty;
        poly.ineq_names[r] = (c.name.empty() ? "cone[" + std::to_string(k) + "]" : c.name) +
                             " face " + std::to_string(f + 1);
      }
    }
  }

  static constexpr int kPolygonFaces = 16;

  IpoptOptions opt_;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
  Ipopt::SmartPtr<QpTnlp> tnlp_;
  QpProblem poly_;          ///< penalised polygon version of a cone problem (workspace)
  Eigen::VectorXd poly_x_;  ///< its solution
  Eigen::VectorXd polish_x_, polish_lambda_;  ///< start of a polishing strict run
  int warm_n_ = -1, warm_m_eq_ = -1, warm_m_in_ = -1, warm_cones_ = -1;
  Eigen::VectorXd warm_x_, warm_lambda_;
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
