#pragma once
// Synthetic robots written as URDF text for the tests that read them with the project's URDF
// reader: a trunk link and legs of any joint count, each joint's placement, axis, limits and
// inertia given (urdf_text), or drawn at random from a seed (random_urdf_robot: random axes and
// inertias that satisfy the triangle inequality), or laid out as a walking robot
// (walking_urdf_robot: yaw, then pitch joints whose limits' middle is a standing pose).
#include <Eigen/Geometry>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"

namespace hexdyn::test {

/// One link's <inertial>: mass, COM, principal moments about axes turned by rpy.
struct UrdfInertial {
  double mass_kg = 0.1;
  Vec3 com_m = Vec3::Zero();
  Vec3 moments_kgm2 = Vec3(1e-4, 1e-4, 1e-4);
  Vec3 rpy = Vec3::Zero();
};

/// One moving joint and the link it moves.
struct UrdfJointSpec {
  std::string type = "revolute";  ///< "revolute" or "prismatic"
  Vec3 xyz = Vec3::Zero(), rpy = Vec3::Zero(), axis = Vec3::UnitY();
  double lower = -3.0, upper = 3.0;
  UrdfInertial inertial;
};

/// One leg: its joints, hip to foot, and the foot point in the last link (a fixed link there).
struct UrdfLegSpec {
  std::vector<UrdfJointSpec> joints;
  Vec3 foot_xyz = Vec3(0.08, 0.0, 0.0);
};

struct UrdfRobotSpec {
  std::string name = "synthetic";
  UrdfInertial trunk{5.0, Vec3::Zero(), Vec3(0.05, 0.08, 0.1), Vec3::Zero()};
  std::vector<UrdfLegSpec> legs;
};

inline std::string urdf_vec(const Vec3& v) {
  std::ostringstream s;
  s << std::setprecision(17) << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

inline std::string urdf_inertial(const UrdfInertial& in) {
  std::ostringstream s;
  s << std::setprecision(17);
  s << "    <inertial><origin xyz=\"" << urdf_vec(in.com_m) << "\" rpy=\"" << urdf_vec(in.rpy)
    << "\"/><mass value=\"" << in.mass_kg << "\"/><inertia ixx=\"" << in.moments_kgm2.x()
    << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << in.moments_kgm2.y() << "\" iyz=\"0\" izz=\""
    << in.moments_kgm2.z() << "\"/></inertial>\n";
  return s.str();
}

/// The URDF text of `spec`: link "trunk", leg l's links "l{l}_link{j}" moved by joints
/// "l{l}_joint{j}", its foot the link "l{l}_foot" fixed at foot_xyz in the last link.
inline std::string urdf_text(const UrdfRobotSpec& spec) {
  std::ostringstream s;
  s << std::setprecision(17);
  s << "<?xml version=\"1.0\"?>\n<robot name=\"" << spec.name << "\">\n";
  s << "  <link name=\"trunk\">\n" << urdf_inertial(spec.trunk) << "  </link>\n";
  for (std::size_t l = 0; l < spec.legs.size(); ++l) {
    const UrdfLegSpec& leg = spec.legs[l];
    const std::string p = "l" + std::to_string(l);
    std::string parent = "trunk";
    for (std::size_t j = 0; j < leg.joints.size(); ++j) {
      const UrdfJointSpec& jt = leg.joints[j];
      const std::string link = p + "_link" + std::to_string(j);
      s << "  <link name=\"" << link << "\">\n" << urdf_inertial(jt.inertial) << "  </link>\n";
      s << "  <joint name=\"" << p << "_joint" << j << "\" type=\"" << jt.type << "\">\n"
        << "    <parent link=\"" << parent << "\"/><child link=\"" << link << "\"/>\n"
        << "    <origin xyz=\"" << urdf_vec(jt.xyz) << "\" rpy=\"" << urdf_vec(jt.rpy) << "\"/>\n"
        << "    <axis xyz=\"" << urdf_vec(jt.axis) << "\"/>\n"
        << "    <limit lower=\"" << jt.lower << "\" upper=\"" << jt.upper
        << "\" effort=\"100\" velocity=\"50\"/>\n  </joint>\n";
      parent = link;
    }
    s << "  <link name=\"" << p << "_foot\"/>\n"
      << "  <joint name=\"" << p << "_foot_joint\" type=\"fixed\">\n"
      << "    <parent link=\"" << parent << "\"/><child link=\"" << p << "_foot\"/>\n"
      << "    <origin xyz=\"" << urdf_vec(leg.foot_xyz) << "\" rpy=\"0 0 0\"/>\n  </joint>\n";
  }
  s << "</robot>\n";
  return s.str();
}

inline double urdf_draw(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// A random inertial: mass, COM, principal moments that satisfy the triangle inequality
/// (each at most the sum of the other two), principal axes turned at random.
inline UrdfInertial random_inertial(std::mt19937& rng, double mass_lo, double mass_hi,
                                    double size_m) {
  UrdfInertial in;
  in.mass_kg = urdf_draw(rng, mass_lo, mass_hi);
  in.com_m = Vec3(urdf_draw(rng, -size_m, size_m), urdf_draw(rng, -size_m, size_m),
                  urdf_draw(rng, -size_m, size_m));
  const double scale = in.mass_kg * size_m * size_m;
  const double a = urdf_draw(rng, 0.5, 1.0) * scale, b = urdf_draw(rng, 0.5, 1.0) * scale;
  in.moments_kgm2 = Vec3(a, b, urdf_draw(rng, std::abs(a - b) + 0.05 * scale, 0.95 * (a + b)));
  in.rpy =
      Vec3(urdf_draw(rng, -M_PI, M_PI), urdf_draw(rng, -1.5, 1.5), urdf_draw(rng, -M_PI, M_PI));
  return in;
}

/// Hip l of n in the URDF trunk frame (x forward, y left): legs numbered front to rear, left
/// (even l) and right (odd l) in turn.
inline Vec3 hip_xyz(int l, int n) {
  const int ranks = (n + 1) / 2, rank = l / 2;
  const double x = ranks == 1 ? 0.0 : 0.3 - 0.6 * rank / (ranks - 1);
  return Vec3(x, l % 2 == 0 ? 0.1 : -0.1, 0.0);
}

/// A robot of leg_joints.size() legs, leg l of leg_joints[l] joints, every joint's placement
/// (links 5–12 cm), orientation, axis and inertia drawn from `rng`; revolute joints limited to
/// ±3 rad, so that every leg's nominal pose (the middle of its limits) is q = 0.
inline UrdfRobotSpec random_urdf_robot(std::mt19937& rng, const std::vector<int>& leg_joints) {
  UrdfRobotSpec spec;
  spec.name = "random";
  spec.trunk = random_inertial(rng, 3.0, 8.0, 0.1);
  const int n = static_cast<int>(leg_joints.size());
  for (int l = 0; l < n; ++l) {
    UrdfLegSpec leg;
    const double side = l % 2 == 0 ? 1.0 : -1.0;
    for (int j = 0; j < leg_joints[l]; ++j) {
      UrdfJointSpec jt;
      // Links 5–10 cm along x and up to 6 cm across, frames turned by up to 1.2 rad about each
      // axis: no two links in line at q = 0 (a leg straight out is singular).
      jt.xyz = j == 0 ? hip_xyz(l, n)
                      : Vec3(urdf_draw(rng, 0.05, 0.1), urdf_draw(rng, -0.06, 0.06),
                             urdf_draw(rng, -0.06, 0.06));
      jt.rpy = Vec3(urdf_draw(rng, -1.2, 1.2), urdf_draw(rng, -1.2, 1.2),
                    (j == 0 ? side * M_PI / 2 : 0.0) + urdf_draw(rng, -1.2, 1.2));
      // A random axis, drawn again while it is within about 45° of the previous joint's (as
      // written in their own frames, which differ by small turns): a leg, not a degenerate arm.
      do {
        jt.axis =
            Vec3(urdf_draw(rng, -1.0, 1.0), urdf_draw(rng, -1.0, 1.0), urdf_draw(rng, -1.0, 1.0))
                .normalized();
      } while (j > 0 && std::abs(jt.axis.dot(leg.joints.back().axis)) > 0.7);
      jt.inertial = random_inertial(rng, 0.05, 0.6, 0.04);
      leg.joints.push_back(jt);
    }
    leg.foot_xyz =
        Vec3(urdf_draw(rng, 0.06, 0.1), urdf_draw(rng, -0.02, 0.02), urdf_draw(rng, -0.02, 0.02));
    spec.legs.push_back(leg);
  }
  return spec;
}

/// A walking robot of n legs of m joints (m ≥ 3): a yaw hip joint turned to point the leg
/// outward, then m − 1 pitch joints along the leg (links of `link_m`), limits whose middle is
/// the standing pose: the first pitch joint level, the second turned 1.2 rad down, each further
/// one 0.2 rad up; random inertias from `rng`.
inline UrdfRobotSpec walking_urdf_robot(std::mt19937& rng, int n, int m, double link_m = 0.1) {
  UrdfRobotSpec spec;
  spec.name = "walker";
  spec.trunk = random_inertial(rng, 3.0, 5.0, 0.1);
  for (int l = 0; l < n; ++l) {
    UrdfLegSpec leg;
    const double side = l % 2 == 0 ? 1.0 : -1.0;
    for (int j = 0; j < m; ++j) {
      UrdfJointSpec jt;
      jt.inertial = random_inertial(rng, 0.05, 0.2, 0.02);
      jt.inertial.com_m = Vec3(0.5 * link_m, 0.0, 0.0);
      if (j == 0) {
        jt.xyz = hip_xyz(l, n);
        jt.rpy = Vec3(0.0, 0.0, side * M_PI / 2);
        jt.axis = Vec3::UnitZ();
        jt.lower = -0.6;
        jt.upper = 0.6;
      } else {
        jt.xyz = Vec3(j == 1 ? 0.04 : link_m, 0.0, 0.0);
        jt.axis = Vec3::UnitY();  // a positive angle turns the link down
        const double mid = j == 1 ? 0.0 : (j == 2 ? 1.2 : -0.2);
        jt.lower = mid - 0.9;
        jt.upper = mid + 0.9;
      }
      leg.joints.push_back(jt);
    }
    leg.foot_xyz = Vec3(link_m, 0.0, 0.0);
    spec.legs.push_back(leg);
  }
  return spec;
}

}  // namespace hexdyn::test
