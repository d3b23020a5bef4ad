#pragma once
/// \file common.hpp
/// Sizes, Eigen types and naming conventions shared by every stage
/// (docs/theory/conventions.md).
///
/// Legs: 1 front-left, 2 front-right, 3 middle-left, 4 middle-right, 5 rear-left,
/// 6 rear-right; in code legs are 0-based (leg index l = i - 1). Joints per leg:
/// coxa, femur, tibia; flat joint index k = 3 l + j with j = 0, 1, 2.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>

#include "hexdyn/core/sizes.hpp"

namespace hexdyn {

inline constexpr int kLegs = 6;
inline constexpr int kJointsPerLeg = 3;
inline constexpr int kJoints = kLegs * kJointsPerLeg;  ///< 18 actuated joints
inline constexpr int kDof = 6 + kJoints;               ///< 24: trunk pose then joints
inline constexpr int kBodies = 1 + kJoints;            ///< trunk, then 3 links per leg
inline constexpr double kGravity = 9.81;               ///< m/s², along −z of G0
static_assert(kLegs <= kMaxLegs && kJoints <= kMaxJoints && kBodies <= kMaxBodies);

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using VecJ = Eigen::Matrix<double, kJoints, 1>;  ///< one value per joint, flat index
using Quat = Eigen::Quaterniond;

/// Flat joint index k = 3(i−1)+(j−1) for leg l = i−1 and joint j−1.
constexpr int joint_index(int leg, int joint) { return kJointsPerLeg * leg + joint; }

/// True for the left legs 1, 3, 5 (0-based 0, 2, 4).
constexpr bool is_left(int leg) { return leg % 2 == 0; }

/// "L1".."L6".
std::string leg_name(int leg);
/// Positional joint names, the files' labels (docs/theory/conventions.md): for a leg of three
/// joints "L{i}_coxa", "L{i}_femur", "L{i}_tibia"; for a leg of `leg_joints` ≠ 3 joints
/// "L{i}_j1" … "L{i}_j{m}".
std::string joint_name(int leg, int joint, int leg_joints = kJointsPerLeg);

/// `x` with `significant_digits` significant digits, as printf's %g writes it: how messages
/// quote a number ("9.61e-06", "0.05").
std::string format_number(double x, int significant_digits);

/// Rotation matrix of Bryant (Cardan x-y-z) angles: R = Rx(α) Ry(β) Rz(θ), body → world.
Mat3 bryant_to_rotation(const Vec3& eta);

}  // namespace hexdyn
