// Floating-base dynamics (dynamics.hpp, spatial.hpp), each result checked against a
// second, independent computation: CRBA against RNEA, foot Jacobians against finite
// differences of the tree FK, RNEA against the whole-robot momentum rate, the mass
// matrix against the kinetic energy and the momentum, the contact split against RNEA.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "hexdyn/core/spatial.hpp"
#include "hexdyn/dynamics/dynamics_samples.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
using namespace test;
namespace {

/// World poses of all bodies through forward_kinematics_tree and the trunk pose.
struct WorldPoses {
  std::array<Mat3, kPaperBodies> R;
  std::array<Vec3, kPaperBodies> p;
};

WorldPoses world_poses(const RobotModel& model, const BaseState& s, const PaperJointVector& q) {
  BodyPoses b;
  forward_kinematics_tree(model, q, b);
  WorldPoses w;
  for (int i = 0; i < kPaperBodies; ++i) {
    w.R[i] = s.W_R_B * b.R_B[i];
    w.p[i] = s.p_W + s.W_R_B * b.p_B[i];
  }
  return w;
}

Vec3 foot_position_W(const RobotModel& model, const BaseState& s, const PaperJointVector& q,
                     int leg) {
  BodyPoses b;
  forward_kinematics_tree(model, q, b);
  return s.p_W + s.W_R_B * tree_foot_position_B(model, b, leg);
}

/// Smooth trajectory through a sample at t = 0: quadratic joints and trunk position,
/// trunk rotation R(t) = exp(ω₀ t + ½ ω̇₀ t²) R₀, so the state at t = 0 is the sample.
struct Trajectory {
  Sample s0;
  Sample at(double t) const {
    Sample s = s0;
    const Vec3 phi = s0.state.omega_W * t + 0.5 * s0.state.omegadot_W * t * t;
    const Vec3 phi_dot = s0.state.omega_W + s0.state.omegadot_W * t;
    s.state.W_R_B = so3_exp(phi) * s0.state.W_R_B;
    s.state.omega_W = so3_left_jacobian(phi) * phi_dot;
    s.state.p_W = s0.state.p_W + s0.state.v_W * t + 0.5 * s0.state.a_W * t * t;
    s.state.v_W = s0.state.v_W + s0.state.a_W * t;
    s.q = s0.q + s0.qd * t + 0.5 * s0.qdd * t * t;
    s.qd = s0.qd + s0.qdd * t;
    return s;  // accelerations are only exact at t = 0 and unused elsewhere
  }
};

/// Fourth-order central difference of f at t = 0.
template <class F>
auto central_difference(F&& f, double h) {
  return ((f(-2.0 * h) - 8.0 * f(-h) + 8.0 * f(h) - f(2.0 * h)) / (12.0 * h)).eval();
}

}  // namespace

