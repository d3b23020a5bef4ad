#include "hexdyn/allocation/qp.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

AllocationBackend::~AllocationBackend() = default;

const QpOutcome& AllocationBackend::solve_as_posed(const QpProblem& problem) {
  as_posed_ = true;
  try {
    solve(problem);
  } catch (...) {
    as_posed_ = false;
    throw;
  }
  as_posed_ = false;
  return out_;
}

const QpOutcome& AllocationBackend::solve(const QpProblem& problem) {
  const auto t0 = std::chrono::steady_clock::now();
  validate_qp_sizes(problem);
  solve_impl(problem);
  out_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out_;
}

void QpProblem::resize(int n, int m_eq, int m_in) {
  H.setZero(n, n);
  g.setZero(n);
  A.setZero(m_eq, n);
  b.setZero(m_eq);
  C.setZero(m_in, n);
  lower.setConstant(m_in, -std::numeric_limits<double>::infinity());
  upper.setConstant(m_in, std::numeric_limits<double>::infinity());
  eq_names.assign(static_cast<std::size_t>(m_eq), std::string());
  ineq_names.assign(static_cast<std::size_t>(m_in), std::string());
  ineq_penalty.setOnes(m_in);
  cones.clear();
  constant = 0.0;
  structure = 0;
}

std::string QpProblem::eq_name(int i) const {
  if (i >= 0 && i < static_cast<int>(eq_names.size()) && !eq_names[i].empty()) return eq_names[i];
  return "eq[" + std::to_string(i) + "]";
}

std::string QpProblem::ineq_name(int i) const {
  if (i >= 0 && i < static_cast<int>(ineq_names.size()) && !ineq_names[i].empty())
    return ineq_names[i];
  return "ineq[" + std::to_string(i) + "]";
}

double QpProblem::objective(const Eigen::VectorXd& x) const {
  return 0.5 * x.dot(H.selfadjointView<Eigen::Lower>() * x) + g.dot(x) + constant;
}

bool copy_problem_values(const QpProblem& from, QpProblem& to, int extra_rows,
                         std::uint64_t structure) {
  const int n = from.variables(), m_eq = from.equalities(), m_in = from.inequalities();
  const int rows = m_in + extra_rows;
  const bool same = to.structure == structure && to.variables() == n && to.equalities() == m_eq &&
                    to.inequalities() == rows;
  if (!same) {
    to.resize(n, m_eq, rows);
    std::copy(from.eq_names.begin(), from.eq_names.end(), to.eq_names.begin());
    std::copy(from.ineq_names.begin(), from.ineq_names.end(), to.ineq_names.begin());
    to.structure = structure;
  }
  to.H = from.H;
  to.g = from.g;
  to.constant = from.constant;
  to.A = from.A;
  to.b = from.b;
  to.C.topRows(m_in) = from.C;
  to.C.bottomRows(extra_rows).setZero();
  to.lower.head(m_in) = from.lower;
  to.lower.tail(extra_rows).setConstant(-std::numeric_limits<double>::infinity());
  to.upper.head(m_in) = from.upper;
  to.upper.tail(extra_rows).setConstant(std::numeric_limits<double>::infinity());
  if (from.ineq_penalty.size())
    to.ineq_penalty.head(m_in) = from.ineq_penalty;
  else
    to.ineq_penalty.head(m_in).setOnes();
  to.ineq_penalty.tail(extra_rows).setOnes();
  to.cones.clear();
  return !same;
}

