// Forward dynamics (dynamics/forward_dynamics.hpp, docs/theory/replay.md#forward-dynamics),
// each result checked against a second computation: the inverse dynamics of its answer
// (rnea), a mass matrix assembled from columns of rnea differences and solved by LU, and
// the free robot integrated for a second, whose kinetic energy and momentum
// (robot_momentum, summed body by body) must not change. Also the root link frame's state
// (model/root_link.hpp), against differences of the trunk's rigid motion.
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/dynamics/dynamics_samples.hpp"
#include "hexdyn/dynamics/forward_dynamics.hpp"
#include "hexdyn/model/root_link.hpp"
#include "hexdyn/paper_sizes.hpp"

namespace hexdyn {
using namespace test;
namespace {

PaperDofVector random_generalised_force(std::mt19937& rng) {
  PaperDofVector tau;
  tau << random_vec3(rng, -30.0, 30.0), random_vec3(rng, -5.0, 5.0),
      random_joint_vector(rng, -3.0, 3.0);
  return tau;
}

/// The sample's state with the accelerations ν̇ (24).
Sample with_acceleration(Sample s, const PaperDofVector& nu_dot) {
  s.state.a_W = nu_dot.head<3>();
  s.state.omegadot_W = nu_dot.segment<3>(3);
  s.qdd = nu_dot.tail<kPaperJoints>();
  return s;
}

/// One model's round trip at kStatesPerRobot random states: rnea(q, ν, FD(q, ν, τ)) = τ, with
/// foot forces at the contact points of random normals (sphere feet) or none.
void check_round_trip(const RobotModel& model, std::mt19937& rng, bool with_forces) {
  RobotData data(model);
  for (int n = 0; n < kStatesPerRobot; ++n) {
    const Sample s = random_sample(rng);
    const PaperDofVector tau = random_generalised_force(rng);
    const auto F = random_forces(rng);
    const FootNormals normals = random_normals(rng);
    const auto* forces = with_forces ? &F : nullptr;
    const PaperDofVector nu_dot =
        forward_dynamics(model, data, s.state, s.q, s.qd, tau, forces, &normals);
    const Sample a = with_acceleration(s, nu_dot);
    const PaperDofVector back = rnea(model, data, a.state, a.q, a.qd, a.qdd, forces, &normals);
    CHECK((back - tau).norm() <= 1e-10 * std::max(1.0, tau.norm()));
    // The joint torques alone: the trunk rows of the inverse dynamics vanish.
    const PaperDofVector nu_dot_j = forward_dynamics_joints(
        model, data, s.state, s.q, s.qd, tau.tail<kPaperJoints>(), forces, &normals);
    const Sample aj = with_acceleration(s, nu_dot_j);
    const PaperDofVector back_j =
        rnea(model, data, aj.state, aj.q, aj.qd, aj.qdd, forces, &normals);
    CHECK(back_j.head<6>().norm() <= 1e-10 * std::max(1.0, tau.norm()));
    CHECK((back_j.tail<kPaperJoints>() - tau.tail<kPaperJoints>()).norm() <=
          1e-10 * std::max(1.0, tau.norm()));
  }
}

}  // namespace

TEST_CASE("forward dynamics inverts rnea at random states", "[dynamics][forward]") {
  std::mt19937 rng(41);
  for (const RobotModel& model : sample_models()) {
    check_round_trip(model, rng, false);
    check_round_trip(model, rng, true);
  }
  for (const RobotModel& model : sphere_foot_models(rng)) check_round_trip(model, rng, true);
}

TEST_CASE("forward dynamics against a mass matrix from rnea columns, solved by LU",
          "[dynamics][forward]") {
  // rnea is affine in ν̇: its column i at ν̇ = e_i minus its value at ν̇ = 0 is column i of
  // M, assembled here without crba; ν̇ = M⁻¹ (τ − rnea(q, ν, 0)) by partial-pivot LU.
  std::mt19937 rng(43);
  for (const RobotModel& model : sphere_foot_models(rng)) {
    RobotData data(model);
    const Sample s = random_sample(rng);
    const PaperDofVector tau = random_generalised_force(rng);
    const auto F = random_forces(rng);
    const FootNormals normals = random_normals(rng);
    const PaperDofVector h = rnea(model, data, with_acceleration(s, PaperDofVector::Zero()).state,
                                  s.q, s.qd, PaperJointVector::Zero(), &F, &normals);
    PaperDofMatrix M;
    for (int i = 0; i < kPaperDof; ++i) {
      const Sample a = with_acceleration(s, PaperDofVector::Unit(i));
      M.col(i) = rnea(model, data, a.state, a.q, a.qd, a.qdd, &F, &normals) - h;
    }
    const PaperDofVector expected = M.partialPivLu().solve(tau - h);
    const PaperDofVector got = forward_dynamics(model, data, s.state, s.q, s.qd, tau, &F, &normals);
    CHECK((got - expected).norm() <= 1e-10 * std::max(1.0, expected.norm()));
    CHECK((data.M - M).norm() <= 1e-12 * M.norm());
  }
}

TEST_CASE("forward dynamics refuses a model whose mass matrix is singular", "[dynamics][forward]") {
  RobotParams p = paper_robot_params();
  p.leg_inertia = LegInertia::kMassless;  // robot.leg_inertia: massless legs
  const RobotModel model = build_robot_model(p);
  RobotData data(model);
  std::mt19937 rng(47);
  const Sample s = random_sample(rng);
  CHECK_THROWS_AS(forward_dynamics(model, data, s.state, s.q, s.qd, PaperDofVector::Zero()),
                  SolverError);
}

// ---- the free robot ----
namespace {

/// The floating robot's state for integration: the trunk's orientation as a unit quaternion
/// (w, x, y, z), its position, ν (24) and q (18).
struct FreeState {
  Eigen::Vector4d quat;
  Vec3 p_W;
  PaperDofVector nu;
  PaperJointVector q;
};

struct FreeRate {
  Eigen::Vector4d quat;
  Vec3 p_W;
  PaperDofVector nu;
  PaperJointVector q;
};

BaseState base_state(const FreeState& x) {
  BaseState b;
  const Eigen::Vector4d u = x.quat.normalized();
  b.W_R_B = Quat(u[0], u[1], u[2], u[3]).toRotationMatrix();
  b.p_W = x.p_W;
  b.v_W = x.nu.head<3>();
  b.omega_W = x.nu.segment<3>(3);
  return b;
}

/// d/dt of the state: q̇ = ½ (0, ω_W) ⊗ q for the world-axes angular velocity, ṗ = v_W,
/// ν̇ the forward dynamics under no force (the model's gravity only).
FreeRate free_rate(const RobotModel& model, RobotData& data, const FreeState& x) {
  const Vec3 w = x.nu.segment<3>(3);
  const double qw = x.quat[0];
  const Vec3 qv = x.quat.tail<3>();
  FreeRate r;
  r.quat << -0.5 * w.dot(qv), 0.5 * (qw * w + w.cross(qv));
  r.p_W = x.nu.head<3>();
  r.q = x.nu.tail<kPaperJoints>();
  r.nu = forward_dynamics(model, data, base_state(x), x.q, x.nu.tail<kPaperJoints>(),
                          PaperDofVector::Zero());
  return r;
}

FreeState moved(const FreeState& x, const FreeRate& r, double h) {
  return {x.quat + h * r.quat, x.p_W + h * r.p_W, x.nu + h * r.nu, x.q + h * r.q};
}

/// One classical Runge–Kutta step of h in the quaternion's four coordinates, the quaternion
/// normalised after the step.
FreeState rk4_step(const RobotModel& model, RobotData& data, const FreeState& x, double h) {
  const FreeRate k1 = free_rate(model, data, x);
  const FreeRate k2 = free_rate(model, data, moved(x, k1, 0.5 * h));
  const FreeRate k3 = free_rate(model, data, moved(x, k2, 0.5 * h));
  const FreeRate k4 = free_rate(model, data, moved(x, k3, h));
  FreeRate sum;
  sum.quat = k1.quat + 2.0 * k2.quat + 2.0 * k3.quat + k4.quat;
  sum.p_W = k1.p_W + 2.0 * k2.p_W + 2.0 * k3.p_W + k4.p_W;
  sum.nu = k1.nu + 2.0 * k2.nu + 2.0 * k3.nu + k4.nu;
  sum.q = k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q;
  FreeState out = moved(x, sum, h / 6.0);
  out.quat.normalize();
  return out;
}

}  // namespace

TEST_CASE("the free robot keeps its kinetic energy and momentum for a second",
          "[dynamics][forward]") {
  // No gravity, no contact, no torque: T = ½ νᵀ M ν, the linear momentum and the angular
  // momentum about the world origin are constants of the motion. RK4 at h = 1 ms leaves at
  // most 2.4e-9 of them on these robots (at h = 0.5 ms 1.6e-10: 1/16, the fourth order).
  std::mt19937 rng(53);
  const double h = 1e-3, duration = 1.0;
  const std::vector<RobotModel>& models = sample_models();
  for (std::size_t i = 0; i < 4; ++i) {
    RobotModel model = models[i];
    model.gravity_W = Vec3::Zero();
    RobotData data(model);
    const Sample s = random_sample(rng);
    FreeState x;
    const Quat q0(s.state.W_R_B);
    x.quat << q0.w(), q0.x(), q0.y(), q0.z();
    x.p_W = s.state.p_W;
    x.nu = velocity_vector(s);
    x.q = s.q;
    const double T0 = kinetic_energy(model, data, base_state(x), x.q, x.nu.tail<kPaperJoints>());
    const Momentum m0 = robot_momentum(model, data, base_state(x), x.q, x.nu.tail<kPaperJoints>());
    double worst_T = 0.0, worst_L = 0.0, worst_H = 0.0;
    for (int step = 0; step < static_cast<int>(std::lround(duration / h)); ++step) {
      x = rk4_step(model, data, x, h);
      const BaseState b = base_state(x);
      const PaperJointVector qd = x.nu.tail<kPaperJoints>();
      const double T = kinetic_energy(model, data, b, x.q, qd);
      const Momentum m = robot_momentum(model, data, b, x.q, qd);
      worst_T = std::max(worst_T, std::abs(T - T0) / T0);
      worst_L = std::max(worst_L, (m.linear_W - m0.linear_W).norm() / m0.linear_W.norm());
      worst_H = std::max(worst_H, (m.angular_O_W - m0.angular_O_W).norm() / m0.angular_O_W.norm());
    }
    INFO("model " << i << ": T0 = " << T0 << " J; largest relative change of T " << worst_T
                  << ", of the linear momentum " << worst_L << ", of the angular momentum "
                  << worst_H);
    CHECK(worst_T <= 1e-8);
    CHECK(worst_L <= 1e-8);
    CHECK(worst_H <= 1e-8);
  }
}

TEST_CASE("the root link frame's state against differences of its rigid motion",
          "[dynamics][forward]") {
  // The trunk moves as p(t) = p + v t + ½ a t², R(t) = exp(ω t + ½ ω̇ t²) R (whose angular
  // velocity and acceleration at t = 0 are ω and ω̇); the root link's origin p(t) + R(t)
  // p_B_root is differentiated numerically.
  std::mt19937 rng(59);
  RobotModel model = sample_models().front();
  for (int trial = 0; trial < 20; ++trial) {
    model.p_B_root = random_vec3(rng, -0.1, 0.1);
    model.B_R_root = random_rotation(rng);
    const BaseState trunk = random_sample(rng).state;
    auto origin = [&](double t) {
      const Mat3 R = so3_exp(trunk.omega_W * t + 0.5 * trunk.omegadot_W * t * t) * trunk.W_R_B;
      return Vec3(trunk.p_W + trunk.v_W * t + 0.5 * trunk.a_W * t * t + R * model.p_B_root);
    };
    const double h = 1e-4;
    const BaseState root = root_link_state(model, trunk);
    CHECK((root.W_R_B - trunk.W_R_B * model.B_R_root).norm() <= 1e-15);
    CHECK((root.p_W - origin(0.0)).norm() <= 1e-15);
    CHECK(relative_error(root.v_W, (origin(h) - origin(-h)) / (2.0 * h)) <= 1e-7);
    CHECK(relative_error(root.a_W, (origin(h) - 2.0 * origin(0.0) + origin(-h)) / (h * h)) <= 1e-6);
    CHECK(root.omega_W == trunk.omega_W);
    CHECK(root.omegadot_W == trunk.omegadot_W);
    // And back.
    const BaseState back = trunk_state_from_root_link(model, root);
    CHECK((back.W_R_B - trunk.W_R_B).norm() <= 1e-14);
    CHECK((back.p_W - trunk.p_W).norm() <= 1e-14);
    CHECK((back.v_W - trunk.v_W).norm() <= 1e-13);
    CHECK((back.a_W - trunk.a_W).norm() <= 1e-12);
  }
}

}  // namespace hexdyn
