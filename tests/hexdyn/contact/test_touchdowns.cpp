// The contact stage's touchdowns (contact/touchdowns.hpp), each against a second
// computation: impact peaks against the quasi-static weight share, the effective mass
// against the minimum kinetic energy of a unit normal foot velocity, the contact frame
// against its definition.
#include <Eigen/Cholesky>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// Kinetic energy of the robot [J] from the body velocities of robot_momentum (computed
/// body by body, independently of the mass matrix).
double kinetic_energy(const RobotModel& model, RobotData& data, const BaseState& base,
                      const JointVector& q, const JointVector& qd) {
  robot_momentum(model, data, base, q, qd);
  double ke = 0.0;
  for (int b = 0; b < model.bodies(); ++b) {
    const RigidInertia& in = model.inertia[b];
    const Mat3& R = data.X_world_body[b].R;
    const Vec3& w = data.omega_body_W[b];
    ke += 0.5 * in.mass_kg * data.v_com_body_W[b].squaredNorm() +
          0.5 * w.dot(R * in.inertia_com * R.transpose() * w);
  }
  return ke;
}

/// Effective mass of a foot along n with the trunk at rest, as the smallest kinetic
/// energy (×2) over leg joint rates that give the foot a unit velocity along n (the
/// impulse a unit normal velocity change costs). The leg's inertia comes from the
/// kinetic energy by polarisation, the foot Jacobian from the analytic leg kinematics.
double effective_mass_by_energy(const RobotModel& model, RobotData& data, const BaseState& base,
                                const JointVector& q, int leg, const Vec3& n_W) {
  BaseState still = base;
  still.v_W.setZero();
  still.omega_W.setZero();
  auto ke = [&](const Vec3& rates) {
    JointVector qd = JointVector::Zero(model.joints());
    qd.segment<3>(model.joint(leg, 0)) = rates;  // the leg's three joints
    return kinetic_energy(model, data, still, q, qd);
  };
  Mat3 M;
  for (int a = 0; a < 3; ++a) M(a, a) = 2.0 * ke(Vec3::Unit(a));
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      M(a, b) = M(b, a) = ke(Vec3::Unit(a) + Vec3::Unit(b)) - 0.5 * M(a, a) - 0.5 * M(b, b);
  const Mat3 J_W =
      base.W_R_B * model.R_B_H[leg] * leg_jacobian_H(model, leg, q.segment<3>(model.joint(leg, 0)));
  // Rates with nᵀ J q̇ = 1: q̇ = x0 + N z, x0 = a/|a|², N an orthonormal basis of a⊥.
  const Vec3 a = J_W.transpose() * n_W.normalized();
  const Vec3 x0 = a / a.squaredNorm();
  Eigen::Matrix<double, 3, 2> N;
  N.col(0) = a.unitOrthogonal();
  N.col(1) = a.normalized().cross(N.col(0));
  const Eigen::Vector2d z = -(N.transpose() * M * N).ldlt().solve(N.transpose() * M * x0);
  const Vec3 qd = x0 + N * z;
  return qd.dot(M * qd);
}

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

}  // namespace

TEST_CASE("touchdowns: each paper touchdown gives one impact above the quasi-static weight share",
          "[touchdowns]") {
  const Scene scene = load_scene(kPaper);
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  std::size_t swings = 0;
  for (const LegPlan& leg : plan.gait.legs) swings += leg.swings.size();
  REQUIRE(swings > 0);
  REQUIRE(tds.size() == swings);
  const double mg = model.total_mass_kg * kGravity;
  for (const Touchdown& td : tds) {
    INFO("leg L" << td.leg + 1 << " at t = " << td.t_s << " s");
    // One touchdown per swing of that leg, at its end, with the configured speed.
    const auto& sws = plan.gait.legs[td.leg].swings;
    CHECK(std::count_if(sws.begin(), sws.end(),
                        [&](const Swing& s) { return s.t_touchdown_s == td.t_s; }) == 1);
    CHECK(std::abs(td.approach_speed_mps - scene.gait.touchdown_speed_mps) <= 1e-12);
    CHECK(td.normal_W == Vec3::UnitZ());
    REQUIRE(td.transient.occurred);
    CHECK_FALSE(td.transient.truncated);
    CHECK(td.transient.duration_s > 0.0);
    // Feet in support just after the transient (the plan's stance legs).
    const double t_after = td.t_s + td.transient.duration_s + 1e-9;
    int support = 0;
    for (const LegPlan& leg : plan.gait.legs) support += !leg_foot_motion(leg, t_after).in_swing;
    REQUIRE(support >= 3);
    INFO("peak " << td.transient.peak_force_N << " N, share " << mg / support << " N of " << support
                 << " feet");
    CHECK(td.transient.peak_force_N > mg / support);
    // The peak lies inside the transient and is the largest sampled force.
    CHECK(td.transient.time_of_peak_s > 0.0);
    CHECK(td.transient.time_of_peak_s < td.transient.duration_s);
    CHECK(*std::max_element(td.transient.force_N.begin(), td.transient.force_N.end()) <=
          td.transient.peak_force_N * (1.0 + 1e-12));
  }
}

