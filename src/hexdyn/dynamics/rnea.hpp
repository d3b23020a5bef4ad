#pragma once
/// \file rnea.hpp
/// Floating-base rigid-body dynamics of the hexapod (docs/theory/stages.md#inverse-dynamics):
/// recursive Newton–Euler (RNEA), composite-rigid-body mass matrix (CRBA), foot Jacobians,
/// whole-robot momentum and the affine split τ = τ₀ − Σ J_jᵀ F used by allocation.
///
/// Calling convention (Pinocchio's Model/Data): the `RobotModel` is const; every
/// buffer lives in a `RobotData` built once from the model; each algorithm writes into
/// the workspace and returns a const reference to its result. No algorithm allocates.
///
/// Generalised coordinates (24 velocities, trunk first, then the 18 joints in flat
/// joint order k = 3 l + j, docs/theory/conventions.md#flat-joint-index):
///
///   ν  = [ v_W ; ω_W ; q̇ ]     v_W: velocity of the trunk origin P0 [m/s], world axes
///                               ω_W: trunk angular velocity [rad/s], world axes
///   ν̇  = [ a_W ; ω̇_W ; q̈ ]     a_W = d v_W/dt: classical acceleration of P0 [m/s²],
///                               world axes; ω̇_W = d ω_W/dt [rad/s²], world axes
///
/// Generalised forces (24): rows 0–2 the force on the trunk [N] and rows 3–5 the
/// moment on the trunk about P0 [N m], both in world axes; rows 6–23 the joint torques
/// [N m]. With these, the power is τᵀν and the equations of motion read
///
///   M(q) ν̇ + h(q, ν) = [ f_base ; n_base ; τ_joints ] + Σ_l J_lᵀ F_l
///
/// where F_l is the force of the terrain on foot l [N], world axes, applied at its contact
/// point, and J_l (3×24) maps ν to the velocity of the tibia's material point at the contact
/// point, in world axes. The contact point is the foot point, or for a sphere foot of radius
/// r (RobotModel::foot_radius_m) the point centre − r n of the sphere, n the unit normal of
/// the surface under it (FootNormals): F at it is F at the centre plus the moment
/// (−r n) × F on the tibia (docs/theory/model.md#sphere-feet). A motion is consistent
/// without a base actuator when the trunk rows (f_base, n_base) vanish.
/// h includes gravity, RobotModel::gravity_W ((0, 0, −9.81) m/s² unless a caller changes it).
///
/// Body frames: body 0 is the trunk (frame L0 at P0); body b = 1 + k is moved by joint
/// k, its frame is the joint frame rotated by q_k about the joint axis (robot_model.hpp).
#include <Eigen/Cholesky>
#include <array>

#include "hexdyn/core/base_state.hpp"
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/spatial.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

using VecDof = Eigen::Matrix<double, kDof, 1>;        ///< 24 generalised values
using MatDof = Eigen::Matrix<double, kDof, kDof>;     ///< 24×24
using FootJacobian = Eigen::Matrix<double, 3, kDof>;  ///< 3×24, world axes
/// Unit normal of the surface under each foot [1], world axes: where a sphere foot touches
/// (file comment). Every algorithm that takes one reads +z under every foot when it is null.
using FootNormals = std::array<Vec3, kLegs>;

/// Total momentum of the whole robot (trunk, payload and all 18 links).
struct Momentum {
  Vec3 linear_W = Vec3::Zero();  ///< Σ m_b v_cb [kg m/s], world axes
  /// About the world origin O: Σ I_b ω_b + c_b × m_b v_cb [kg m²/s], world axes.
  Vec3 angular_O_W = Vec3::Zero();
  Vec3 angular_com_W = Vec3::Zero();  ///< about the whole-robot COM (centroidal) [kg m²/s]
  Vec3 com_W = Vec3::Zero();          ///< whole-robot centre of mass [m]
  double mass_kg = 0.0;               ///< total mass [kg]
};

/// Affine split of the equations of motion in the foot forces
/// (docs/theory/stages.md#inverse-dynamics):
///   trunk rows:  Σ_l JbT[l] F_l = trunk_rhs          (6 equations)
///   joint rows:  τ = tau0 − Σ_l JjT[l] F_l           (18 torques)
/// F_l: force of the terrain on foot l [N], world axes. Rows of JbT are (force [N],
/// moment about P0 [N m]) in world axes; JjT[l] is non-zero only in leg l's 3 rows.
struct ContactSplit {
  Vec6 trunk_rhs = Vec6::Zero();  ///< trunk rows of M ν̇ + h (no foot forces) [N, N m]
  VecJ tau0 = VecJ::Zero();       ///< joint rows of M ν̇ + h (no foot forces) [N m]
  std::array<Eigen::Matrix<double, kJoints, 3>, kLegs> JjT;  ///< transposed joint block of J_l [m]
  std::array<Eigen::Matrix<double, 6, 3>, kLegs> JbT;        ///< transposed base block of J_l
};

/// Per-run workspace (Pinocchio's `Data`). All buffers are fixed-size; algorithms
/// overwrite the fields they document and leave the others untouched. A RobotData
/// belongs to the model it was built from (it caches the body inertias); use one per
/// thread or MPI rank.
struct RobotData {
  explicit RobotData(const RobotModel& model);

