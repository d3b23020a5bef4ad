/// \file model/redundant_leg.cpp
/// A leg chain's foot position and its derivatives of orders 1 to 3 on nested dual numbers,
/// and the redundant leg's resolution (model/redundant_leg.hpp).
#include "hexdyn/model/redundant_leg.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace hexdyn {
namespace {

/// A dual number v + d ε (ε² = 0) over T, itself a double or a dual number: nesting k levels
/// carries the mixed derivative of order k in k directions.
template <typename T>
struct Dual {
  T v, d;
  Dual() : v(0.0), d(0.0) {}
  explicit Dual(double x) : v(x), d(0.0) {}
  Dual(T value, T derivative) : v(value), d(derivative) {}
};

template <typename T>
Dual<T> operator+(const Dual<T>& a, const Dual<T>& b) {
  return {a.v + b.v, a.d + b.d};
}
template <typename T>
Dual<T> operator-(const Dual<T>& a, const Dual<T>& b) {
  return {a.v - b.v, a.d - b.d};
}
template <typename T>
Dual<T> operator*(const Dual<T>& a, const Dual<T>& b) {
  return {a.v * b.v, a.v * b.d + a.d * b.v};
}
template <typename T>
Dual<T> operator*(const Dual<T>& a, double s) {
  return {a.v * s, a.d * s};
}
template <typename T>
Dual<T> operator*(double s, const Dual<T>& a) {
  return {a.v * s, a.d * s};
}
template <typename T>
Dual<T> sin(const Dual<T>& a) {
  using std::cos;
  using std::sin;
  return {sin(a.v), cos(a.v) * a.d};
}
template <typename T>
Dual<T> cos(const Dual<T>& a) {
  using std::cos;
  using std::sin;
  return {cos(a.v), (sin(a.v) * a.d) * -1.0};
}

template <typename S>
using V3 = std::array<S, 3>;
template <typename S>
using M3 = std::array<std::array<S, 3>, 3>;

/// R p for a rotation R over S and a constant vector p.
template <typename S>
V3<S> times(const M3<S>& R, const Vec3& p) {
  V3<S> out;
  for (int i = 0; i < 3; ++i) out[i] = R[i][0] * p[0] + R[i][1] * p[1] + R[i][2] * p[2];
  return out;
}

/// R A for a constant A.
template <typename S>
M3<S> times(const M3<S>& R, const Mat3& A) {
  M3<S> out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[i][j] = R[i][0] * A(0, j) + R[i][1] * A(1, j) + R[i][2] * A(2, j);
  return out;
}

/// R · Rot(a, θ), Rot(a, θ) = I + sin θ [a]× + (1 − cos θ) [a]×² (Rodrigues).
template <typename S>
M3<S> times_rotation(const M3<S>& R, const Vec3& a, const S& theta) {
  using std::cos;
  using std::sin;
  const S s = sin(theta), c1 = S(1.0) - cos(theta);
  Mat3 K;
  K << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  const Mat3 K2 = K * K;
  M3<S> rot;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rot[i][j] = s * K(i, j) + c1 * K2(i, j) + S(i == j ? 1.0 : 0.0);
  M3<S> out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[i][j] = R[i][0] * rot[0][j] + R[i][1] * rot[1][j] + R[i][2] * rot[2][j];
  return out;
}

/// The foot position in H over the scalar S, q given as S values.
template <typename S>
V3<S> foot_position(const SerialChain& chain, const S* q) {
  M3<S> R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = S(i == j ? 1.0 : 0.0);
  V3<S> p{S(0.0), S(0.0), S(0.0)};
  for (int k = 0; k < chain.count; ++k) {
    const ChainJoint& joint = chain.joints[static_cast<std::size_t>(k)];
    const V3<S> offset = times(R, joint.p_parent_m);
    for (int i = 0; i < 3; ++i) p[i] = p[i] + offset[i];
    R = times(R, joint.R_parent);
    if (joint.type == ChainJointType::kRevolute) {
      R = times_rotation(R, joint.axis, q[k]);
    } else {
      const V3<S> along = times(R, joint.axis);
      for (int i = 0; i < 3; ++i) p[i] = p[i] + along[i] * q[k];
    }
  }
  const V3<S> foot = times(R, chain.p_foot_m);
  for (int i = 0; i < 3; ++i) p[i] = p[i] + foot[i];
  return p;
}

using D1 = Dual<double>;
using D2 = Dual<D1>;
using D3 = Dual<D2>;

/// f(q + s u + r v + t w) on nested duals: the ε_s ε_r ε_t part is ∇³f[u, v, w]; with w = 0
/// and the D2 type, ∇²f[u, v]; with D1, ∇f u.
std::array<D1, kMaxChainJoints> seed1(const ChainVector& q, const ChainVector& u) {
  std::array<D1, kMaxChainJoints> x{};
  for (Eigen::Index k = 0; k < q.size(); ++k) x[static_cast<std::size_t>(k)] = D1(q[k], u[k]);
  return x;
}

std::array<D2, kMaxChainJoints> seed2(const ChainVector& q, const ChainVector& u,
                                      const ChainVector& v) {
  std::array<D2, kMaxChainJoints> x{};
  for (Eigen::Index k = 0; k < q.size(); ++k)
    x[static_cast<std::size_t>(k)] = D2(D1(q[k], u[k]), D1(v[k], 0.0));
  return x;
}

std::array<D3, kMaxChainJoints> seed3(const ChainVector& q, const ChainVector& u,
                                      const ChainVector& v, const ChainVector& w) {
  std::array<D3, kMaxChainJoints> x{};
  for (Eigen::Index k = 0; k < q.size(); ++k)
    x[static_cast<std::size_t>(k)] =
        D3(D2(D1(q[k], u[k]), D1(v[k], 0.0)), D2(D1(w[k], 0.0), D1(0.0, 0.0)));
  return x;
}

ChainVector unit(int m, int a) {
  ChainVector e = ChainVector::Zero(m);
  e[a] = 1.0;
  return e;
}

}  // namespace

