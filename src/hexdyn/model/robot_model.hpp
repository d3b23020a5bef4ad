#pragma once
/// \file robot_model.hpp
/// The immutable robot description (Pinocchio's `Model` role): kinematic tree,
/// joint placements, inertias, and the per-leg analytic kinematics (FK, IK,
/// Jacobian and its time derivative).
///
/// Tree: body 0 is the trunk (trunk + payload, floating); body b = 1 + k is moved by
/// joint k (flat index, docs/theory/conventions.md#flat-joint-index), its parent is the
/// trunk for a leg's first (hip) joint and the previous link otherwise. The counts (legs,
/// joints, bodies) are the model's (fill_leg_table); storage has the capacities of
/// core/sizes.hpp.
///
/// Leg frame H_l ("hip frame"): the coxa joint frame at zero coxa angle, origin at the
/// coxa joint (p_hip_B, R_B_H = R_parent_joint of the coxa body). The foot point is
/// p_foot_last[l] in the frame of the leg's foot body (its last link; the tibia of a
/// three-joint leg): the point the IK
/// places and the FK, Jacobians and J̇ below describe. A sphere foot (foot_radius_m[l] > 0)
/// has its centre there; it touches a surface of unit normal n at the contact point
/// centre − r n, where the terrain's forces act (dynamics/rnea.hpp,
/// docs/theory/model.md#sphere-feet).
///
/// One builder (build_robot_model(const UrdfRobot&), urdf_robot.hpp) makes every model from
/// a description: a URDF's, or the YAML robot's (model/paper_robot.hpp paper_description).
/// Two leg geometries (LegGeometry):
///  - kPaperPlanar, the paper robot described in YAML, switched to its closed forms after
///    the build (use_paper_closed_forms; the tree and inertias are the description's):
///    z of H_l along the trunk normal, x the leg's outward direction at zero coxa angle;
///    link frames at zero angles parallel to H_l with x along the link; positive
///    femur/tibia angles raise the link (rotation about −y); foot at (l3, 0, 0) of the
///    tibia. FK, Jacobian, J̇ and IK are the closed forms in link lengths and offsets.
///  - kChain, any leg of three revolute joints (a URDF robot, urdf_robot.hpp): joint
///    placements, axes, zero poses and signs as the description gives them. FK is the
///    composition of the joint transforms; Jacobian columns a_k × (p_foot − p_k) and J̇
///    analytic; IK in closed form for the yaw–pitch–pitch family (the second and third
///    axes parallel, the first not parallel to them), Levenberg–Marquardt on the FK
///    otherwise (leg_chain.cpp).
/// A leg of more than three joints, or with a prismatic joint, is solved on its SerialChain
/// (leg_chain_table, built with the model): the redundant resolution of
/// model/redundant_leg.hpp toward the leg's nominal pose (docs/theory/model.md#redundant-legs).
/// Every stage reaches a leg's kinematics through the leg_* functions below, whatever the leg.
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/redundant_leg.hpp"

