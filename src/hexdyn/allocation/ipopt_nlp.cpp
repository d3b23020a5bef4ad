#include "hexdyn/allocation/ipopt_nlp.hpp"

#include <IpIpoptCalculatedQuantities.hpp>
#include <IpIpoptData.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

namespace hexdyn::ipopt_nlp {
namespace {

double clamp_bound(double v) {
  if (!(v > -kQpInfinity)) return -kIpoptInf;
  if (!(v < kQpInfinity)) return kIpoptInf;
  return v;
}

}  // namespace

void QpTnlp::setup(const QpProblem& problem, Mode m, double rho, double cone_eps) {
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

bool QpTnlp::get_nlp_info(Index& nv_out, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                          IndexStyleEnum& index_style) {
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

bool QpTnlp::get_bounds_info(Index nv_in, Number* x_l, Number* x_u, Index m, Number* g_l,
                             Number* g_u) {
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

bool QpTnlp::get_starting_point(Index nv_in, bool init_x, Number* x, bool init_z, Number* z_L,
                                Number* z_U, Index m, bool init_lambda, Number* lambda) {
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

double QpTnlp::smooth_norm(const Number* x, int k) const {
  const SecondOrderCone& c = p->cones[k];
  return std::sqrt(x[c.tangent1] * x[c.tangent1] + x[c.tangent2] * x[c.tangent2] + eps * eps);
}

double QpTnlp::mu_n_plus_slack(const Number* x, int k) const {
  const SecondOrderCone& c = p->cones[k];
  double v = c.mu * x[c.normal];
  if (mode == Mode::kSlack) v += x[n + cone_slack(k)];
  return v;
}

bool QpTnlp::eval_f(Index, const Number* x, bool, Number& obj) {
  Eigen::Map<const Eigen::VectorXd> xv(x, n);
  obj = 0.5 * xv.dot(H * xv) + p->g.dot(xv) + p->constant;
  for (int j = 0; j < n_slack; ++j) obj += slack_weight[j] * x[n + j];
  return true;
}

bool QpTnlp::eval_grad_f(Index, const Number* x, bool, Number* grad) {
  Eigen::Map<const Eigen::VectorXd> xv(x, n);
  Eigen::Map<Eigen::VectorXd>(grad, n) = H * xv + p->g;
  for (int j = 0; j < n_slack; ++j) grad[n + j] = slack_weight[j];
  return true;
}

bool QpTnlp::eval_g(Index, const Number* x, bool, Index m, Number* g) {
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

bool QpTnlp::eval_jac_g(Index, const Number* x, bool, Index, Index nele, Index* iRow, Index* jCol,
                        Number* values) {
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

bool QpTnlp::eval_h(Index, const Number* x, bool, Number obj_factor, Index, const Number* lambda,
                    bool, Index nele, Index* iRow, Index* jCol, Number* values) {
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

void QpTnlp::finalize_solution(Ipopt::SolverReturn, Index nv_in, const Number* x, const Number* z_L,
                               const Number*, Index m, const Number*, const Number* lambda, Number,
                               const Ipopt::IpoptData* ip_data,
                               Ipopt::IpoptCalculatedQuantities* ip_cq) {
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

}  // namespace hexdyn::ipopt_nlp
