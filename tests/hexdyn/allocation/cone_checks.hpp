#pragma once
/// \file cone_checks.hpp
/// Independent checks of answers to cone problems (allocation/cone_backend.hpp), shared by
/// test_cone.cpp (agreement over whole runs) and test_cone_hard.cpp (hard cases): the KKT
/// conditions by the one checker of kkt_check.hpp; the closed-form projection onto one cone; the
/// penalised objective; and the penalised problem re-solved in extended precision on the structure
/// an answer identifies.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/cone_backend.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/kkt_check.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/allocation/qp_test_problems.hpp"

namespace hexdyn::test::cone {

using test::check_kkt;
using test::check_penalised_kkt;
using test::KktVerdict;

inline double inf_norm(const Eigen::VectorXd& v) {
  return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0;
}

/// Ipopt's absolute stationarity tolerance as a reference (IpoptOptions::dual_inf_tol).
/// Penalised Ipopt runs at 1e-12 end at Ipopt's acceptable level, where dual_inf_tol is not
/// tested; with 1e-9 the reference's earlier (converged) solves stop elsewhere, and on the
/// paper run its relaxed answers land within 1.5e-8 N of the extended-precision optimum
/// (3.4e-6 N with the default; test_cone.cpp explains that sample).
inline constexpr double kReferenceDualInfTol = 1e-9;

/// Ipopt as the reference: tolerance 1e-12, absolute stationarity 1e-9, cold starts.
inline std::unique_ptr<AllocationBackend> reference_ipopt(double slack_penalty = 1e6) {
  IpoptOptions o;
  o.tolerance = 1e-12;
  o.dual_inf_tol = kReferenceDualInfTol;
  o.slack_penalty = slack_penalty;
  o.warm_start = false;
  return make_ipopt_backend(o);
}

inline std::unique_ptr<AllocationBackend> cone_backend(double slack_penalty = 1e6) {
  ConeOptions o;
  o.qp.slack_penalty = slack_penalty;
  return make_cone_backend(o);
}

/// Largest cone violation ‖t‖ − μ n relative to max(1, ‖t‖) (≤ 0 when every cone holds).
inline double worst_cone_violation(const QpProblem& p, const Eigen::VectorXd& x) {
  double worst = -kInf;
  for (const SecondOrderCone& c : p.cones) {
    const double r = std::hypot(x[c.tangent1], x[c.tangent2]);
    worst = std::max(worst, (r - c.mu * x[c.normal]) / std::max(1.0, r));
  }
  return worst;
}

/// ½xᵀHx + gᵀx + c + ρ Σ w · (violation of each row and cone), in row units; violations
/// within rounding (1e-12·(1 + |bound|)) count as 0.
inline double penalised_objective(const QpProblem& p, const Eigen::VectorXd& x, double rho) {
  auto beyond = [](double v, double bound) {
    return v > 1e-12 * (1.0 + std::abs(bound)) ? v : 0.0;
  };
  double v = 0.0;
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    const double w = p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0;
    if (p.lower[i] > -kQpInfinity) v += w * beyond(p.lower[i] - c, p.lower[i]);
    if (p.upper[i] < kQpInfinity) v += w * beyond(c - p.upper[i], p.upper[i]);
  }
  for (const SecondOrderCone& c : p.cones) {
    const double bound = c.mu * x[c.normal];
    v += c.penalty * beyond(std::hypot(x[c.tangent1], x[c.tangent2]) - bound, bound);
  }
  return p.objective(x) + rho * v;
}

/// Projection of (t, n) onto {‖t‖ ≤ μ n} in the metric ½|·|²: closed form.
inline Eigen::Vector3d project_onto_cone(const Eigen::Vector3d& a, double mu) {
  const Eigen::Vector2d t = a.head<2>();
  const double n = a[2], r = t.norm();
  if (r <= mu * n) return a;
  if (mu * r <= -n) return Eigen::Vector3d::Zero();
  // The nearest point on the ray n = r'/μ in the plane of t: minimise (r' − r)² + (r'/μ − n)².
  const double rp = (r + n / mu) / (1.0 + 1.0 / (mu * mu));
  Eigen::Vector3d out;
  out << rp * t / r, rp / mu;
  return out;
}

/// One foot, min ½|x − a|² subject to its cone (and n ≥ 0, as the allocation has).
inline QpProblem single_foot(const Eigen::Vector3d& a, double mu) {
  QpProblem p;
  p.resize(3, 0, 1);
  p.H.setIdentity();
  p.g = -a;
  p.constant = 0.5 * a.squaredNorm();
  p.C(0, 2) = 1.0;
  p.lower[0] = 0.0;
  p.ineq_names = {"normal L1"};
  p.ineq_penalty[0] = 1e3;
  p.cones.push_back({0, 1, 2, mu, "friction cone L1", 1e3});
  return p;
}