void validate_qp_sizes(const QpProblem& p) {
  const int n = p.variables(), m_eq = p.equalities(), m_in = p.inequalities();
  auto fail = [](const std::string& what, long expected, long got) {
    std::ostringstream os;
    os << "QP: " << what << ": expected " << expected << ", got " << got;
    throw SolverError(os.str());
  };
  if (p.H.rows() != n) fail("rows of H (= size of g)", n, p.H.rows());
  if (p.H.cols() != n) fail("columns of H (= size of g)", n, p.H.cols());
  if (p.A.rows() != m_eq) fail("rows of A (= size of b)", m_eq, p.A.rows());
  if (m_eq > 0 && p.A.cols() != n) fail("columns of A (= size of g)", n, p.A.cols());
  if (p.C.rows() != m_in) fail("rows of C (= size of lower)", m_in, p.C.rows());
  if (m_in > 0 && p.C.cols() != n) fail("columns of C (= size of g)", n, p.C.cols());
  if (p.upper.size() != m_in) fail("size of upper (= size of lower)", m_in, p.upper.size());
  if (!p.eq_names.empty() && static_cast<int>(p.eq_names.size()) != m_eq)
    fail("number of equality row names", m_eq, static_cast<long>(p.eq_names.size()));
  if (!p.ineq_names.empty() && static_cast<int>(p.ineq_names.size()) != m_in)
    fail("number of inequality row names", m_in, static_cast<long>(p.ineq_names.size()));
  if (p.ineq_penalty.size() != 0 && p.ineq_penalty.size() != m_in)
    fail("size of ineq_penalty (or 0)", m_in, p.ineq_penalty.size());
  for (int i = 0; i < p.ineq_penalty.size(); ++i) {
    if (!(std::isfinite(p.ineq_penalty[i]) && p.ineq_penalty[i] > 0.0)) {
      std::ostringstream os;
      os << "QP: ineq_penalty of " << p.ineq_name(i) << " must be finite and > 0, got "
         << p.ineq_penalty[i];
      throw SolverError(os.str());
    }
  }
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    for (int idx : {c.tangent1, c.tangent2, c.normal}) {
      if (idx < 0 || idx >= n) {
        std::ostringstream os;
        os << "QP: cone " << k << " index out of range [0, " << n << "): got " << idx;
        throw SolverError(os.str());
      }
    }
    if (c.tangent1 == c.tangent2 || c.tangent1 == c.normal || c.tangent2 == c.normal) {
      std::ostringstream os;
      os << "QP: cone " << k << " needs three distinct indices, got (" << c.tangent1 << ", "
         << c.tangent2 << ", " << c.normal << ")";
      throw SolverError(os.str());
    }
    if (!(std::isfinite(c.mu) && c.mu >= 0.0)) {
      std::ostringstream os;
      os << "QP: cone " << k << " friction coefficient must be finite and >= 0, got " << c.mu;
      throw SolverError(os.str());
    }
    if (!(std::isfinite(c.penalty) && c.penalty > 0.0)) {
      std::ostringstream os;
      os << "QP: cone " << k << " penalty must be finite and > 0, got " << c.penalty;
      throw SolverError(os.str());
    }
  }
}

namespace {
bool has_lower(double l) { return l > -kQpInfinity; }
bool has_upper(double u) { return u < kQpInfinity; }

std::string cone_label(const QpProblem& p, std::size_t k) {
  return p.cones[k].name.empty() ? "cone[" + std::to_string(k) + "]" : p.cones[k].name;
}

/// out[i] = M.row(i).dot(x) for every row, bit for bit: Eigen's dot of a row of a
/// column-major matrix (a strided row, not vectorised) starts from M(i, 0) x[0] and adds
/// M(i, j) x[j] for j = 1, 2, … in turn, and so does this sweep, one contiguous column at a
/// time (the same IEEE products and sums, only in another order across rows). An empty
/// product (no columns) is 0, as the dot's. out must hold M.rows() values.
/// (tests/hexdyn/allocation/test_violations.cpp compares the two bit for bit.)
void row_products(const Eigen::MatrixXd& M, const Eigen::VectorXd& x, double* out) {
  if (M.rows() == 0) return;
  Eigen::Map<Eigen::VectorXd> y(out, M.rows());
  if (M.cols() == 0) {
    y.setZero();
    return;
  }
  y = M.col(0) * x[0];
  for (Eigen::Index j = 1; j < M.cols(); ++j) y += M.col(j) * x[j];
}

/// A row or cone that misses its bound by `violation` (> 0 or NaN, row units): the largest
/// violation `worst` follows it, and the row joins `violated` beyond tol · max(1, |bound|).
void note_violation(double violation, double bound, int row, double tol, double& worst,
                    std::vector<std::pair<double, int>>& violated) {
  const double v = std::isfinite(violation) ? violation : std::numeric_limits<double>::infinity();
  worst = std::max(worst, v);
  if (!(v <= tol * std::max(1.0, std::abs(bound)))) violated.emplace_back(v, row);
}

/// Appends the name of row `row` (numbered as ViolationWorkspace::violated) to `text`.
void append_row_name(const QpProblem& p, int row, std::string& text) {
  const int m_eq = p.equalities(), m_in = p.inequalities();
  if (row < m_eq)
    text += p.eq_name(row);
  else if (row < m_eq + m_in)
    text += p.ineq_name(row - m_eq);
  else
    text += cone_label(p, static_cast<std::size_t>(row - m_eq - m_in));
}
}  // namespace

std::string describe_violations(const QpProblem& p, const Eigen::VectorXd& x, double tol,
                                double* max_violation) {
  ViolationWorkspace workspace;
  return describe_violations(p, x, tol, max_violation, workspace);
}

