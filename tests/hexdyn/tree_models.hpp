#pragma once
/// Robots of any shape built by hand, for the model and dynamics tests: a RobotModel whose tree is
/// drawn at random (seeded) for given legs of given joint counts (random joint placements and axes,
/// positive masses, inertias that satisfy the triangle inequality), filled by fill_leg_table;
/// and a forward kinematics of its own (Eigen::AngleAxisd per joint, world frame), a second
/// computation of the poses the dynamics use.
#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <vector>

#include "hexdyn/core/base_state.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/sample_models.hpp"

namespace hexdyn::test {

inline double draw(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

inline Vec3 draw_vec3(std::mt19937& rng, double lo, double hi) {
  return Vec3(draw(rng, lo, hi), draw(rng, lo, hi), draw(rng, lo, hi));
}

inline Mat3 draw_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Quat r(n(rng), n(rng), n(rng), n(rng));
  return r.normalized().toRotationMatrix();
}

/// A body of random mass, COM and rotational inertia (principal moments that satisfy the
/// triangle inequality, principal axes rotated at random).
inline RigidInertia draw_inertia(std::mt19937& rng, double mass_lo, double mass_hi, double size_m) {
  RigidInertia in;
  in.mass_kg = draw(rng, mass_lo, mass_hi);
  in.com_m = draw_vec3(rng, -size_m, size_m);
  const Mat3 R = draw_rotation(rng);
  const Vec3 moments = random_inertia(rng, in.mass_kg * size_m * size_m);
  in.inertia_com = R * moments.asDiagonal() * R.transpose();
  return in;
}

/// A robot of leg_joints.size() legs, leg l of leg_joints[l] joints, its tree flat leg by leg
/// (body b moved by joint b − 1); the joints of flat index in `prismatic` slide, the others
/// turn. Hips alternate left (x < 0) and right, front to rear; every joint placement,
/// orientation and axis and every inertia is drawn. Point feet.
inline RobotModel tree_model(std::mt19937& rng, const std::vector<int>& leg_joints,
                             const std::vector<int>& prismatic = {}) {
  RobotModel m;
  m.leg_geometry = LegGeometry::kChain;
  m.parent[0] = -1;
  m.R_parent_joint[0].setIdentity();
  m.p_parent_joint[0].setZero();
  m.axis[0].setZero();
  m.inertia[0] = draw_inertia(rng, 2.0, 8.0, 0.1);
  m.trunk_only = m.inertia[0];
  const int n_legs = static_cast<int>(leg_joints.size());
  int b = 1;
  for (int l = 0; l < n_legs; ++l) {
    const double side = l % 2 == 0 ? -1.0 : 1.0;
    const double y = 0.3 - 0.6 * (l / 2) / std::max(1, (n_legs - 1) / 2);
    for (int j = 0; j < leg_joints[l]; ++j, ++b) {
      m.parent[b] = j == 0 ? 0 : b - 1;
      m.p_parent_joint[b] = j == 0 ? Vec3(side * draw(rng, 0.05, 0.15), y, draw(rng, -0.03, 0.03))
                                   : draw_vec3(rng, -0.12, 0.12);
      m.R_parent_joint[b] = draw_rotation(rng);
      m.axis[b] = draw_vec3(rng, -1.0, 1.0).normalized();
      m.inertia[b] = draw_inertia(rng, 0.05, 0.6, 0.05);
    }
  }
  for (int k : prismatic) m.joint_type[k] = JointType::kPrismatic;
  fill_leg_table(m);
  for (int l = 0; l < m.legs(); ++l) {
    m.p_foot_last[l] = draw_vec3(rng, -0.1, 0.1);
    m.foot_radius_m[l] = 0.0;
  }
  m.total_mass_kg = 0.0;
  for (int k = 0; k < m.bodies(); ++k) m.total_mass_kg += m.inertia[k].mass_kg;
  return m;
}

/// The shapes the tests run: a quadruped 4 × 3, a hexapod of 4-joint legs and a biped 2 × 6,
/// then a quadruped whose knees slide and a biped with a sliding joint in each leg.
struct TreeShape {
  const char* name;
  std::vector<int> leg_joints;
  std::vector<int> prismatic;  ///< flat indices of the sliding joints
};
inline std::vector<TreeShape> tree_shapes() {
  return {{"quadruped 4x3", {3, 3, 3, 3}, {}},
          {"hexapod 6x4", {4, 4, 4, 4, 4, 4}, {}},
          {"biped 2x6", {6, 6}, {}},
          {"quadruped 4x3, prismatic knees", {3, 3, 3, 3}, {1, 4, 7, 10}},
          {"biped 2x6, a prismatic joint a leg", {6, 6}, {2, 11}}};
}

/// Body poses in the world for the trunk pose of `state` and joint positions q, composed joint
/// by joint with Eigen::AngleAxisd, or a slide along the axis for a prismatic joint
/// (independent of the model's and the dynamics' own).
struct TreePoses {
  std::vector<Mat3> R;
  std::vector<Vec3> p;
};
inline TreePoses tree_poses(const RobotModel& m, const BaseState& state, const JointVector& q) {
  TreePoses w;
  w.R.assign(m.bodies(), state.W_R_B);
  w.p.assign(m.bodies(), state.p_W);
  for (int b = 1; b < m.bodies(); ++b) {
    const int a = m.parent[b];
    if (m.prismatic(b - 1)) {
      w.p[b] =
          w.p[a] + w.R[a] * (m.p_parent_joint[b] + m.R_parent_joint[b] * (q[b - 1] * m.axis[b]));
      w.R[b] = w.R[a] * m.R_parent_joint[b];
      continue;
    }
    w.p[b] = w.p[a] + w.R[a] * m.p_parent_joint[b];
    w.R[b] =
        w.R[a] * m.R_parent_joint[b] * Eigen::AngleAxisd(q[b - 1], m.axis[b]).toRotationMatrix();
  }
  return w;
}

/// Foot point of leg l in the world [m].
inline Vec3 tree_foot(const RobotModel& m, const TreePoses& w, int l) {
  const int b = m.foot_body(l);
  return w.p[b] + w.R[b] * m.p_foot_last[l];
}

/// A random state of the robot: trunk pose and twist and accelerations, joint vectors.
struct TreeState {
  BaseState state;
  JointVector q, qd, qdd;
};
inline TreeState draw_tree_state(std::mt19937& rng, const RobotModel& m) {
  TreeState s;
  s.state.W_R_B = draw_rotation(rng);
  s.state.p_W = draw_vec3(rng, -1.0, 1.0);
  s.state.v_W = draw_vec3(rng, -1.0, 1.0);
  s.state.omega_W = draw_vec3(rng, -2.0, 2.0);
  s.state.a_W = draw_vec3(rng, -5.0, 5.0);
  s.state.omegadot_W = draw_vec3(rng, -5.0, 5.0);
  s.q.resize(m.joints());
  s.qd.resize(m.joints());
  s.qdd.resize(m.joints());
  for (int k = 0; k < m.joints(); ++k) {
    s.q[k] = m.prismatic(k) ? draw(rng, -0.1, 0.1) : draw(rng, -2.0, 2.0);
    s.qd[k] = draw(rng, -3.0, 3.0);
    s.qdd[k] = draw(rng, -10.0, 10.0);
  }
  return s;
}

/// ν = [v_W; ω_W; q̇] and ν̇ = [a_W; ω̇_W; q̈] (6 + joints).
inline DofVector tree_velocity(const TreeState& s) {
  DofVector nu(6 + s.qd.size());
  nu << s.state.v_W, s.state.omega_W, s.qd;
  return nu;
}
inline DofVector tree_acceleration(const TreeState& s) {
  DofVector a(6 + s.qdd.size());
  a << s.state.a_W, s.state.omegadot_W, s.qdd;
  return a;
}

}  // namespace hexdyn::test
