// What a URDF robot's result says about it, against second computations: /model/urdf
// (robot_urdf) read back by the URDF reader is the original description to 1e-12 (masses,
// inertias, joint placements, axes, feet, FK) with its root link at the original root
// link's frame; the hip directions footholds follow are the zero-pose legs' directions;
// the default nominal stance is "femur level, tibia plumb"; the paper robot's directions
// are exactly ±x.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "hexdyn/model/leg_chain.hpp"
#include "hexdyn/model/stance.hpp"
#include "hexdyn/model/urdf.hpp"
#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn {
namespace {

const std::string kData = std::string(HEXDYN_SOURCE_DIR) + "/tests/data/urdf/robots/";

struct Case {
  std::string file, forward;
};
const Case kCases[] = {{"phantomx_mark4.urdf", "+x"}, {"kraby.urdf", "+y"}};

UrdfRobot read(const std::string& file, const std::string& forward) {
  UrdfReadOptions o;
  o.forward_axis = forward;
  return read_urdf_robot(kData + file, o);
}

void check_inertia(const RigidInertia& a, const RigidInertia& b) {
  CHECK(std::abs(a.mass_kg - b.mass_kg) <= 1e-12);
  if (a.mass_kg > 0.0) {
    CHECK((a.com_m - b.com_m).cwiseAbs().maxCoeff() <= 1e-12);
    CHECK((a.inertia_com - b.inertia_com).cwiseAbs().maxCoeff() <= 1e-12);
  }
}

}  // namespace

TEST_CASE("/model/urdf of a URDF robot reads back as the original description", "[robot_output]") {
  for (const Case& c : kCases) {
    INFO(c.file);
    const UrdfRobot original = read(c.file, c.forward);
    const RobotModel model = build_robot_model(original);
    UrdfReadOptions o;
    o.forward_axis = c.forward;  // the written root link is the original root link frame
    for (int i = 1; i <= kPaperLegs; ++i) o.foot_links.push_back("L" + std::to_string(i) + "_foot");
    const UrdfRobot back =
        read_urdf_robot_from_string(robot_urdf(model, original.name), "written", o);
    CHECK((back.B_R_U - original.B_R_U).cwiseAbs().maxCoeff() == 0.0);
    CHECK((back.B_R_root - original.B_R_root).cwiseAbs().maxCoeff() <= 1e-12);
    CHECK((back.p_B_root - original.p_B_root).cwiseAbs().maxCoeff() <= 1e-12);
    CHECK(std::abs(back.total_mass_kg - original.total_mass_kg) <= 1e-12);
    check_inertia(back.trunk, original.trunk);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const UrdfLeg &a = back.legs[leg], &b = original.legs[leg];
      for (int j = 0; j < kPaperLegJoints; ++j) {
        CHECK(a.joints[j].name == b.joints[j].name);  // the description's own joint names
        CHECK((a.joints[j].p_parent_joint - b.joints[j].p_parent_joint).cwiseAbs().maxCoeff() <=
              1e-12);
        CHECK((a.joints[j].R_parent_joint - b.joints[j].R_parent_joint).cwiseAbs().maxCoeff() <=
              1e-12);
        CHECK((a.joints[j].axis - b.joints[j].axis).cwiseAbs().maxCoeff() <= 1e-12);
        CHECK(a.joints[j].lower_rad == b.joints[j].lower_rad);
        CHECK(a.joints[j].upper_rad == b.joints[j].upper_rad);
        CHECK(a.joints[j].effort_Nm == b.joints[j].effort_Nm);
        check_inertia(a.joints[j].inertia, b.joints[j].inertia);
      }
      CHECK((a.p_foot_last - b.p_foot_last).cwiseAbs().maxCoeff() <= 1e-12);
    }
    // FK of both models at random angles.
    const RobotModel model_back = build_robot_model(back);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (int trial = 0; trial < 10; ++trial) {
      PaperJointVector q;
      for (int k = 0; k < kPaperJoints; ++k) q[k] = u(rng);
      BodyPoses pa, pb;
      forward_kinematics_tree(model, q, pa);
      forward_kinematics_tree(model_back, q, pb);
      for (int leg = 0; leg < kPaperLegs; ++leg)
        CHECK((tree_foot_position_B(model, pa, leg) - tree_foot_position_B(model_back, pb, leg))
                  .norm() <= 1e-12);
    }
  }
}

TEST_CASE("hip directions: the legs' zero-pose directions, the paper's exactly +-x",
          "[robot_output]") {
  for (const Case& c : kCases) {
    INFO(c.file);
    const RobotModel m = build_robot_model(read(c.file, c.forward));
    BodyPoses poses;
    forward_kinematics_tree(m, PaperJointVector::Zero(), poses);
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      Vec3 d = tree_foot_position_B(m, poses, leg) - m.p_parent_joint[m.body(leg, 0)];
      d.z() = 0.0;
      CHECK((m.hip_outward_B[leg] - d.normalized()).norm() <= 1e-12);
      CHECK(m.hip_outward_B[leg].z() == 0.0);
    }
  }
  const RobotModel paper = build_robot_model(test::paper_robot_params());
  for (int leg = 0; leg < kPaperLegs; ++leg)
    CHECK(paper.hip_outward_B[leg] == Vec3(is_left(leg) ? -1.0 : 1.0, 0.0, 0.0));
}

TEST_CASE("default nominal stance: femur level, tibia plumb, inside the joint limits",
          "[robot_output]") {
  for (const Case& c : kCases) {
    INFO(c.file);
    const RobotModel m = build_robot_model(read(c.file, c.forward));
    for (int leg = 0; leg < kPaperLegs; ++leg) {
      const NominalStance s = default_nominal_stance(m, leg);
      REQUIRE(s.from_pose);
      PaperJointVector q = PaperJointVector::Zero();
      for (int j = 0; j < m.leg(leg).n_joints; ++j) {
        const int k = m.joint(leg, j);
        q[k] = s.q[j];
        CHECK(s.q[j] >= m.joint_lower_rad[k]);
        CHECK(s.q[j] <= m.joint_upper_rad[k]);
      }
      BodyPoses poses;
      forward_kinematics_tree(m, q, poses);
      const Vec3 femur = poses.p_B[m.body(leg, 1)], tibia = poses.p_B[m.body(leg, 2)];
      const Vec3 foot = tree_foot_position_B(m, poses, leg);
      CHECK(std::abs(tibia.z() - femur.z()) <= 1e-9);  // femur level
      CHECK((foot - tibia).head<2>().norm() <= 1e-9);  // tibia plumb
      const Vec3 hip = m.p_parent_joint[m.body(leg, 0)];
      CHECK(s.radius_m == Approx((foot - hip).head<2>().norm()).epsilon(1e-12));
      CHECK(s.depth_m == Approx(hip.z() - foot.z()).epsilon(1e-12));
    }
  }
}

}  // namespace hexdyn
