// URDF robots (urdf_reader.hpp, urdf_robot.hpp, leg_chain.hpp), each checked against a
// second computation: forward kinematics, centre of mass, total mass and whole-robot
// inertia against the URDF's raw joints and inertials composed here from urdfdom's
// unmerged data (no fixed-joint merging, no leg mapping, no hexdyn frames); RNEA against
// CRBA on the loaded models; IK round trips; the paper robot written as URDF and read
// back; the chain kinematics against the paper robot's closed forms; every validation
// rule with a small URDF that breaks it (tests/data/urdf/).
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/model/leg_chain.hpp"
#include "hexdyn/model/urdf.hpp"
#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

const std::string kData = std::string(HEXDYN_SOURCE_DIR) + "/tests/data/urdf/";
const std::string kMark4 = kData + "robots/phantomx_mark4.urdf";
const std::string kKraby = kData + "robots/kraby.urdf";
const std::string kHuma = kData + "robots/phantomx_humarobotics.urdf";

UrdfReadOptions kraby_options() {
  UrdfReadOptions o;
  o.forward_axis = "+y";  // Kraby's middle legs stand out along ±x of its trunk link
  return o;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The URDF as urdfdom reads it, and the raw composition of its joints (second computation).
struct RawUrdf {
  urdf::ModelInterfaceSharedPtr model;
  explicit RawUrdf(const std::string& path) : model(urdf::parseURDF(file_text(path))) {
    REQUIRE(model);
  }

  static Mat3 rotation(const urdf::Rotation& r) {
    return Eigen::Quaterniond(r.w, r.x, r.y, r.z).toRotationMatrix();
  }

  /// Pose of `link` in the root link frame, joint angles by URDF joint name (absent: 0).
  std::pair<Mat3, Vec3> pose(const std::string& link,
                             const std::map<std::string, double>& q) const {
    Mat3 R = Mat3::Identity();
    Vec3 p = Vec3::Zero();
    std::vector<urdf::JointConstSharedPtr> chain;
    for (auto l = model->getLink(link); l->parent_joint;
         l = model->getLink(l->parent_joint->parent_link_name))
      chain.push_back(l->parent_joint);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const urdf::Joint& j = **it;
      const urdf::Pose& o = j.parent_to_joint_origin_transform;
      p += R * Vec3(o.position.x, o.position.y, o.position.z);
      R = R * rotation(o.rotation);
      if (j.type != urdf::Joint::FIXED) {
        const auto a = q.find(j.name);
        const double angle = a == q.end() ? 0.0 : a->second;
        R = R * Eigen::AngleAxisd(angle, Vec3(j.axis.x, j.axis.y, j.axis.z).normalized())
                    .toRotationMatrix();
      }
    }
    return {R, p};
  }

  double total_mass() const {
    double m = 0.0;
    for (const auto& [name, l] : model->links_)
      if (l->inertial) m += l->inertial->mass;
    return m;
  }

  /// Centre of mass and rotational inertia about the root origin, root axes.
  std::pair<Vec3, Mat3> com_and_inertia(const std::map<std::string, double>& q) const {
    Vec3 mc = Vec3::Zero();
    Mat3 I_O = Mat3::Zero();
    for (const auto& [name, l] : model->links_) {
      if (!l->inertial) continue;
      const auto [R, p] = pose(name, q);
      const urdf::Inertial& in = *l->inertial;
      const Mat3 Ri = R * rotation(in.origin.rotation);
      Mat3 Ic;
      Ic << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Vec3 c = p + R * Vec3(in.origin.position.x, in.origin.position.y, in.origin.position.z);
      mc += in.mass * c;
      I_O += Ri * Ic * Ri.transpose() +
             in.mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
    }
    return {mc / total_mass(), I_O};
  }
};

/// Random joint angles inside the limits (shrunk by 10 %), by URDF joint name and flat.
PaperJointVector random_joints(const RobotModel& m, std::mt19937& rng,
                               std::map<std::string, double>& by_name) {
  std::uniform_real_distribution<double> u(0.05, 0.95);
  PaperJointVector q;
  for (int k = 0; k < kPaperJoints; ++k) {
    const double lo = std::isfinite(m.joint_lower_rad[k]) ? m.joint_lower_rad[k] : -M_PI;
    const double hi = std::isfinite(m.joint_upper_rad[k]) ? m.joint_upper_rad[k] : M_PI;
    q[k] = lo + (hi - lo) * u(rng);
    by_name[m.joint_source_names[k]] = q[k];
  }
  return q;
}

struct Loaded {
  std::string path;
  UrdfRobot robot;
  RobotModel model;
};

std::vector<Loaded> real_robots() {
  std::vector<Loaded> out;
  for (const auto& [path, opt] :
       {std::pair{kMark4, UrdfReadOptions{}}, std::pair{kKraby, kraby_options()}}) {
    UrdfRobot r = read_urdf_robot(path, opt);
    RobotModel m = build_robot_model(r);
    out.push_back({path, r, m});
  }
  return out;
}

