#pragma once
/// \file rnea.hpp
/// Floating-base rigid-body dynamics of the robot (docs/theory/stages.md#inverse-dynamics):
/// recursive Newton–Euler (RNEA), composite-rigid-body mass matrix (CRBA), foot Jacobians,
/// whole-robot momentum and the affine split τ = τ₀ − Σ J_jᵀ F used by allocation.
///
/// Calling convention (Pinocchio's Model/Data): the `RobotModel` is const; every
/// buffer lives in a `RobotData` built once from the model; each algorithm writes into
/// the workspace and returns a const reference to its result. No algorithm allocates.
///
/// Generalised coordinates (6 + n velocities, n = model.joints(): trunk first, then the joints
/// in flat order k = model.joint(l, j), docs/theory/conventions.md#flat-joint-index):
///
///   ν  = [ v_W ; ω_W ; q̇ ]     v_W: velocity of the trunk origin P0 [m/s], world axes
///                               ω_W: trunk angular velocity [rad/s], world axes
///   ν̇  = [ a_W ; ω̇_W ; q̈ ]     a_W = d v_W/dt: classical acceleration of P0 [m/s²],
///                               world axes; ω̇_W = d ω_W/dt [rad/s²], world axes
///
/// Generalised forces (6 + n): rows 0–2 the force on the trunk [N] and rows 3–5 the
/// moment on the trunk about P0 [N m], both in world axes; rows 6 … 5 + n the joint torques
/// [N m]. With these, the power is τᵀν and the equations of motion read
///
///   M(q) ν̇ + h(q, ν) = [ f_base ; n_base ; τ_joints ] + Σ_l J_lᵀ F_l
///
/// where F_l is the force of the terrain on foot l [N], world axes, applied at its contact
/// point, and J_l (3 × (6 + n)) maps ν to the velocity of the foot body's material point at the
/// contact point, in world axes. The contact point is the foot point, or for a sphere foot of
/// radius r (RobotModel::foot_radius_m) the point centre − r n of the sphere, n the unit normal of
/// the surface under it (FootNormals): F at it is F at the centre plus the moment
/// (−r n) × F on the foot body (docs/theory/model.md#sphere-feet). A motion is consistent
/// without a base actuator when the trunk rows (f_base, n_base) vanish.
/// h includes gravity, RobotModel::gravity_W ((0, 0, −9.81) m/s² unless a caller changes it).
///
/// Body frames: body 0 is the trunk (frame L0 at P0); body b = 1 + k is moved by joint
/// k, its frame is the joint frame rotated by q_k about the joint axis a (a revolute joint:
/// motion subspace S = [a; 0], q_k [rad], τ_k [N m]) or moved by q_k along it (a prismatic
/// joint, RobotModel::joint_type: S = [0; a], q_k [m], τ_k the force along a [N])
/// (robot_model.hpp).
///
/// Sizes: every per-body and per-leg array has the capacity of core/sizes.hpp, of which the
/// model's counts are used; the generalised vectors and matrices are sized once, from the
/// model, when the RobotData is built. The per-body 6-D algebra is fixed-size.
#include <Eigen/Cholesky>
#include <array>

#include "hexdyn/core/base_state.hpp"
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/spatial.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// Unit normal of the surface under each foot [1], world axes: where a sphere foot touches
/// (file comment). Every algorithm that takes one reads +z under every foot when it is null.
using FootNormals = LegArray<Vec3>;

/// Per-leg 3-vectors an algorithm reads (foot forces, surface normals), or none: a view of
/// a caller's per-leg array (a LegArray, or a std::array of the model's leg count) made from
/// a pointer to it, or from nullptr. Entries 0 … model.legs() − 1 are read.
class LegVectors {
 public:
  LegVectors(std::nullptr_t = nullptr) {}  // NOLINT(google-explicit-constructor)
  template <std::size_t N>
  LegVectors(const std::array<Vec3, N>* a)  // NOLINT(google-explicit-constructor)
      : data_(a != nullptr ? a->data() : nullptr) {}
  bool empty() const { return data_ == nullptr; }
  const Vec3& operator[](int l) const { return data_[l]; }

 private:
  const Vec3* data_ = nullptr;
};