  // --- kinematics (every algorithm below refreshes these for its q and base pose) ---
  std::array<Transform, kBodies> X_parent_body;  ///< parent_X_b: body b's frame in its parent's
  std::array<Transform, kBodies> X_world_body;   ///< W_X_b: body b's frame in G0 (R: b → world)
  std::array<Inertia, kBodies> I_body;           ///< body inertias in body frames (from the model)
  /// The joint rotations of the model, expanded once (Rodrigues, axis a, K = [a]×):
  /// parent_R_b(q) = R_pj (a aᵀ + cos q (1 − a aᵀ) + sin q K) = R_fixed + cos q R_cos + sin q
  /// R_sin.
  std::array<Mat3, kBodies> R_fixed, R_cos, R_sin;

  // --- recursive passes, body coordinates ---
  std::array<Motion, kBodies> v_body;    ///< spatial velocity of body b, body-b coordinates
  std::array<Motion, kBodies> a_body;    ///< spatial acceleration (gravity included in rnea)
  std::array<Force, kBodies> f_body;     ///< force across joint b (body 0: trunk wrench)
  std::array<Inertia, kBodies> Ic_body;  ///< composite inertia of the subtree at b (crba)

  // --- body velocities in world axes (robot_momentum) ---
  std::array<Vec3, kBodies> omega_body_W;  ///< angular velocity of body b [rad/s]
  std::array<Vec3, kBodies> v_com_body_W;  ///< velocity of body b's COM [m/s]

  // --- results ---
  VecDof tau = VecDof::Zero();  ///< rnea: generalised force M ν̇ + h − Σ J_lᵀ F_l
  MatDof M = MatDof::Zero();    ///< crba: joint-space inertia matrix
  std::array<FootJacobian, kLegs> J_foot_W;  ///< foot_jacobians: v_contact_W = J ν
  std::array<Vec3, kLegs> p_foot_W;          ///< contact points in G0 [m]
  std::array<Vec3, kLegs> a_foot_bias_W;     ///< foot_bias_accelerations: J̇ ν [m/s²]
  Momentum momentum;                         ///< robot_momentum
  ContactSplit split;                        ///< contact_split
  // --- forward dynamics (forward_dynamics.hpp) ---
  VecDof bias = VecDof::Zero();    ///< h(q, ν) − Σ J_lᵀ F_l
  Eigen::LLT<MatDof> M_llt;        ///< Cholesky factor of M
  VecDof nu_dot = VecDof::Zero();  ///< ν̇, the result
};

/// Fills data.X_parent_body and data.X_world_body for the trunk pose of `state`
/// (W_R_B, p_W only) and joint angles q (18) [rad].
void update_kinematics(const RobotModel& model, RobotData& data, const BaseState& state,
                       const VecJ& q);

/// Recursive Newton–Euler: returns τ = M(q) ν̇ + h(q, ν) − Σ_l J_lᵀ F_l (24, see the
/// file comment), gravity included. q, qd, qdd: joint angles [rad], rates [rad/s],
/// accelerations [rad/s²] (18 each). foot_forces_W: optional forces of the terrain on
/// the six feet [N], world axes, applied at the contact points (nullptr: none) for the
/// surface normals normals_W (file comment).
/// Also fills kinematics, v_body, a_body, f_body. Result in data.tau.
const VecDof& rnea(const RobotModel& model, RobotData& data, const BaseState& state, const VecJ& q,
                   const VecJ& qd, const VecJ& qdd,
                   const std::array<Vec3, kLegs>* foot_forces_W = nullptr,
                   const FootNormals* normals_W = nullptr);

/// Composite-rigid-body algorithm: the symmetric positive definite mass matrix M(q)
/// (24×24) in the coordinates of the file comment. Uses only the pose of `state`.
/// Also fills kinematics and Ic_body. Result in data.M.
const MatDof& crba(const RobotModel& model, RobotData& data, const BaseState& state, const VecJ& q);

/// Contact points p_foot_W [m] (file comment) and their Jacobians J_foot_W (3×24 each, the
/// velocity of the tibia's material point there, v = J ν): base block
/// [I₃, −[p_foot_W − p_W]×], joint columns axis_W × (p_foot_W − p_joint_W) for the three
/// joints of the leg, zero elsewhere. Uses only the pose of `state`.
void foot_jacobians(const RobotModel& model, RobotData& data, const BaseState& state, const VecJ& q,
                    const FootNormals* normals_W = nullptr);

/// Accelerations at zero generalised acceleration, J̇ ν (3 per leg) [m/s²], world axes, of
/// the tibia's material points at the contact points (foot_jacobians): their classical
/// acceleration is J ν̇ + J̇ ν. Uses the pose and twist of `state` and joint rates qd
/// [rad/s]; ignores a_W, ω̇_W and gravity.
/// Result in data.a_foot_bias_W; also overwrites v_body and a_body.
const std::array<Vec3, kLegs>& foot_bias_accelerations(const RobotModel& model, RobotData& data,
                                                       const BaseState& state, const VecJ& q,
                                                       const VecJ& qd,
                                                       const FootNormals* normals_W = nullptr);

/// Whole-robot momentum, summed body by body from world-frame body velocities
/// (independent of rnea/crba). Uses the pose and twist of `state`, q and qd.
/// Also fills omega_body_W and v_com_body_W. Result in data.momentum.
const Momentum& robot_momentum(const RobotModel& model, RobotData& data, const BaseState& state,
                               const VecJ& q, const VecJ& qd);

/// The affine split (docs/theory/stages.md#inverse-dynamics) for the prescribed motion
/// (state, q, qd, qdd), the forces acting at the contact points of normals_W.
/// Runs rnea without foot forces (data.tau holds its result afterwards) and
/// foot_jacobians. Result in data.split.
const ContactSplit& contact_split(const RobotModel& model, RobotData& data, const BaseState& state,
                                  const VecJ& q, const VecJ& qd, const VecJ& qdd,
                                  const FootNormals* normals_W = nullptr);

}  // namespace hexdyn