TEST_CASE("spatial algebra agrees with its 6x6 matrix forms", "[dynamics][spatial]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Transform X{random_rotation(rng), random_vec3(rng, -1.0, 1.0)};
    const Motion m{random_vec3(rng, -1.0, 1.0), random_vec3(rng, -1.0, 1.0)};
    const Motion a{random_vec3(rng, -1.0, 1.0), random_vec3(rng, -1.0, 1.0)};
    const Force f{random_vec3(rng, -1.0, 1.0), random_vec3(rng, -1.0, 1.0)};
    const Mat6 Xm = X.motion_matrix(), Xf = X.force_matrix();
    CHECK((X.apply(m).vector() - Xm * m.vector()).norm() < 1e-13);
    CHECK((X.apply(f).vector() - Xf * f.vector()).norm() < 1e-13);
    CHECK((X.apply_inverse(X.apply(m)).vector() - m.vector()).norm() < 1e-13);
    CHECK((X.apply_inverse(X.apply(f)).vector() - f.vector()).norm() < 1e-13);
    CHECK((X.inverse().motion_matrix() - Xm.inverse()).norm() < 1e-12);
    CHECK((Xf - Xm.inverse().transpose()).norm() < 1e-12);
    CHECK(std::abs(dot(X.apply(f), X.apply(m)) - dot(f, m)) < 1e-13);  // power invariance
    const Transform Y{random_rotation(rng), random_vec3(rng, -1.0, 1.0)};
    CHECK(((X * Y).motion_matrix() - Xm * Y.motion_matrix()).norm() < 1e-12);
    // crf(a) = −crm(a)ᵀ, and a × a = 0
    Mat6 crm, crf;
    for (int i = 0; i < 6; ++i) {
      crm.col(i) = cross(a, Motion::from_vector(Vec6::Unit(i))).vector();
      crf.col(i) = cross(a, Force::from_vector(Vec6::Unit(i))).vector();
    }
    CHECK((crf + crm.transpose()).norm() < 1e-13);
    CHECK(cross(a, a).vector().norm() < 1e-13);
    // Inertia: h = I v, transformation X* I X⁻¹, sum of matrices.
    const Inertia I{uniform(rng, 0.1, 2.0), random_vec3(rng, -0.2, 0.2),
                    Mat3(test::random_inertia(rng, 0.1).asDiagonal())};
    const Inertia J{uniform(rng, 0.1, 2.0), random_vec3(rng, -0.2, 0.2),
                    Mat3(test::random_inertia(rng, 0.1).asDiagonal())};
    CHECK(((I * m).vector() - I.matrix() * m.vector()).norm() < 1e-13);
    CHECK((X.apply(I).matrix() - Xf * I.matrix() * Xm.inverse()).norm() < 1e-12);
    CHECK(((I + J).matrix() - I.matrix() - J.matrix()).norm() < 1e-12);
  }
}

TEST_CASE("rnea equals crba M times acceleration plus rnea at zero acceleration", "[dynamics]") {
  std::mt19937 rng(11);
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    for (int n = 0; n < kStatesPerRobot; ++n) {
      const Sample s = random_sample(rng);
      const PaperDofVector tau = rnea(model, data, s.state, s.q, s.qd, s.qdd);
      BaseState s0 = s.state;
      s0.a_W.setZero();
      s0.omegadot_W.setZero();
      const PaperDofVector h = rnea(model, data, s0, s.q, s.qd, PaperJointVector::Zero());
      const PaperDofMatrix M = crba(model, data, s.state, s.q);
      const PaperDofVector expected = M * acceleration_vector(s) + h;
      CHECK((tau - expected).norm() <= 1e-10 * std::max(1.0, tau.norm()));
      CHECK((M - M.transpose()).norm() <= 1e-14 * M.norm());
      const Eigen::SelfAdjointEigenSolver<PaperDofMatrix> eig(M);
      CHECK(eig.eigenvalues().minCoeff() > 0.0);
      // Trunk block: total mass times identity.
      CHECK((M.topLeftCorner<3, 3>() - model.total_mass_kg * Mat3::Identity()).norm() < 1e-12);
    }
  }
}

TEST_CASE("rnea at rest holds the weight of the robot", "[dynamics]") {
  std::mt19937 rng(13);
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    Sample s = random_sample(rng);
    s.state.v_W.setZero();
    s.state.omega_W.setZero();
    s.state.a_W.setZero();
    s.state.omegadot_W.setZero();
    const PaperDofVector tau =
        rnea(model, data, s.state, s.q, PaperJointVector::Zero(), PaperJointVector::Zero());
    const WorldPoses w = world_poses(model, s.state, s.q);
    const Vec3 g(0.0, 0.0, -kGravity);
    // Trunk rows: the wrench about P0 that supports the whole robot against gravity.
    BodyPoses b;
    forward_kinematics_tree(model, s.q, b);
    const Vec3 c_W = s.state.p_W + s.state.W_R_B * center_of_mass_B(model, b);
    const Vec3 support = -model.total_mass_kg * g;
    CHECK((tau.head<3>() - support).norm() < 1e-10 * support.norm());
    CHECK((tau.segment<3>(3) - (c_W - s.state.p_W).cross(support)).norm() < 1e-10 * support.norm());
    // Joint rows: each joint holds the gravity moment of the bodies outboard of it.
    for (int k = 0; k < kPaperJoints; ++k) {
      const int bj = 1 + k;
      const Vec3 axis_W = w.R[bj] * model.axis[bj];
      double expected = 0.0;
      for (int d = bj; d < kPaperBodies; ++d) {
        int a = d;
        while (a > bj) a = model.parent[a];
        if (a != bj) continue;  // d is not in the subtree of bj
        const Vec3 c_d = w.p[d] + w.R[d] * model.inertia[d].com_m;
        expected -= axis_W.dot((c_d - w.p[bj]).cross(model.inertia[d].mass_kg * g));
      }
      CHECK(tau[6 + k] == Approx(expected).margin(1e-12));
    }
  }
}

