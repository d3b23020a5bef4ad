// Robot model and analytic leg kinematics (robot_model.hpp), each checked against a
// second computation: IK against FK, the Jacobian and its time derivative against
// central finite differences, the analytic leg FK against the generic tree FK, the
// total mass against the sum of the parameters, and the reach limits against the
// planar leg geometry worked out in the test.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

constexpr int kRandomRobots = 24;
constexpr int kDrawsPerLeg = 12;

/// The paper robot first, then random valid robots (fixed seed).
std::vector<RobotParams> sample_robots() {
  std::vector<RobotParams> robots{test::paper_robot_params()};
  std::mt19937 rng(20240611);
  for (int i = 0; i < kRandomRobots; ++i) robots.push_back(test::random_robot_params(rng));
  return robots;
}

/// Planar reach of the wrist (femur axis → foot) for a foot target in the hip frame,
/// from the leg geometry: the foot lies |w| to the side of the leg plane, the femur
/// axis l1 out and d1 below the coxa joint.
double planar_distance(const RobotParams& p, const Vec3& p_H) {
  const double w = p.joint_offset_m[1] + p.joint_offset_m[2];
  const double rho = std::sqrt(p_H.x() * p_H.x() + p_H.y() * p_H.y() - w * w);
  return std::hypot(rho - p.link_length_m[0], p_H.z() + p.joint_offset_m[0]);
}

/// Planar distance of the foot from the coxa axis in the leg plane for angles q.
double leg_plane_rho(const RobotParams& p, const Vec3& q) {
  return p.link_length_m[0] + p.link_length_m[1] * std::cos(q[1]) +
         p.link_length_m[2] * std::cos(q[1] + q[2]);
}

TEST_CASE("leg IK inverts leg FK on the paper robot and random robots", "[robot_model]") {
  std::mt19937 rng(7);
  int draws = 0, solved = 0, recovered = 0, paper_failures = 0;
  const auto robots = sample_robots();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const RobotModel model = build_robot_model(robots[r]);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (int d = 0; d < kDrawsPerLeg; ++d) {
        const Vec3 q = test::random_leg_angles(rng);
        const Vec3 x = leg_foot_position_H(model, leg, q);
        const LegIkResult ik = leg_inverse_kinematics(model, leg, x);
        ++draws;
        // The drawn angles lie inside the joint limits and away from full extension
        // and full fold; when the foot is also on the outward side of the coxa axis
        // they are the knee-up solution IK must find.
        const bool outward = leg_plane_rho(robots[r], q) > 1e-3;
        INFO("robot " << r << " leg " << leg << " q " << q.transpose() << " reason " << ik.reason);
        if (outward) {
          CHECK(ik.ok);
        }
        if (!ik.ok) {
          if (r == 0) ++paper_failures;
          continue;
        }
        ++solved;
        INFO("ik " << ik.q.transpose());
        const Vec3 x_back = leg_foot_position_H(model, leg, ik.q);
        CHECK((x_back - x).cwiseAbs().maxCoeff() <= 1e-12);
        CHECK(ik.margin_m >= model.ik_min_margin_m);
        if (outward) {
          CHECK((ik.q - q).cwiseAbs().maxCoeff() <= 1e-9);
          ++recovered;
        }
      }
    }
  }
  CHECK(paper_failures == 0);
  // Most draws are solvable; most of them must give back the drawn angles.
  CHECK(solved >= 0.9 * draws);
  CHECK(recovered >= 0.8 * draws);
}

TEST_CASE("leg Jacobian matches central finite differences of the leg FK", "[robot_model]") {
  std::mt19937 rng(11);
  const double h = 1e-6;
  double worst = 0.0;
  for (const RobotParams& params : sample_robots()) {
    const RobotModel model = build_robot_model(params);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (int d = 0; d < 4; ++d) {
        const Vec3 q = test::random_leg_angles(rng);
        const Mat3 J = leg_jacobian_H(model, leg, q);
        Mat3 J_fd;
        for (int j = 0; j < 3; ++j) {
          Vec3 e = Vec3::Zero();
          e[j] = h;
          J_fd.col(j) =
              (leg_foot_position_H(model, leg, q + e) - leg_foot_position_H(model, leg, q - e)) /
              (2 * h);
        }
        worst = std::max(worst, (J - J_fd).cwiseAbs().maxCoeff());
        INFO("leg " << leg << " q " << q.transpose() << "\nJ\n" << J << "\nJ_fd\n" << J_fd);
        REQUIRE((J - J_fd).cwiseAbs().maxCoeff() <= 1e-8);
      }
    }
  }
  CHECK(worst > 0.0);  // the comparison did run on non-trivial data
}