/// Rows named in a "relaxed: a by 1, b by 2" message, sorted.
inline std::vector<std::string> named_rows(const std::string& message) {
  std::vector<std::string> names;
  const std::string prefix = "relaxed: ";
  if (message.rfind(prefix, 0) != 0) return names;
  std::size_t pos = prefix.size();
  while (pos < message.size()) {
    const std::size_t by = message.find(" by ", pos);
    if (by == std::string::npos) break;
    names.push_back(message.substr(pos, by - pos));
    const std::size_t comma = message.find(", ", by);
    if (comma == std::string::npos) break;
    pos = comma + 2;
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// Violation of every row and cone at x (row units; 0 where it holds).
inline Eigen::VectorXd violations(const QpProblem& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(p.inequalities() + static_cast<int>(p.cones.size()));
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    if (p.lower[i] > -kQpInfinity) v[i] += std::max(0.0, p.lower[i] - c);
    if (p.upper[i] < kQpInfinity) v[i] += std::max(0.0, c - p.upper[i]);
  }
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    v[p.inequalities() + static_cast<int>(k)] =
        std::max(0.0, std::hypot(x[c.tangent1], x[c.tangent2]) - c.mu * x[c.normal]);
  }
  return v;
}

/// The L1-penalised cone problem re-solved in extended precision on the structure that an
/// answer identifies: a third computation, independent of both back ends' stopping rules.
struct ExtendedSolution {
  Eigen::VectorXd x;
  bool certified = false;  ///< x is the penalised optimum (see extended_precision_cone_x)
  std::string why;         ///< what failed when not certified
};

