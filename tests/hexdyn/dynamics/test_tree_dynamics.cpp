// The dynamics of robots that are not six legs of three joints (a quadruped 4 × 3, a hexapod
// of 4-joint legs, a biped 2 × 6, and a quadruped and a biped with prismatic joints;
// tree_models.hpp), each result against a second computation:
// RNEA against CRBA and RNEA at rest, forward dynamics against RNEA, the foot Jacobians
// against central differences of the foot points of an independent forward kinematics, J̇ν
// against central differences of Jν along the motion, and ½ νᵀMν against the kinetic energy
// summed over the bodies from their velocities (themselves against central differences of the
// independent body poses).
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "hexdyn/core/spatial.hpp"
#include "hexdyn/dynamics/forward_dynamics.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/tree_models.hpp"

namespace hexdyn {
using namespace test;
namespace {

constexpr int kStates = 4;

/// The state moved for a time h at constant generalised velocity nu: p_W + h v_W,
/// exp(h [ω_W]×) W_R_B, q + h q̇ (ν of the rnea.hpp convention).
BaseState moved_base(const BaseState& s, const DofVector& nu, double h) {
  BaseState m = s;
  m.p_W = s.p_W + h * nu.head<3>();
  const Vec3 phi = h * nu.segment<3>(3);
  const double angle = phi.norm();
  const Mat3 R = angle > 0.0 ? Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix()
                             : Mat3::Identity().eval();
  m.W_R_B = R * s.W_R_B;
  return m;
}

JointVector moved_joints(const JointVector& q, const DofVector& nu, double h) {
  return q + h * nu.tail(q.size());
}

/// Angular velocity of a rotation R(t) from R(t + h) and R(t − h): the axial vector of
/// (R₊ − R₋) Rᵀ / 2h.
Vec3 angular_rate(const Mat3& R_plus, const Mat3& R_minus, const Mat3& R, double h) {
  const Mat3 W = (R_plus - R_minus) * R.transpose() / (2.0 * h);
  return 0.5 * Vec3(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1));
}

}  // namespace

TEST_CASE("robots of other shapes get a leg table of their own", "[tree_dynamics]") {
  std::mt19937 rng(431);
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    REQUIRE(m.legs() == static_cast<int>(shape.leg_joints.size()));
    int joints = 0;
    for (int l = 0; l < m.legs(); ++l) {
      CHECK(m.leg(l).n_joints == shape.leg_joints[l]);
      CHECK(m.leg(l).first_joint == joints);
      CHECK(m.leg(l).side == (l % 2 == 0 ? LegSide::kLeft : LegSide::kRight));
      CHECK(m.leg(l).row == l / 2);
      for (int j = 0; j < m.leg(l).n_joints; ++j) CHECK(m.body(l, j) == 1 + joints + j);
      joints += shape.leg_joints[l];
      CHECK(m.foot_body(l) == joints);
    }
    CHECK(m.joints() == joints);
    CHECK(m.bodies() == joints + 1);
    CHECK(m.dofs() == joints + 6);
  }
}

TEST_CASE("the model's tree FK places every body as the independent one, any shape",
          "[tree_dynamics]") {
  std::mt19937 rng(438);
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    for (int i = 0; i < kStates; ++i) {
      const TreeState s = draw_tree_state(rng, m);
      BaseState at_origin;  // the trunk frame B is the world frame
      const TreePoses w = tree_poses(m, at_origin, s.q);
      BodyPoses poses;
      forward_kinematics_tree(m, s.q, poses);
      for (int b = 0; b < m.bodies(); ++b) {
        INFO("body " << b);
        CHECK((poses.p_B[b] - w.p[b]).norm() <= 1e-13);
        CHECK((poses.R_B[b] - w.R[b]).norm() <= 1e-13);
      }
    }
  }
}

