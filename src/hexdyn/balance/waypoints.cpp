#include "hexdyn/balance/waypoints.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <utility>

namespace hexdyn {
namespace {

using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

/// Solves, per axis, min Σ c_k (w_k − g_k)² + β Σ (w_{k+1} − w_k)² / Δ_k + (ρ/2) Σ (w_k − h_k)²
/// (Δ_k: span_s) subject to Σ a0_k w_k = f0 and Σ aT_k w_k = fT: a tridiagonal system
/// bordered by the two equalities, solved through their Schur complement. The matrix and the
/// borders do not change between ADMM iterations: the Thomas algorithm's factors, the borders'
/// solutions and the Schur complement are formed once, and a solve is one forward and one back
/// substitution.
class BorderedTridiagonal {
 public:
  BorderedTridiagonal(Eigen::VectorXd diag, Eigen::VectorXd off, Eigen::VectorXd a0,
                      Eigen::VectorXd aT)
      : n_(static_cast<int>(diag.size())),
        diag_(std::move(diag)),
        off_(std::move(off)),
        a0_(std::move(a0)),
        aT_(std::move(aT)),
        c_(n_),
        m_(n_) {
    c_[0] = n_ > 1 ? off_[0] / diag_[0] : 0.0;
    m_[0] = diag_[0];
    for (int i = 1; i < n_; ++i) {
      m_[i] = diag_[i] - off_[i - 1] * c_[i - 1];
      c_[i] = i + 1 < n_ ? off_[i] / m_[i] : 0.0;
    }
    y0_ = substitute(a0_);
    yT_ = substitute(aT_);
    Eigen::Matrix2d S;
    S << a0_.dot(y0_), a0_.dot(yT_), aT_.dot(y0_), aT_.dot(yT_);
    schur_ = S.completeOrthogonalDecomposition();
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs, double f0, double fT) const {
    const Eigen::VectorXd x0 = substitute(rhs);
    const Eigen::Vector2d mu = schur_.solve(Eigen::Vector2d(a0_.dot(x0) - f0, aT_.dot(x0) - fT));
    return x0 - mu[0] * y0_ - mu[1] * yT_;
  }

 private:
  Eigen::VectorXd substitute(const Eigen::VectorXd& b) const {
    Eigen::VectorXd d(n_), x(n_);
    d[0] = b[0] / diag_[0];
    for (int i = 1; i < n_; ++i) d[i] = (b[i] - off_[i - 1] * d[i - 1]) / m_[i];
    x[n_ - 1] = d[n_ - 1];
    for (int i = n_ - 2; i >= 0; --i) x[i] = d[i] - c_[i] * x[i + 1];
    return x;
  }