TEST_CASE("urdf reader: leg FK of the real robots equals the URDF's joints composed",
          "[urdf_reader]") {
  std::mt19937 rng(3);
  for (const Loaded& l : real_robots()) {
    const RawUrdf raw(l.path);
    CHECK(l.robot.trunk_link == raw.model->getRoot()->name);
    for (int d = 0; d < 20; ++d) {
      std::map<std::string, double> by_name;
      const PaperJointVector q = random_joints(l.model, rng, by_name);
      BodyPoses poses;
      forward_kinematics_tree(l.model, q, poses);
      for (int leg = 0; leg < kPaperLegs; ++leg) {
        const Vec3 q_leg = q.segment<3>(paper_joint_index(leg, 0));
        const Vec3 p_B =
            l.model.p_hip_B[leg] + l.model.R_B_H[leg] * leg_foot_position_H(l.model, leg, q_leg);
        const Vec3 expected_U = raw.pose(l.robot.legs[leg].foot_source, by_name).second;
        INFO(l.path << " leg " << leg << " foot " << l.robot.legs[leg].foot_source);
        CHECK((l.robot.B_R_U.transpose() * p_B - expected_U).norm() <= 1e-12);
        CHECK((tree_foot_position_B(l.model, poses, leg) - p_B).norm() <= 1e-12);
      }
    }
  }
}

TEST_CASE("urdf reader: legs map to L1..L6 by hip position, URDF names kept", "[urdf_reader]") {
  const Loaded mark4 = real_robots()[0];
  const char* side[2] = {"left", "right"};
  const char* row[3] = {"front", "middle", "back"};
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const std::string prefix = std::string(side[leg % 2]) + "_" + row[leg / 2] + "_";
    CHECK(mark4.model.joint_source_names[paper_joint_index(leg, 0)] == prefix + "coxa");
    CHECK(mark4.model.joint_source_names[paper_joint_index(leg, 1)] == prefix + "femur");
    CHECK(mark4.model.joint_source_names[paper_joint_index(leg, 2)] == prefix + "tibia");
    CHECK(mark4.robot.legs[leg].foot_source == "pxmark4/" + prefix + "foot_link");
    for (int j = 0; j < 3; ++j)
      CHECK(mark4.model.effort_limit_Nm[paper_joint_index(leg, j)] == 3.0);
  }
  CHECK(mark4.model.joint_lower_rad[1] == -1.710422666954443);
  CHECK(mark4.model.joint_upper_rad[2] == 2.181661564992912);
  // Kraby: hips from the raw URDF, in hexdyn's axes (forward +y): left x < 0, front first.
  const Loaded kraby = real_robots()[1];
  const RawUrdf raw(kKraby);
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const Vec3 hip = raw.pose(kraby.robot.legs[leg].joints[0].link, {}).second;
    CHECK((hip.x() < 0.0) == is_left(leg));
    if (leg >= 2)
      CHECK(hip.y() < raw.pose(kraby.robot.legs[leg - 2].joints[0].link, {}).second.y());
    CHECK(kraby.model.effort_limit_Nm[paper_joint_index(leg, 0)] == 1.18);
  }
}

TEST_CASE("urdf reader: mass, centre of mass and inertia equal the sum over the URDF's inertials",
          "[urdf_reader]") {
  std::mt19937 rng(5);
  for (const Loaded& l : real_robots()) {
    const RawUrdf raw(l.path);
    CHECK(std::abs(l.model.total_mass_kg - raw.total_mass()) <= 1e-12);
    CHECK(std::abs(l.robot.total_mass_kg - raw.total_mass()) <= 1e-12);
    for (int d = 0; d < 10; ++d) {
      std::map<std::string, double> by_name;
      const PaperJointVector q = random_joints(l.model, rng, by_name);
      BodyPoses poses;
      forward_kinematics_tree(l.model, q, poses);
      const auto [c_U, I_U] = raw.com_and_inertia(by_name);
      const Mat3& B_R_U = l.robot.B_R_U;
      CHECK((B_R_U.transpose() * center_of_mass_B(l.model, poses) - c_U).norm() <= 1e-12);
      Mat3 I_B = Mat3::Zero();
      for (int b = 0; b < kPaperBodies; ++b) {
        const RigidInertia& in = l.model.inertia[b];
        const Vec3 c = poses.p_B[b] + poses.R_B[b] * in.com_m;
        I_B += poses.R_B[b] * in.inertia_com * poses.R_B[b].transpose() +
               in.mass_kg * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
      }
      CHECK((B_R_U.transpose() * I_B * B_R_U - I_U).norm() <= 1e-12 * I_U.norm());
    }
  }
  // Mark IV: 3.216 kg; Kraby: 1.645 kg with the trunk's COM 0.203 m above its frame.
  CHECK(std::abs(real_robots()[0].model.total_mass_kg - 3.21627) < 1e-5);
  CHECK(std::abs(real_robots()[1].model.total_mass_kg - 1.645) < 1e-9);
  CHECK(std::abs(real_robots()[1].model.inertia[0].com_m.z() - 0.203) < 1e-3);
}