TEST_CASE("foot Jacobians match finite differences of the tree kinematics", "[dynamics]") {
  std::mt19937 rng(17);
  const double h = 1e-6;
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    const Sample s = random_sample(rng);
    foot_jacobians(model, data, s.state, s.q);
    for (int l = 0; l < kPaperLegs; ++l) {
      CHECK((data.p_foot_W[l] - foot_position_W(model, s.state, s.q, l)).norm() < 1e-14);
      PaperFootJacobian J_fd;
      for (int i = 0; i < kPaperDof; ++i) {
        // Move along generalised velocity e_i: p(t) = p + v t, R(t) = exp(ω t) R, q + q̇ t.
        auto foot_at = [&](double t) {
          BaseState st = s.state;
          const PaperDofVector e = PaperDofVector::Unit(i);
          st.p_W += e.head<3>() * t;
          st.W_R_B = so3_exp(e.segment<3>(3) * t) * s.state.W_R_B;
          const PaperJointVector q = s.q + e.tail<kPaperJoints>() * t;
          return foot_position_W(model, st, q, l);
        };
        J_fd.col(i) = (foot_at(h) - foot_at(-h)) / (2.0 * h);
      }
      CHECK((data.J_foot_W[l] - J_fd).cwiseAbs().maxCoeff() < 1e-7);
    }
  }
}

TEST_CASE("rnea with foot forces equals rnea without minus J^T F", "[dynamics]") {
  std::mt19937 rng(19);
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    for (int n = 0; n < kStatesPerRobot; ++n) {
      const Sample s = random_sample(rng);
      const auto F = random_forces(rng);
      const PaperDofVector tau_free = rnea(model, data, s.state, s.q, s.qd, s.qdd);
      const PaperDofVector tau_forced = rnea(model, data, s.state, s.q, s.qd, s.qdd, &F);
      foot_jacobians(model, data, s.state, s.q);
      PaperDofVector expected = tau_free;
      for (int l = 0; l < kPaperLegs; ++l) expected -= data.J_foot_W[l].transpose() * F[l];
      CHECK((tau_forced - expected).norm() <= 1e-10 * std::max(1.0, tau_forced.norm()));
    }
  }
}

TEST_CASE("momentum rate equals gravity plus trunk wrench plus foot forces", "[dynamics]") {
  std::mt19937 rng(23);
  const Vec3 g(0.0, 0.0, -kGravity);
  const double h = 1e-3;
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    const Trajectory traj{random_sample(rng)};
    const auto F = random_forces(rng);
    auto momentum_at = [&](double t) {
      const Sample s = traj.at(t);
      const Momentum& m = robot_momentum(model, data, s.state, s.q, s.qd);
      Vec6 out;
      out << m.linear_W, m.angular_O_W;
      return out;
    };
    const Vec6 rate = central_difference(momentum_at, h);

    const Sample& s = traj.s0;
    const Momentum m0 = robot_momentum(model, data, s.state, s.q, s.qd);
    const PaperDofVector tau = rnea(model, data, s.state, s.q, s.qd, s.qdd, &F);
    foot_jacobians(model, data, s.state, s.q);
    BodyPoses b;
    forward_kinematics_tree(model, s.q, b);
    const Vec3 c_W = s.state.p_W + s.state.W_R_B * center_of_mass_B(model, b);
    CHECK((m0.com_W - c_W).norm() < 1e-14);
    // External wrench about the world origin: gravity at the COM, trunk wrench at P0,
    // terrain forces at the feet.
    const Vec3 f_base = tau.head<3>(), n_base = tau.segment<3>(3);
    Vec3 force = model.total_mass_kg * g + f_base;
    Vec3 moment = c_W.cross(model.total_mass_kg * g) + s.state.p_W.cross(f_base) + n_base;
    for (int l = 0; l < kPaperLegs; ++l) {
      force += F[l];
      moment += data.p_foot_W[l].cross(F[l]);
    }
    Vec6 expected;
    expected << force, moment;
    CHECK(relative_error(rate, expected) < 1e-6);
  }
}

