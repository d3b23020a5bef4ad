#pragma once
/// \file problem.hpp
/// The allocation problem of one sample (docs/theory/allocation.md#variables,
/// docs/theory/allocation.md#rows): torque-optimal foot
/// forces under the trunk equations, torque limits, minimum normal forces and friction.
///
/// Variables, stacked by leg in the contact frame [t1 t2 n] of each foot
/// (contact/touchdowns.hpp): (f_t1, f_t2, f_n) [N] for a support leg, (f_t1, f_t2) for a
/// leg in its impact transient (f_n is the transient's force, a known input), nothing for
/// a swing leg (F = 0).
///
/// Rows, in order: the six trunk equations (lower = upper, so that they can be relaxed);
/// then per leg with variables one torque row per joint, a support leg's minimum normal
/// force, and its friction faces (a pyramid, or for an impact leg under the exact cone the
/// inscribed 16-gon; a support leg under the exact cone gets a second-order cone instead).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/core/sizes.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// Where each leg's force lives among the problem's variables, and the forces that are
/// known: the one description of the variable layout, returned by the builder and read by
/// forces_from_solution.
struct AllocationLayout {
  /// The six trunk equations (force, then moment, world axes), the first inequality rows of
  /// every allocation problem, each with lower = upper so that it can be relaxed.
  static constexpr int kTrunkRows = 6;
  struct Leg {
    int offset = -1;  ///< index of the leg's first variable, −1 without variables
    /// Variables of the leg: 3 for a support leg (f_t1, f_t2, f_n), 2 for a leg in its
    /// impact transient (f_t1, f_t2), 0 for a swing leg.
    int count = 0;
    Mat3 W_R_contact = Mat3::Identity();  ///< contact frame [t1 t2 n] in world axes
    double known_normal_force_N = 0.0;    ///< an impact leg's transient force along n [N]
    /// The leg's friction rows: faces f = 0 … friction_faces − 1 at inequality rows
    /// friction_row + f, each  cos a f_t1 + sin a f_t2 ≤ μ·face_reach·f_n (allocation/friction.hpp,
    /// f_n the variable of a support leg or known_normal_force_N of an impact leg); −1 and 0
    /// without faces. cone: index of the leg's second-order cone in QpProblem::cones, −1 none.
    int friction_row = -1;
    int friction_faces = 0;
    double face_reach = 1.0;  ///< cos(π / friction_faces), the face's reach per unit μ f_n
    int cone = -1;
  };
  LegArray<Leg> legs;  ///< the first n_legs are the robot's
  int n_legs = 0;
  int variables = 0;
  /// Largest excess [N m] of a swing-leg torque over its limit (a constant row that no
  /// force can change), 0 when none.
  double constant_excess_Nm = 0.0;
  /// Names that row ("torque L1_femur (swing leg) by 0.3"), empty when none.
  std::string constant_violation;
};

/// The drive train's part of one sample
/// (docs/theory/drive-train.md#allocation-with-the-drive-train), for a robot with actuators: per
/// joint the known offset τ_drive − τ = J_a q̈ + τ_c sgn(q̇) + b q̇ [N m], the bounds lower_Nm ≤
/// τ_drive ≤ limit_Nm [N m] (lower_Nm = −limit_Nm but for a three-phase motor at speed) with the
/// kind of bound that gave them (1 peak, 2 voltage, 0 the allocation's own torque limit;
/// drive/drive.hpp DriveBound) and the objective's weight of τ_drive² (1 for torque_squared, c R /
/// (G k_t η)² for copper_loss).
/// The first joints entries are read (every vector starts at the capacity, zero offsets and
/// limits, unit weights, so that a caller may fill them by index).
struct DriveRows {
  JointVector offset_Nm = JointVector::Zero(kMaxJoints);
  JointVector limit_Nm = JointVector::Zero(kMaxJoints);
  JointVector lower_Nm = JointVector::Zero(kMaxJoints);
  JointArray<std::int8_t> bound{};
  JointVector weight = JointVector::Ones(kMaxJoints);
};

/// The legs' joints as the allocation reads them, the model's leg table (RobotModel::leg):
/// leg l's joints are the flat indices first_joint[l] … first_joint[l] + n_joints[l] − 1,
/// hip to foot; joints is their total.
struct AllocationLegs {
  int legs = 0;
  int joints = 0;
  LegArray<int> first_joint{};
  LegArray<int> n_joints{};
};
/// The leg table of `model`.
AllocationLegs allocation_legs(const RobotModel& model);
/// `legs` legs of `leg_joints` joints each, in the flat order.
AllocationLegs uniform_allocation_legs(int legs, int leg_joints);

/// The dynamics' terms of one sample the allocation reads (dynamics/rnea.hpp ContactSplit, in
/// capacity types: a robot of any size up to core/sizes.hpp's), also for inputs built by hand.
using AllocationSplit = ContactSplit;

/// Builds the allocation problem of one sample of a robot with legs `legs` into `qp`
/// (resized) and returns its layout. Legs in `phase` kSwing carry no force, kImpact legs carry
/// the known normal force `impact_force_N[l]` [N] along the third column of W_R_contact[l]
/// (the contact frames, world axes); the per-leg spans hold at least legs.legs entries. Sets
/// qp.structure to a key of the row layout (the friction model and each leg's phase), so
/// that back ends recognise problems built alike. With `drive` (not null), the torque rows
/// bound the drive torques τ + offset by drive->lower_Nm and drive->limit_Nm and the objective is
/// Σ weight_k (τ_k + offset_k)²; without it, |τ| by the allocation's limits and Σ τ².
AllocationLayout build_allocation_problem(const AllocationLegs& legs, const AllocationParams& alloc,
                                          const ContactParams& contact, const ContactSplit& split,
                                          std::span<const ContactPhase> phase,
                                          std::span<const double> impact_force_N,
                                          std::span<const Mat3> W_R_contact, QpProblem& qp,
                                          const DriveRows* drive = nullptr);
/// The same for a robot whose legs all have three joints (joints: split.tau0's size), for
/// callers that do not pass the leg table yet.
AllocationLayout build_allocation_problem(const AllocationParams& alloc,
                                          const ContactParams& contact, const ContactSplit& split,
                                          std::span<const ContactPhase> phase,
                                          std::span<const double> impact_force_N,
                                          std::span<const Mat3> W_R_contact, QpProblem& qp,
                                          const DriveRows* drive = nullptr);

/// Foot forces F_W [N] (world axes, terrain on foot; layout.n_legs entries written) and joint
/// torques tau [N m] (assigned split.tau0, joints) of a solution x (size layout.variables) of
/// the problem `layout` was built with: τ = τ₀ − Σ J_jᵀ F. Split: a ContactSplit or an
/// AllocationSplit; Tau: a joint vector.
template <class Split, class Tau>
void forces_from_solution(const Split& split, const AllocationLayout& layout,
                          const Eigen::VectorXd& x, std::span<Vec3> F_W, Tau& tau) {
  tau = split.tau0;
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    F_W[l].setZero();
    if (leg.count == 3) {
      F_W[l] = leg.W_R_contact * x.segment<3>(leg.offset);
    } else if (leg.count == 2) {
      F_W[l] = leg.W_R_contact.leftCols<2>() * x.segment<2>(leg.offset) +
               leg.known_normal_force_N * leg.W_R_contact.col(2);
    }
    tau -= split.JjT[l] * F_W[l];
  }
}

}  // namespace hexdyn
