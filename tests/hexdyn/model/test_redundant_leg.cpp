// Leg chains of 3 to 6 joints and the redundant leg's resolution (model/redundant_leg.hpp)
// against second computations made here: the foot by Eigen's own frame composition
// (AngleAxis, Translation), the Jacobian by the geometric rule w_k × (p − o_k), every higher
// derivative by central differences of the one below, the optimum by its reduced gradient
// (an SVD's null space, not the multipliers) and by feasible neighbours, and q̇, q̈ by
// differences of the resolution along a smooth foot path.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "hexdyn/model/redundant_leg.hpp"

namespace hexdyn {
namespace {

/// A chain of `m` joints with seeded random placements (2–10 cm), orientations and axes;
/// joint `prismatic` (−1: none) slides.
SerialChain random_chain(int m, unsigned seed, int prismatic = -1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SerialChain c;
  c.count = m;
  for (int k = 0; k < m; ++k) {
    ChainJoint& j = c.joints[static_cast<std::size_t>(k)];
    j.p_parent_m = Vec3(0.06 + 0.04 * u(rng), 0.02 * u(rng), 0.02 * u(rng));
    j.R_parent = Eigen::Quaterniond(1.0, 0.4 * u(rng), 0.4 * u(rng), 0.4 * u(rng))
                     .normalized()
                     .toRotationMatrix();
    j.axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    j.type = k == prismatic ? ChainJointType::kPrismatic : ChainJointType::kRevolute;
  }
  c.p_foot_m = Vec3(0.08, 0.01, -0.02);
  return c;
}

ChainVector random_q(int m, unsigned seed, double spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-spread, spread);
  ChainVector q(m);
  for (int k = 0; k < m; ++k) q[k] = u(rng);
  return q;
}

/// The frames of every joint and the foot by Eigen's transforms: o_k, w_k (hip frame).
struct Frames {
  std::vector<Vec3> origin, axis;
  Vec3 foot;
};

Frames eigen_frames(const SerialChain& c, const ChainVector& q) {
  Frames f;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int k = 0; k < c.count; ++k) {
    const ChainJoint& j = c.joints[static_cast<std::size_t>(k)];
    T = T * Eigen::Translation3d(j.p_parent_m) * Eigen::Isometry3d(j.R_parent);
    f.origin.push_back(T.translation());
    f.axis.push_back(T.linear() * j.axis);
    if (j.type == ChainJointType::kRevolute)
      T = T * Eigen::AngleAxisd(q[k], j.axis);
    else
      T = T * Eigen::Translation3d(q[k] * j.axis);
  }
  f.foot = T * c.p_foot_m;
  return f;
}

const int kChains[][2] = {{3, -1}, {4, -1}, {5, -1}, {6, -1}, {4, 2}};

TEST_CASE("a chain's foot and Jacobian equal Eigen's frames and the geometric rule",
          "[redundant]") {
  for (const auto& spec : kChains) {
    const SerialChain c = random_chain(spec[0], 11u + spec[0], spec[1]);
    for (unsigned s = 0; s < 5; ++s) {
      const ChainVector q = random_q(c.count, 100u + s, 2.0);
      const Frames f = eigen_frames(c, q);
      CHECK((chain_foot_position(c, q) - f.foot).norm() < 1e-15);
      const ChainJacobian J = chain_jacobian(c, q);
      for (int k = 0; k < c.count; ++k) {
        const Vec3 col = c.joints[static_cast<std::size_t>(k)].type == ChainJointType::kRevolute
                             ? Vec3(f.axis[k].cross(f.foot - f.origin[k]))
                             : f.axis[k];
        CHECK((J.col(k) - col).norm() < 1e-15);
      }
    }
  }
}

TEST_CASE("second and third chain derivatives equal central differences", "[redundant]") {
  const double h = 1e-5;
  for (const auto& spec : kChains) {
    const SerialChain c = random_chain(spec[0], 21u + spec[0], spec[1]);
    const int m = c.count;
    const ChainVector q = random_q(m, 7u, 1.5), u = random_q(m, 8u, 1.0), v = random_q(m, 9u, 1.0),
                      w = random_q(m, 10u, 1.0);
    // Hessians: differences of the Jacobian.
    const std::array<ChainMatrix, 3> H = chain_hessians(c, q);
    for (int b = 0; b < m; ++b) {
      ChainVector e = ChainVector::Zero(m);
      e[b] = h;
      const ChainJacobian dJ = (chain_jacobian(c, q + e) - chain_jacobian(c, q - e)) / (2 * h);
      for (int i = 0; i < 3; ++i)
        CHECK((H[static_cast<std::size_t>(i)].col(b) - dJ.row(i).transpose()).norm() < 1e-9);
    }
    // ∇²f[u, v]: the derivative of J u along v.
    const Vec3 second = chain_second_derivative(c, q, u, v);
    const Vec3 fd2 =
        (chain_jacobian(c, q + h * v) * u - chain_jacobian(c, q - h * v) * u) / (2 * h);
    CHECK((second - fd2).norm() < 1e-9);
    // ∇³f[u, v, w]: the derivative of ∇²f[u, v] along w.
    const Vec3 third = chain_third_derivative(c, q, u, v, w);
    const Vec3 fd3 = (chain_second_derivative(c, q + h * w, u, v) -
                      chain_second_derivative(c, q - h * w, u, v)) /
                     (2 * h);
    CHECK((third - fd3).norm() < 1e-8);
  }
}

RedundantResolution resolution_of(int m) {
  RedundantResolution r;
  r.q_nominal = random_q(m, 31u, 0.5);
  r.weight = ChainVector::Constant(m, 1.0) + 0.5 * random_q(m, 32u, 1.0).cwiseAbs();
  return r;
}

