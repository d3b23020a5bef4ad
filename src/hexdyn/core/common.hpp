#pragma once
/// \file common.hpp
/// Sizes, Eigen types and naming conventions shared by every stage
/// (docs/theory/conventions.md).
///
/// Legs L1 … Ln in the order of docs/theory/conventions.md (the paper's hexapod: 1 front-left,
/// 2 front-right, 3 middle-left, 4 middle-right, 5 rear-left, 6 rear-right); in code legs are
/// 0-based (leg index l = i - 1). Counts and the flat joint order are the robot model's
/// (model/robot_model.hpp leg table); capacities are core/sizes.hpp's.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <string>

#include "hexdyn/core/sizes.hpp"

namespace hexdyn {

inline constexpr double kGravity = 9.81;  ///< m/s², along −z of G0
/// Joints of a leg whose joints take the names coxa, femur, tibia (joint_name).
inline constexpr int kNamedLegJoints = 3;

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Quat = Eigen::Quaterniond;

/// std::remainder(x, 2π), the angle in [−π, π]. The remainder is exact (IEEE 754), and an angle
/// already within ±π is its own remainder (a tie, x = ±π, keeps the even quotient 0), so the
/// library call is needed only outside: the same bits, without its cost on most angles.
inline double wrap_angle(double x) {
  return std::abs(x) <= M_PI ? x : std::remainder(x, 2.0 * M_PI);
}

/// True for the left legs 1, 3, 5 of the YAML robot's numbering (0-based 0, 2, 4); a URDF
/// robot's side is its leg table's (RobotModel::leg(l).side).
constexpr bool is_left(int leg) { return leg % 2 == 0; }

/// "L1".."L6".
std::string leg_name(int leg);
/// Positional joint names, the files' labels (docs/theory/conventions.md): for a leg of three
/// joints "L{i}_coxa", "L{i}_femur", "L{i}_tibia"; for a leg of `leg_joints` ≠ 3 joints
/// "L{i}_j1" … "L{i}_j{m}".
std::string joint_name(int leg, int joint, int leg_joints = kNamedLegJoints);

/// `x` with `significant_digits` significant digits, as printf's %g writes it: how messages
/// quote a number ("9.61e-06", "0.05").
std::string format_number(double x, int significant_digits);

/// Rotation matrix of Bryant (Cardan x-y-z) angles: R = Rx(α) Ry(β) Rz(θ), body → world.
Mat3 bryant_to_rotation(const Vec3& eta);

}  // namespace hexdyn
