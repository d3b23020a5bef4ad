// URDF export: the robot read back from the URDF text alone (a hand-written XML scan
// and an independent forward kinematics) must be the simulated robot.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <string>

#include "hexdyn/model/urdf.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"

namespace {

using hexdyn::Mat3;
using hexdyn::Vec3;

struct UrdfJoint {
  std::string name, type, parent, child;
  Vec3 xyz = Vec3::Zero(), rpy = Vec3::Zero(), axis = Vec3::Zero();
  bool has_axis = false, has_limit = false;
  double lower = 0.0, upper = 0.0, effort = 0.0, velocity = 0.0;
};

struct UrdfLink {
  bool has_inertial = false;
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
};

struct UrdfDoc {
  std::string robot_name;
  std::map<std::string, UrdfLink> links;
  std::map<std::string, UrdfJoint> joints;  ///< by name
  std::map<std::string, std::string> joint_of_child;
};

std::map<std::string, std::string> attributes(const std::string& text) {
  static const std::regex kAttr(R"re(([A-Za-z_]+)\s*=\s*"([^"]*)")re");
  std::map<std::string, std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kAttr);
       it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = (*it)[2];
  return out;
}

Vec3 triple(const std::string& text) {
  std::istringstream is(text);
  Vec3 v;
  is >> v.x() >> v.y() >> v.z();
  REQUIRE(!is.fail());
  return v;
}

/// Minimal scan of the tags of a URDF document (no comments inside tags, no CDATA).
UrdfDoc parse_urdf(const std::string& xml) {
  static const std::regex kComment(R"(<!--[\s\S]*?-->)");
  const std::string text = std::regex_replace(xml, kComment, "");
  static const std::regex kTag(R"(<(/?)([A-Za-z_?]+)([^>]*?)(/?)>)");
  UrdfDoc doc;
  std::string link, joint;
  bool in_inertial = false;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kTag); it != std::sregex_iterator();
       ++it) {
    const bool closing = (*it)[1] == "/";
    const bool self_closing = (*it)[4] == "/";
    const std::string tag = (*it)[2];
    auto attr = attributes((*it)[3]);
    if (closing) {
      if (tag == "link") link.clear();
      if (tag == "joint") joint.clear();
      if (tag == "inertial") in_inertial = false;
      continue;
    }
    if (tag == "robot") {
      doc.robot_name = attr["name"];
    } else if (tag == "link") {
      REQUIRE(doc.links.count(attr["name"]) == 0);
      doc.links[attr["name"]] = UrdfLink{};
      if (!self_closing) link = attr["name"];
    } else if (tag == "joint") {
      UrdfJoint j;
      j.name = attr["name"];
      j.type = attr["type"];
      REQUIRE(doc.joints.count(j.name) == 0);
      doc.joints[j.name] = j;
      joint = j.name;
    } else if (tag == "inertial") {
      REQUIRE(!link.empty());
      doc.links[link].has_inertial = true;
      in_inertial = true;
    } else if (tag == "mass" && in_inertial) {
      doc.links[link].mass = std::stod(attr["value"]);
    } else if (tag == "origin" && in_inertial) {
      doc.links[link].com = triple(attr["xyz"]);
    } else if (!joint.empty()) {
      UrdfJoint& j = doc.joints[joint];
      if (tag == "parent") j.parent = attr["link"];
      if (tag == "child") j.child = attr["link"];
      if (tag == "origin") {
        j.xyz = triple(attr["xyz"]);
        j.rpy = triple(attr["rpy"]);
      }
      if (tag == "axis") {
        j.axis = triple(attr["xyz"]);
        j.has_axis = true;
      }
      if (tag == "limit") {
        j.has_limit = true;
        j.lower = std::stod(attr["lower"]);
        j.upper = std::stod(attr["upper"]);
        j.effort = std::stod(attr["effort"]);
        j.velocity = std::stod(attr["velocity"]);
      }
    }
  }
  for (const auto& [name, j] : doc.joints) doc.joint_of_child[j.child] = name;
  return doc;
}

