#pragma once
/// \file kkt_check.hpp
/// The one optimality check of the allocation tests, for every back end: the KKT
/// conditions of a QpProblem (allocation/qp.hpp), with or without friction cones, as posed
/// or in its exact L1-penalised form, at an outcome's x and row multipliers. No cone
/// multiplier from the back end is needed: the stationarity residual on a cone's variables
/// must lie in the dual cone (as posed) or in the penalty's subdifferential (penalised).
///
/// With y = H x + g − Aᵀλ_eq − Cᵀλ_in and, per variable j, the size of its terms
/// s_j = |H x|_j + |g|_j + (|A|ᵀ|λ_eq|)_j + (|C|ᵀ|λ_in|)_j:
///  - off the cones, |y_j| ≤ tol·(1 + s_j);
///  - equality rows hold to tol·(1 + |b_i|);
///  - an inequality row i, with κ = ρ w_i (penalised) and d = tol·(1 + |bound|):
///    as posed, it holds to d and λ_i lies in [0, ∞) at its lower bound, (−∞, 0] at its
///    upper bound, {0} strictly inside (within tol·(1 + max|λ|));
///    penalised, λ_i lies between the penalty's slopes on either side of C_i x ± d: κ below
///    the lower bound, −κ above the upper bound, 0 inside (within tol·(1 + κ));
///  - a cone k on (t, n), with r = ‖t‖ and c = tol·(1 + κ + s_t1 + s_t2 + s_n):
///    as posed, r − μ n ≤ tol·max(1, r), (y_t, y_n) in the dual cone (μ‖y_t‖ ≤ y_n + c) and
///    complementary (|y_tᵀt + y_n n| ≤ c·(1 + r + |n|)), and where the back end reports
///    λ_cone and the cone is active away from its apex, λ_cone = y_n / μ;
///    penalised, (y_t, y_n) = κ(−t/r, μ) where the cone is violated, 0 strictly inside,
///    s(−u, μ) with s ∈ [0, κ], ‖u‖ ≤ 1 on its boundary.
/// The problem being convex, these certify an optimum (the unique one where H is positive
/// definite).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/qp.hpp"

namespace hexdyn::test {

/// The verdict of check_kkt: true when every condition holds, else the first that fails.
/// Catch2 prints it, so CHECK(check_kkt(...)) shows the reason of a failure.
struct KktVerdict {
  bool ok = true;
  std::string why;
  explicit operator bool() const { return ok; }
};

inline std::ostream& operator<<(std::ostream& os, const KktVerdict& v) {
  return os << (v.ok ? std::string("KKT conditions hold") : "KKT: " + v.why);
}

namespace detail {

inline KktVerdict check_kkt_conditions(const QpProblem& p, const QpOutcome& out, double tol,
                                       bool penalised, double rho) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::ostringstream os;
  auto fail = [&os]() { return KktVerdict{false, os.str()}; };
  const int n = p.variables(), m_eq = p.equalities(), m_in = p.inequalities();
  if (out.x.size() != n || out.lambda_eq.size() != m_eq || out.lambda_ineq.size() != m_in) {
    os << "sizes of x / lambda_eq / lambda_ineq do not match the problem";
    return fail();
  }
  if (!out.x.allFinite() || !out.lambda_eq.allFinite() || !out.lambda_ineq.allFinite()) {
    os << "non-finite x or multipliers";
    return fail();
  }
  const Eigen::VectorXd& x = out.x;
  const Eigen::MatrixXd H = p.H.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd y = H * x + p.g;
  Eigen::VectorXd scale = (H * x).cwiseAbs() + p.g.cwiseAbs();
  if (m_eq > 0) {
    y -= p.A.transpose() * out.lambda_eq;
    scale += p.A.cwiseAbs().transpose() * out.lambda_eq.cwiseAbs();
  }
  if (m_in > 0) {
    y -= p.C.transpose() * out.lambda_ineq;
    scale += p.C.cwiseAbs().transpose() * out.lambda_ineq.cwiseAbs();
  }