TEST_CASE("kinetic energy and momentum agree with the mass matrix", "[dynamics]") {
  std::mt19937 rng(29);
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    for (int n = 0; n < kStatesPerRobot; ++n) {
      const Sample s = random_sample(rng);
      const PaperDofVector nu = velocity_vector(s);
      const PaperDofMatrix& M = crba(model, data, s.state, s.q);
      const PaperDofVector Mnu = M * nu;
      const double T_matrix = 0.5 * nu.dot(Mnu);

      // Body by body from geometric Jacobian columns of the tree FK.
      const WorldPoses w = world_poses(model, s.state, s.q);
      double T_direct = 0.0;
      Vec3 L = Vec3::Zero(), H_P0 = Vec3::Zero();
      for (int b = 0; b < kPaperBodies; ++b) {
        const Vec3 c = w.p[b] + w.R[b] * model.inertia[b].com_m;
        Vec3 omega = s.state.omega_W;
        Vec3 v_c = s.state.v_W + s.state.omega_W.cross(c - s.state.p_W);
        for (int a = b; a > 0; a = model.parent[a]) {
          const Vec3 axis_W = w.R[a] * model.axis[a];
          omega += axis_W * s.qd[a - 1];
          v_c += axis_W.cross(c - w.p[a]) * s.qd[a - 1];
        }
        const double m = model.inertia[b].mass_kg;
        const Mat3 I_W = w.R[b] * model.inertia[b].inertia_com * w.R[b].transpose();
        T_direct += 0.5 * (m * v_c.squaredNorm() + omega.dot(I_W * omega));
        L += m * v_c;
        H_P0 += I_W * omega + (c - s.state.p_W).cross(m * v_c);
      }
      CHECK(T_matrix == Approx(T_direct).epsilon(1e-12));
      // ∂T/∂ν of the trunk rows: linear momentum and angular momentum about P0.
      CHECK(relative_error(Mnu.head<3>(), L) < 1e-12);
      CHECK(relative_error(Mnu.segment<3>(3), H_P0) < 1e-12);
      const Momentum& mom = robot_momentum(model, data, s.state, s.q, s.qd);
      CHECK(relative_error(mom.linear_W, L) < 1e-12);
      CHECK(relative_error(mom.angular_O_W - s.state.p_W.cross(mom.linear_W), H_P0) < 1e-12);
      CHECK(relative_error(mom.angular_com_W, H_P0 - (mom.com_W - s.state.p_W).cross(L)) < 1e-12);
    }
  }
}

TEST_CASE("foot bias accelerations match finite differences of foot positions", "[dynamics]") {
  std::mt19937 rng(31);
  const double h = 1e-3;
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    const Trajectory traj{random_sample(rng)};
    const Sample& s = traj.s0;
    foot_jacobians(model, data, s.state, s.q);
    const auto J = data.J_foot_W;
    const auto bias = foot_bias_accelerations(model, data, s.state, s.q, s.qd);
    for (int l = 0; l < kPaperLegs; ++l) {
      auto velocity_at = [&](double t) {
        const Sample st = traj.at(t);
        foot_jacobians(model, data, st.state, st.q);
        return (data.J_foot_W[l] * velocity_vector(st)).eval();
      };
      const Vec3 a_fd = central_difference(velocity_at, h);
      const Vec3 a = J[l] * acceleration_vector(s) + bias[l];
      CHECK(relative_error(a, a_fd) < 1e-6);
    }
  }
}