Vec3 chain_foot_position(const SerialChain& chain, const ChainVector& q) {
  const V3<double> p = foot_position(chain, q.data());
  return {p[0], p[1], p[2]};
}

ChainJacobian chain_jacobian(const SerialChain& chain, const ChainVector& q) {
  const int m = chain.count;
  ChainJacobian J(3, m);
  for (int a = 0; a < m; ++a) {
    const auto x = seed1(q, unit(m, a));
    const V3<D1> p = foot_position(chain, x.data());
    for (int i = 0; i < 3; ++i) J(i, a) = p[i].d;
  }
  return J;
}

std::array<ChainMatrix, 3> chain_hessians(const SerialChain& chain, const ChainVector& q) {
  const int m = chain.count;
  std::array<ChainMatrix, 3> H;
  for (ChainMatrix& h : H) h.setZero(m, m);
  for (int a = 0; a < m; ++a)
    for (int b = a; b < m; ++b) {
      const auto x = seed2(q, unit(m, a), unit(m, b));
      const V3<D2> p = foot_position(chain, x.data());
      for (int i = 0; i < 3; ++i)
        H[static_cast<std::size_t>(i)](a, b) = H[static_cast<std::size_t>(i)](b, a) = p[i].d.d;
    }
  return H;
}

Vec3 chain_second_derivative(const SerialChain& chain, const ChainVector& q, const ChainVector& u,
                             const ChainVector& v) {
  const auto x = seed2(q, u, v);
  const V3<D2> p = foot_position(chain, x.data());
  return {p[0].d.d, p[1].d.d, p[2].d.d};
}

Vec3 chain_third_derivative(const SerialChain& chain, const ChainVector& q, const ChainVector& u,
                            const ChainVector& v, const ChainVector& w) {
  const auto x = seed3(q, u, v, w);
  const V3<D3> p = foot_position(chain, x.data());
  return {p[0].d.d.d, p[1].d.d.d, p[2].d.d.d};
}