double objective(const RedundantResolution& r, const ChainVector& q) {
  return 0.5 * (q - r.q_nominal).dot(r.weight.cwiseProduct(q - r.q_nominal));
}

TEST_CASE("the resolution reaches the foot and is the constrained optimum", "[redundant]") {
  for (const auto& spec : kChains) {
    const SerialChain c = random_chain(spec[0], 41u + spec[0], spec[1]);
    const int m = c.count;
    const RedundantResolution r = resolution_of(m);
    for (unsigned s = 0; s < 4; ++s) {
      const Vec3 p = chain_foot_position(c, r.q_nominal + random_q(m, 50u + s, 0.3));
      const RedundantLegMotion mo =
          redundant_leg_motion(c, r, p, Vec3::Zero(), Vec3::Zero(), r.q_nominal);
      REQUIRE(mo.converged);
      CHECK((chain_foot_position(c, mo.q) - p).norm() < 1e-13);
      if (m == 3) continue;
      // Reduced gradient on J's null space (from an SVD) vanishes.
      const ChainJacobian J = chain_jacobian(c, mo.q);
      const Eigen::MatrixXd Jd = J;
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jd, Eigen::ComputeFullV);
      const Eigen::MatrixXd Z = svd.matrixV().rightCols(m - 3);
      const Eigen::VectorXd grad = r.weight.cwiseProduct(mo.q - r.q_nominal);
      CHECK((Z.transpose() * grad).norm() < 1e-12 * (1.0 + grad.norm()));
      // No feasible neighbour is better: a null-space move brought back onto f = p by
      // least-norm Newton steps.
      const double best = objective(r, mo.q);
      for (int k = 0; k < m - 3; ++k)
        for (double step : {-1e-3, 1e-3}) {
          ChainVector x = mo.q + step * ChainVector(Z.col(k));
          for (int it = 0; it < 20; ++it) {
            const ChainJacobian Jx = chain_jacobian(c, x);
            const Vec3 e = p - chain_foot_position(c, x);
            x += Jx.transpose() * (Jx * Jx.transpose()).ldlt().solve(e);
          }
          CHECK((chain_foot_position(c, x) - p).norm() < 1e-14);
          CHECK(objective(r, x) >= best);
        }
    }
  }
}

/// A smooth foot path inside the chain's workspace: the foot of the joint path
/// q_nom + a sin(ωt) + b cos(2ωt), with ṗ = J q̇ and p̈ = J q̈ + ∇²f[q̇, q̇] (the chain's
/// derivatives, checked above against Eigen's frames and differences).
struct Path {
  const SerialChain& c;
  ChainVector q0, a, b;
  double omega = 3.0;
  ChainVector q(double t) const {
    return q0 + a * std::sin(omega * t) + b * std::cos(2 * omega * t);
  }
  ChainVector qd(double t) const {
    return omega * a * std::cos(omega * t) - 2 * omega * b * std::sin(2 * omega * t);
  }
  ChainVector qdd(double t) const {
    return -omega * omega * a * std::sin(omega * t) -
           4 * omega * omega * b * std::cos(2 * omega * t);
  }
  Vec3 p(double t) const { return chain_foot_position(c, q(t)); }
  Vec3 pd(double t) const { return chain_jacobian(c, q(t)) * qd(t); }
  Vec3 pdd(double t) const {
    return chain_jacobian(c, q(t)) * qdd(t) + chain_second_derivative(c, q(t), qd(t), qd(t));
  }
};

TEST_CASE("q̇ and q̈ of the resolution equal differences along a foot path, and keep the foot",
          "[redundant]") {
  for (const auto& spec : kChains) {
    const SerialChain c = random_chain(spec[0], 61u + spec[0], spec[1]);
    const int m = c.count;
    const RedundantResolution r = resolution_of(m);
    const Path path{c, r.q_nominal, random_q(m, 71u, 0.1), random_q(m, 72u, 0.05)};
    ChainVector q_prev = r.q_nominal;
    for (double t : {0.1, 0.45, 0.8}) {
      const RedundantLegMotion mo =
          redundant_leg_motion(c, r, path.p(t), path.pd(t), path.pdd(t), q_prev);
      REQUIRE(mo.converged);
      q_prev = mo.q;
      const double h = 1e-4;
      const auto q_at = [&](double ti) {
        return redundant_leg_motion(c, r, path.p(ti), Vec3::Zero(), Vec3::Zero(), mo.q).q;
      };
      const ChainVector qm = q_at(t - h), qp = q_at(t + h);
      const ChainVector qd_fd = (qp - qm) / (2 * h);
      const ChainVector qdd_fd = (qp - 2 * mo.q + qm) / (h * h);
      CHECK((mo.qd - qd_fd).norm() < 1e-7 * (1.0 + mo.qd.norm()));
      CHECK((mo.qdd - qdd_fd).norm() < 1e-5 * (1.0 + mo.qdd.norm()));
      // The foot moves as the plan says: f(q) = p, J q̇ = ṗ, J q̈ + J̇ q̇ = p̈.
      const ChainJacobian J = chain_jacobian(c, mo.q);
      CHECK((chain_foot_position(c, mo.q) - path.p(t)).norm() < 1e-13);
      CHECK((J * mo.qd - path.pd(t)).norm() < 1e-13);
      CHECK((J * mo.qdd + chain_second_derivative(c, mo.q, mo.qd, mo.qd) - path.pdd(t)).norm() <
            1e-11);
    }
  }
}

}  // namespace
}  // namespace hexdyn