  int n_;
  Eigen::VectorXd diag_, off_, a0_, aT_, c_, m_, y0_, yT_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix2d> schur_;
};

}  // namespace

/// The waypoints nearest the targets g (weights c) inside their regions whose functionals
/// equal F's s parts: w_k = Π_k(g_k + (a_k · λ) / (2 c_k)) with the four multipliers λ found by a
/// damped semi-smooth Newton method on the residual.
std::vector<Vec2> solve_waypoints(const std::vector<SupportRegion>& region,
                                  const std::vector<Vec2>& g, const std::vector<double>& c,
                                  const Functionals& F, double* residual) {
  const int n = static_cast<int>(g.size());
  std::vector<Vec2> w(n);
  std::vector<Mat2> D(n);
  const auto evaluate = [&](const Vec4& lam) {
    Vec4 r = Vec4::Zero();
    for (int k = 0; k < n; ++k) {
      const Vec2 shift = (F.a[k].x() * lam.head<2>() + F.a[k].y() * lam.tail<2>()) / (2.0 * c[k]);
      const Projection p = project(region[k], g[k] + shift);
      w[k] = p.point;
      D[k] = p.derivative;
      r.head<2>() += F.a[k].x() * w[k];
      r.tail<2>() += F.a[k].y() * w[k];
    }
    r.head<2>() -= F.s_start;
    r.tail<2>() -= F.s_end;
    return r;
  };
  Vec4 lam = Vec4::Zero();
  Vec4 r = evaluate(lam);
  const double scale = 1.0 + F.s_start.norm() + F.s_end.norm();
  for (int it = 0; it < 100 && r.norm() > 1e-15 * scale; ++it) {
    Mat4 J = Mat4::Zero();
    for (int k = 0; k < n; ++k) {
      const Vec2& a = F.a[k];
      const Mat2 Dk = D[k] / (2.0 * c[k]);
      J.block<2, 2>(0, 0) += a.x() * a.x() * Dk;
      J.block<2, 2>(0, 2) += a.x() * a.y() * Dk;
      J.block<2, 2>(2, 0) += a.y() * a.x() * Dk;
      J.block<2, 2>(2, 2) += a.y() * a.y() * Dk;
    }
    J += (1e-14 * (J.trace() + 1e-300)) * Mat4::Identity();
    const Vec4 step = -J.completeOrthogonalDecomposition().solve(r);
    double t = 1.0, before = r.norm();
    Vec4 trial;
    for (int ls = 0; ls < 40; ++ls, t *= 0.5) {
      trial = evaluate(lam + t * step);
      if (trial.norm() < before * (1.0 - 1e-4 * t)) break;
    }
    if (!(trial.norm() < before)) break;
    lam += t * step;
    r = trial;
  }
  r = evaluate(lam);
  *residual = r.norm() / scale;
  return w;
}

/// Waypoints that keep the ZMP path smooth: ADMM on the smoothed objective of BorderedTridiagonal
/// (β = 16/ω², so that the path does not change faster than the pendulum can follow) with each
/// waypoint held in its region, for kAdmmIterations from the targets projected onto their regions
/// (a smoother, not solved to optimality: docs/theory/balance.md#the-waypoints); the exact
/// projection solve_waypoints then polishes its answer into the regions and onto the two
/// equalities. A fixed count keeps the waypoints a continuous function of the passes' data.
std::vector<Vec2> smooth_waypoints(const std::vector<SupportRegion>& region,
                                   const std::vector<Vec2>& g, const std::vector<double>& c,
                                   const std::vector<double>& span_s, const Functionals& F,
                                   double omega, double* residual) {
  const int n = static_cast<int>(g.size());
  // ρ = 5/ω: on the shipped balanced scenes 100 iterations leave the ADMM's primal residual
  // near 1e-5 m and the energies within 0.5 % of the converged smoother; ρ = 1/ω left 1e-3 m
  // after 400 (docs/theory/balance.md#the-waypoints).
  constexpr int kAdmmIterations = 100;
  const double beta = 16.0 / (omega * omega), rho = 5.0 / omega;
  Eigen::VectorXd diag(n), off = Eigen::VectorXd::Zero(std::max(n - 1, 1)), a0(n), aT(n);
  for (int k = 0; k < n; ++k) {
    diag[k] = 2.0 * c[k] + rho;
    a0[k] = F.a[k].x();
    aT[k] = F.a[k].y();
  }
  for (int k = 0; k + 1 < n; ++k) {
    const double s = 2.0 * beta / span_s[k];
    diag[k] += s;
    diag[k + 1] += s;
    off[k] = -s;
  }
  const BorderedTridiagonal system(diag, off, a0, aT);
  std::vector<Vec2> v(n), y(n, Vec2::Zero()), w(n);
  for (int k = 0; k < n; ++k) v[k] = project(region[k], g[k]).point;
  for (int it = 0; it < kAdmmIterations; ++it) {
    for (int axis = 0; axis < 2; ++axis) {
      Eigen::VectorXd rhs(n);
      for (int k = 0; k < n; ++k)
        rhs[k] = 2.0 * c[k] * g[k][axis] + rho * (v[k][axis] - y[k][axis]);
      const Eigen::VectorXd x = system.solve(rhs, F.s_start[axis], F.s_end[axis]);
      for (int k = 0; k < n; ++k) w[k][axis] = x[k];
    }
    double primal = 0.0;
    for (int k = 0; k < n; ++k) {
      v[k] = project(region[k], w[k] + y[k]).point;
      y[k] += w[k] - v[k];
      primal = std::max(primal, (w[k] - v[k]).norm());
    }
    if (primal < 1e-10) break;
  }
  return solve_waypoints(region, v, c, F, residual);
}

}  // namespace hexdyn