TEST_CASE("urdf reader: RNEA of the loaded robots equals M(q) a + h from CRBA", "[urdf_reader]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Loaded& l : real_robots()) {
    RobotData data(l.model);
    for (int n = 0; n < 10; ++n) {
      std::map<std::string, double> names;
      const PaperJointVector q = random_joints(l.model, rng, names);
      PaperJointVector qd, qdd;
      for (int k = 0; k < kPaperJoints; ++k) qd[k] = 2.0 * u(rng), qdd[k] = 5.0 * u(rng);
      BaseState s;
      s.W_R_B = bryant_to_rotation(Vec3(0.3 * u(rng), 0.3 * u(rng), u(rng)));
      s.p_W = Vec3(u(rng), u(rng), 0.2 + 0.1 * u(rng));
      s.v_W = Vec3(u(rng), u(rng), u(rng));
      s.omega_W = Vec3(u(rng), u(rng), u(rng));
      s.a_W = Vec3(u(rng), u(rng), u(rng));
      s.omegadot_W = Vec3(u(rng), u(rng), u(rng));
      const PaperDofVector tau = rnea(l.model, data, s, q, qd, qdd);
      BaseState s0 = s;
      s0.a_W.setZero();
      s0.omegadot_W.setZero();
      const PaperDofVector h = rnea(l.model, data, s0, q, qd, PaperJointVector::Zero());
      const PaperDofMatrix M = crba(l.model, data, s, q);
      PaperDofVector a;
      a << s.a_W, s.omegadot_W, qdd;
      CHECK((tau - (M * a + h)).norm() <= 1e-10 * std::max(1.0, tau.norm()));
      CHECK((M.topLeftCorner<3, 3>() - l.model.total_mass_kg * Mat3::Identity()).norm() < 1e-12);
      CHECK(Eigen::SelfAdjointEigenSolver<PaperDofMatrix>(M).eigenvalues().minCoeff() > 0.0);
    }
  }
}

TEST_CASE("urdf reader: chain Jacobian and its derivative match finite differences",
          "[urdf_reader]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> rate(-2.0, 2.0);
  const double h = 1e-6;
  for (const Loaded& l : real_robots()) {
    for (int d = 0; d < 8; ++d) {
      std::map<std::string, double> names;
      const PaperJointVector q = random_joints(l.model, rng, names);
      for (int leg = 0; leg < kPaperLegs; ++leg) {
        const Vec3 ql = q.segment<3>(paper_joint_index(leg, 0));
        const Vec3 qd(rate(rng), rate(rng), rate(rng));
        Mat3 J_fd;
        for (int j = 0; j < 3; ++j) {
          Vec3 e = Vec3::Zero();
          e[j] = h;
          J_fd.col(j) = (leg_foot_position_H(l.model, leg, ql + e) -
                         leg_foot_position_H(l.model, leg, ql - e)) /
                        (2 * h);
        }
        CHECK((leg_jacobian_H(l.model, leg, ql) - J_fd).cwiseAbs().maxCoeff() <= 1e-9);
        const Mat3 Jd_fd = (leg_jacobian_H(l.model, leg, ql + h * qd) -
                            leg_jacobian_H(l.model, leg, ql - h * qd)) /
                           (2 * h);
        CHECK((leg_jacobian_dot_H(l.model, leg, ql, qd) - Jd_fd).cwiseAbs().maxCoeff() <= 1e-8);
      }
    }
  }
}

/// Knee above the femur-joint-to-foot chord (along the trunk normal) by more than 2 mm, the
/// foot outward of the coxa axis (on the femur joint's side) by more than 2 cm and outward
/// of the femur joint (the chord leans out by more than 0.1 rad from the normal), the leg
/// away from singular configurations (smallest singular value of J above 5 mm/rad).
bool knee_up_outward(const RobotModel& m, int leg, const Vec3& q) {
  const LegChainPose c = chain_pose(m, leg, q);
  const Vec3 up = m.R_B_H[leg].transpose() * Vec3::UnitZ();
  const Vec3 chord = (c.p_foot_H - c.o_H[1]).normalized();
  Vec3 knee = c.o_H[2] - c.o_H[1];
  knee -= knee.dot(chord) * chord;
  const Vec3 a0 = c.w_H[0];
  const Vec3 foot_radial = c.p_foot_H - c.p_foot_H.dot(a0) * a0;
  const Vec3 femur_radial = (c.o_H[1] - c.o_H[1].dot(a0) * a0).normalized();
  const Mat3 J = leg_jacobian_H(m, leg, q);
  const double sigma_min =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Mat3>(J.transpose() * J).eigenvalues().minCoeff());
  return knee.dot(up) > 2e-3 && foot_radial.dot(femur_radial) > 2e-2 &&
         chord.dot(femur_radial) > 0.1 && sigma_min > 5e-3;
}

