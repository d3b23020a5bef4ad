// Kinematics of legs of any length through the model's leg entry points (robot_model.hpp:
// leg_inverse_kinematics, leg_motion_H), on synthetic robots written as URDF text here
// (tests/hexdyn/urdf_writer.hpp: random inertias and joint axes, fixed seeds) and read by the
// project's URDF reader: a quadruped 4x3, a hexapod of 4-joint legs, a 6x5 robot, an octopod
// 8x3 and a biped 2x6, and a quadruped whose knees slide (a tree built by hand: the URDF
// reader does not build prismatic joints yet). Second computations: the feet by Eigen's
// transforms of the URDF's own numbers (rpy, xyz, axis), and the body poses of the model's
// tree (forward_kinematics_tree, not the leg chains); q̇ and q̈ by central differences of q
// along a smooth foot path; the null space of J by an SVD.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/model/urdf_robot.hpp"
#include "hexdyn/tree_models.hpp"
#include "hexdyn/urdf_writer.hpp"

namespace hexdyn {
namespace {

struct Shape {
  const char* name;
  std::vector<int> leg_joints;
  unsigned seed;
};

const std::vector<Shape>& shapes() {
  static const std::vector<Shape> s{{"quadruped 4x3", {3, 3, 3, 3}, 41u},
                                    {"hexapod 6x4", {4, 4, 4, 4, 4, 4}, 42u},
                                    {"hexapod 6x5", {5, 5, 5, 5, 5, 5}, 43u},
                                    {"octopod 8x3", {3, 3, 3, 3, 3, 3, 3, 3}, 44u},
                                    {"biped 2x6", {6, 6}, 45u}};
  return s;
}

Mat3 rpy_rotation(const Vec3& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

/// Foot of leg l in the URDF trunk frame from the description's own numbers.
Vec3 spec_foot_U(const test::UrdfRobotSpec& spec, int l, const LegVector& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const test::UrdfLegSpec& leg = spec.legs[static_cast<std::size_t>(l)];
  for (std::size_t j = 0; j < leg.joints.size(); ++j) {
    const test::UrdfJointSpec& jt = leg.joints[j];
    T = T * Eigen::Translation3d(jt.xyz) * Eigen::Isometry3d(rpy_rotation(jt.rpy));
    const double qj = q[static_cast<Eigen::Index>(j)];
    if (jt.type == "prismatic")
      T = T * Eigen::Translation3d(qj * jt.axis.normalized());
    else
      T = T * Eigen::AngleAxisd(qj, jt.axis.normalized());
  }
  return T * leg.foot_xyz;
}

/// Foot of leg l in its hip frame by the model's tree (every body placed in the trunk frame).
Vec3 tree_foot_H(const RobotModel& m, int leg, const LegVector& q_leg) {
  JointVector q = JointVector::Zero(m.joints());
  q.segment(m.joint(leg, 0), m.leg(leg).n_joints) = q_leg;
  BodyPoses poses;
  forward_kinematics_tree(m, q, poses);
  return m.R_B_H[leg].transpose() * (tree_foot_position_B(m, poses, leg) - m.p_hip_B[leg]);
}

LegVector near_nominal(const RobotModel& m, int leg, std::mt19937& rng, double spread) {
  LegVector q = m.leg_resolution[leg].q_nominal;
  for (Eigen::Index j = 0; j < q.size(); ++j) q[j] += test::draw(rng, -spread, spread);
  return q;
}

/// Joint positions near the nominal pose where the leg is away from a singularity: the smallest
/// singular value of its Jacobian (an SVD here) above 0.005 m/rad, drawn again until it is
/// (farther from the nominal pose after every hundred draws).
LegVector regular_pose(const RobotModel& m, int leg, std::mt19937& rng, double spread) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const LegVector q = near_nominal(m, leg, rng, spread * (1.0 + attempt / 100));
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(leg_jacobian(m, leg, q)));
    if (svd.singularValues()[2] > 0.005) return q;
  }
  FAIL("leg " << leg << ": no regular pose near the nominal one");
  return LegVector();
}

struct Read {
  test::UrdfRobotSpec spec;
  UrdfRobot robot;
  RobotModel model;
};

Read read_shape(const Shape& shape) {
  std::mt19937 rng(shape.seed);
  Read r;
  r.spec = test::random_urdf_robot(rng, shape.leg_joints);
  r.robot = read_urdf_robot_from_string(test::urdf_text(r.spec), std::string(shape.name) + ".urdf");
  r.model = build_robot_model(r.robot);
  return r;
}