namespace hexdyn {

/// One rigid body's spatial inertia parameters in its own frame.
struct RigidInertia {
  double mass_kg = 0.0;
  Vec3 com_m = Vec3::Zero();        ///< centre of mass in the body frame
  Mat3 inertia_com = Mat3::Zero();  ///< rotational inertia about the COM, body axes [kg m²]
};

/// Sum of two bodies expressed in the same frame (parallel-axis theorem); a massless part
/// adds nothing (and two massless parts give a massless body).
RigidInertia combine_inertias(const RigidInertia& a, const RigidInertia& b);

/// How the legs' kinematics are evaluated (file comment).
enum class LegGeometry { kPaperPlanar, kChain };

/// Inverse kinematics of a kChain leg, chosen from the geometry when the model is built.
enum class LegIkMethod {
  kYawPitchPitch,  ///< closed form: axes 2 and 3 parallel, axis 1 not parallel to them
  kNumeric,        ///< Levenberg–Marquardt on the FK with the analytic Jacobian
};

/// Precomputed data of a kChain leg's IK (prepare_leg_chains). Frames: H (= the coxa joint
/// frame), J1 (the femur joint frame at zero femur angle, fixed in the coxa link).
struct LegIkData {
  LegIkMethod method = LegIkMethod::kNumeric;
  Vec3 a0_H = Vec3::UnitZ();       ///< coxa axis, H (unit)
  Vec3 w1_H = Vec3::UnitY();       ///< femur axis at zero coxa angle, H (unit)
  Vec3 o1_H = Vec3::Zero();        ///< femur joint origin at zero coxa angle, H [m]
  Mat3 H_R_J1 = Mat3::Identity();  ///< femur joint frame → coxa link frame
  Vec3 a1_J1 = Vec3::UnitY();      ///< femur axis, J1 (unit)
  Vec3 e1_J1 = Vec3::UnitX(), e2_J1 = Vec3::UnitZ();  ///< plane basis ⊥ a1, e2 = a1 × e1
  double l2_m = 0.0, alpha_rad = 0.0;  ///< femur joint → tibia joint, in-plane length, angle
  double l3_m = 0.0, gamma_rad = 0.0;  ///< tibia joint → foot at zero tibia angle, in plane
  double axis_sign = 1.0;              ///< tibia axis = axis_sign · femur axis
  double kappa_m = 0.0;                ///< w1(q0)·p_foot for every foot of the leg [m]
  Vec3 outward_H = Vec3::UnitX();      ///< outward direction at zero coxa angle (⊥ up), H
  Vec3 up_H = Vec3::UnitZ();           ///< trunk normal, H
  Vec3 q_start = Vec3::Zero();         ///< numeric IK: starting joint angles [rad]
};

/// How a joint moves the body after it: about its axis (revolute, q in rad) or along it
/// (prismatic, q in m).
enum class JointType { kRevolute, kPrismatic };

/// Side of the trunk a leg's hip is on: x < 0 in the trunk frame is left
/// (docs/theory/conventions.md).
enum class LegSide { kLeft, kRight };

/// One leg of a model (RobotModel::leg): its joints and bodies in the flat order and its place
/// on the trunk. Joint first_joint + j moves body first_body + j (j = 0 … n_joints − 1, hip to
/// foot); the foot point p_foot_last is fixed in foot_body, the last of them.
struct LegInfo {
  std::string name;     ///< "L1", "L2", …
  int first_joint = 0;  ///< flat index of the hip joint
  int n_joints = 0;     ///< joints from the trunk to the foot body
  int first_body = 0;   ///< body moved by the hip joint (its parent is the trunk)
  int foot_body = 0;    ///< body that carries the foot point
  LegSide side = LegSide::kLeft;
  int row = 0;  ///< rank front to rear among the legs of its side (0: front)
};

struct RobotModel {
  // --- leg table (fill_leg_table): legs(), leg(l), joint(l, j), body(l, j), foot_body(l) ---
  int n_legs = 0;
  int n_joints = 0;             ///< actuated joints, all legs (flat order: leg by leg, hip to foot)
  int n_bodies = 0;             ///< trunk and the bodies the joints move (n_joints + 1)
  LegArray<LegInfo> leg_table;  ///< the first n_legs entries
  int legs() const { return n_legs; }
  int joints() const { return n_joints; }
  int bodies() const { return n_bodies; }
  /// Generalised coordinates: the trunk's six, then the joints.
  int dofs() const { return 6 + n_joints; }
  const LegInfo& leg(int l) const { return leg_table[l]; }
  /// Flat index of joint j (0 at the hip) of leg l.
  int joint(int l, int j) const { return leg_table[l].first_joint + j; }
  /// Body moved by joint j of leg l.
  int body(int l, int j) const { return leg_table[l].first_body + j; }
  /// Body that carries leg l's foot point.
  int foot_body(int l) const { return leg_table[l].foot_body; }
  // --- tree (bodies 0 … n_bodies − 1; the entries after them are unused) ---
  /// parent[0] = -1; every unused entry holds -1 too (fill_leg_table counts the bodies by it).
  BodyArray<int> parent = unused_parents();
  BodyArray<Mat3> R_parent_joint;   ///< joint frame orientation in parent frame
  BodyArray<Vec3> p_parent_joint;   ///< joint frame origin in parent frame [m]
  BodyArray<Vec3> axis;             ///< joint axis in the joint frame (unit)
  BodyArray<RigidInertia> inertia;  ///< body 0: trunk and payload combined
  // --- separate parts kept for the URDF ---
  RigidInertia trunk_only;  ///< trunk structure alone, trunk frame
  RigidInertia payload;     ///< payload alone, trunk frame
  // --- analytic leg parameters ---
  std::array<double, 3> link_length_m{};  ///< l1, l2, l3
  double d1_m = 0.0;                      ///< femur axis below the coxa link [m]
  /// How each joint moves, flat index (revolute unless a builder says otherwise). The
  /// dynamics (rnea.hpp) and forward_kinematics_tree(model, q, …) take both kinds; the leg
  /// kinematics (FK, IK, Jacobians below) and the kinematics stage revolute joints.
  JointArray<JointType> joint_type{};
  bool prismatic(int k) const { return joint_type[k] == JointType::kPrismatic; }
  // Per-leg (LegArray) and per-joint (JointArray) storage: the first legs() / joints()
  // entries are used.
  LegArray<double> lateral_m{};  ///< signed lateral foot offset side·(d2+d3) [m]
  LegArray<double> d2_signed_m{}, d3_signed_m{};
  LegArray<Vec3> p_hip_B;  ///< coxa joint in the trunk frame [m]
  LegArray<Mat3> R_B_H;    ///< hip frame → trunk frame
  /// Joint limits per joint, flat index [rad] (±inf: a continuous joint).
  JointArray<double> joint_lower_rad{}, joint_upper_rad{};
  /// Effort limit per joint from the description [N m]; +inf when it gives none.
  JointArray<double> effort_limit_Nm{};
  /// Velocity limit per joint from the description [rad/s]; +inf when it gives none.
  JointArray<double> velocity_limit_radps{};
  /// The drive train of each joint, flat index (RobotParams::drive, scene key `actuators`):
  /// gear, motor, friction and bounds (docs/theory/drive-train.md). Absent (drive.present
  /// false): ideal joints, τ_drive = τ.
  DriveTrainParams drive;
  double ik_min_margin_m = 1e-4;
  double total_mass_kg = 0.0;
  // --- leg geometry (file comment) ---
  LegGeometry leg_geometry = LegGeometry::kPaperPlanar;
  LegArray<Vec3> p_foot_last;  ///< foot point in the leg's foot body frame [m]
  /// Sphere foot radius per leg [m]: p_foot_last is the sphere's centre; 0 a point foot.
  LegArray<double> foot_radius_m{};
  LegArray<LegIkData> leg_ik;  ///< kChain only
  /// Every leg as a serial chain in its hip frame H (prepare_serial_chains): joint 0 at H's
  /// origin, then the tree's placements, axes and joint kinds, the foot point p_foot_last.
  LegArray<SerialChain> leg_chain_table;
  /// Whether leg l is solved on leg_chain_table[l] by the redundant resolution (more than three
  /// joints, or a prismatic joint) rather than by the three-joint solvers.
  LegArray<bool> leg_on_chain{};
  /// The nominal pose and weights of the resolution per leg (prepare_serial_chains): q_nominal
  /// the middle of each joint's limits (0 for an unlimited joint), W = 1 / range² (range 2π
  /// for an unlimited revolute joint, 0.1 m for an unlimited prismatic one).
  LegArray<RedundantResolution> leg_resolution;
  /// Joint names in the description, flat order (URDF: its own names; YAML: L{i}_coxa …).
  JointArray<std::string> joint_source_names;
  /// Each hip's outward direction at zero coxa angle, horizontal in the trunk frame (unit,
  /// z = 0): footholds lie along it (planning/gait.hpp). The paper robot: ±x exactly (its
  /// legs stand straight out); a URDF robot: R_B_H · leg_ik.outward_H.
  LegArray<Vec3> hip_outward_B;
  /// The description's root link frame in the trunk frame B: the frame /base/* and the
  /// root link of /model/urdf describe (a YAML robot: B itself).
  Vec3 p_B_root = Vec3::Zero();      ///< [m]
  Mat3 B_R_root = Mat3::Identity();  ///< root link axes → trunk axes
  /// Gravity in G0 [m/s²] (Pinocchio's Model::gravity): every dynamics algorithm reads it;
  /// a test of the free robot sets it to zero.
  Vec3 gravity_W = Vec3(0.0, 0.0, -kGravity);