TEST_CASE("urdf reader: IK round trip on the real robots, closed form and numeric",
          "[urdf_reader]") {
  std::mt19937 rng(13);
  for (const Loaded& l : real_robots()) {
    RobotModel numeric = l.model;
    for (auto& d : numeric.leg_ik) d.method = LegIkMethod::kNumeric;
    int draws = 0, recovered = 0, numeric_solved = 0;
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      REQUIRE(l.model.leg_ik[leg].method == LegIkMethod::kYawPitchPitch);
      for (int d = 0; d < 60; ++d) {
        std::map<std::string, double> names;
        const Vec3 q = random_joints(l.model, rng, names).segment<3>(paper_joint_index(leg, 0));
        const Vec3 p = leg_foot_position_H(l.model, leg, q);
        const LegIkResult ik = leg_inverse_kinematics(l.model, leg, p);
        INFO(l.path << " leg " << leg << " q " << q.transpose() << " ik " << ik.q.transpose() << " "
                    << ik.reason);
        ++draws;
        if (ik.ok) CHECK((leg_foot_position_H(l.model, leg, ik.q) - p).norm() <= 1e-12);
        if (knee_up_outward(l.model, leg, q)) {
          REQUIRE(ik.ok);
          CHECK((ik.q - q).cwiseAbs().maxCoeff() <= 1e-9);
          ++recovered;
        }
        const LegIkResult nk = leg_inverse_kinematics(numeric, leg, p);
        if (nk.ok) {
          ++numeric_solved;
          CHECK((leg_foot_position_H(numeric, leg, nk.q) - p).norm() <= 1e-12);
        }
      }
    }
    INFO(l.path << ": " << recovered << " of " << draws << " draws knee-up and outward, "
                << numeric_solved << " solved numerically");
    CHECK(recovered >= draws / 5);
    CHECK(numeric_solved >= 0.9 * draws);
  }
}

TEST_CASE("urdf reader: chain kinematics equal the paper robot's closed forms", "[urdf_reader]") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> rate(-2.0, 2.0);
  std::vector<RobotParams> robots{test::paper_robot_params()};
  for (int i = 0; i < 12; ++i) robots.push_back(test::random_robot_params(rng));
  int compared = 0;
  for (const RobotParams& params : robots) {
    const RobotModel paper = build_robot_model(params);
    RobotModel chain = paper;
    chain.leg_geometry = LegGeometry::kChain;
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      REQUIRE(chain.leg_ik[leg].method == LegIkMethod::kYawPitchPitch);
      for (int d = 0; d < 10; ++d) {
        const Vec3 q = test::random_leg_angles(rng);
        const Vec3 qd(rate(rng), rate(rng), rate(rng));
        const Vec3 p = leg_foot_position_H(paper, leg, q);
        CHECK((leg_foot_position_H(chain, leg, q) - p).norm() <= 1e-15);
        CHECK((leg_jacobian_H(chain, leg, q) - leg_jacobian_H(paper, leg, q)).norm() <= 1e-14);
        CHECK((leg_jacobian_dot_H(chain, leg, q, qd) - leg_jacobian_dot_H(paper, leg, q, qd))
                  .norm() <= 1e-13);
        const LegIkResult a = leg_inverse_kinematics(paper, leg, p),
                          b = leg_inverse_kinematics(chain, leg, p);
        INFO("leg " << leg << " q " << q.transpose() << " paper " << a.q.transpose() << " "
                    << a.reason << " chain " << b.q.transpose() << " " << b.reason);
        CHECK(a.ok == b.ok);
        if (a.ok && b.ok) {
          CHECK((a.q - b.q).cwiseAbs().maxCoeff() <= 1e-12);
          CHECK(std::abs(a.margin_m - b.margin_m) <= 1e-12);
          ++compared;
        }
      }
    }
  }
  CHECK(compared >= 400);
}

void check_same_model(const RobotModel& a, const RobotModel& b, double tol) {
  CHECK(std::abs(a.total_mass_kg - b.total_mass_kg) <= tol);
  for (int k = 0; k < kPaperBodies; ++k) {
    INFO("body " << k);
    CHECK(a.parent[k] == b.parent[k]);
    CHECK((a.p_parent_joint[k] - b.p_parent_joint[k]).norm() <= tol);
    CHECK((a.R_parent_joint[k] - b.R_parent_joint[k]).norm() <= tol);
    CHECK((a.axis[k] - b.axis[k]).norm() <= tol);
    CHECK(std::abs(a.inertia[k].mass_kg - b.inertia[k].mass_kg) <= tol);
    CHECK((a.inertia[k].com_m - b.inertia[k].com_m).norm() <= tol);
    CHECK((a.inertia[k].inertia_com - b.inertia[k].inertia_com).norm() <= tol);
  }
  for (int leg = 0; leg < kPaperLegs; ++leg)
    CHECK((a.p_foot_last[leg] - b.p_foot_last[leg]).norm() <= tol);
}

TEST_CASE("urdf reader: the paper robot written as URDF and read back is the same model",
          "[urdf_reader]") {
  std::mt19937 rng(19);
  for (LegInertia legs : {LegInertia::kFull, LegInertia::kMassless}) {
    RobotParams params = test::paper_robot_params();
    params.leg_inertia = legs;
    const RobotModel paper = build_robot_model(params);
    UrdfReadOptions opt;
    opt.forward_axis = "+y";  // robot_urdf writes the trunk in hexdyn's axes
    const UrdfRobot robot =
        read_urdf_robot_from_string(robot_urdf(paper, "paper"), "paper.urdf", opt);
    const RobotModel back = build_robot_model(robot, paper.ik_min_margin_m);
    CHECK(robot.B_R_U == Mat3::Identity());
    check_same_model(paper, back, 1e-12);
    for (int k = 0; k < kPaperJoints; ++k) {
      CHECK(back.joint_source_names[k] == joint_name(k / 3, k % 3));
      CHECK(back.joint_lower_rad[k] == paper.joint_lower_rad[k]);
      CHECK(back.joint_upper_rad[k] == paper.joint_upper_rad[k]);
    }
    int compared = 0;
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      for (int d = 0; d < 20; ++d) {
        const Vec3 q = test::random_leg_angles(rng);
        const Vec3 p_B = paper.p_hip_B[leg] + paper.R_B_H[leg] * leg_foot_position_H(paper, leg, q);
        CHECK((back.p_hip_B[leg] + back.R_B_H[leg] * leg_foot_position_H(back, leg, q) - p_B)
                  .norm() <= 1e-12);
        const Vec3 p_H = back.R_B_H[leg].transpose() * (p_B - back.p_hip_B[leg]);
        const LegIkResult a = leg_inverse_kinematics(
            paper, leg, paper.R_B_H[leg].transpose() * (p_B - paper.p_hip_B[leg]));
        const LegIkResult b = leg_inverse_kinematics(back, leg, p_H);
        CHECK(a.ok == b.ok);
        if (a.ok && b.ok) {
          CHECK((a.q - b.q).cwiseAbs().maxCoeff() <= 1e-12);
          ++compared;
        }
      }
    }
    CHECK(compared >= 60);
  }
}