/// A smooth foot path in the hip frame: the foot of the joint path
/// q(t) = q0 + a sin(ωt) + b cos(2ωt), inside the leg's workspace by construction, with
/// ṗ = J q̇ and p̈ = J q̈ + ∇²f[q̇, q̇] from the leg's chain (model/redundant_leg.hpp, whose
/// derivatives test_redundant_leg.cpp checks against Eigen's frames and differences).
struct FootPath {
  const SerialChain* chain = nullptr;
  LegVector q0, a, b;
  double omega = 2.0;
  void at(double t, Vec3& p, Vec3& pd, Vec3& pdd) const {
    const LegVector q = q0 + a * std::sin(omega * t) + b * std::cos(2 * omega * t);
    const LegVector qd = omega * a * std::cos(omega * t) - 2 * omega * b * std::sin(2 * omega * t);
    const LegVector qdd =
        -omega * omega * a * std::sin(omega * t) - 4 * omega * omega * b * std::cos(2 * omega * t);
    p = chain_foot_position(*chain, q);
    pd = chain_jacobian(*chain, q) * qd;
    pdd = chain_jacobian(*chain, q) * qdd + chain_second_derivative(*chain, q, qd, qd);
  }
};

LegMotion motion_at(const RobotModel& m, int leg, const FootPath& path, double t) {
  Vec3 p, pd, pdd;
  path.at(t, p, pd, pdd);
  LegMotion out;
  leg_motion_H(m, leg, p, pd, pdd, out);
  return out;
}

/// q̇ and q̈ of leg_motion_H against central differences of q along `path` at t.
void check_rates(const RobotModel& m, int leg, const FootPath& path, double t) {
  const LegMotion c = motion_at(m, leg, path, t);
  INFO("leg " << leg << " t " << t << ": " << c.ik.reason);
  REQUIRE(c.ik.ok);
  // q̇ against differences of q; q̈ against differences of q̇ (which is q's derivative by the
  // first check) and, more loosely (the IK's rounding over h²), second differences of q.
  const double h1 = 1e-5, h2 = 1e-3;
  const LegMotion a = motion_at(m, leg, path, t - h1), b = motion_at(m, leg, path, t + h1);
  const LegMotion a2 = motion_at(m, leg, path, t - h2), b2 = motion_at(m, leg, path, t + h2);
  REQUIRE((a.ik.ok && b.ik.ok && a2.ik.ok && b2.ik.ok));
  const LegVector qd_fd = (b.ik.q - a.ik.q) / (2.0 * h1);
  const LegVector qdd_fd = (b.qd - a.qd) / (2.0 * h1);
  const LegVector qdd_fd2 = (b2.ik.q - 2.0 * c.ik.q + a2.ik.q) / (h2 * h2);
  INFO("qd " << c.qd.transpose() << "\nfd " << qd_fd.transpose() << "\nqdd " << c.qdd.transpose()
             << "\nfd " << qdd_fd.transpose());
  CHECK((c.qd - qd_fd).norm() <= 1e-6 * (1.0 + c.qd.norm()));
  CHECK((c.qdd - qdd_fd).norm() <= 1e-6 * (1.0 + c.qdd.norm()));
  CHECK((c.qdd - qdd_fd2).norm() <= 1e-4 * (1.0 + c.qdd.norm()));
}

FootPath path_around(const RobotModel& m, int leg, std::mt19937& rng) {
  FootPath path;
  path.chain = &m.leg_chain_table[leg];
  path.q0 = regular_pose(m, leg, rng, 0.2);
  const int n = m.leg(leg).n_joints;
  path.a = path.b = LegVector::Zero(n);
  for (int j = 0; j < n; ++j) {
    path.a[j] = test::draw(rng, -0.1, 0.1);
    path.b[j] = test::draw(rng, -0.05, 0.05);
  }
  return path;
}

TEST_CASE("synthetic URDF robots: the model's feet are the description's", "[any_leg]") {
  for (const Shape& shape : shapes()) {
    INFO(shape.name);
    const Read r = read_shape(shape);
    const RobotModel& m = r.model;
    REQUIRE(m.legs() == static_cast<int>(shape.leg_joints.size()));
    std::mt19937 rng(shape.seed + 100u);
    for (int leg = 0; leg < m.legs(); ++leg) {
      REQUIRE(m.leg(leg).n_joints == shape.leg_joints[static_cast<std::size_t>(leg)]);
      CHECK(m.leg_on_chain[leg] == (m.leg(leg).n_joints != 3));
      for (int s = 0; s < 5; ++s) {
        const LegVector q = near_nominal(m, leg, rng, 1.0);
        const Vec3 foot_B = r.robot.B_R_U * spec_foot_U(r.spec, leg, q);
        const Vec3 foot_H = m.R_B_H[leg].transpose() * (foot_B - m.p_hip_B[leg]);
        CHECK((tree_foot_H(m, leg, q) - foot_H).norm() < 1e-14);
        CHECK((leg_foot_position(m, leg, q) - foot_H).norm() < 1e-14);
      }
    }
  }
}