Mat3 rot_x(double a) {
  Mat3 R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
Mat3 rot_y(double a) {
  Mat3 R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Mat3 rot_z(double a) {
  Mat3 R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

/// Rodrigues' formula for a rotation by `angle` about the unit vector `u`.
Mat3 rodrigues(const Vec3& u, double angle) {
  Mat3 K;
  K << 0, -u.z(), u.y(), u.z(), 0, -u.x(), -u.y(), u.x(), 0;
  return Mat3::Identity() + std::sin(angle) * K + (1.0 - std::cos(angle)) * K * K;
}

struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
};

/// Pose of `link` in the root frame, composing joint origins and axis rotations from
/// the URDF numbers; `angles` by joint name (missing names: 0).
Pose urdf_link_pose(const UrdfDoc& doc, const std::string& link,
                    const std::map<std::string, double>& angles) {
  const auto it = doc.joint_of_child.find(link);
  if (it == doc.joint_of_child.end()) return Pose{};  // the root
  const UrdfJoint& j = doc.joints.at(it->second);
  const Pose parent = urdf_link_pose(doc, j.parent, angles);
  const Mat3 R_origin = rot_z(j.rpy.z()) * rot_y(j.rpy.y()) * rot_x(j.rpy.x());
  double q = 0.0;
  if (j.type == "revolute") q = angles.count(j.name) ? angles.at(j.name) : 0.0;
  Pose out;
  out.p = parent.p + parent.R * j.xyz;
  out.R = parent.R * R_origin * (j.type == "revolute" ? rodrigues(j.axis, q) : Mat3::Identity());
  return out;
}

}  // namespace

TEST_CASE("urdf: rotation_to_rpy reproduces the rotation", "[urdf]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  for (int n = 0; n < 200; ++n) {
    const Mat3 R =
        hexdyn::Quat(Eigen::Vector4d::Random().normalized()).toRotationMatrix() * rot_z(u(rng));
    const Vec3 rpy = hexdyn::rotation_to_rpy(R);
    const Mat3 back = rot_z(rpy.z()) * rot_y(rpy.y()) * rot_x(rpy.x());
    CHECK((back - R).cwiseAbs().maxCoeff() < 1e-14);
  }
  for (double pitch : {M_PI / 2, -M_PI / 2}) {
    const Mat3 R = rot_z(0.3) * rot_y(pitch) * rot_x(-0.2);
    const Vec3 rpy = hexdyn::rotation_to_rpy(R);
    const Mat3 back = rot_z(rpy.z()) * rot_y(rpy.y()) * rot_x(rpy.x());
    CHECK((back - R).cwiseAbs().maxCoeff() < 1e-14);
  }
  const Vec3 yaw_only = hexdyn::rotation_to_rpy(rot_z(M_PI));
  CHECK(yaw_only.x() == 0.0);
  CHECK(yaw_only.y() == 0.0);
  CHECK(std::abs(yaw_only.z()) == Approx(M_PI).margin(1e-15));
}