/// Reads `file` of tests/data/urdf/ and returns the ConfigError message ("" if none).
std::string refusal(const std::string& path, const UrdfReadOptions& opt = {}) {
  try {
    read_urdf_robot(path, opt);
  } catch (const ConfigError& e) {
    CHECK(e.exit_status() == 2);
    return e.what();
  }
  return "";
}

TEST_CASE("urdf reader: each broken description is refused with one line naming what and why",
          "[urdf_reader]") {
  struct Case {
    const char* file;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {"mass_zero.urdf", {"link 'leg'", "mass 0 kg with a nonzero inertia", "expected > 0"}},
      {"mass_negative.urdf", {"link 'leg'", "mass -0.1 kg"}},
      {"inertia_not_positive_definite.urdf", {"link 'leg'", "not positive definite"}},
      {"inertia_triangle.urdf", {"link 'leg'", "triangle inequality"}},
      {"nan_mass.urdf", {"link 'leg'", "value=\"nan\"", "not finite"}},
      {"inf_origin.urdf", {"joint 'hip'", "xyz=\"0 inf 0\"", "not finite"}},
      {"unknown_joint_type.urdf", {"not a valid URDF", "[hip]", "no known type [hinge]"}},
      // Prismatic joints are read now (test_urdf_legs.cpp); this file's one leg is refused.
      {"prismatic_joint.urdf",
       {"trunk 'trunk'", "1 moving joints leave the trunk", "expected at least 2 legs"}},
      {"missing_parent.urdf",
       {"not a valid URDF", "parent link [thigh] of joint [knee] not found"}},
      {"duplicate_link.urdf", {"link 'leg' is not unique"}},
      {"duplicate_joint.urdf", {"joint 'hip' is not unique"}},
      {"loop_two_parents.urdf", {"link 'b'", "child of two joints", "kinematic loop"}},
      {"cycle_detached.urdf", {"link 'a'", "not connected to the root link 'trunk'", "cycle"}},
      {"leg_not_3r.urdf",
       {"leg L4 (chain 'leg3_coxa_joint')", "2 moving joints", "expected 3 to 6"}},
      {"no_foot_frame.urdf",
       {"chain 'leg0_coxa_joint'", "on the axis of its last joint", "robot.foot_links"}},
  };
  for (const Case& c : cases) {
    const std::string path = kData + c.file;
    const std::string msg = refusal(path);
    INFO(c.file << ": " << msg);
    REQUIRE(!msg.empty());
    CHECK(msg.rfind(path + ": ", 0) == 0);
    CHECK(msg.find('\n') == std::string::npos);
    for (const auto& e : c.expected) CHECK(msg.find(e) != std::string::npos);
  }
  // The valid hexapod these are cut from loads; without a foot frame, options give one.
  CHECK(refusal(kData + "valid_hexapod.urdf").empty());
  // Five legs are read (2 to 8 are), in the documented order: three on the left.
  const UrdfRobot five = read_urdf_robot(kData + "five_legs.urdf");
  REQUIRE(five.n_legs() == 5);
  for (int leg = 0; leg < 5; ++leg)  // written front left, front right, …, rear left
    CHECK(five.legs[leg].joints[0].name == "leg" + std::to_string(leg) + "_coxa_joint");
  UrdfReadOptions offset;
  offset.foot_offset = std::vector<Vec3>{Vec3(0.1, 0.0, 0.0)};
  CHECK(refusal(kData + "no_foot_frame.urdf", offset).empty());
  const UrdfRobot with_offset = read_urdf_robot(kData + "no_foot_frame.urdf", offset);
  const UrdfRobot with_links = read_urdf_robot(kData + "valid_hexapod.urdf");
  for (int leg = 0; leg < kPaperLegs; ++leg)
    CHECK((with_offset.legs[leg].p_foot_last - with_links.legs[leg].p_foot_last).norm() <= 1e-15);
  // Kraby with the default forward axis cannot be mapped: the message says which key to set.
  const std::string kraby = refusal(kKraby);
  CHECK(kraby.find("robot.forward_axis") != std::string::npos);
  CHECK(refusal(kData + "missing_file.urdf").find("missing_file.urdf: does not exist") !=
        std::string::npos);
}