namespace {

constexpr int kMaxKkt = kMaxChainJoints + 3;
using KktMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxKkt, kMaxKkt>;
using KktVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxKkt, 1>;

/// K = [H Jᵀ; J 0], H = W + Σ λ_i ∇²f_i (hess: the ∇²f_i at the same q).
KktMatrix kkt_matrix(const std::array<ChainMatrix, 3>& hess, const ChainVector& weight,
                     const Vec3& lambda, const ChainJacobian& J) {
  const int m = static_cast<int>(weight.size());
  KktMatrix K = KktMatrix::Zero(m + 3, m + 3);
  K.topLeftCorner(m, m) = weight.asDiagonal();
  for (int i = 0; i < 3; ++i)
    K.topLeftCorner(m, m) += lambda[i] * hess[static_cast<std::size_t>(i)];
  K.topRightCorner(m, 3) = J.transpose();
  K.bottomLeftCorner(3, m) = J;
  return K;
}

/// One damped least-squares step from q towards f(q) = p with damping `damping` (relative to
/// the trace of J W⁻¹ Jᵀ), pulled to the nominal pose in J's null space (W-weighted), at most
/// 0.5 rad (or m) per joint.
ChainVector reach_step(const SerialChain& chain, const RedundantResolution& res,
                       const ChainVector& w_inv, const ChainVector& q, const Vec3& e,
                       double damping) {
  const ChainJacobian J = chain_jacobian(chain, q);
  const Mat3 A = J * w_inv.asDiagonal() * J.transpose();
  const Eigen::LDLT<Mat3> A_damped(A + damping * std::max(1e-12, A.trace()) * Mat3::Identity());
  ChainVector step = w_inv.asDiagonal() * J.transpose() * A_damped.solve(e);
  // The projection undamped where A is invertible: a damped one leaves part of the pull
  // along J's range, which stalls the foot short of p by about damping / σ² of the pull.
  const ChainVector pull = res.q_nominal - q;
  const Eigen::LDLT<Mat3> A_exact(A);
  Vec3 z = A_exact.solve(J * pull);
  if (A_exact.info() != Eigen::Success || !(A_exact.vectorD().minCoeff() > 0.0) || !z.allFinite())
    z = A_damped.solve(J * pull);
  step += 0.1 * (pull - w_inv.asDiagonal() * J.transpose() * z);
  const double longest = step.cwiseAbs().maxCoeff();
  if (longest > 0.5) step *= 0.5 / longest;
  return step;
}

/// Levenberg–Marquardt steps from q towards f(q) = p (reach_step), each pulled to the nominal
/// pose in J's null space: a step that brings the foot nearer is taken and the damping
/// lowered, else the damping raised; stops when the foot is within 1e-9 m, after 100 steps or
/// when the damping can rise no further.
void reach(const SerialChain& chain, const RedundantResolution& res, const Vec3& p, ChainVector& q,
           int& iterations) {
  const ChainVector w_inv = res.weight.cwiseInverse();
  double damping = 1e-6;
  Vec3 e = p - chain_foot_position(chain, q);
  for (int it = 0; it < 100 && e.norm() > 1e-9; ++it, ++iterations) {
    const ChainVector q_new = q + reach_step(chain, res, w_inv, q, e, damping);
    const Vec3 e_new = p - chain_foot_position(chain, q_new);
    if (e_new.norm() < e.norm()) {
      q = q_new;
      e = e_new;
      damping = std::max(0.3 * damping, 1e-9);
    } else {
      damping *= 10.0;
      if (damping > 1e6) return;
    }
  }
}

/// |[W (q − q_nom) + Jᵀ λ; f(q) − p]|, the optimality conditions' residual.
double kkt_residual(const SerialChain& chain, const RedundantResolution& res, const Vec3& p,
                    const ChainVector& q, const Vec3& lambda) {
  const ChainVector g =
      res.weight.cwiseProduct(q - res.q_nominal) + chain_jacobian(chain, q).transpose() * lambda;
  return std::sqrt(g.squaredNorm() + (chain_foot_position(chain, q) - p).squaredNorm());
}

/// Whether H is positive definite on J's null space (m > 3), or J is square.
bool reduced_hessian_positive(const KktMatrix& K, const ChainJacobian& J, int m) {
  if (m <= 3) return true;
  const Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxChainJoints, 3> Jt = J.transpose();
  const Eigen::HouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxChainJoints, 3>> qr(
      Jt);
  const ChainMatrix Q = qr.householderQ() * ChainMatrix::Identity(m, m);
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxChainJoints, kMaxChainJoints>
      Z = Q.rightCols(m - 3);
  const ChainMatrix reduced = Z.transpose() * K.topLeftCorner(m, m) * Z;
  const Eigen::LLT<ChainMatrix> llt(reduced);
  return llt.info() == Eigen::Success;
}

}  // namespace