TEST_CASE("leg Jacobian derivative matches finite differences along q + qd t", "[robot_model]") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> rate(-2.0, 2.0);
  const double h = 1e-6;
  for (const RobotParams& params : sample_robots()) {
    const RobotModel model = build_robot_model(params);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (int d = 0; d < 4; ++d) {
        const Vec3 q = test::random_leg_angles(rng);
        const Vec3 qd(rate(rng), rate(rng), rate(rng));
        const Mat3 Jd = leg_jacobian_dot_H(model, leg, q, qd);
        const Mat3 Jd_fd =
            (leg_jacobian_H(model, leg, q + h * qd) - leg_jacobian_H(model, leg, q - h * qd)) /
            (2 * h);
        INFO("leg " << leg << " q " << q.transpose() << " qd " << qd.transpose() << "\nJd\n"
                    << Jd << "\nJd_fd\n"
                    << Jd_fd);
        REQUIRE((Jd - Jd_fd).cwiseAbs().maxCoeff() <= 1e-7);
        // Jd is linear in qd: Jd(2 qd) = 2 Jd(qd) and Jd(0) = 0.
        CHECK((leg_jacobian_dot_H(model, leg, q, 2.0 * qd) - 2.0 * Jd).cwiseAbs().maxCoeff() <=
              1e-12);
        CHECK(leg_jacobian_dot_H(model, leg, q, Vec3::Zero()).cwiseAbs().maxCoeff() == 0.0);
      }
    }
  }
}

TEST_CASE("analytic leg FK equals the generic tree FK", "[robot_model]") {
  std::mt19937 rng(17);
  for (const RobotParams& params : sample_robots()) {
    const RobotModel model = build_robot_model(params);
    for (int d = 0; d < 5; ++d) {
      PaperJointVector q;
      for (int leg = 0; leg < kPaperLegs; ++leg)
        q.segment<3>(paper_joint_index(leg, 0)) = test::random_leg_angles(rng);
      BodyPoses poses;
      forward_kinematics_tree(model, q, poses);
      for (int leg = 0; leg < kPaperLegs; ++leg) {
        const Vec3 q_leg = q.segment<3>(paper_joint_index(leg, 0));
        const Vec3 analytic =
            model.p_hip_B[leg] + model.R_B_H[leg] * leg_foot_position_H(model, leg, q_leg);
        const Vec3 tree = tree_foot_position_B(model, poses, leg);
        INFO("leg " << leg << " analytic " << analytic.transpose() << " tree " << tree.transpose());
        CHECK((analytic - tree).cwiseAbs().maxCoeff() <= 1e-12);
      }
    }
  }
}

TEST_CASE("rotation from cos and sin equals Eigen's AngleAxis bit for bit", "[robot_model]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-10.0, 10.0);
  std::vector<Vec3> axes{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitY()};
  for (int i = 0; i < 200; ++i) axes.push_back(Vec3(u(rng), u(rng), u(rng)).normalized());
  for (const Vec3& a : axes)
    for (int k = 0; k < 20; ++k) {
      const double t = k == 0 ? 0.0 : angle(rng);
      const Mat3 expected = Eigen::AngleAxisd(t, a).toRotationMatrix();
      const Mat3 R = rot_axis_cs(a, std::cos(t), std::sin(t));
      INFO("axis " << a.transpose() << " angle " << t);
      CHECK((R.array() == expected.array()).all());
    }
}

