#pragma once
/// Sample robots for tests (after Pinocchio's buildModels): the paper's robot, and
/// random but valid robots (positive masses, physically consistent inertias, legs
/// long enough to stand) with random reachable leg states.
#include <random>

#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/paper_sizes.hpp"

namespace hexdyn::test {

/// Table 1 of the paper with the assumed hip layout of configs/paper.yaml.
inline RobotParams paper_robot_params() {
  RobotParams p;
  p.trunk = {0.65, Vec3(1.66e-2, 2.52e-3, 1.69e-2), Vec3::Zero()};
  p.payload = {4.244, Vec3(9e-3, 3e-3, 11e-3), Vec3::Zero()};
  p.link[0] = {0.150, Vec3(7.1e-5, 10.8e-5, 5.7e-5), Vec3(0.0425, 0, 0)};
  p.link[1] = {0.041, Vec3(2.0e-5, 8.7e-5, 10.0e-5), Vec3(0.060, 0, 0)};
  p.link[2] = {0.110, Vec3(9.8e-5, 8.7e-5, 2.1e-5), Vec3(0.050, 0, 0)};
  p.link_length_m = {0.085, 0.120, 0.100};
  p.joint_offset_m = {0.008, 0.018, 0.020};
  const double hx = 0.08, hy = 0.2;
  for (int leg = 0; leg < p.legs; ++leg) {
    const double x = is_left(leg) ? -hx : hx;
    const double y = (leg / 2 == 0) ? hy : (leg / 2 == 1 ? 0.0 : -hy);
    p.hip_position_m[leg] = Vec3(x, y, 0.0);
    p.hip_yaw_rad[leg] = is_left(leg) ? M_PI : 0.0;
  }
  p.joint_min_rad = {-1.5, -1.5, -2.8};
  p.joint_max_rad = {1.5, 1.5, 0.0};
  p.ik_min_margin_m = 1e-4;
  return p;
}

/// Principal moments that satisfy the triangle inequality (a physical body).
inline Vec3 random_inertia(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(0.2, 1.0);
  for (;;) {
    Vec3 I(u(rng), u(rng), u(rng));
    if (I.x() + I.y() >= I.z() && I.y() + I.z() >= I.x() && I.x() + I.z() >= I.y())
      return scale * I;
  }
}

/// A random valid robot: every mass, length, offset, COM and hip placement drawn.
inline RobotParams random_robot_params(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto in = [&](double a, double b) { return a + (b - a) * u(rng); };
  RobotParams p = paper_robot_params();
  p.trunk = {in(0.3, 2.0), random_inertia(rng, 1e-2),
             Vec3(in(-0.02, 0.02), in(-0.02, 0.02), in(-0.01, 0.01))};
  p.payload = {in(0.5, 5.0), random_inertia(rng, 5e-3),
               Vec3(in(-0.03, 0.03), in(-0.03, 0.03), in(0.0, 0.05))};
  for (int j = 0; j < p.leg_joints; ++j) {
    p.link_length_m[j] = in(0.05, 0.15);
    p.link[j] = {in(0.02, 0.3), random_inertia(rng, 1e-4),
                 Vec3(in(0.2, 0.8) * p.link_length_m[j], in(-0.01, 0.01), in(-0.01, 0.01))};
    p.joint_offset_m[j] = in(0.0, 0.03);
  }
  for (int leg = 0; leg < p.legs; ++leg) {
    p.hip_position_m[leg] =
        Vec3(in(0.04, 0.12) * (is_left(leg) ? -1 : 1), in(-0.25, 0.25), in(-0.02, 0.02));
    p.hip_yaw_rad[leg] = (is_left(leg) ? M_PI : 0.0) + in(-0.5, 0.5);
  }
  return p;
}

/// Random joint angles of one leg whose foot is reachable by the knee-up IK branch
/// with margin (drawn in joint space, inside the limits, away from singularities).
inline Vec3 random_leg_angles(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto in = [&](double a, double b) { return a + (b - a) * u(rng); };
  return Vec3(in(-1.0, 1.0), in(-1.0, 1.0), in(-2.5, -0.2));
}

/// Random state vector of all 18 joints.
inline PaperJointVector random_joint_vector(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  PaperJointVector v;
  for (int k = 0; k < kPaperJoints; ++k) v[k] = u(rng);
  return v;
}

/// IMPACT contact parameters K [N/m^e], e, C_max [N·s/m], p [m] (μ left at its default).
inline ContactParams contact_params(double K, double e, double C, double p) {
  ContactParams c;
  c.stiffness = K;
  c.exponent = e;
  c.damping_max_Nspm = C;
  c.full_damping_depth_m = p;
  return c;
}

}  // namespace hexdyn::test