/// valid_hexapod.urdf with `from` replaced by `to` on the first line holding `marker`.
std::string edited_hexapod(const std::string& marker, const std::string& from,
                           const std::string& to) {
  std::string text = file_text(kData + "valid_hexapod.urdf");
  const std::size_t line = text.find(marker);
  REQUIRE(line != std::string::npos);
  const std::size_t at = text.find(from, line);
  REQUIRE(at != std::string::npos);
  REQUIRE(at < text.find('\n', line));
  return text.replace(at, from.size(), to);
}

/// The one-line message of reading `text`, or "" when it loads.
std::string text_refusal(const std::string& text) {
  try {
    (void)read_urdf_robot_from_string(text, "hexapod.urdf");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// A URDF's values are held to the scene's plausibility bounds (core/value_bounds.hpp): each
// edit of the valid hexapod just beyond a bound is refused in one line naming the file, the
// link or joint and the value; the same edit at the bound loads.
TEST_CASE("urdf reader: masses, inertias, origins and limits within the scene's bounds",
          "[urdf_reader][sizes]") {
  struct Edit {
    const char* marker;
    const char* from;
    const char* inside;
    const char* beyond;
    std::vector<std::string> expected;
  };
  const char* trunk = "<link name=\"trunk\">";
  const char* coxa = "<joint name=\"leg0_coxa_joint\"";
  const char* foot = "<joint name=\"leg0_foot_joint\"";
  const std::vector<Edit> edits = {
      {trunk,
       "<mass value=\"1.0\"/>",
       "<mass value=\"10000\"/>",
       "<mass value=\"1e300\"/>",
       {"link 'trunk'", "mass 1e+300 kg", "expected at most 10000 kg"}},
      {trunk,
       "ixx=\"0.01\" iyy=\"0.01\" izz=\"0.015\"",
       "ixx=\"600\" iyy=\"600\" izz=\"1000\"",
       "ixx=\"600\" iyy=\"600\" izz=\"1000.001\"",
       {"link 'trunk'", "inertia too large", "1000", "at most 1000 kg m2"}},
      // The triangle inequality within its relative tolerance of 1e-9.
      {trunk,
       "izz=\"0.015\"",
       "izz=\"0.02000000001\"",
       "izz=\"0.0200000001\"",
       {"link 'trunk'", "triangle inequality"}},
      {trunk,
       "<mass value=\"1.0\"/>",
       "<mass value=\"1.0\"/><origin xyz=\"0 0 -10\"/>",
       "<mass value=\"1.0\"/><origin xyz=\"0 0 -10.01\"/>",
       {"link 'trunk'", "<inertial><origin xyz=\"0 0 -10.01\">", "within +-10 m"}},
      {foot,
       "xyz=\"0.1 0 0\"",
       "xyz=\"10 0 0\"",
       "xyz=\"10.01 0 0\"",
       {"joint 'leg0_foot_joint'", "<origin xyz=\"10.01 0 0\">", "within +-10 m"}},
      {coxa,
       "lower=\"-2\" upper=\"2\"",
       "lower=\"-12.566370\" upper=\"12.566370\"",
       "lower=\"-2\" upper=\"12.6\"",
       {"joint 'leg0_coxa_joint'", "limits [-2, 12.6] rad", "[-4 pi, 4 pi]"}},
      {coxa,
       "effort=\"2\"",
       "effort=\"1e6\"",
       "effort=\"2e6\"",
       {"joint 'leg0_coxa_joint'", "effort limit 2e+06 N m", "[0, 1e+06]"}},
      {coxa,
       "velocity=\"5\"",
       "velocity=\"1e4\"",
       "velocity=\"1.0001e4\"",
       {"joint 'leg0_coxa_joint'", "velocity limit 10001 rad/s", "[0, 10000]"}},
  };
  for (const Edit& e : edits) {
    INFO(e.beyond);
    CHECK(text_refusal(edited_hexapod(e.marker, e.from, e.inside)).empty());
    const std::string msg = text_refusal(edited_hexapod(e.marker, e.from, e.beyond));
    INFO(msg);
    CHECK(msg.rfind("hexapod.urdf: ", 0) == 0);
    CHECK(msg.find('\n') == std::string::npos);
    for (const std::string& part : e.expected) CHECK(msg.find(part) != std::string::npos);
  }
  // The mass that ran to NaN torques before: refused whatever the link.
  const UrdfRobot heavy = read_urdf_robot_from_string(
      edited_hexapod(trunk, "<mass value=\"1.0\"/>", "<mass value=\"10000\"/>"), "h.urdf");
  CHECK(std::isfinite(build_robot_model(heavy).total_mass_kg));
}

TEST_CASE("urdf reader: plausibility is judged on the bodies the dynamics uses", "[urdf_reader]") {
  // A camera frame fixed to the trunk with an inertia no body has (izz above ixx + iyy) and a
  // massless <inertial> (mass 0, zero tensor): the trunk they join is physical, so the
  // description is read, and the merged trunk has their masses (0.05 kg and nothing).
  const std::string trunk_line = "<link name=\"trunk\">";
  const std::string camera =
      "<link name=\"camera\"><inertial><origin xyz=\"0.05 0 0.02\"/><mass value=\"0.05\"/>"
      "<inertia ixx=\"1e-6\" iyy=\"1e-6\" izz=\"5e-6\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>"
      "</inertial></link><joint name=\"camera_joint\" type=\"fixed\"><parent link=\"trunk\"/>"
      "<child link=\"camera\"/></joint>"
      "<link name=\"optical\"><inertial><mass value=\"0\"/><inertia ixx=\"0\" iyy=\"0\" "
      "izz=\"0\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link><joint name=\"optical_joint\" "
      "type=\"fixed\"><parent link=\"camera\"/><child link=\"optical\"/></joint>";
  const std::string with_camera = edited_hexapod(trunk_line, trunk_line, camera + trunk_line);
  CHECK(text_refusal(with_camera).empty());
  const UrdfRobot plain = read_urdf_robot_from_string(file_text(kData + "valid_hexapod.urdf"), "h");
  const UrdfRobot merged = read_urdf_robot_from_string(with_camera, "h");
  CHECK(merged.total_mass_kg == Approx(plain.total_mass_kg + 0.05).epsilon(1e-14));
  CHECK(merged.trunk.mass_kg == Approx(plain.trunk.mass_kg + 0.05).epsilon(1e-14));
  // The same camera on a trunk too light to hide it: the merged body breaks the rule, and the
  // message names the body's link and the links merged into it.
  const std::string light = edited_hexapod(trunk_line, "ixx=\"0.01\" iyy=\"0.01\" izz=\"0.015\"",
                                           "ixx=\"1e-9\" iyy=\"1e-9\" izz=\"1e-9\"");
  std::string light_with_camera = light;
  light_with_camera.insert(light_with_camera.find(trunk_line), camera);
  const std::string msg = text_refusal(light_with_camera);
  INFO(msg);
  CHECK(msg.find("link 'trunk': inertia breaks the triangle inequality") != std::string::npos);
  CHECK(msg.find("of the body with the links fixed to it: 'camera', 'optical'") !=
        std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
  // Rotational inertia without mass is refused on the link itself.
  const std::string spinning = edited_hexapod(
      trunk_line, trunk_line,
      "<link name=\"wheel\"><inertial><mass value=\"0\"/><inertia ixx=\"1e-4\" iyy=\"1e-4\" "
      "izz=\"1e-4\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link><joint name=\"wj\" "
      "type=\"fixed\"><parent link=\"trunk\"/><child link=\"wheel\"/></joint>" +
          trunk_line);
  CHECK(text_refusal(spinning).find("link 'wheel': mass 0 kg with a nonzero inertia") !=
        std::string::npos);
}

TEST_CASE("urdf reader: Solo-12 and ANYmal C pass the value checks and read as four legs",
          "[urdf_reader]") {
  // Their wide joint limits (±10 rad, ±3π), massless camera frames and degenerate camera and
  // hatch inertias fixed to the trunk are accepted; their legs are checked in
  // test_urdf_legs.cpp.
  for (const char* file : {"solo12.urdf", "anymal_c.urdf"}) {
    const std::string path = std::string(HEXDYN_SOURCE_DIR) + "/robots/" + file;
    INFO(refusal(path));
    REQUIRE(refusal(path).empty());
    CHECK(read_urdf_robot(path).n_legs() == 4);
  }
}

TEST_CASE("urdf reader: the HumaRobotics PhantomX is refused for its inertias", "[urdf_reader]") {
  const std::string msg = refusal(kHuma);
  INFO(msg);
  CHECK(msg.rfind(kHuma + ": link '", 0) == 0);
  CHECK(msg.find("triangle inequality") != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
}

// ---- feet (docs/user/robots.md#feet) ----

/// The hexapod's leg mapped from chain `chain` (its first joint's name).
int leg_of_chain(const UrdfRobot& robot, const std::string& chain) {
  for (int leg = 0; leg < kPaperLegs; ++leg)
    if (robot.legs[leg].joints[0].name == chain) return leg;
  FAIL("no leg from chain " << chain);
  return -1;
}

/// Reads `text` with robot.foot_offset: `p` on leg `leg`, a point of no collision elsewhere.
std::string offset_refusal(const std::string& text, int leg, const Vec3& p, UrdfRobot* out) {
  UrdfReadOptions o;
  o.foot_offset = std::vector<Vec3>(kPaperLegs, Vec3(0.1, 0.0, 0.0));
  (*o.foot_offset)[leg] = p;
  try {
    *out = read_urdf_robot_from_string(text, "hexapod.urdf", o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST_CASE("urdf reader: a sphere <collision> at a chain's end is the default foot",
          "[urdf_reader][feet]") {
  // Kraby's legs end in 5 mm end caps: the foot is the cap's sphere, centred where the
  // chain's end link (the cap) has its origin.
  const UrdfRobot kraby = read_urdf_robot(kKraby, kraby_options());
  UrdfReadOptions caps = kraby_options();
  for (int i = 0; i < kPaperLegs; ++i) caps.foot_links.push_back("endcap_" + std::to_string(i));
  const UrdfRobot at_caps = read_urdf_robot(kKraby, caps);
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    const UrdfLeg& l = kraby.legs[leg];
    INFO(leg_name(leg) << " " << l.foot_source);
    CHECK(l.foot_kind == FootSource::kSphereCollision);
    CHECK(l.foot_source.rfind("endcap_", 0) == 0);
    CHECK(l.foot_radius_m == 0.005);
    CHECK((l.p_foot_last - at_caps.legs[leg].p_foot_last).norm() <= 1e-15);
    CHECK(at_caps.legs[leg].foot_radius_m == 0.0);
    CHECK(leg_mapping_entries(kraby)[leg].find(" radius 0.005") != std::string::npos);
  }
  UrdfReadOptions points = kraby_options();
  points.foot_radius = 0.0;
  CHECK(read_urdf_robot(kKraby, points).legs[2].foot_radius_m == 0.0);
  // A sphere foot survives /model/urdf: read back without foot keys, the same centres, radii.
  const RobotModel model = build_robot_model(kraby);
  const UrdfRobot back =
      read_urdf_robot_from_string(robot_urdf(model, "kraby"), "model.urdf", kraby_options());
  const RobotModel model_back = build_robot_model(back);
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    CHECK((model_back.p_foot_last[leg] - model.p_foot_last[leg]).norm() <= 1e-15);
    CHECK(model_back.foot_radius_m[leg] == model.foot_radius_m[leg]);
  }
}

TEST_CASE("urdf reader: robot.foot_offset per leg, checked against the collision geometry",
          "[urdf_reader][feet]") {
  // Leg order: each leg's own point lands on that leg, L1 … L6, whatever the chains' order.
  UrdfReadOptions o;
  o.foot_offset.emplace(kPaperLegs);
  for (int leg = 0; leg < kPaperLegs; ++leg) (*o.foot_offset)[leg] = Vec3(0.1, 0.001 * leg, 0.0);
  const UrdfRobot r = read_urdf_robot(kData + "valid_hexapod.urdf", o);
  for (int leg = 0; leg < kPaperLegs; ++leg) {
    CHECK(r.legs[leg].p_foot_last == (*o.foot_offset)[leg]);
    CHECK(r.legs[leg].foot_kind == FootSource::kFootOffset);
    CHECK(r.legs[leg].foot_check.find("not checked: no <collision>") == 0);
  }
  // leg0's tibia: a cylinder along its x (0 ≤ x ≤ 0.1, radius 0.01) and a box at its end,
  // yawed by 0.5 rad (half sides 0.01, 0.02, 0.015).
  const std::string tibia =
      "<link name=\"leg0_tibia\"><collision><origin xyz=\"0.05 0 0\" rpy=\"0 1.5707963267948966 "
      "0\"/><geometry><cylinder radius=\"0.01\" length=\"0.1\"/></geometry></collision>"
      "<collision><origin xyz=\"0.1 0 0\" rpy=\"0 0 0.5\"/><geometry><box size=\"0.02 0.04 "
      "0.03\"/></geometry></collision></link>";
  const std::string text =
      edited_hexapod("<link name=\"leg0_tibia\"/>", "<link name=\"leg0_tibia\"/>", tibia);
  const int leg = leg_of_chain(read_urdf_robot_from_string(text, "h.urdf"), "leg0_coxa_joint");
  const Mat3 yaw = Eigen::AngleAxisd(0.5, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 box = Vec3(0.1, 0.0, 0.0);
  UrdfRobot got;
  CHECK(offset_refusal(text, leg, Vec3(0.03, 0.009, 0.0), &got).empty());
  CHECK(got.legs[leg].foot_check == "inside the cylinder <collision> of leg0_tibia");
  CHECK(offset_refusal(text, leg, box + yaw * Vec3(0.009, 0.018, 0.0), &got).empty());
  CHECK(got.legs[leg].foot_check == "inside the box <collision> of leg0_tibia");
  // Just outside the cylinder's side, and beyond the yawed box's end: refused, naming the leg.
  const std::string side = offset_refusal(text, leg, Vec3(0.03, 0.0102, 0.0), &got);
  CHECK(side.find("hexapod.urdf: leg " + leg_name(leg) +
                  " (chain 'leg0_coxa_joint'): robot.foot_offset (0.03, 0.0102, 0) m lies "
                  "outside the <collision> geometry of its last link 'leg0_tibia' (cylinder, "
                  "box; 0.0002 m from the nearest)") == 0);
  const std::string end = offset_refusal(text, leg, box + yaw * Vec3(0.012, 0.0, 0.0), &got);
  CHECK(end.find("(cylinder, box; 0.002 m from the nearest)") != std::string::npos);
  CHECK(end.find('\n') == std::string::npos);
  // A mesh, whose file is not read, leaves the check undecided: accepted, and said.
  const std::string meshed = edited_hexapod(
      "<link name=\"leg0_tibia\"/>", "<link name=\"leg0_tibia\"/>",
      tibia.substr(0, tibia.size() - 7) +
          "<collision><geometry><mesh filename=\"tibia.stl\"/></geometry></collision></link>");
  CHECK(offset_refusal(meshed, leg, Vec3(0.03, 0.0102, 0.0), &got).empty());
  CHECK(got.legs[leg].foot_check ==
        "not checked: mesh <collision> geometry of 'leg0_tibia' (files not read)");
  CHECK(leg_mapping_text(got).find("foot check: not checked: mesh") != std::string::npos);
}

}  // namespace
}  // namespace hexdyn