TEST_CASE("hip frames follow the parameters", "[robot_model]") {
  for (const RobotParams& params : sample_robots()) {
    const RobotModel model = build_robot_model(params);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const double a = params.hip_yaw_rad[leg];
      Mat3 Rz;
      Rz << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
      CHECK((model.R_B_H[leg] - Rz).cwiseAbs().maxCoeff() <= 1e-15);
      CHECK(model.p_hip_B[leg] == params.hip_position_m[leg]);
      // At zero angles the foot is (l1 + l2 + l3) out along the hip x axis, d1 below
      // it, and (d2 + d3) to the side, mirrored left/right.
      const Vec3 foot0 = leg_foot_position_H(model, leg, Vec3::Zero());
      const double L = params.link_length_m[0] + params.link_length_m[1] + params.link_length_m[2];
      const double side = is_left(leg) ? -1.0 : 1.0;
      CHECK(std::abs(foot0.x() - L) <= 1e-15);
      CHECK(std::abs(foot0.y() - side * (params.joint_offset_m[1] + params.joint_offset_m[2])) <=
            1e-15);
      CHECK(std::abs(foot0.z() + params.joint_offset_m[0]) <= 1e-15);
    }
  }
}

TEST_CASE("total mass is the sum of the parameter masses", "[robot_model]") {
  for (const RobotParams& p : sample_robots()) {
    const RobotModel model = build_robot_model(p);
    const double links = p.link[0].mass_kg + p.link[1].mass_kg + p.link[2].mass_kg;
    const double expected = p.trunk.mass_kg + p.payload.mass_kg + kPaperLegs * links;
    CHECK(std::abs(model.total_mass_kg - expected) <= 1e-12 * expected);
    // Body 0 carries trunk and payload together.
    CHECK(std::abs(model.inertia[0].mass_kg - (p.trunk.mass_kg + p.payload.mass_kg)) <= 1e-14);
  }
  const RobotParams paper = test::paper_robot_params();
  CHECK(std::abs(build_robot_model(paper).total_mass_kg - 6.7) <= 1e-12);
}

TEST_CASE("paper robot: lateral foot offsets point forward on both sides", "[robot_model]") {
  const RobotParams p = test::paper_robot_params();
  const RobotModel model = build_robot_model(p);
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const Vec3 foot_B =
        model.p_hip_B[leg] + model.R_B_H[leg] * leg_foot_position_H(model, leg, Vec3::Zero());
    const double reach = p.link_length_m[0] + p.link_length_m[1] + p.link_length_m[2];
    const double side = is_left(leg) ? -1.0 : 1.0;
    INFO("leg " << leg << " foot " << foot_B.transpose());
    CHECK(std::abs(foot_B.x() - (p.hip_position_m[leg].x() + side * reach)) <= 1e-12);
    CHECK(std::abs(foot_B.y() - (p.hip_position_m[leg].y() + p.joint_offset_m[1] +
                                 p.joint_offset_m[2])) <= 1e-12);
  }
}

TEST_CASE("IK refuses a target beyond reach with a negative margin", "[robot_model]") {
  for (const RobotParams& params : sample_robots()) {
    const RobotModel model = build_robot_model(params);
    const double L = params.link_length_m[0] + params.link_length_m[1] + params.link_length_m[2];
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (const Vec3& target : {Vec3(L + 0.05, 0.0, 0.0), Vec3(0.3 * L, 0.2 * L, -1.2 * L),
                                 Vec3(-0.8 * L, 1.1 * L, 0.3 * L)}) {
        const LegIkResult ik = leg_inverse_kinematics(model, leg, target);
        INFO("leg " << leg << " target " << target.transpose() << " reason " << ik.reason);
        CHECK_FALSE(ik.ok);
        CHECK(ik.reason.find("extension") != std::string::npos);
        CHECK(ik.margin_m < 0.0);
        const double expected_margin =
            params.link_length_m[1] + params.link_length_m[2] - planar_distance(params, target);
        CHECK(std::abs(ik.margin_m - expected_margin) <= 1e-12);
      }
    }
  }
}

TEST_CASE("IK refuses a target at full extension", "[robot_model]") {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> angle(-1.0, 1.0);
  for (const RobotParams& params : sample_robots()) {
    const RobotModel model = build_robot_model(params);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (double knee : {0.0, -1e-6, -5e-7}) {
        const Vec3 q(angle(rng), angle(rng), knee);
        const Vec3 target = leg_foot_position_H(model, leg, q);
        // The wrist is (l2 + l3) from the femur axis, up to second order in the knee angle.
        REQUIRE(std::abs(planar_distance(params, target) -
                         (params.link_length_m[1] + params.link_length_m[2])) <= 1e-11);
        const LegIkResult ik = leg_inverse_kinematics(model, leg, target);
        INFO("leg " << leg << " q " << q.transpose() << " reason " << ik.reason << " margin "
                    << ik.margin_m);
        CHECK_FALSE(ik.ok);
        CHECK(ik.reason.find("extension") != std::string::npos);
        CHECK(ik.margin_m < model.ik_min_margin_m);
        CHECK(std::abs(ik.margin_m) <= 1e-11);
      }
    }
  }
}