TEST_CASE("touchdowns: foot effective mass equals the minimum-energy normal impulse",
          "[touchdowns]") {
  // The paper's touchdowns, in the state at touchdown.
  const Scene scene = load_scene(kPaper);
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  REQUIRE(!tds.empty());
  RobotKinematicState s;
  for (const Touchdown& td : tds) {
    robot_state_at(model, plan, td.t_s, s);
    const double expected =
        effective_mass_by_energy(model, data, s.trunk, s.q, td.leg, td.normal_W);
    INFO("leg L" << td.leg + 1 << " at t = " << td.t_s << " s: " << td.effective_mass_kg << " vs "
                 << expected);
    CHECK(std::abs(td.effective_mass_kg - expected) <= 1e-10 * expected);
    // Bounded by the leg's mass: the foot never drags more than its own leg.
    CHECK(expected <
          scene.robot.link[0].mass_kg + scene.robot.link[1].mass_kg + scene.robot.link[2].mass_kg);
  }
  // Random robots, states and directions; base velocities do not matter.
  std::mt19937 rng(20240611);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const RobotModel rm = build_robot_model(test::random_robot_params(rng));
    RobotData rd(rm);
    BaseState base;
    base.W_R_B = random_rotation(rng);
    base.p_W = Vec3(g(rng), g(rng), g(rng));
    base.v_W = Vec3(g(rng), g(rng), g(rng));
    base.omega_W = Vec3(g(rng), g(rng), g(rng));
    JointVector q(rm.joints());
    for (int l = 0; l < rm.legs(); ++l) q.segment<3>(rm.joint(l, 0)) = test::random_leg_angles(rng);
    const int leg = trial % rm.legs();
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const double got = foot_effective_mass(rm, rd, base, q, leg, n);
    const double expected = effective_mass_by_energy(rm, rd, base, q, leg, n);
    INFO("trial " << trial << ": " << got << " vs " << expected);
    CHECK(std::isfinite(got));
    CHECK(got > 0.0);
    CHECK(std::abs(got - expected) <= 1e-9 * expected);
    // A sphere foot centred at the same point: its contact point, r below the centre along
    // n, has the centre's normal effective mass (the arm −r n is along n;
    // docs/theory/contact.md#touchdown-transient), though its Jacobian is not the centre's.
    RobotModel sphere = rm;
    sphere.foot_radius_m.fill(0.03);
    RobotData sd(sphere);
    const double got_sphere = foot_effective_mass(sphere, sd, base, q, leg, n);
    CHECK(std::abs(got_sphere - expected) <= 1e-9 * expected);
    FootNormals normals;
    normals.fill(n);
    foot_jacobians(sphere, sd, base, q, &normals);
    const PaperFootJacobian J_contact = sd.J_foot_W[leg];
    foot_jacobians(rm, rd, base, q);
    CHECK((J_contact - rd.J_foot_W[leg]).norm() > 1e-3);
  }
}

TEST_CASE("touchdowns: contact frames are orthonormal, right-handed, with n third",
          "[touchdowns]") {
  std::vector<Vec3> normals = {Vec3::UnitZ(),   -Vec3::UnitZ(),         Vec3::UnitX(),
                               -Vec3::UnitX(),  Vec3::UnitY(),          Vec3(1.0, 0.0, 1e-12),
                               Vec3(0, 0, 7.0), Vec3(0.0, -0.196, 0.98)};
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < 200; ++k) normals.emplace_back(g(rng), g(rng), g(rng));
  for (const Vec3& n : normals) {
    INFO("n = " << n.transpose());
    const Mat3 R = contact_frame(n);
    CHECK(R.allFinite());
    CHECK((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() <= 1e-14);
    CHECK(std::abs(R.determinant() - 1.0) <= 1e-14);
    CHECK((R.col(2) - n.normalized()).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((R.col(0).cross(R.col(1)) - R.col(2)).cwiseAbs().maxCoeff() <= 1e-14);
    // t1 is the world x axis made orthogonal to n, when x is not along n.
    const Vec3 x_perp = Vec3::UnitX() - n.normalized().x() * n.normalized();
    if (x_perp.norm() > 1e-6)
      CHECK((R.col(0) - x_perp.normalized()).cwiseAbs().maxCoeff() <= 1e-12);
  }
  // On a tread the frame is the world frame.
  CHECK((contact_frame(Vec3::UnitZ()) - Mat3::Identity()).cwiseAbs().maxCoeff() == 0.0);
}

}  // namespace hexdyn