TEST_CASE("RNEA = CRBA times the acceleration plus RNEA at rest, any shape", "[tree_dynamics]") {
  std::mt19937 rng(432);
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    RobotData data(m);
    for (int i = 0; i < kStates; ++i) {
      const TreeState s = draw_tree_state(rng, m);
      const DofVector tau = rnea(m, data, s.state, s.q, s.qd, s.qdd);
      REQUIRE(tau.size() == m.dofs());
      BaseState rest = s.state;
      rest.a_W.setZero();
      rest.omegadot_W.setZero();
      const DofVector h = rnea(m, data, rest, s.q, s.qd, JointVector::Zero(m.joints()));
      const DofMatrix M = crba(m, data, s.state, s.q);
      REQUIRE(M.rows() == m.dofs());
      const DofVector expected = M * tree_acceleration(s) + h;
      CHECK((tau - expected).norm() <= 1e-10 * expected.norm());
      CHECK((M - M.transpose()).norm() <= 1e-14 * M.norm());
    }
  }
}

TEST_CASE("forward dynamics inverts RNEA, any shape", "[tree_dynamics]") {
  std::mt19937 rng(433);
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    RobotData data(m);
    for (int i = 0; i < kStates; ++i) {
      const TreeState s = draw_tree_state(rng, m);
      DofVector tau_gen(m.dofs());
      for (int k = 0; k < m.dofs(); ++k) tau_gen[k] = draw(rng, -20.0, 20.0);
      LegArray<Vec3> F;
      for (int l = 0; l < m.legs(); ++l) F[l] = draw_vec3(rng, -30.0, 30.0);
      const DofVector nu_dot = forward_dynamics(m, data, s.state, s.q, s.qd, tau_gen, &F);
      TreeState a = s;
      a.state.a_W = nu_dot.head<3>();
      a.state.omegadot_W = nu_dot.segment<3>(3);
      a.qdd = nu_dot.tail(m.joints());
      const DofVector tau = rnea(m, data, a.state, a.q, a.qd, a.qdd, &F);
      CHECK((tau - tau_gen).norm() <= 1e-9 * tau_gen.norm());
      // The joint-torque form: zero force on the trunk.
      const JointVector tau_j = tau_gen.tail(m.joints());
      const DofVector nu_dot_j = forward_dynamics_joints(m, data, s.state, s.q, s.qd, tau_j, &F);
      a.state.a_W = nu_dot_j.head<3>();
      a.state.omegadot_W = nu_dot_j.segment<3>(3);
      a.qdd = nu_dot_j.tail(m.joints());
      const DofVector tau2 = rnea(m, data, a.state, a.q, a.qd, a.qdd, &F);
      CHECK(tau2.head<6>().norm() <= 1e-9 * tau_gen.norm());
      CHECK((tau2.tail(m.joints()) - tau_j).norm() <= 1e-9 * tau_gen.norm());
    }
  }
}

TEST_CASE("foot Jacobians are the derivatives of the foot points, any shape", "[tree_dynamics]") {
  std::mt19937 rng(434);
  const double h = 1e-6;
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    RobotData data(m);
    for (int i = 0; i < kStates; ++i) {
      const TreeState s = draw_tree_state(rng, m);
      foot_jacobians(m, data, s.state, s.q);
      const TreePoses w0 = tree_poses(m, s.state, s.q);
      for (int l = 0; l < m.legs(); ++l) {
        INFO("leg " << l);
        CHECK((data.p_foot_W[l] - tree_foot(m, w0, l)).norm() <= 1e-13);
        REQUIRE(data.J_foot_W[l].cols() == m.dofs());
        for (int c = 0; c < m.dofs(); ++c) {
          const DofVector e = DofVector::Unit(m.dofs(), c);
          const auto foot = [&](double t) {
            return tree_foot(m, tree_poses(m, moved_base(s.state, e, t), moved_joints(s.q, e, t)),
                             l);
          };
          const Vec3 fd = (foot(h) - foot(-h)) / (2.0 * h);
          CHECK((data.J_foot_W[l].col(c) - fd).norm() <= 1e-7);
          const bool own =
              c < 6 || (c - 6 >= m.joint(l, 0) && c - 6 < m.joint(l, 0) + m.leg(l).n_joints);
          if (!own) CHECK(data.J_foot_W[l].col(c).norm() == 0.0);
        }
      }
    }
  }
}