TEST_CASE("contact split reproduces rnea with foot forces", "[dynamics]") {
  std::mt19937 rng(37);
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    for (int n = 0; n < kStatesPerRobot; ++n) {
      const Sample s = random_sample(rng);
      const auto F = random_forces(rng);
      const ContactSplit split = contact_split(model, data, s.state, s.q, s.qd, s.qdd);
      const PaperDofVector tau = rnea(model, data, s.state, s.q, s.qd, s.qdd, &F);
      Vec6 trunk = split.trunk_rhs;
      PaperJointVector joints = split.tau0;
      for (int l = 0; l < kPaperLegs; ++l) {
        trunk -= split.JbT[l] * F[l];
        joints -= split.JjT[l] * F[l];
        // Leg l's forces load only leg l's joints.
        Eigen::Matrix<double, kPaperJoints, 3> other_legs = split.JjT[l];
        other_legs.middleRows<3>(3 * l).setZero();
        CHECK(other_legs.norm() == 0.0);
      }
      CHECK((trunk - tau.head<6>()).norm() <= 1e-10 * std::max(1.0, tau.norm()));
      CHECK((joints - tau.tail<kPaperJoints>()).norm() <= 1e-10 * std::max(1.0, tau.norm()));
    }
  }
}

// ---- sphere feet (docs/theory/model.md#sphere-feet) ----
namespace {

/// The tibia's angular-velocity Jacobian of leg l (3×24): ω_tibia = J_ω ν, from the tree's
/// world poses alone: the trunk's ω and each leg joint's axis in world axes.
Eigen::Matrix<double, 3, kPaperDof> tibia_angular_jacobian(const RobotModel& model, const Sample& s,
                                                           int l) {
  const WorldPoses w = world_poses(model, s.state, s.q);
  Eigen::Matrix<double, 3, kPaperDof> J = Eigen::Matrix<double, 3, kPaperDof>::Zero();
  J.block<3, 3>(0, 3).setIdentity();
  for (int j = 0; j < model.leg(l).n_joints; ++j) {
    const int k = model.joint(l, j);
    const int b = model.body(l, j);
    // The joint frame's axes are the child body's at any angle (rotation about the axis).
    J.col(6 + k) = w.R[b] * model.axis[b];
  }
  return J;
}

/// State s moved by t along the generalised velocity ν: p + v t, R = exp(ω t) R, q + q̇ t.
Sample moved(const Sample& s, const PaperDofVector& nu, double t) {
  Sample m = s;
  m.state.p_W += nu.head<3>() * t;
  m.state.W_R_B = so3_exp(nu.segment<3>(3) * t) * s.state.W_R_B;
  m.q = s.q + nu.tail<kPaperJoints>() * t;
  return m;
}

}  // namespace