  /// Every entry -1: no body (parent's initial value).
  static BodyArray<int> unused_parents() {
    BodyArray<int> p;
    p.fill(-1);
    return p;
  }
};

/// Builds the model from validated parameters (no checks beyond those of load_scene): the
/// URDF robot's description, or the YAML robot's (paper_description) with its closed forms.
RobotModel build_robot_model(const RobotParams& params);

/// Fills the leg table and the counts from the tree. The bodies are 1 … n − 1 up to the last
/// with a parent (parent ≥ 0; unused entries hold -1), each after its parent. Every child of
/// the trunk, in body order, starts a leg whose chain of single children ends at its foot body;
/// the legs are flat, leg by leg (the bodies of a leg consecutive, the next leg's hip the body
/// after the previous foot; body b moved by joint b − 1); names L1, L2, … in the builder's
/// order; side from the sign of the hip's x in the trunk frame (p_parent_joint of its first
/// body), row by order within its side (the builders number legs front to rear). Throws
/// std::logic_error, one line naming the leg and the body, for kMinLegs … kMaxLegs legs not
/// found, a leg of fewer than kMinLegJoints or more than kMaxLegJoints joints, a chain that
/// branches, bodies out of the flat order, or a hip on the trunk's centre line
/// (|x| ≤ 1e-9 m).
void fill_leg_table(RobotModel& model);

/// Fills p_hip_B, R_B_H and leg_ik of every leg from the tree (parent, placements, axes),
/// p_foot_last and the joint limits. Called by the builders of kChain models; call it
/// again after editing the tree of a model by hand.
void prepare_leg_chains(RobotModel& model);

/// Foot position of leg `leg` in its hip frame for joint angles q = (θ1, β2, β3) [m].
Vec3 leg_foot_position_H(const RobotModel& model, int leg, const Vec3& q);

/// Foot Jacobian ∂p_H/∂q (3×3), hip frame.
Mat3 leg_jacobian_H(const RobotModel& model, int leg, const Vec3& q);

/// Time derivative of the foot Jacobian for joint rates qd (3×3), hip frame.
Mat3 leg_jacobian_dot_H(const RobotModel& model, int leg, const Vec3& q, const Vec3& qd);

/// Cosines and sines of a kPaperPlanar leg's angles q = (θ1, β2, β3) as its Jacobians use
/// them: θ1, β2 and β2 + β3.
struct LegTrig {
  double c1 = 1.0, s1 = 0.0;    ///< θ1
  double c2 = 1.0, s2 = 0.0;    ///< β2
  double c23 = 1.0, s23 = 0.0;  ///< β2 + β3
};
LegTrig leg_trig(const Vec3& q);

/// leg_jacobian_H and leg_jacobian_dot_H of a kPaperPlanar leg from its LegTrig, for a
/// caller that needs both at one q: the same values, bit for bit, the trig computed once.
Mat3 paper_leg_jacobian_H(const RobotModel& model, int leg, const LegTrig& trig);
Mat3 paper_leg_jacobian_dot_H(const RobotModel& model, int leg, const LegTrig& trig,
                              const Vec3& qd);

/// IK, knee-up branch with the foot outside the coxa axis: the paper's closed form
/// (kPaperPlanar), the yaw–pitch–pitch closed form or Levenberg–Marquardt (kChain; see
/// leg_chain.cpp for the branch rules and the margin). A leg on its chain (leg_on_chain): the
/// redundant resolution's q, margin the smallest singular value of its 3 × m Jacobian [m/rad].
struct LegIkResult {
  LegVector q = LegVector::Zero(3);  ///< the leg's joint positions (n_joints entries)
  double margin_m = 0.0;  ///< distance to the nearest workspace boundary (≥ ik_min_margin)
  /// The unit of margin_m: "m", or "rad" when a joint is outside its limits (margin_m then the
  /// angle to the nearer limit, negative).
  const char* margin_unit = "m";
  bool ok = false;
  std::string reason;  ///< why not ok: "beyond full extension", "joint limit", ...
};

/// Planar two-link workspace check of the closed-form IK: the wrist point at `dist_m` from the
/// femur axis, links l2, l3. Sets `r.margin_m` to the distance from full extension or full
/// fold and returns false with `r.reason` set when that is below `min_margin_m`.
bool planar_reach_ok(double dist_m, double l2_m, double l3_m, double min_margin_m, LegIkResult& r);

/// p_H: foot target in the hip frame. Never throws; callers turn !ok into ReachError.
LegIkResult leg_inverse_kinematics(const RobotModel& model, int leg, const Vec3& p_H);

/// Builds leg_chain_table, leg_on_chain and leg_resolution of every leg from the tree (called
/// by prepare_leg_chains); for a leg on its chain, leg_ik's outward direction from the chain's
/// foot at zero joint positions.
void prepare_serial_chains(RobotModel& model);

/// Makes q (one position per joint of leg `leg`, inside its limits) the pose a leg on its chain
/// resolves toward (leg_resolution[leg].q_nominal, and the numeric IK's start); the weights
/// stay. Precondition: leg_on_chain[leg] and q.size() == leg(leg).n_joints.
void set_leg_nominal_pose(RobotModel& model, int leg, const LegVector& q);

/// Foot position of leg `leg` in its hip frame for its joint positions q (n_joints entries) [m].
Vec3 leg_foot_position(const RobotModel& model, int leg, const LegVector& q);

/// ∂p_H/∂q of leg `leg` (3 × n_joints), hip frame; for a three-revolute leg leg_jacobian_H.
LegJacobian leg_jacobian(const RobotModel& model, int leg, const LegVector& q);

/// A leg's joint positions, rates and accelerations for its foot target (leg_motion_H).
/// cos_q, sin_q: std::cos and std::sin of a revolute joint's angle; 1 and 0 for a prismatic
/// joint (its body does not turn). Fixed capacity: filling one never allocates.
struct LegMotion {
  LegIkResult ik;  ///< q, and whether the target is reached (ok, margin, reason)
  LegVector qd, qdd, cos_q, sin_q;
};

/// The motion of leg `leg` whose foot (the IK target) is at p_H, moving at pd_H and
/// accelerating at pdd_H, all in its hip frame. Three revolute joints: the IK
/// (leg_inverse_kinematics), q̇ = J⁻¹ṗ and q̈ = J⁻¹(p̈ − J̇q̇). A leg on its chain: the redundant
/// resolution (model/redundant_leg.hpp) from the leg's nominal pose. When !out.ik.ok the rates
/// are not set; when the Jacobian is singular they are not finite (the caller refuses both).
void leg_motion_H(const RobotModel& model, int leg, const Vec3& p_H, const Vec3& pd_H,
                  const Vec3& pdd_H, LegMotion& out);
/// The same with the foot's velocity v_F and acceleration a_F given in the axes of a frame F
/// whose rotation from H is F_R_H (ṗ_H = F_R_Hᵀ v_F): the kinematics stage's call, with F the
/// trunk frame and F_R_H = R_B_H[leg].
void leg_motion(const RobotModel& model, int leg, const Vec3& p_H, const Mat3& F_R_H,
                const Vec3& v_F, const Vec3& a_F, LegMotion& out);

/// Upper bound of the distance of leg `leg`'s foot from its hip [m]. The paper geometry: the
/// foot's distance at zero angles (every leg straight out). A chain: the larger of that and the
/// sum of the link lengths along the chain's placements, hip → second joint → … → last joint →
/// foot point, plus each prismatic joint's largest travel (max |limit|, 0 when unlimited).
double leg_reach_m(const RobotModel& model, int leg);

/// The largest leg_reach_m over the legs [m] (0 for a robot without legs): a bound on the trunk's
/// height above its feet whatever the posture.
double longest_leg_reach_m(const RobotModel& model);

/// True when some joint of the model slides (JointType::kPrismatic).
bool has_prismatic_joints(const RobotModel& model);

/// Poses of every body in the trunk frame for joint positions q (model.joints(): angles of
/// revolute joints [rad], slides of prismatic joints [m]).
struct BodyPoses {
  BodyArray<Mat3> R_B;  ///< body → trunk rotation (the first model.bodies() entries)
  BodyArray<Vec3> p_B;  ///< body origin in the trunk frame [m]
};
void forward_kinematics_tree(const RobotModel& model, const JointVector& q, BodyPoses& out);
/// The same from cos q and sin q (model.joints() each, as std::cos and std::sin give them),
/// for a caller that has them already: the same poses, bit for bit. Revolute joints only.
void forward_kinematics_tree(const RobotModel& model, const JointVector& cos_q,
                             const JointVector& sin_q, BodyPoses& out);

/// Eigen::AngleAxisd(angle, axis).toRotationMatrix() from cos(angle) and sin(angle): the
/// same operations, so the same bits. axis: unit.
Mat3 rot_axis_cs(const Vec3& axis, double cos_angle, double sin_angle);

/// Foot point of leg `leg` in the trunk frame computed through the generic tree
/// (a second computation of the analytic FK).
Vec3 tree_foot_position_B(const RobotModel& model, const BodyPoses& poses, int leg);

/// True when some leg has a sphere foot (foot_radius_m > 0).
bool has_sphere_feet(const RobotModel& model);

/// Whole-robot centre of mass in the trunk frame [m].
Vec3 center_of_mass_B(const RobotModel& model, const BodyPoses& poses);

}  // namespace hexdyn