/// Transposed joint block of a foot Jacobian: (joints) × 3.
using JointForceMap = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxJoints, 3>;

/// Total momentum of the whole robot (trunk, payload and every link).
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
///   joint rows:  τ = tau0 − Σ_l JjT[l] F_l           (one torque per joint)
/// F_l: force of the terrain on foot l [N], world axes. Rows of JbT are (force [N],
/// moment about P0 [N m]) in world axes; JjT[l] is non-zero only in leg l's rows.
/// Sized by RobotData's constructor (tau0 and each JjT: model.joints() rows).
struct ContactSplit {
  Vec6 trunk_rhs = Vec6::Zero();  ///< trunk rows of M ν̇ + h (no foot forces) [N, N m]
  JointVector tau0;               ///< joint rows of M ν̇ + h (no foot forces) [N m]
  using JointRows = JointForceMap;
  LegArray<JointForceMap> JjT;                ///< transposed joint block of J_l [m]
  LegArray<Eigen::Matrix<double, 6, 3>> JbT;  ///< transposed base block of J_l
};

/// Per-run workspace (Pinocchio's `Data`). All buffers have a fixed capacity (no heap),
/// sized from the model by the constructor; algorithms
/// overwrite the fields they document and leave the others untouched. A RobotData
/// belongs to the model it was built from (it caches the body inertias); use one per
/// thread or MPI rank.
struct RobotData {
  explicit RobotData(const RobotModel& model);

  // --- kinematics (every algorithm below refreshes these for its q and base pose) ---
  BodyArray<Transform> X_parent_body;  ///< parent_X_b: body b's frame in its parent's
  BodyArray<Transform> X_world_body;   ///< W_X_b: body b's frame in G0 (R: b → world)
  BodyArray<Inertia> I_body;           ///< body inertias in body frames (from the model)
  /// The joint rotations of the model, expanded once (Rodrigues, axis a, K = [a]×):
  /// parent_R_b(q) = R_pj (a aᵀ + cos q (1 − a aᵀ) + sin q K) = R_fixed + cos q R_cos + sin q
  /// R_sin.
  BodyArray<Mat3> R_fixed, R_cos, R_sin;
  /// A prismatic joint's axis in its parent's frame, R_pj a: parent_p_b(q) = p_pj + q R_pj a
  /// (its parent_R_b = R_fixed = R_pj, R_cos = R_sin = 0).
  BodyArray<Vec3> slide;
  /// The trunk pose and joint angles X_parent_body and X_world_body were last computed for
  /// (kinematics_q empty before the first computation): update_kinematics returns at once when
  /// called again with the same values, bit for bit (a replay step's bias forces, mass matrix
  /// and contacts ask for one state's transforms in turn).
  Mat3 kinematics_W_R_B = Mat3::Zero();
  Vec3 kinematics_p_W = Vec3::Zero();
  JointVector kinematics_q;

  // --- recursive passes, body coordinates ---
  BodyArray<Motion> v_body;    ///< spatial velocity of body b, body-b coordinates
  BodyArray<Motion> a_body;    ///< spatial acceleration (gravity included in rnea)
  BodyArray<Force> f_body;     ///< force across joint b (body 0: trunk wrench)
  BodyArray<Inertia> Ic_body;  ///< composite inertia of the subtree at b (crba)

  // --- body velocities in world axes (robot_momentum) ---
  BodyArray<Vec3> omega_body_W;  ///< angular velocity of body b [rad/s]
  BodyArray<Vec3> v_com_body_W;  ///< velocity of body b's COM [m/s]

  // --- results ---
  DofVector tau;                   ///< rnea: generalised force M ν̇ + h − Σ J_lᵀ F_l
  DofMatrix M;                     ///< crba: joint-space inertia matrix
  LegArray<DofJacobian> J_foot_W;  ///< foot_jacobians: v_contact_W = J ν
  LegArray<Vec3> p_foot_W;         ///< contact points in G0 [m]
  LegArray<Vec3> a_foot_bias_W;    ///< foot_bias_accelerations: J̇ ν [m/s²]
  Momentum momentum;               ///< robot_momentum
  ContactSplit split;              ///< contact_split
  // --- forward dynamics (forward_dynamics.hpp) ---
  DofVector bias;               ///< h(q, ν) − Σ J_lᵀ F_l
  Eigen::LLT<DofMatrix> M_llt;  ///< Cholesky factor of M
  DofVector nu_dot;             ///< ν̇, the result
};