TEST_CASE("J-dot nu is the derivative of J nu along the motion, any shape", "[tree_dynamics]") {
  std::mt19937 rng(435);
  const double h = 1e-5;
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    RobotData data(m), moved(m);
    for (int i = 0; i < kStates; ++i) {
      const TreeState s = draw_tree_state(rng, m);
      const DofVector nu = tree_velocity(s);
      const LegArray<Vec3> bias = foot_bias_accelerations(m, data, s.state, s.q, s.qd);
      const auto velocities = [&](double t) {
        foot_jacobians(m, moved, moved_base(s.state, nu, t), moved_joints(s.q, nu, t));
        LegArray<Vec3> v;
        for (int l = 0; l < m.legs(); ++l) v[l] = moved.J_foot_W[l] * nu;
        return v;
      };
      const LegArray<Vec3> plus = velocities(h), minus = velocities(-h);
      for (int l = 0; l < m.legs(); ++l) {
        INFO("leg " << l);
        const Vec3 fd = (plus[l] - minus[l]) / (2.0 * h);
        CHECK((bias[l] - fd).norm() <= 1e-6 * std::max(1.0, fd.norm()));
      }
    }
  }
}

TEST_CASE("the kinetic energy from M equals the sum over the bodies, any shape",
          "[tree_dynamics]") {
  std::mt19937 rng(436);
  const double h = 1e-6;
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    RobotData data(m);
    for (int i = 0; i < kStates; ++i) {
      const TreeState s = draw_tree_state(rng, m);
      const DofVector nu = tree_velocity(s);
      const double T_M = kinetic_energy(m, data, s.state, s.q, s.qd);
      robot_momentum(m, data, s.state, s.q, s.qd);
      const TreePoses w = tree_poses(m, s.state, s.q);
      const TreePoses wp = tree_poses(m, moved_base(s.state, nu, h), moved_joints(s.q, nu, h));
      const TreePoses wm = tree_poses(m, moved_base(s.state, nu, -h), moved_joints(s.q, nu, -h));
      double T_bodies = 0.0;
      for (int b = 0; b < m.bodies(); ++b) {
        INFO("body " << b);
        const RigidInertia& in = m.inertia[b];
        const Vec3& omega = data.omega_body_W[b];
        const Vec3& v_com = data.v_com_body_W[b];
        // The body velocities against the independent poses.
        const Vec3 c_plus = wp.p[b] + wp.R[b] * in.com_m, c_minus = wm.p[b] + wm.R[b] * in.com_m;
        CHECK((v_com - (c_plus - c_minus) / (2.0 * h)).norm() <= 1e-6);
        CHECK((omega - angular_rate(wp.R[b], wm.R[b], w.R[b], h)).norm() <= 1e-6);
        const Mat3 I_W = w.R[b] * in.inertia_com * w.R[b].transpose();
        T_bodies += 0.5 * in.mass_kg * v_com.squaredNorm() + 0.5 * omega.dot(I_W * omega);
      }
      CHECK(std::abs(T_M - T_bodies) <= 1e-10 * T_bodies);
    }
  }
}

TEST_CASE("the contact split of another shape is RNEA's, sized by the model", "[tree_dynamics]") {
  std::mt19937 rng(437);
  for (const TreeShape& shape : tree_shapes()) {
    INFO(shape.name);
    const RobotModel m = tree_model(rng, shape.leg_joints, shape.prismatic);
    RobotData data(m);
    const TreeState s = draw_tree_state(rng, m);
    LegArray<Vec3> F;
    for (int l = 0; l < m.legs(); ++l) F[l] = draw_vec3(rng, -30.0, 30.0);
    const DofVector tau_F = rnea(m, data, s.state, s.q, s.qd, s.qdd, &F);
    const ContactSplit& split = contact_split(m, data, s.state, s.q, s.qd, s.qdd);
    REQUIRE(split.tau0.size() == m.joints());
    Vec6 trunk = split.trunk_rhs;
    JointVector tau = split.tau0;
    for (int l = 0; l < m.legs(); ++l) {
      REQUIRE(split.JjT[l].rows() == m.joints());
      trunk -= split.JbT[l] * F[l];
      tau -= split.JjT[l] * F[l];
    }
    CHECK((trunk - tau_F.head<6>()).norm() <= 1e-10 * tau_F.norm());
    CHECK((tau - tau_F.tail(m.joints())).norm() <= 1e-10 * tau_F.norm());
  }
}

}  // namespace hexdyn