TEST_CASE("urdf: structure, names, limits and total mass of the paper robot", "[urdf]") {
  const hexdyn::RobotModel model = hexdyn::build_robot_model(hexdyn::test::paper_robot_params());
  const std::string text = hexdyn::robot_urdf(model, "hexapod<paper>");
  const UrdfDoc doc = parse_urdf(text);
  CHECK(doc.robot_name == "hexapod&lt;paper&gt;");
  REQUIRE(doc.links.count("trunk") == 1);
  REQUIRE(doc.links.count("payload") == 1);
  CHECK(doc.joint_of_child.count("trunk") == 0);  // the root
  CHECK(doc.joints.at("payload_mount").type == "fixed");
  CHECK(doc.joints.at("payload_mount").parent == "trunk");
  CHECK(doc.links.size() == 2 + 6 * 4);
  CHECK(doc.joints.size() == 1 + 6 * 4);
  double mass = 0.0;
  for (const auto& [name, link] : doc.links) mass += link.mass;
  CHECK(std::abs(mass - model.total_mass_kg) < 1e-12);
  CHECK(std::abs(mass - 6.7) < 1e-12);
  for (int leg = 0; leg < hexdyn::kPaperLegs; ++leg) {
    const std::string L = hexdyn::leg_name(leg);
    for (int j = 0; j < hexdyn::kPaperLegJoints; ++j) {
      const UrdfJoint& jt = doc.joints.at(hexdyn::joint_name(leg, j));
      CHECK(jt.type == "revolute");
      CHECK(jt.has_axis);
      REQUIRE(jt.has_limit);
      CHECK(jt.lower == model.joint_lower_rad[hexdyn::paper_joint_index(leg, j)]);
      CHECK(jt.upper == model.joint_upper_rad[hexdyn::paper_joint_index(leg, j)]);
      CHECK(jt.effort == 6.0);
      CHECK(jt.velocity == 10.0);
      CHECK(doc.links.at(jt.child).has_inertial);
    }
    CHECK(doc.joints.at(L + "_coxa").parent == "trunk");
    CHECK(doc.joints.at(L + "_coxa").child == L + "_coxa_link");
    CHECK(doc.joints.at(L + "_femur").parent == L + "_coxa_link");
    CHECK(doc.joints.at(L + "_tibia").child == L + "_tibia_link");
    const UrdfJoint& foot = doc.joints.at(L + "_foot_fixed");
    CHECK(foot.type == "fixed");
    CHECK(foot.parent == L + "_tibia_link");
    CHECK(foot.child == L + "_foot");
    CHECK_FALSE(doc.links.at(L + "_foot").has_inertial);
  }
}

TEST_CASE("urdf: FK from the URDF numbers reproduces the simulated feet and COM", "[urdf]") {
  std::mt19937 rng(20261121);
  for (int robot = 0; robot < 25; ++robot) {
    const hexdyn::RobotModel model =
        hexdyn::build_robot_model(hexdyn::test::random_robot_params(rng));
    const UrdfDoc doc = parse_urdf(hexdyn::robot_urdf(model, "random"));
    double mass = 0.0;
    for (const auto& [name, link] : doc.links) mass += link.mass;
    CHECK(std::abs(mass - model.total_mass_kg) < 1e-12);
    for (int sample = 0; sample < 8; ++sample) {
      const hexdyn::PaperJointVector q = hexdyn::test::random_joint_vector(rng, -2.5, 2.5);
      hexdyn::BodyPoses poses;
      hexdyn::forward_kinematics_tree(model, q, poses);
      std::map<std::string, double> angles;
      for (int leg = 0; leg < hexdyn::kPaperLegs; ++leg)
        for (int j = 0; j < hexdyn::kPaperLegJoints; ++j)
          angles[hexdyn::joint_name(leg, j)] = q[hexdyn::paper_joint_index(leg, j)];
      for (int leg = 0; leg < hexdyn::kPaperLegs; ++leg) {
        const Pose foot = urdf_link_pose(doc, hexdyn::leg_name(leg) + "_foot", angles);
        const Vec3 expected = hexdyn::tree_foot_position_B(model, poses, leg);
        INFO("robot " << robot << " leg " << leg);
        CHECK((foot.p - expected).norm() < 1e-12);
      }
      // Whole-robot centre of mass from the URDF inertials (mass, COM origin).
      Vec3 com = Vec3::Zero();
      for (const auto& [name, link] : doc.links) {
        const Pose pose = urdf_link_pose(doc, name, angles);
        com += link.mass * (pose.p + pose.R * link.com);
      }
      com /= mass;
      CHECK((com - hexdyn::center_of_mass_B(model, poses)).norm() < 1e-12);
    }
  }
}