/// Fills data.X_parent_body and data.X_world_body for the trunk pose of `state`
/// (W_R_B, p_W only) and joint angles q (model.joints()) [rad]; nothing when they already
/// hold that pose and q (RobotData::kinematics_q).
void update_kinematics(const RobotModel& model, RobotData& data, const BaseState& state,
                       const JointVector& q);

/// Recursive Newton–Euler: returns τ = M(q) ν̇ + h(q, ν) − Σ_l J_lᵀ F_l (6 + joints, see the
/// file comment), gravity included. q, qd, qdd: joint angles [rad], rates [rad/s],
/// accelerations [rad/s²] (model.joints() each). foot_forces_W: optional forces of the
/// terrain on the feet [N], world axes, applied at the contact points (nullptr: none) for the
/// surface normals normals_W (file comment).
/// Also fills kinematics, v_body, a_body, f_body. Result in data.tau.
const DofVector& rnea(const RobotModel& model, RobotData& data, const BaseState& state,
                      const JointVector& q, const JointVector& qd, const JointVector& qdd,
                      LegVectors foot_forces_W = nullptr, LegVectors normals_W = nullptr);

/// Composite-rigid-body algorithm: the symmetric positive definite mass matrix M(q)
/// ((6 + joints)²) in the coordinates of the file comment. Uses only the pose of `state`.
/// Also fills kinematics and Ic_body. Result in data.M.
const DofMatrix& crba(const RobotModel& model, RobotData& data, const BaseState& state,
                      const JointVector& q);

/// Contact points p_foot_W [m] (file comment) and their Jacobians J_foot_W (3 × (6 + joints)
/// each, the velocity of the foot body's material point there, v = J ν): base block
/// [I₃, −[p_foot_W − p_W]×], joint columns axis_W × (p_foot_W − p_joint_W) for the joints of
/// the leg, zero elsewhere. Uses only the pose of `state`.
void foot_jacobians(const RobotModel& model, RobotData& data, const BaseState& state,
                    const JointVector& q, LegVectors normals_W = nullptr);
/// foot_jacobians at the poses already in `data`: precondition, update_kinematics of `state`
/// and its joint angles was the last call to change them (it saves a second pass).
void foot_jacobians_at_poses(const RobotModel& model, RobotData& data, const BaseState& state,
                             LegVectors normals_W = nullptr);

/// Accelerations at zero generalised acceleration, J̇ ν (3 per leg) [m/s²], world axes, of
/// the foot bodies' material points at the contact points (foot_jacobians): their classical
/// acceleration is J ν̇ + J̇ ν. Uses the pose and twist of `state` and joint rates qd
/// [rad/s]; ignores a_W, ω̇_W and gravity.
/// Result in data.a_foot_bias_W; also overwrites v_body and a_body.
const LegArray<Vec3>& foot_bias_accelerations(const RobotModel& model, RobotData& data,
                                              const BaseState& state, const JointVector& q,
                                              const JointVector& qd,
                                              LegVectors normals_W = nullptr);

/// Whole-robot momentum, summed body by body from world-frame body velocities
/// (independent of rnea/crba). Uses the pose and twist of `state`, q and qd.
/// Also fills omega_body_W and v_com_body_W. Result in data.momentum.
const Momentum& robot_momentum(const RobotModel& model, RobotData& data, const BaseState& state,
                               const JointVector& q, const JointVector& qd);

/// The affine split (docs/theory/stages.md#inverse-dynamics) for the prescribed motion
/// (state, q, qd, qdd), the forces acting at the contact points of normals_W.
/// Runs rnea without foot forces (data.tau holds its result afterwards) and
/// foot_jacobians. Result in data.split.
const ContactSplit& contact_split(const RobotModel& model, RobotData& data, const BaseState& state,
                                  const JointVector& q, const JointVector& qd,
                                  const JointVector& qdd, LegVectors normals_W = nullptr);

}  // namespace hexdyn