TEST_CASE("synthetic URDF robots: IK round trips through the tree's FK to 1e-12 m", "[any_leg]") {
  for (const Shape& shape : shapes()) {
    INFO(shape.name);
    const Read r = read_shape(shape);
    const RobotModel& m = r.model;
    std::mt19937 rng(shape.seed + 200u);
    int solved = 0;
    for (int leg = 0; leg < m.legs(); ++leg)
      for (int s = 0; s < 8; ++s) {
        const Vec3 p_H = tree_foot_H(m, leg, regular_pose(m, leg, rng, 0.3));
        const LegIkResult ik = leg_inverse_kinematics(m, leg, p_H);
        INFO("leg " << leg << " target " << p_H.transpose() << ": " << ik.reason);
        REQUIRE(ik.ok);
        REQUIRE(ik.q.size() == m.leg(leg).n_joints);
        CHECK((tree_foot_H(m, leg, ik.q) - p_H).norm() < 1e-12);
        ++solved;
      }
    CHECK(solved == 8 * m.legs());
  }
}

TEST_CASE("synthetic URDF robots: q̇ and q̈ are central differences of q along a foot path",
          "[any_leg]") {
  for (const Shape& shape : shapes()) {
    INFO(shape.name);
    const Read r = read_shape(shape);
    std::mt19937 rng(shape.seed + 300u);
    for (int leg = 0; leg < r.model.legs(); ++leg) {
      const FootPath path = path_around(r.model, leg, rng);
      for (double t : {0.1, 0.45, 0.8}) check_rates(r.model, leg, path, t);
    }
  }
}

TEST_CASE("a 4-joint leg's null-space motion leaves the foot where the path puts it", "[any_leg]") {
  const Read r = read_shape(shapes()[1]);  // the hexapod of 4-joint legs
  const RobotModel& m = r.model;
  std::mt19937 rng(7u);
  for (int leg = 0; leg < m.legs(); ++leg) {
    const FootPath path = path_around(m, leg, rng);
    double largest_null = 0.0;
    for (int i = 0; i <= 20; ++i) {
      const double t = 0.05 * i;
      Vec3 p, pd, pdd;
      path.at(t, p, pd, pdd);
      LegMotion mo;
      leg_motion_H(m, leg, p, pd, pdd, mo);
      INFO("leg " << leg << " t " << t << ": " << mo.ik.reason);
      REQUIRE(mo.ik.ok);
      // The foot: the tree's FK of q is the path's point.
      CHECK((tree_foot_H(m, leg, mo.ik.q) - p).norm() < 1e-12);
      // The rates: J q̇ = ṗ, and the part of q̇ in J's null space (an SVD's last vector).
      const LegJacobian J = leg_jacobian(m, leg, mo.ik.q);
      CHECK((J * mo.qd - pd).norm() < 1e-12 * (1.0 + pd.norm()));
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(J), Eigen::ComputeFullV);
      const Eigen::VectorXd null = svd.matrixV().col(3);
      CHECK((J * null).norm() < 1e-12);
      largest_null = std::max(largest_null, std::abs(null.dot(Eigen::VectorXd(mo.qd))));
      // The accelerations: J q̈ + J̇ q̇ = p̈ (J̇ q̇ by differences of J along q̇).
      const double h = 1e-6;
      const Vec3 Jd_qd =
          (leg_jacobian(m, leg, mo.ik.q + h * mo.qd) - leg_jacobian(m, leg, mo.ik.q - h * mo.qd)) *
          mo.qd / (2.0 * h);
      CHECK((J * mo.qdd + Jd_qd - pdd).norm() < 1e-7 * (1.0 + pdd.norm()));
    }
    // The resolution moves the leg in its null space as the foot moves (it is no fixed
    // pseudo-inverse of a frozen pose).
    CHECK(largest_null > 1e-4);
  }
}

TEST_CASE("legs with a prismatic joint run on their chain", "[any_leg]") {
  std::mt19937 rng(51u);
  RobotModel m = test::tree_model(rng, {3, 3, 3, 3}, {1, 4, 7, 10});
  for (int k = 0; k < m.joints(); ++k) {
    m.joint_lower_rad[k] = m.prismatic(k) ? -0.5 : -3.0;
    m.joint_upper_rad[k] = m.prismatic(k) ? 0.5 : 3.0;
    m.joint_source_names[k] = "j" + std::to_string(k);
  }
  prepare_leg_chains(m);
  for (int leg = 0; leg < m.legs(); ++leg) {
    REQUIRE(m.leg_on_chain[leg]);
    for (int s = 0; s < 5; ++s) {
      const Vec3 p_H = tree_foot_H(m, leg, regular_pose(m, leg, rng, 0.1));
      const LegIkResult ik = leg_inverse_kinematics(m, leg, p_H);
      INFO("leg " << leg << ": " << ik.reason);
      REQUIRE(ik.ok);
      CHECK((tree_foot_H(m, leg, ik.q) - p_H).norm() < 1e-12);
    }
    const FootPath path = path_around(m, leg, rng);
    for (double t : {0.2, 0.7}) check_rates(m, leg, path, t);
  }
}

}  // namespace
}  // namespace hexdyn
