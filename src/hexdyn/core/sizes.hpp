#pragma once
/// \file sizes.hpp
/// Capacities of a robot model and the storage types sized by them
/// (docs/theory/conventions.md#sizes).
///
/// A robot has n legs (kMinLegs … kMaxLegs) of m joints each (kMinLegJoints … kMaxLegJoints;
/// m may differ between legs). Its counts are known only at run time (RobotModel::legs(),
/// n_joints, n_bodies); the storage of every per-sample quantity has a fixed capacity, so that
/// no sample allocates: an Eigen vector or matrix of dynamic size with a compile-time maximum
/// keeps its coefficients inside the object, and a per-leg or per-body std::array has the
/// capacity's length, of which the model's count is used (loops run to the model's count,
/// never over the whole array).
#include <Eigen/Core>
#include <array>

namespace hexdyn {

inline constexpr int kMinLegs = 2;       ///< fewest legs a robot may have
inline constexpr int kMaxLegs = 8;       ///< most legs a robot may have
inline constexpr int kMinLegJoints = 3;  ///< fewest joints from the trunk to a foot
inline constexpr int kMaxLegJoints = 6;  ///< most joints from the trunk to a foot
inline constexpr int kMaxJoints = kMaxLegs * kMaxLegJoints;  ///< 48 actuated joints
inline constexpr int kMaxBodies = 1 + kMaxJoints;            ///< trunk, then one per joint
inline constexpr int kMaxDof = 6 + kMaxJoints;               ///< trunk pose, then joints
inline constexpr int kMaxLegForces = 3 * kMaxLegs;           ///< three force components a leg

/// One value per joint, flat order (size: the model's joint count).
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxJoints, 1>;
/// One value per generalised coordinate: trunk (6), then joints (size 6 + joints).
using DofVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDof, 1>;
/// A matrix over the generalised coordinates (the mass matrix: (6 + joints)²).
using DofMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxDof, kMaxDof>;
/// A foot's 3 × (6 + joints) Jacobian.
using DofJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxDof>;
/// One value per joint of one leg, hip to foot (size: the leg's joint count).
using LegVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLegJoints, 1>;
/// A foot's 3 × m Jacobian with respect to its own leg's joints.
using LegJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxLegJoints>;

/// Per-leg storage: the first RobotModel::legs() entries are used.
template <class T>
using LegArray = std::array<T, kMaxLegs>;
/// Per-joint storage of one leg, hip to foot: the first LegInfo::n_joints entries are used.
template <class T>
using LegJointArray = std::array<T, kMaxLegJoints>;
/// Per-body storage: the first RobotModel::n_bodies entries are used (body 0: the trunk).
template <class T>
using BodyArray = std::array<T, kMaxBodies>;
/// Per-joint storage of non-numeric values (names, drive data): the first n_joints are used.
template <class T>
using JointArray = std::array<T, kMaxJoints>;

}  // namespace hexdyn