TEST_CASE("IK solves a knee-up pose with the wrist behind and above the femur axis",
          "[robot_model]") {
  // A tibia longer than the femur, the femur pointing down and the tibia folded back
  // up: the wrist direction, measured from the femur axis, is β2 + φ < −π with
  // φ = atan2(l3 sin β3, l2 + l3 cos β3). The drawn angles are inside the limits,
  // away from full extension and full fold, with the foot outward of the coxa axis.
  RobotParams params = test::paper_robot_params();
  params.link_length_m = {0.15, 0.06, 0.14};
  const RobotModel model = build_robot_model(params);
  const Vec3 q(0.2, -1.2, -2.4);
  const double phi = std::atan2(0.14 * std::sin(q[2]), 0.06 + 0.14 * std::cos(q[2]));
  REQUIRE(q[1] + phi < -M_PI);
  REQUIRE(leg_plane_rho(params, q) > 0.0);
  for (int j = 0; j < kPaperLegJoints; ++j) {
    REQUIRE(q[j] > params.joint_min_rad[j]);
    REQUIRE(q[j] < params.joint_max_rad[j]);
  }
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const Vec3 target = leg_foot_position_H(model, leg, q);
    const LegIkResult ik = leg_inverse_kinematics(model, leg, target);
    INFO("leg " << leg << " reason " << ik.reason << " q " << ik.q.transpose());
    CHECK(ik.ok);
    CHECK((ik.q - q).cwiseAbs().maxCoeff() <= 1e-9);
  }
}

TEST_CASE("IK refuses a fully folded leg", "[robot_model]") {
  // Equal femur and tibia: folding the knee by π brings the foot onto the femur axis.
  RobotParams params = test::paper_robot_params();
  params.link_length_m[1] = 0.11;
  params.link_length_m[2] = 0.10;
  params.joint_min_rad[2] = -M_PI;
  const RobotModel model = build_robot_model(params);
  const Vec3 target = leg_foot_position_H(model, 1, Vec3(0.2, 0.4, -M_PI + 1e-7));
  const LegIkResult ik = leg_inverse_kinematics(model, 1, target);
  INFO(ik.reason << " margin " << ik.margin_m);
  CHECK_FALSE(ik.ok);
  CHECK(ik.reason.find("fold") != std::string::npos);
  CHECK(std::abs(ik.margin_m) <= 1e-9);
}

TEST_CASE("IK outside a joint limit reports the angle past the limit in rad", "[robot_model]") {
  // The foot of q, whose femur angle is 0.1 rad above a femur limit lowered to q[1] − 0.1: the
  // closed form finds q again and refuses it, its margin the angle to the limit, in rad.
  RobotParams params = test::paper_robot_params();
  const Vec3 q(0.2, 0.4, -1.0);
  params.joint_max_rad[1] = q[1] - 0.1;
  const RobotModel model = build_robot_model(params);
  const LegIkResult ik = leg_inverse_kinematics(model, 1, leg_foot_position_H(model, 1, q));
  INFO(ik.reason);
  CHECK_FALSE(ik.ok);
  CHECK(ik.reason.find("outside its limits") != std::string::npos);
  CHECK(std::string(ik.margin_unit) == "rad");
  CHECK(ik.margin_m == Approx(-0.1).margin(1e-9));
  // Within the limits, a reach margin is a length.
  params.joint_max_rad[1] = q[1] + 0.1;
  const RobotModel wide = build_robot_model(params);
  const LegIkResult ok = leg_inverse_kinematics(wide, 1, leg_foot_position_H(wide, 1, q));
  CHECK(ok.ok);
  CHECK(std::string(ok.margin_unit) == "m");
}

}  // namespace
}  // namespace hexdyn