TEST_CASE("sphere feet: the contact point's Jacobian against finite differences of the FK",
          "[dynamics][sphere]") {
  std::mt19937 rng(41);
  const double h = 1e-6;
  for (const RobotModel& model : sphere_foot_models(rng)) {
    RobotData data(model);
    const Sample s = random_sample(rng);
    const FootNormals n = random_normals(rng);
    foot_jacobians(model, data, s.state, s.q, &n);
    const WorldPoses w0 = world_poses(model, s.state, s.q);
    for (int l = 0; l < kPaperLegs; ++l) {
      const double r = model.foot_radius_m[l];
      const int tibia = model.foot_body(l);
      // The contact point is on the sphere, r below its centre along the normal.
      const Vec3 center = foot_position_W(model, s.state, s.q, l);
      CHECK((data.p_foot_W[l] - (center - r * n[l])).norm() < 1e-14);
      // The tibia's material point at the contact, frozen in the tibia, moved by the FK.
      const Vec3 material = w0.R[tibia].transpose() * (data.p_foot_W[l] - w0.p[tibia]);
      PaperFootJacobian J_material, J_rolling;
      for (int i = 0; i < kPaperDof; ++i) {
        const PaperDofVector e = PaperDofVector::Unit(i);
        auto point_at = [&](double t) {
          const Sample m = moved(s, e, t);
          const WorldPoses w = world_poses(model, m.state, m.q);
          return (w.p[tibia] + w.R[tibia] * material).eval();
        };
        // The rolling contact: the point of the sphere against the surface, r below the
        // centre, wherever the centre goes.
        auto contact_at = [&](double t) {
          const Sample m = moved(s, e, t);
          return (foot_position_W(model, m.state, m.q, l) - r * n[l]).eval();
        };
        J_material.col(i) = (point_at(h) - point_at(-h)) / (2.0 * h);
        J_rolling.col(i) = (contact_at(h) - contact_at(-h)) / (2.0 * h);
      }
      CHECK((data.J_foot_W[l] - J_material).cwiseAbs().maxCoeff() < 1e-7);
      // The contact point rolls with the centre: its rate differs from the material
      // point's by the tibia's rotation about the centre, ω × (−r n).
      const auto J_w = tibia_angular_jacobian(model, s, l);
      const PaperFootJacobian expected_rolling = data.J_foot_W[l] - r * skew(n[l]) * J_w;
      CHECK((J_rolling - expected_rolling).cwiseAbs().maxCoeff() < 1e-7);
      // Rolling without slip: a motion that holds the material point still (J ν = 0)
      // moves the contact point by r ω × n, the arc the sphere rolls through.
      PaperDofVector nu = PaperDofVector::Zero();
      nu.segment<3>(3) = random_vec3(rng, -1.0, 1.0);
      nu.segment<3>(6 + 3 * l) = random_vec3(rng, -2.0, 2.0);
      nu.head<3>() = -(data.J_foot_W[l].rightCols<kPaperDof - 3>() * nu.tail<kPaperDof - 3>());
      REQUIRE((data.J_foot_W[l] * nu).norm() < 1e-12);
      const Vec3 omega = J_w * nu;
      auto rolled_at = [&](double t) {
        const Sample m = moved(s, nu, t);
        return (foot_position_W(model, m.state, m.q, l) - r * n[l]).eval();
      };
      const Vec3 v_contact = (rolled_at(h) - rolled_at(-h)) / (2.0 * h);
      CHECK((v_contact - r * omega.cross(n[l])).norm() < 1e-7);
    }
  }
}

TEST_CASE("sphere feet: a force at the contact point is the force at the centre plus its moment",
          "[dynamics][sphere]") {
  std::mt19937 rng(43);
  for (const RobotModel& model : sphere_foot_models(rng)) {
    RobotModel point_feet = model;  // the same robot, its forces at the sphere centres
    point_feet.foot_radius_m.fill(0.0);
    RobotData data(model), data_center(point_feet);
    for (int k = 0; k < kStatesPerRobot; ++k) {
      const Sample s = random_sample(rng);
      const auto F = random_forces(rng);
      const FootNormals n = random_normals(rng);
      const PaperDofVector tau = rnea(model, data, s.state, s.q, s.qd, s.qdd, &F, &n);
      // τ = τ₀ − Σ J_cᵀ F − Σ J_ωᵀ ((p − c) × F): the centre's Jacobian and the tibia's
      // rotation, the contact point p = c − r n.
      PaperDofVector expected = rnea(point_feet, data_center, s.state, s.q, s.qd, s.qdd);
      foot_jacobians(point_feet, data_center, s.state, s.q);
      for (int l = 0; l < kPaperLegs; ++l) {
        const Vec3 arm = -model.foot_radius_m[l] * n[l];
        expected -= data_center.J_foot_W[l].transpose() * F[l] +
                    tibia_angular_jacobian(model, s, l).transpose() * arm.cross(F[l]);
      }
      CHECK((tau - expected).norm() <= 1e-10 * std::max(1.0, tau.norm()));
      // The contact split carries the same arms.
      const ContactSplit& split = contact_split(model, data, s.state, s.q, s.qd, s.qdd, &n);
      PaperJointVector joints = split.tau0;
      Vec6 trunk = split.trunk_rhs;
      for (int l = 0; l < kPaperLegs; ++l) {
        joints -= split.JjT[l] * F[l];
        trunk -= split.JbT[l] * F[l];
      }
      CHECK((joints - tau.tail<kPaperJoints>()).norm() <= 1e-10 * std::max(1.0, tau.norm()));
      CHECK((trunk - tau.head<6>()).norm() <= 1e-10 * std::max(1.0, tau.norm()));
      // Without a normal, the surfaces are level: +z under every foot.
      FootNormals up;
      up.fill(Vec3::UnitZ());
      const PaperDofVector tau_default = rnea(model, data, s.state, s.q, s.qd, s.qdd, &F);
      const PaperDofVector tau_up = rnea(model, data, s.state, s.q, s.qd, s.qdd, &F, &up);
      CHECK(tau_default == tau_up);
    }
  }
}