  std::vector<bool> on_cone(static_cast<std::size_t>(n), false);
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    const double kappa = penalised ? rho * c.penalty : 0.0;
    const Eigen::Vector2d t(x[c.tangent1], x[c.tangent2]), yt(y[c.tangent1], y[c.tangent2]);
    const double xn = x[c.normal], yn = y[c.normal], r = t.norm(), excess = r - c.mu * xn;
    const double ytol =
        tol * (1.0 + kappa + scale[c.tangent1] + scale[c.tangent2] + scale[c.normal]);
    const double compl_tol = ytol * (1.0 + r + std::abs(xn));
    const double d = tol * std::max(1.0, r);
    bool ok = true;
    if (!penalised) {
      if (excess > d) {
        os << "cone " << k << " violated by " << excess;
        return fail();
      }
      ok = c.mu * yt.norm() <= yn + ytol && std::abs(yt.dot(t) + yn * xn) <= compl_tol;
      if (ok && out.lambda_cone.size() == static_cast<int>(p.cones.size()) && r > 1e-6 &&
          c.mu > 0.0 &&
          std::abs(out.lambda_cone[k] - yn / c.mu) > 1e-6 * (1.0 + ytol / tol) / c.mu) {
        os << "cone " << k << ": λ_cone " << out.lambda_cone[k] << " vs y_n/μ " << yn / c.mu;
        return fail();
      }
    } else if (excess > d) {
      ok = (yt + kappa * t / r).norm() <= ytol && std::abs(yn - kappa * c.mu) <= ytol;
    } else if (excess < -d) {
      ok = yt.norm() <= ytol && std::abs(yn) <= ytol;
    } else {
      ok = yn >= -ytol && yn <= kappa * c.mu + ytol && c.mu * yt.norm() <= yn + ytol &&
           std::abs(yt.dot(t) + yn * xn) <= compl_tol;
    }
    if (!ok) {
      os << "cone " << k << ": excess " << excess << ", residual (" << yt.transpose() << ", " << yn
         << ") not in " << (penalised ? "the penalty's subdifferential" : "the dual cone")
         << " (ρw = " << kappa << ")";
      return fail();
    }
    for (int idx : {c.tangent1, c.tangent2, c.normal})
      on_cone[static_cast<std::size_t>(idx)] = true;
  }

  for (int j = 0; j < n; ++j) {
    if (!on_cone[static_cast<std::size_t>(j)] && std::abs(y[j]) > tol * (1.0 + scale[j])) {
      os << "stationarity residual " << y[j] << " in variable " << j;
      return fail();
    }
  }
  for (int i = 0; i < m_eq; ++i) {
    const double res = p.A.row(i).dot(x) - p.b[i];
    if (std::abs(res) > tol * (1.0 + std::abs(p.b[i]))) {
      os << "equality " << p.eq_name(i) << " residual " << res;
      return fail();
    }
  }
  const double lambda_scale = 1.0 + (m_in > 0 ? out.lambda_ineq.lpNorm<Eigen::Infinity>() : 0.0);
  for (int i = 0; i < m_in; ++i) {
    const double c = p.C.row(i).dot(x), lam = out.lambda_ineq[i];
    const double lo = p.lower[i], hi = p.upper[i];
    const bool has_lo = lo > -kQpInfinity, has_hi = hi < kQpInfinity;
    const double dlo = has_lo ? tol * (1.0 + std::abs(lo)) : 0.0;
    const double dhi = has_hi ? tol * (1.0 + std::abs(hi)) : 0.0;
    double lmin = 0.0, lmax = 0.0, ltol = 0.0;
    if (!penalised) {
      if (has_lo && lo - c > dlo) {
        os << "inequality " << p.ineq_name(i) << " below its lower bound by " << lo - c;
        return fail();
      }
      if (has_hi && c - hi > dhi) {
        os << "inequality " << p.ineq_name(i) << " above its upper bound by " << c - hi;
        return fail();
      }
      if (has_lo && c - lo <= dlo) lmax = kInf;
      if (has_hi && hi - c <= dhi) lmin = -kInf;
      ltol = tol * lambda_scale;
    } else {
      // λ is minus the slope of the penalty: κ below the lower bound, −κ above the upper
      // one (both, cancelling, between crossed bounds); at a kink any value in between.
      const double kappa = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
      auto minus_slope = [&](double at) {
        return (has_lo && at < lo ? kappa : 0.0) - (has_hi && at > hi ? kappa : 0.0);
      };
      const double d = std::max(dlo, dhi);
      lmin = std::min(minus_slope(c - d), minus_slope(c + d));
      lmax = std::max(minus_slope(c - d), minus_slope(c + d));
      ltol = tol * (1.0 + kappa);
    }
    if (lam < lmin - ltol || lam > lmax + ltol) {
      os << "inequality " << p.ineq_name(i) << ": C x = " << c << " in [" << lo << ", " << hi
         << "], λ = " << lam << " not in [" << lmin << ", " << lmax << "]";
      return fail();
    }
  }
  return {};
}

}  // namespace detail

/// KKT conditions of `p` as posed at `out` (x, λ_eq, λ_ineq; λ_cone compared where given).
inline KktVerdict check_kkt(const QpProblem& p, const QpOutcome& out, double tol) {
  return detail::check_kkt_conditions(p, out, tol, false, 0.0);
}

/// KKT conditions of the L1-penalised form of `p` with penalty ρ (rows and cones weighted
/// by their penalty w) at `out`: the certificate of a relaxed answer.
inline KktVerdict check_penalised_kkt(const QpProblem& p, const QpOutcome& out, double rho,
                                      double tol) {
  return detail::check_kkt_conditions(p, out, tol, true, rho);
}

}  // namespace hexdyn::test