std::string describe_violations(const QpProblem& p, const Eigen::VectorXd& x, double tol,
                                double* max_violation, ViolationWorkspace& ws) {
  const int m_eq = p.equalities(), m_in = p.inequalities();
  ws.violated.clear();
  double worst = 0.0;
  // A row that holds changes nothing: that common case is decided inline.
  auto consider = [&](double violation, double bound, int row) {
    if (violation <= 0.0) return;
    note_violation(violation, bound, row, tol, worst, ws.violated);
  };
  if (x.size() == p.variables()) {
    ws.row_value.resize(static_cast<std::size_t>(p.A.rows() + p.C.rows()));
    const double* Ax = ws.row_value.data();
    const double* Cx = Ax + p.A.rows();
    row_products(p.A, x, ws.row_value.data());
    row_products(p.C, x, ws.row_value.data() + p.A.rows());
    for (int i = 0; i < m_eq; ++i) {
      const double r = Ax[i] - p.b[i];
      consider(std::abs(r), p.b[i], i);
    }
    for (int i = 0; i < m_in; ++i) {
      const double c = Cx[i];
      const double below = has_lower(p.lower[i]) ? p.lower[i] - c : -1.0;
      const double above = has_upper(p.upper[i]) ? c - p.upper[i] : -1.0;
      if (below >= above && has_lower(p.lower[i]))
        consider(below, p.lower[i], m_eq + i);
      else if (has_upper(p.upper[i]))
        consider(above, p.upper[i], m_eq + i);
    }
    for (std::size_t k = 0; k < p.cones.size(); ++k) {
      const SecondOrderCone& c = p.cones[k];
      const double bound = c.mu * x[c.normal];
      consider(std::hypot(x[c.tangent1], x[c.tangent2]) - bound, bound,
               m_eq + m_in + static_cast<int>(k));
    }
  }
  if (max_violation) *max_violation = worst;
  if (ws.violated.empty()) return {};
  std::stable_sort(ws.violated.begin(), ws.violated.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string text;
  char buf[32];
  for (const auto& [v, row] : ws.violated) {
    if (!text.empty()) text += ", ";
    append_row_name(p, row, text);
    text += " by ";
    // printf's %.3g, which std::to_chars with a precision is defined to equal.
    text.append(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 3).ptr);
  }
  return text;
}

Eigen::VectorXd qp_fallback_point(const QpProblem& p) {
  const int n = p.variables();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  if (n == 0 || p.equalities() == 0 || p.A.cols() != n || !p.A.allFinite() || !p.b.allFinite())
    return x;
  Eigen::VectorXd ls = p.A.completeOrthogonalDecomposition().solve(p.b);
  if (ls.allFinite()) x = ls;
  return x;
}

double qp_feasibility_tolerance(double tolerance) { return std::max(1e-6, 1e3 * tolerance); }

namespace {
/// Eigen's allFinite() without its temporaries (it compares (M − M) with itself): one pass.
template <typename Matrix>
bool all_finite(const Matrix& m) {
  const double* x = m.data();
  bool finite = true;
  for (Eigen::Index i = 0; i < m.size(); ++i) finite &= std::isfinite(x[i]);
  return finite;
}
}  // namespace

std::string qp_first_non_finite(const QpProblem& p) {
  if (!all_finite(p.H)) return "H";
  if (!all_finite(p.g)) return "g";
  if (!std::isfinite(p.constant)) return "constant";
  if (!all_finite(p.A)) return "A";
  if (!all_finite(p.b)) return "b";
  if (!all_finite(p.C)) return "C";
  for (int i = 0; i < p.inequalities(); ++i)
    if (std::isnan(p.lower[i]) || std::isnan(p.upper[i])) return "bounds of " + p.ineq_name(i);
  return {};
}

void qp_fail_with_fallback(const QpProblem& p, double feasibility_tol, const std::string& why,
                           QpOutcome& out) {
  out.status = SolverStatus::kFailed;
  out.x = qp_fallback_point(p);
  out.lambda_eq.setZero(p.equalities());
  out.lambda_ineq.setZero(p.inequalities());
  out.lambda_cone.setZero(static_cast<int>(p.cones.size()));
  double viol = 0.0;
  const std::string v = describe_violations(p, out.x, feasibility_tol, &viol);
  out.max_violation = std::isfinite(viol) ? viol : std::numeric_limits<double>::max();
  out.objective = p.objective(out.x);
  if (!std::isfinite(out.objective)) out.objective = 0.0;
  out.message = "failed: " + why + "; fallback x = least-squares solution of the equalities";
  if (!v.empty()) out.message += "; violated: " + v;
}

void qp_solve_without_variables(const QpProblem& p, double feasibility_tol, QpOutcome& out) {
  out.x.resize(0);
  out.lambda_eq.setZero(p.equalities());
  out.lambda_ineq.setZero(p.inequalities());
  out.lambda_cone.resize(0);
  out.objective = p.constant;
  const std::string v = describe_violations(p, out.x, feasibility_tol, &out.max_violation);
  out.status = v.empty() ? SolverStatus::kOptimal : SolverStatus::kFailed;
  out.message = v.empty() ? std::string() : "failed: no variables; violated: " + v;
}

}  // namespace hexdyn