/// Structure, read from the answer `out` at thresholds 1e-9·(1 + |bound|):
///  - a row beyond a bound enters as the fixed linear term of its penalty (slope ρw), a
///    row at a bound with λ ≠ 0 is held there (multiplier ν), the others are left out;
///  - a cone violated by ‖t‖ − μn enters as the objective term ρw(‖t‖ − μn), a cone on its
///    boundary away from the apex is held there (‖t‖ = μn, multiplier s), a cone at its apex
///    (‖t‖ ≤ 1e-9 N) is held there by t = 0 and n = 0 (multipliers ν_t, ν_n), the others are
///    left out.
/// Newton's method in long double on the resulting KKT system (stationarity, held rows,
/// held cones), from out.x. `certified` when, at the new x, the system holds to 1e-12
/// relative to max(|H x|, |g|) (multipliers of ρ w ≈ 1e6–1e9 set its rounding level), every
/// multiplier lies in its penalty's subdifferential (ν between 0 and ρw on the side of its bound,
/// ±ρw for l = u rows; s in [0, ρw]; at an apex (ν_t, y_n) in the subdifferential of the cone's
/// penalty there, μ‖ν_t‖ ≤ y_n ≤ ρwμ, for some split of ν_n plus the multipliers of held rows on n
/// alone into y_n and those rows' share within their own ranges) and every row and cone left out or
/// penalised is still on the side it was identified on. Those are the KKT conditions of the
/// penalised problem, which is convex: x is then its optimum to extended-precision rounding,
/// whatever produced the structure.
inline ExtendedSolution extended_precision_cone_x(const QpProblem& p, const QpOutcome& out,
                                                  double rho) {
  using LD = long double;
  using MatL = Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>;
  using VecL = Eigen::Matrix<LD, Eigen::Dynamic, 1>;
  ExtendedSolution res;
  const int n = p.variables();
  auto weight = [&](int i) { return p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0; };
  auto near = [](double bound) { return 1e-9 * (1.0 + std::abs(bound)); };
  enum class Row { kOut, kBelow, kAbove, kAtLower, kAtUpper };
  enum class Cone { kOut, kViolated, kHeld, kApex };
  std::vector<Row> row(static_cast<std::size_t>(p.inequalities()), Row::kOut);
  std::vector<Cone> cone(p.cones.size(), Cone::kOut);
  VecL g = p.g.cast<LD>();
  std::vector<int> held;  // inequality rows held at a bound
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(out.x), lo = p.lower[i], hi = p.upper[i];
    const LD kappa = LD(rho) * weight(i);
    Row& r = row[static_cast<std::size_t>(i)];
    if (lo > -kQpInfinity && c < lo - near(lo)) {
      r = Row::kBelow, g -= kappa * p.C.row(i).transpose().cast<LD>();
    } else if (hi < kQpInfinity && c > hi + near(hi)) {
      r = Row::kAbove, g += kappa * p.C.row(i).transpose().cast<LD>();
    } else if (out.lambda_ineq[i] != 0.0 && lo > -kQpInfinity && std::abs(c - lo) <= near(lo)) {
      r = Row::kAtLower, held.push_back(i);
    } else if (out.lambda_ineq[i] != 0.0 && hi < kQpInfinity && std::abs(c - hi) <= near(hi)) {
      r = Row::kAtUpper, held.push_back(i);
    }
  }
  std::vector<int> held_cones, apex_cones;
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    const double t = std::hypot(out.x[c.tangent1], out.x[c.tangent2]),
                 excess = t - c.mu * out.x[c.normal];
    if (excess > near(t)) {
      cone[k] = Cone::kViolated;
    } else if (excess >= -near(t)) {
      if (t <= 1e-9)
        cone[k] = Cone::kApex, apex_cones.push_back(static_cast<int>(k));
      else
        cone[k] = Cone::kHeld, held_cones.push_back(static_cast<int>(k));
    }
  }
  const int q = static_cast<int>(held.size()), b = static_cast<int>(held_cones.size());
  const int e = 3 * static_cast<int>(apex_cones.size()), N = n + q + b + e;  // apex: t1, t2, n = 0
  const MatL H = p.H.cast<LD>().selfadjointView<Eigen::Lower>();
  VecL z = VecL::Zero(N);
  z.head(n) = out.x.cast<LD>();
  for (int j = 0; j < q; ++j) z[n + j] = out.lambda_ineq[held[static_cast<std::size_t>(j)]];
  for (int j = 0; j < b; ++j)
    z[n + q + j] = out.lambda_cone.size() == static_cast<int>(p.cones.size())
                       ? out.lambda_cone[held_cones[static_cast<std::size_t>(j)]]
                       : 0.0;
  // F(z) = (H x + g + Σ_violated ρw ∇(‖t‖ − μn) − Σ ν_j C_j − Σ s_k ∇(μn − ‖t‖),
  //         C_j x − bound_j, μ n − ‖t‖) and its Jacobian.
  VecL F(N);
  MatL J(N, N);
  auto evaluate = [&]() {
    const VecL x = z.head(n);
    F.setZero();
    J.setZero();
    F.head(n) = H * x + g;
    J.topLeftCorner(n, n) = H;
    for (int j = 0; j < q; ++j) {
      const int i = held[static_cast<std::size_t>(j)];
      const VecL a = p.C.row(i).transpose().cast<LD>();
      F.head(n) -= z[n + j] * a;
      J.block(0, n + j, n, 1) = -a;
      J.block(n + j, 0, 1, n) = a.transpose();
      const LD bound = row[static_cast<std::size_t>(i)] == Row::kAtLower ? p.lower[i] : p.upper[i];
      F[n + j] = a.dot(x) - bound;
    }
    auto cone_terms = [&](const SecondOrderCone& c, LD weight_on_norm, int col) {
      // weight_on_norm · ∇(‖t‖ − μn) added to stationarity, its Hessian to J; col ≥ 0:
      // the multiplier column of a held cone (weight_on_norm = s).
      const LD t1 = x[c.tangent1], t2 = x[c.tangent2], r = std::sqrt(t1 * t1 + t2 * t2);
      const LD d1 = t1 / r, d2 = t2 / r, mu = c.mu;
      F[c.tangent1] += weight_on_norm * d1;
      F[c.tangent2] += weight_on_norm * d2;
      F[c.normal] -= weight_on_norm * mu;
      const LD k = weight_on_norm / r;
      J(c.tangent1, c.tangent1) += k * (1 - d1 * d1);
      J(c.tangent2, c.tangent2) += k * (1 - d2 * d2);
      J(c.tangent1, c.tangent2) -= k * d1 * d2;
      J(c.tangent2, c.tangent1) -= k * d1 * d2;
      if (col >= 0) {
        J(c.tangent1, col) = d1, J(c.tangent2, col) = d2, J(c.normal, col) = -mu;
        J(col, c.tangent1) = -d1, J(col, c.tangent2) = -d2, J(col, c.normal) = mu;
        F[col] = mu * x[c.normal] - r;
      }
    };
    for (int j = 0; j < e; ++j) {
      const SecondOrderCone& c =
          p.cones[static_cast<std::size_t>(apex_cones[static_cast<std::size_t>(j / 3)])];
      const int v = j % 3 == 0   ? c.tangent1
                    : j % 3 == 1 ? c.tangent2
                                 : c.normal,
                col = n + q + b + j;
      F[v] -= z[col];
      J(v, col) = -1, J(col, v) = 1;
      F[col] = x[v];
    }
    for (std::size_t k = 0; k < p.cones.size(); ++k)
      if (cone[k] == Cone::kViolated) cone_terms(p.cones[k], LD(rho) * p.cones[k].penalty, -1);
    for (int j = 0; j < b; ++j)
      cone_terms(p.cones[static_cast<std::size_t>(held_cones[static_cast<std::size_t>(j)])],
                 z[n + q + j], n + q + j);
  };
  const LD scale =
      1 + H.cwiseAbs().maxCoeff() * z.head(n).cwiseAbs().maxCoeff() + g.cwiseAbs().maxCoeff();
  LD residual = 0;
  for (int it = 0; it < 60; ++it) {
    evaluate();
    residual = F.cwiseAbs().maxCoeff() / scale;
    if (residual <= 1e-17L) break;
    z -= J.completeOrthogonalDecomposition().solve(F);
  }
  evaluate();
  residual = F.cwiseAbs().maxCoeff() / scale;
  res.x = z.head(n).cast<double>();
  std::ostringstream os;
  if (!(residual <= 1e-12L)) os << "KKT residual " << static_cast<double>(residual) << "; ";
  const double mtol = 1e-9 * (1.0 + rho * 1e3);
  // Held rows on the normal force alone (C_i = α e_n, α > 0) of a cone at its apex share
  // ν_n with the cone: checked together below, not alone.
  auto on_normal_only = [&](int i, int normal) {
    for (int v = 0; v < n; ++v)
      if ((v == normal) != (p.C(i, v) != 0.0)) return false;
    return p.C(i, normal) > 0.0;
  };
  for (int j = 0; j < static_cast<int>(apex_cones.size()); ++j) {
    const SecondOrderCone& c =
        p.cones[static_cast<std::size_t>(apex_cones[static_cast<std::size_t>(j)])];
    const int col = n + q + b + 3 * j;
    const double nu_t = std::hypot(static_cast<double>(z[col]), static_cast<double>(z[col + 1]));
    double total = static_cast<double>(z[col + 2]), row_lo = 0.0, row_hi = 0.0;
    for (int h = 0; h < q; ++h) {
      const int i = held[static_cast<std::size_t>(h)];
      if (!on_normal_only(i, c.normal)) continue;
      const double a = p.C(i, c.normal), nu = static_cast<double>(z[n + h]),
                   kappa = rho * weight(i);
      total += a * nu;
      if (row[static_cast<std::size_t>(i)] == Row::kAtLower)
        row_hi += a * kappa;
      else
        row_lo -= a * kappa;
      row[static_cast<std::size_t>(i)] = Row::kOut;  // checked here, not alone
      z[n + h] = 0;
    }
    // y_n ∈ [μ‖ν_t‖, ρwμ] and total − y_n ∈ [row_lo, row_hi].
    const double lo = std::max(c.mu * nu_t, total - row_hi),
                 hi = std::min(rho * c.penalty * c.mu, total - row_lo);
    if (lo > hi + mtol) os << c.name << " at its apex: ν_t " << nu_t << ", ν_n " << total << "; ";
  }
  for (int j = 0; j < q; ++j) {
    const int i = held[static_cast<std::size_t>(j)];
    const double nu = static_cast<double>(z[n + j]), kappa = rho * weight(i);
    const bool lu = p.lower[i] == p.upper[i];
    const double lo = lu || row[static_cast<std::size_t>(i)] == Row::kAtUpper ? -kappa : 0.0;
    const double hi = lu || row[static_cast<std::size_t>(i)] == Row::kAtLower ? kappa : 0.0;
    if (nu < lo - mtol || nu > hi + mtol) os << p.ineq_name(i) << ": ν = " << nu << "; ";
  }
  for (int j = 0; j < b; ++j) {
    const SecondOrderCone& c =
        p.cones[static_cast<std::size_t>(held_cones[static_cast<std::size_t>(j)])];
    const double s = static_cast<double>(z[n + q + j]);
    if (s < -mtol || s > rho * c.penalty + mtol) os << c.name << ": s = " << s << "; ";
  }
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(res.x), lo = p.lower[i], hi = p.upper[i];
    const Row r = row[static_cast<std::size_t>(i)];
    const bool ok = r == Row::kBelow   ? c <= lo + near(lo)
                    : r == Row::kAbove ? c >= hi - near(hi)
                    : r == Row::kOut   ? (lo <= -kQpInfinity || c >= lo - near(lo)) &&
                                           (hi >= kQpInfinity || c <= hi + near(hi))
                                     : true;
    if (!ok) os << p.ineq_name(i) << " changed side; ";
  }
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    const double t = std::hypot(res.x[c.tangent1], res.x[c.tangent2]),
                 excess = t - c.mu * res.x[c.normal];
    if ((cone[k] == Cone::kViolated && !(excess >= -near(t) && t > 0.0)) ||
        (cone[k] == Cone::kOut && excess > near(t)))
      os << c.name << " changed side; ";
  }
  res.why = os.str();
  res.certified = res.why.empty();
  return res;
}

}  // namespace hexdyn::test::cone
