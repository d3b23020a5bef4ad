#pragma once
// The paper robot's sizes (configs/paper.yaml: six legs of three joints, docs/theory/model.md),
// for the tests of that robot and of robots built in its shape (sample_models.hpp). The program
// itself takes every size from the robot model (core/sizes.hpp, model/robot_model.hpp).
#include <Eigen/Core>

namespace hexdyn {

inline constexpr int kPaperLegs = 6;
inline constexpr int kPaperLegJoints = 3;
inline constexpr int kPaperJoints = kPaperLegs * kPaperLegJoints;  ///< 18
inline constexpr int kPaperDof = 6 + kPaperJoints;                 ///< 24: trunk, then joints
inline constexpr int kPaperBodies = 1 + kPaperJoints;              ///< trunk, then the links

/// One value per joint of the paper robot, flat order.
using PaperJointVector = Eigen::Matrix<double, kPaperJoints, 1>;
using PaperDofVector = Eigen::Matrix<double, kPaperDof, 1>;
using PaperDofMatrix = Eigen::Matrix<double, kPaperDof, kPaperDof>;
using PaperFootJacobian = Eigen::Matrix<double, 3, kPaperDof>;

/// Flat index of joint j of leg l of the paper robot: 3 l + j.
constexpr int paper_joint_index(int leg, int joint) { return kPaperLegJoints * leg + joint; }

}  // namespace hexdyn