RedundantLegMotion redundant_leg_motion(const SerialChain& chain,
                                        const RedundantResolution& resolution, const Vec3& p_H,
                                        const Vec3& pd_H, const Vec3& pdd_H,
                                        const ChainVector& q_start) {
  const int m = chain.count;
  const ChainVector& w = resolution.weight;
  RedundantLegMotion out;
  ChainVector q = q_start;
  reach(chain, resolution, p_H, q, out.iterations);
  // Newton on the optimality conditions, λ first from their least-squares fit at q.
  ChainJacobian J = chain_jacobian(chain, q);
  const ChainVector w_inv = w.cwiseInverse();
  const Mat3 A = J * w_inv.asDiagonal() * J.transpose();
  Vec3 lambda = -A.ldlt().solve(J * (q - resolution.q_nominal));
  KktMatrix K;
  std::array<ChainMatrix, 3> hess;  // at q, also for the accelerations below
  for (int it = 0; it < 60; ++it, ++out.iterations) {
    J = chain_jacobian(chain, q);
    hess = chain_hessians(chain, q);
    KktVector r(m + 3);
    r.head(m) = w.cwiseProduct(q - resolution.q_nominal) + J.transpose() * lambda;
    r.tail(3) = chain_foot_position(chain, q) - p_H;
    const double scale = 1.0 + w.cwiseProduct(q - resolution.q_nominal).norm();
    K = kkt_matrix(hess, w, lambda, J);
    if (r.head(m).norm() <= 1e-13 * scale && r.tail(3).norm() <= 1e-13) {
      // One more full step takes q to the rounding floor (rates and accelerations below use
      // K at the q before it, which differs by rounding).
      const KktVector last = -Eigen::PartialPivLU<KktMatrix>(K).solve(r);
      q += last.head(m);
      lambda += last.tail(3);
      out.converged = true;
      break;
    }
    const KktVector step = -Eigen::PartialPivLU<KktMatrix>(K).solve(r);
    // Backtracking on the residual: far from the optimum (an ill-conditioned J, a reduced
    // Hessian not yet positive) a full step can throw q far away. Near it (residual below
    // 1e-8) full steps, which converge quadratically down to rounding.
    const double longest = step.head(m).cwiseAbs().maxCoeff();
    double alpha = longest > 0.5 ? 0.5 / longest : 1.0;
    const double r_now = r.norm();
    for (int half = 0; half < 20 && r_now > 1e-8; ++half, alpha *= 0.5)
      if (kkt_residual(chain, resolution, p_H, q + alpha * step.head(m),
                       lambda + alpha * step.tail(3)) < r_now)
        break;
    q += alpha * step.head(m);
    lambda += alpha * step.tail(3);
  }
  out.q = q;
  out.lambda = lambda;
  out.foot_error_m = (chain_foot_position(chain, q) - p_H).norm();
  out.converged = out.converged && reduced_hessian_positive(K, J, m);
  // Rates: K [q̇; λ̇] = [0; ṗ].
  const Eigen::PartialPivLU<KktMatrix> lu(K);
  KktVector rhs = KktVector::Zero(m + 3);
  rhs.tail(3) = pd_H;
  const KktVector rate = lu.solve(rhs);
  out.qd = rate.head(m);
  out.lambda_dot = rate.tail(3);
  // Accelerations: K [q̈; λ̈] = [−(2 Σ λ̇_i ∇²f_i q̇ + Σ λ_i ∇³f_i[q̇, q̇, ·]); p̈ − ∇²f[q̇, q̇]].
  for (int a = 0; a < m; ++a) {
    double top = 0.0;
    for (int i = 0; i < 3; ++i)
      top += 2.0 * out.lambda_dot[i] * (hess[static_cast<std::size_t>(i)].row(a).dot(out.qd));
    top += lambda.dot(chain_third_derivative(chain, q, out.qd, out.qd, unit(m, a)));
    rhs[a] = -top;
  }
  rhs.tail(3) = pdd_H - chain_second_derivative(chain, q, out.qd, out.qd);
  out.qdd = lu.solve(rhs).head(m);
  return out;
}

}  // namespace hexdyn