TEST_CASE("sphere feet: contact point accelerations match finite differences",
          "[dynamics][sphere]") {
  std::mt19937 rng(47);
  const double h = 1e-3;
  for (const RobotModel& model : sphere_foot_models(rng)) {
    RobotData data(model);
    const Trajectory traj{random_sample(rng)};
    const Sample& s = traj.s0;
    const FootNormals n = random_normals(rng);
    foot_jacobians(model, data, s.state, s.q, &n);
    const auto J = data.J_foot_W;
    const auto bias = foot_bias_accelerations(model, data, s.state, s.q, s.qd, &n);
    const WorldPoses w0 = world_poses(model, s.state, s.q);
    for (int l = 0; l < kPaperLegs; ++l) {
      // The material point at the contact, followed along the trajectory.
      const int tibia = model.foot_body(l);
      RobotModel frozen = model;  // a point foot at the material point
      frozen.foot_radius_m[l] = 0.0;
      frozen.p_foot_last[l] = w0.R[tibia].transpose() * (data.p_foot_W[l] - w0.p[tibia]);
      RobotData d(frozen);
      auto velocity_at = [&](double t) {
        const Sample st = traj.at(t);
        foot_jacobians(frozen, d, st.state, st.q);
        return (d.J_foot_W[l] * velocity_vector(st)).eval();
      };
      const Vec3 a_fd = central_difference(velocity_at, h);
      const Vec3 a = J[l] * acceleration_vector(s) + bias[l];
      CHECK(relative_error(a, a_fd) < 1e-6);
    }
  }
}

TEST_CASE("update_kinematics keeps a state's transforms and recomputes on any change",
          "[dynamics]") {
  // One workspace asked for states in turn (the same state again, one joint angle changed, the
  // trunk moved or turned) against a fresh workspace for each: the same transforms, bit for
  // bit, and a change in any one input is never taken for the state before.
  std::mt19937 rng(97);
  for (const RobotModel& model : sample_models()) {
    RobotData kept(model);
    for (int n = 0; n < kStatesPerRobot; ++n) {
      const Sample a = random_sample(rng);
      Sample b = a;
      const int which = n % 3;
      if (which == 0) b.q[n % model.joints()] += 1e-9;
      if (which == 1) b.state.p_W.z() += 1e-12;
      if (which == 2) b.state.W_R_B = random_rotation(rng);
      for (const Sample* s : std::initializer_list<const Sample*>{&a, &a, &b, &a, &b, &b}) {
        update_kinematics(model, kept, s->state, s->q);
        RobotData fresh(model);
        update_kinematics(model, fresh, s->state, s->q);
        for (int body = 0; body < model.bodies(); ++body) {
          REQUIRE(kept.X_world_body[body].R == fresh.X_world_body[body].R);
          REQUIRE(kept.X_world_body[body].p == fresh.X_world_body[body].p);
          REQUIRE(kept.X_parent_body[body].R == fresh.X_parent_body[body].R);
          REQUIRE(kept.X_parent_body[body].p == fresh.X_parent_body[body].p);
        }
      }
    }
  }
}

}  // namespace hexdyn
