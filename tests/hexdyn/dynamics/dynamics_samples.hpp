#pragma once
/// Random states, forces and surface normals for the dynamics tests, and the sample models
/// they run on (the paper's robot and random robots, tests/hexdyn/sample_models.hpp), shared
/// by test_rnea.cpp and test_forward_dynamics.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "hexdyn/core/spatial.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/paper_sizes.hpp"
#include "hexdyn/sample_models.hpp"
#include "hexdyn/tree_models.hpp"

namespace hexdyn::test {

constexpr int kRandomRobots = 24;
constexpr int kStatesPerRobot = 3;

inline double uniform(std::mt19937& rng, double lo, double hi) { return draw(rng, lo, hi); }

inline Vec3 random_vec3(std::mt19937& rng, double lo, double hi) { return draw_vec3(rng, lo, hi); }

inline Mat3 random_rotation(std::mt19937& rng) { return draw_rotation(rng); }

/// exp of the skew matrix of φ (Rodrigues), with series near φ = 0.
inline Mat3 so3_exp(const Vec3& phi) {
  const double th = phi.norm();
  const Mat3 P = skew(phi);
  const double a = th < 1e-4 ? 1.0 - th * th / 6.0 : std::sin(th) / th;
  const double b = th < 1e-4 ? 0.5 - th * th / 24.0 : (1.0 - std::cos(th)) / (th * th);
  return Mat3::Identity() + a * P + b * P * P;
}

/// Left Jacobian of SO(3): d/dt exp(φ) · exp(φ)ᵀ = skew(J_l(φ) φ̇).
inline Mat3 so3_left_jacobian(const Vec3& phi) {
  const double th = phi.norm();
  const Mat3 P = skew(phi);
  const double b =
      th < 1e-2 ? 0.5 - th * th / 24.0 + std::pow(th, 4) / 720.0 : (1.0 - std::cos(th)) / (th * th);
  const double c = th < 1e-2 ? 1.0 / 6.0 - th * th / 120.0 + std::pow(th, 4) / 5040.0
                             : (th - std::sin(th)) / (th * th * th);
  return Mat3::Identity() + b * P + c * P * P;
}

struct Sample {
  BaseState state;
  PaperJointVector q, qd, qdd;
};

inline Sample random_sample(std::mt19937& rng) {
  Sample s;
  s.state.W_R_B = random_rotation(rng);
  s.state.p_W = random_vec3(rng, -1.0, 1.0);
  s.state.v_W = random_vec3(rng, -1.0, 1.0);
  s.state.omega_W = random_vec3(rng, -2.0, 2.0);
  s.state.a_W = random_vec3(rng, -3.0, 3.0);
  s.state.omegadot_W = random_vec3(rng, -5.0, 5.0);
  for (int l = 0; l < kPaperLegs; ++l) s.q.segment<3>(3 * l) = random_leg_angles(rng);
  s.qd = random_joint_vector(rng, -2.0, 2.0);
  s.qdd = random_joint_vector(rng, -5.0, 5.0);
  return s;
}

inline std::array<Vec3, kPaperLegs> random_forces(std::mt19937& rng) {
  std::array<Vec3, kPaperLegs> F;
  for (auto& f : F) f = random_vec3(rng, -20.0, 20.0);
  return F;
}

inline PaperDofVector velocity_vector(const Sample& s) {
  PaperDofVector nu;
  nu << s.state.v_W, s.state.omega_W, s.qd;
  return nu;
}

inline PaperDofVector acceleration_vector(const Sample& s) {
  PaperDofVector a;
  a << s.state.a_W, s.state.omegadot_W, s.qdd;
  return a;
}

/// The paper's robot and kRandomRobots random robots (fixed seed).
inline const std::vector<RobotModel>& sample_models() {
  static const std::vector<RobotModel> models = [] {
    std::vector<RobotModel> m;
    m.push_back(build_robot_model(paper_robot_params()));
    std::mt19937 rng(20240611);
    for (int i = 0; i < kRandomRobots; ++i)
      m.push_back(build_robot_model(random_robot_params(rng)));
    return m;
  }();
  return models;
}

template <class A, class B>
inline double relative_error(const A& got, const B& expected) {
  return (got - expected).norm() / std::max(1.0, expected.norm());
}

/// The sample models with a sphere foot of a random radius on every leg.
inline std::vector<RobotModel> sphere_foot_models(std::mt19937& rng) {
  std::vector<RobotModel> out = sample_models();
  for (RobotModel& m : out)
    for (double& r : m.foot_radius_m) r = uniform(rng, 0.005, 0.04);
  return out;
}

/// A random upward unit normal per foot (up to 60° from +z).
inline FootNormals random_normals(std::mt19937& rng) {
  FootNormals n;
  for (Vec3& v : n) {
    do v = random_vec3(rng, -1.0, 1.0) + Vec3(0.0, 0.0, 1.0);
    while (v.norm() < 0.5 || v.normalized().z() < 0.5);
    v.normalize();
  }
  return n;
}

}  // namespace hexdyn::test
