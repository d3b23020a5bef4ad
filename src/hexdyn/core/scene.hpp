#pragma once
/// \file scene.hpp
/// The typed, validated scene a run is made of. Produced by `load_scene` (config.hpp)
/// from YAML; every field is SI. Field comments give units; which values come from
/// the paper and which are assumptions is said in configs/paper.yaml.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/height_map.hpp"
#include "hexdyn/core/robustness_params.hpp"

namespace hexdyn {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct UrdfRobot;  // model/urdf_robot.hpp: a legged robot read from a URDF file

/// Values per joint in flat joint order, resolved for a robot of `count` joints (its
/// RobotModel::joints()): the first `count` entries of a fixed capacity are used.
template <class T>
struct JointValues {
  int count = 0;  ///< joints of the robot the values were resolved for
  JointArray<T> values{};
  JointValues() = default;
  /// The N values of `a` (a robot of N joints).
  template <std::size_t N>
  JointValues(const std::array<T, N>& a)  // NOLINT(google-explicit-constructor): a value
      : count(static_cast<int>(N)) {
    static_assert(N <= kMaxJoints);
    for (std::size_t k = 0; k < N; ++k) values[k] = a[k];
  }
  int size() const { return count; }
  T& operator[](int k) { return values[static_cast<std::size_t>(k)]; }
  const T& operator[](int k) const { return values[static_cast<std::size_t>(k)]; }
};

/// Mass and principal moments of one rigid body about its centre of mass,
/// in the body's own frame.
struct BodyParams {
  double mass_kg = 0.0;
  Vec3 inertia_kgm2 = Vec3::Zero();  ///< (Ixx, Iyy, Izz) about the COM, body axes
  Vec3 com_m = Vec3::Zero();         ///< COM in the body frame [m]
};

/// One leg's standing pose of a URDF robot and how it was obtained (model/stance.hpp): the
/// legs' radii give gait.foot_lateral's default.
struct NominalStance {
  /// The leg's joint positions, one per joint hip to foot [rad; m for a prismatic joint], the
  /// description's signs and zero poses.
  LegVector q = LegVector::Zero(3);
  double radius_m = 0.0;  ///< horizontal distance of the foot from the coxa joint [m]
  double depth_m = 0.0;   ///< height of the coxa joint above the foot, along the trunk normal [m]
  bool from_pose = true;  ///< false: the default pose was out of reach, mid-range used
  /// "nominal pose" (the default pose), "robot.nominal_pose" (given) or "fallback: mid-range
  /// joint angles (WHY)", WHY saying why the default pose was out of reach.
  std::string source;
};

/// The motor's current convention (scene key `winding`;
/// docs/theory/drive-train.md#three-phase-motors): k_t is the motor's torque per ampere of the
/// stated current I, and the copper loss is R I² (DC; power-invariant three-phase, I the q-axis
/// current of the power-invariant transform) or (3/2) R I² (amplitude-invariant three-phase, I the
/// q-axis current's amplitude), R per phase for a three-phase motor.
enum class Winding : std::int8_t { kDc = 0, kThreePhaseAmplitude = 1, kThreePhasePower = 2 };

/// The factor c of the copper loss c R I² of `w`: 3/2 amplitude-invariant, else 1.
inline double copper_factor(Winding w) { return w == Winding::kThreePhaseAmplitude ? 1.5 : 1.0; }

/// One joint's two-node thermal model (docs/theory/drive-train.md#thermal-model): winding and
/// housing, each a heat capacity, the winding coupled to the housing and the housing to the
/// ambient through thermal resistances. Absent (present = false): no thermal results.
struct ThermalParams {
  bool present = false;
  double winding_housing_KpW = 0.0;   ///< R_th,wh, winding to housing [K/W]
  double winding_capacity_JpK = 0.0;  ///< C_th,w [J/K]
  double housing_ambient_KpW = 0.0;   ///< R_th,ha, housing to ambient [K/W]
  double housing_capacity_JpK = 0.0;  ///< C_th,h [J/K]
  double ambient_degC = 25.0;         ///< T_a, also the start temperature of both nodes [°C]
  double limit_degC = kInfinity;      ///< the winding's rated temperature [°C]; inf: none
};

/// One joint's drive train, resolved (config/actuators.hpp; docs/theory/drive-train.md): a
/// geared DC or three-phase motor. Joint side unless said; an optional value absent is +inf (a
/// bound or a window that never applies).
struct ActuatorParams {
  std::string model;                  ///< the shipped table's name it started from, or ""
  double gear_ratio = 1.0;            ///< G [–], motor turns per joint turn
  double torque_constant_NmpA = 0.0;  ///< k_t, motor side, per ampere of `winding`'s I [N m/A]
  double resistance_ohm = 0.0;        ///< R, winding (per phase for three-phase) [Ω]
  double armature_kgm2 = 0.0;         ///< J_a = G² J_m (+ the gear stages'), joint side [kg m²]
  double coulomb_friction_Nm = 0.0;   ///< τ_c [N m]
  double viscous_friction_Nmsprad = 0.0;    ///< b [N m s/rad]
  double gear_efficiency = 1.0;             ///< η ∈ (0, 1]
  double voltage_V = kInfinity;             ///< V, supply [V]; inf: no voltage bound
  double peak_torque_Nm = kInfinity;        ///< |τ_drive| bound [N m]; inf: none
  double continuous_torque_Nm = kInfinity;  ///< the thermal rating, RMS [N m]; inf: none
  double regeneration = 0.0;                ///< r ∈ [0, 1], share of negative power recovered
  double thermal_window_s = kInfinity;      ///< RMS window [s]; inf: the whole run
  /// Three-phase: the largest phase-voltage amplitude over the supply voltage (1/2 sinusoidal
  /// PWM, 1/√3 space-vector PWM) [–].
  double voltage_utilization = 0.5;
  /// The thermal model's values (ThermalParams, thermal_params()); NaN: not given, no model.
  double thermal_resistance_winding_KpW = std::numeric_limits<double>::quiet_NaN();
  double thermal_capacity_winding_JpK = std::numeric_limits<double>::quiet_NaN();
  double thermal_resistance_housing_KpW = std::numeric_limits<double>::quiet_NaN();
  double thermal_capacity_housing_JpK = std::numeric_limits<double>::quiet_NaN();
  double ambient_temperature_degC = 25.0;
  double winding_temperature_limit_degC = kInfinity;
  Winding winding = Winding::kDc;
  /// The gear stages motor to joint, as given (ratio, inertia turning at the stage's output
  /// [kg m²]); empty: one ratio `gear_ratio`. Kept for the resolved configuration.
  std::vector<std::array<double, 2>> gear_stages;
};

/// The thermal model of `a` (present when its four resistances and capacities are given).
inline ThermalParams thermal_params(const ActuatorParams& a) {
  ThermalParams p;
  p.present = !std::isnan(a.thermal_resistance_winding_KpW) &&
              !std::isnan(a.thermal_capacity_winding_JpK) &&
              !std::isnan(a.thermal_resistance_housing_KpW) &&
              !std::isnan(a.thermal_capacity_housing_JpK);
  p.winding_housing_KpW = a.thermal_resistance_winding_KpW;
  p.winding_capacity_JpK = a.thermal_capacity_winding_JpK;
  p.housing_ambient_KpW = a.thermal_resistance_housing_KpW;
  p.housing_capacity_JpK = a.thermal_capacity_housing_JpK;
  p.ambient_degC = a.ambient_temperature_degC;
  p.limit_degC = a.winding_temperature_limit_degC;
  return p;
}

/// The drive trains of the robot's joints (scene key `actuators`), flat joint order: part of
/// the robot (RobotParams::drive, RobotModel::drive). Absent (present = false): the paper's
/// idealised joints, τ_drive = τ, no electrical results.
struct DriveTrainParams {
  bool present = false;
  JointValues<ActuatorParams> joints;
};

/// Leg inertia model: the full coupled dynamics of the leg links, or massless legs whose
/// link masses are lumped into the trunk as point masses at their hips (coxa joints).
enum class LegInertia { kFull, kMassless };

/// The legs and joints of the robot of the YAML keys (robot.trunk, coxa, femur, tibia, hips):
/// six legs L1 … L6 of three joints, coxa, femur, tibia (docs/theory/conventions.md).
inline constexpr int kYamlRobotLegs = 6;
inline constexpr int kYamlRobotLegJoints = 3;

struct RobotParams {
  /// The robot's legs: the YAML robot's six, or a URDF robot's (its legs read).
  int legs = kYamlRobotLegs;
  /// Joints of each leg of the YAML robot (a URDF robot's legs have their own counts).
  int leg_joints = kYamlRobotLegJoints;
  BodyParams trunk;    ///< trunk structure, frame L0 at P0
  BodyParams payload;  ///< rigidly fixed to the trunk; com_m in the trunk frame
  /// Links of every leg, the first leg_joints used: coxa (i1), femur (i2), tibia (i3). COM
  /// and axes in the link frame (x along the link from its joint, z the trunk normal at zero
  /// angles).
  LegJointArray<BodyParams> link;
  LegJointArray<double> link_length_m{};  ///< l1, l2, l3
  /// DH joint offsets (assumed meaning): d1 along the coxa axis (femur axis below the
  /// coxa link), d2 and d3 along the femur and tibia axes (lateral link offsets,
  /// mirrored on the left so that every offset points forward at zero coxa angle).
  LegJointArray<double> joint_offset_m{};
  /// Coxa joint positions in the trunk frame, legs L1 … L6 (the first `legs`) [m]
  /// (assumption).
  LegArray<Vec3> hip_position_m = [] {
    LegArray<Vec3> zero;
    zero.fill(Vec3::Zero());
    return zero;
  }();
  /// Hip yaw: angle about the trunk z axis from trunk +x to the leg's outward axis;
  /// right legs 0, left legs π when the legs stand straight out [rad].
  LegArray<double> hip_yaw_rad{};
  /// Joint-angle limits used by IK checks [rad]: min, max per joint of a leg.
  LegJointArray<double> joint_min_rad{};
  LegJointArray<double> joint_max_rad{};
  /// Smallest allowed distance of the wrist point to the boundary of the leg's
  /// planar workspace (full extension or full fold) [m]: below it IK refuses.
  double ik_min_margin_m = 1e-4;
  LegInertia leg_inertia = LegInertia::kFull;  ///< robot.leg_inertia
  /// robot.foot_radius: a sphere foot of this radius centred at the tibia's end (l3, 0, 0);
  /// 0 a point foot [m] (docs/theory/model.md#sphere-feet).
  double foot_radius_m = 0.0;
  /// A robot read from its URDF (robot.urdf, config/robot_config.cpp), or null for the robot
  /// described by the YAML keys above. When set, build_robot_model builds the model from
  /// it and every field above except legs and ik_min_margin_m is unused.
  std::shared_ptr<const UrdfRobot> urdf;
  /// A URDF robot's standing pose of each leg, L1 … Ln (unused for the YAML robot).
  std::vector<NominalStance> stance;
  /// The joints' drive trains (scene key `actuators`, config/actuators.hpp); the model
  /// carries them (RobotModel::drive).
  DriveTrainParams drive;
};

enum class TerrainType { kFlat, kSlope, kStairs, kHeightMap };

/// One step of a staircase given step by step (`terrain.steps` as a list;
/// docs/theory/stages.md#terrain): the riser at the step's start, then the tread above it.
struct StairStep {
  double riser_m = 0.0;   ///< signed rise of the riser [m]: > 0 up, < 0 down along +y
  double tread_m = 0.0;   ///< going: horizontal run from this riser to the next [m], > 0
  double nosing_m = 0.0;  ///< overhang of the higher tread's edge over this riser [m], ≥ 0
};

struct TerrainParams {
  TerrainType type = TerrainType::kStairs;
  double ground_height_m = 0.0;   ///< flat: height; stairs: height before the first riser
  double slope_rad = 0.0;         ///< slope: inclination, rising along +y
  double slope_origin_y_m = 0.0;  ///< slope: y where the slope starts from ground height
  double riser_height_m = 0.05;   ///< stairs: h_s (< 0 descends along +y)
  double tread_depth_m = 0.25;    ///< stairs: b_s
  int steps = 10;                 ///< stairs: number of risers; the top tread is endless
  double first_riser_y_m = 0.0;   ///< stairs: y of the first riser
  double nosing_m = 0.0;          ///< stairs: overhang of every nosing (terrain.nosing)
  /// height_map: the grid (core/height_map.hpp), shared by the copies of a scene; its
  /// reference line is ground_height_m + tan(slope_rad) y (slope_origin_y_m 0): the slope
  /// terrain.height_map.slope gives, or the least-squares line through every node, and the
  /// intercept fitted likewise.
  std::shared_ptr<const HeightMap> map;
  double map_edge_height_m = 0.02;  ///< height_map: a step higher than this is an edge [m]
  double map_max_slope_rad = 0.35;  ///< height_map: ground steeper than this takes no foot
  /// Stairs given step by step: `steps` entries, riser k at first_riser_y + Σ_{j<k} tread_j
  /// (landings folded into the tread before them). Empty for uniform stairs (riser_height,
  /// tread_depth, nosing). A list that is uniform with no nosing is read as uniform stairs.
  std::vector<StairStep> step_list;
};

/// Inclination of the terrain's mean line along +y [rad]: atan(h_s / b_s) on stairs (the
/// trunk's pitch α0, docs/theory/conventions.md#trunk-orientation-bryant-angles), the
/// slope on a slope, 0 on flat ground.
inline double mean_slope_rad(const TerrainParams& t) {
  switch (t.type) {
    case TerrainType::kStairs: {
      if (t.step_list.empty()) return std::atan2(t.riser_height_m, t.tread_depth_m);
      double rise = 0.0, run = 0.0;  // over the whole list, the last tread included
      for (const StairStep& s : t.step_list) {
        rise += s.riser_m;
        run += s.tread_m;
      }
      return std::atan2(rise, run);
    }
    case TerrainType::kSlope:
    case TerrainType::kHeightMap:
      return t.slope_rad;
    case TerrainType::kFlat:
      return 0.0;
  }
  return 0.0;
}

/// gait.pattern: how each leg's lift-off phase is set (model/gait_pattern.hpp,
/// docs/theory/stages.md#gait-patterns). The enumerators are in the order of the key's
/// choices.
enum class GaitPattern {
  kWave,    ///< Song and Waldron's wave gait (the crawl on four legs, the tripod at β = ½ on six)
  kTrot,    ///< diagonal pairs: alternate ranks, the sides opposite
  kPace,    ///< the left legs against the right legs
  kBound,   ///< the front half of each side against the rear half
  kCustom,  ///< the phases of gait.phases
};

/// How a swing foot moves (gait.swing_profile; planning/gait.hpp).
enum class SwingProfile {
  kStaged,   ///< lift, then the horizontal transfer at the apex, then the descent (the paper)
  kBlended,  ///< the horizontal transfer over the whole swing, the lift and descent within it
};

struct GaitParams {
  double duty_factor = 0.5;  ///< β ∈ [1/2, 1): support fraction of each leg
  double stroke_m = 0.125;   ///< s0: foot travel relative to the trunk per stance
  /// Horizontal distance of footholds from the hip along the hip's outward direction
  /// (RobotModel::hip_outward_B; the paper robot: straight out, ±x) [m]. A URDF robot's
  /// default is its nominal stance radius (config/robot_config.hpp).
  double foot_lateral_m = 0.17;
  double foothold_margin_m = 0.02;    ///< minimum distance of a foothold from nosing and riser
  double swing_clearance_m = 0.002;   ///< Δh over the highest terrain under the swing path
  double touchdown_speed_mps = 0.05;  ///< downward foot speed at touchdown
  double lift_fraction = 0.3;         ///< share of swing time spent lifting
  double lower_fraction = 0.2;        ///< nominal share of swing time spent lowering
  SwingProfile swing_profile = SwingProfile::kStaged;  ///< gait.swing_profile
  /// gait.pattern; a scene that gives gait.phases without it is kCustom, one that gives
  /// neither kWave (config/scene_read_motion.cpp).
  GaitPattern pattern = GaitPattern::kWave;
  /// gait.phases: each leg's lift-off phase in [0, 1), in leg order L1 … Ln, given with
  /// pattern kCustom; empty for the other patterns, whose phases follow from the legs
  /// (model/gait_pattern.hpp).
  std::vector<double> liftoff_phases;
};

/// How the trunk's start P0(0) is given (docs/theory/stages.md#posture; planning/posture.hpp).
enum class PostureMode {
  kAbsolute,  ///< motion.initial_position: P0(0) in G0 as given
  kRelative,  ///< motion.posture.height and start_y: P0(0) relative to the terrain
  kAuto,      ///< motion.posture.height: auto, chosen for the largest kinematic margin
};

/// The trunk's posture relative to the terrain (planning/posture.hpp has the definitions).
struct PostureParams {
  PostureMode mode = PostureMode::kAbsolute;
  /// kRelative: vertical height of P0 above the terrain's reference line (the mean slope
  /// line through the tread centres on stairs, the surface on slopes and flat ground) [m].
  double height_m = 0.0;
  /// kRelative, kAuto: y of P0 at t = 0 measured from the terrain's origin (the first
  /// riser on stairs, the foot of a slope, y = 0 on flat ground); negative before it [m].
  double start_y_m = 0.0;
  /// kAuto: range searched for the trunk height [m].
  double height_min_m = 0.0, height_max_m = 0.0;
  /// kAuto: when true, gait.foot_lateral may be changed within [min, max] (only when the
  /// height alone leaves a smallest margin below target_margin_m) [m].
  bool vary_foot_lateral = false;
  double foot_lateral_min_m = 0.0, foot_lateral_max_m = 0.0;
  double target_margin_m = 0.01;  ///< kAuto: see vary_foot_lateral [m]
  /// kAuto: smallest vertical distance of P0 above the highest terrain under the trunk
  /// (planning/posture.hpp: h − h_s/2 on stairs) [m].
  double trunk_clearance_m = 0.05;
};

/// motion.trunk: the straight path of the paper, or a balanced one (balance/balance.hpp): the
/// straight path plus a horizontal offset that keeps the ZMP in the support.
enum class TrunkPath { kStraight, kBalanced };

struct MotionParams {
  TrunkPath trunk = TrunkPath::kStraight;  ///< motion.trunk
  /// motion.balance_margin: the balanced trunk's stability margin, the ZMP path's least
  /// distance from the edges of the support where the feet leave room for it [m].
  double balance_margin_m = 0.01;
  /// Cycle durations [s]; either given (paper) or derived from peak speed and ramp.
  std::vector<double> cycle_durations_s;
  double peak_speed_mps = 0.1;   ///< cruise speed of the trunk along the slope
  double ramp_duration_s = 0.8;  ///< duration of the C² speed ramps at start and end
  /// Trunk P0 in G0 at t = 0 when posture.mode is kAbsolute; otherwise planning
  /// (plan_motion) computes it from `posture` and this value is not used.
  Vec3 initial_position_m{0.0, 0.412, 0.235};
  PostureParams posture;
  int cycles = 3;
};

/// Touchdown model: the compliant IMPACT transient (contact.hpp), or rigid: the foot is a
/// support leg from the instant of touchdown, its impulse not resolved in time.
enum class ContactModel { kCompliant, kRigid };

/// What a compliant touchdown's transient carries (docs/theory/contact.md#loaded-touchdowns):
/// the paper's isolated leg, whose force falls back to zero, or the leg's share of the load,
/// which the force rises to and settles at while the allocation holds the trunk.
enum class TouchdownModel { kPaper, kLoaded };

/// The forward replay's tangential law (docs/theory/replay.md#tangential-force): stick–slip
/// (contact/stick_slip.hpp: a spring to an anchor, capped at μ_s F_n, sliding at μ_d F_n) or
/// the regularised Coulomb law of contact/simulation_contact.hpp.
enum class FrictionLaw { kStickSlip, kRegularised };

struct ContactParams {
  ContactModel model = ContactModel::kCompliant;       ///< contact.model
  TouchdownModel touchdown = TouchdownModel::kLoaded;  ///< contact.touchdown
  double stiffness = 1e5;                              ///< K [N/m^e]
  double exponent = 2.2;                               ///< e
  double damping_max_Nspm = 10.0;                      ///< C_max [N·s/m]
  double full_damping_depth_m = 1e-5;                  ///< p [m]
  double friction_coefficient = 0.3;                   ///< μ
  /// The tangential law of forward simulation (contact/simulation_contact.hpp, after
  /// MSC.ADAMS' contact friction): μ_s (contact.static_friction, default μ), μ_d
  /// (contact.dynamic_friction, default μ_s), and the transition speeds v_s < v_d.
  double static_friction = 0.3;                        ///< μ_s
  double dynamic_friction = 0.3;                       ///< μ_d
  double stiction_velocity_mps = 1e-3;                 ///< v_s [m/s]
  double friction_velocity_mps = 1e-2;                 ///< v_d [m/s]
  FrictionLaw friction_law = FrictionLaw::kStickSlip;  ///< contact.friction_law
  /// Stick–slip: k_t (contact.tangential_stiffness) and c_t (contact.tangential_damping).
  double tangential_stiffness_Npm = 1e6;  ///< k_t [N/m]
  double tangential_damping_Nspm = 1e3;   ///< c_t [N s/m]
};

/// replay.early_contact: what the joint PD damps towards while a foot the plan still swings
/// meets the terrain (docs/theory/replay.md#early-contact): the planned rates (`follow`), or, on
/// a face the foot could stand on, the rates that hold it still until the plan's touchdown
/// (`hold`).
enum class EarlyContact { kFollow, kHold };

/// `replay:` the forward replay of a result (replay/replay.hpp, docs/theory/replay.md).
struct ReplayParams {
  double kp_Nmprad = 10.0;  ///< replay.kp: joint PD stiffness on the planned angles [N m/rad]
  double kd_Nmsprad = 0.1;  ///< replay.kd: joint PD damping on the planned rates [N m s/rad]
  /// replay.kp: auto, replay.kd: auto (the defaults): the gains follow the robot
  /// (replay/replay.hpp resolved_gains); kp_Nmprad and kd_Nmsprad then hold the light robot's.
  bool kp_auto = true, kd_auto = true;
  double step_s = 1e-3;  ///< replay.step: the integrator's largest step [s]
  /// replay.tolerance: a step is halved while the contact forces it applied differ from the
  /// contact law at its end by more than this fraction of the robot's weight [1].
  double tolerance = 0.05;
  /// replay.saturate: with actuators, bound each joint's drive torque by its torque–speed
  /// envelope at the joint's speed (drive/drive.hpp drive_torque_limit) [–].
  bool saturate = true;
  EarlyContact early_contact = EarlyContact::kFollow;  ///< replay.early_contact
};

/// Allocation back end: the dense dual active-set QP (allocation/active_set_backend.hpp; with the
/// exact cone, its sequential outer approximation, allocation/cone_backend.hpp), the default for
/// every friction model, or Ipopt (allocation/ipopt_backend.cpp: the reference).
enum class AllocationSolver { kActiveSet, kIpopt };
/// allocation.objective: the paper's Σ τ² (eq. 9) of the drive torques, or the copper loss
/// Σ R_j I_j² of the actuators (a weighted Σ τ², docs/theory/drive-train.md#objective).
enum class AllocationObjective { kTorqueSquared, kCopperLoss };
enum class FrictionModel { kPyramid4, kPyramid8, kCone };

struct AllocationParams {
  AllocationSolver solver = AllocationSolver::kActiveSet;
  FrictionModel friction = FrictionModel::kPyramid4;
  AllocationObjective objective = AllocationObjective::kTorqueSquared;
  double torque_limit_Nm = 6.0;  ///< |τ| bound of every joint, unless joint_torque_limit_Nm is set
  /// Per-joint |τ| bounds in flat joint order [N m]: a URDF robot's effort limits when the
  /// scene gives no allocation.torque_limit (+inf for a joint without one); unset: the
  /// scalar torque_limit_Nm for every joint.
  std::optional<JointValues<double>> joint_torque_limit_Nm;
  double min_normal_force_N = 0.0;
  double tolerance = 1e-9;
  double slack_penalty = 1e6;
};

enum class OutputGrid { kUniform, kAdaptive };

/// output.tolerance's default: the tightest tolerance whose refinement keeps the 1,000-scenario
/// stair grid within twice the time of the grid as built (docs/validation/grid-accuracy.md).
inline constexpr double kDefaultOutputTolerance = 1e-2;

struct OutputParams {
  double sample_step_s = 0.05;
  OutputGrid grid = OutputGrid::kAdaptive;
  int impact_samples = 16;     ///< adaptive grid: intervals across each impact transient
  double event_step_s = 1e-2;  ///< adaptive grid: finest step next to touchdowns and lift-offs
  /// output.tolerance: the relative error the adaptive grid is refined to, for the energies
  /// (total, per joint) and the peaks (joint torque, total power, contact force)
  /// (docs/theory/output-grid.md#error-control); 0: no refinement.
  double tolerance = kDefaultOutputTolerance;
  /// output.compression: deflate (true: shuffle + deflate on numeric datasets of at least
  /// 4 KiB, io/h5io.hpp) or none (every dataset contiguous and uncompressed).
  bool compress = true;
  /// output.required_friction: compute the least μ each sample needs
  /// (docs/theory/grip.md#required-friction) and write /contacts/required_friction.
  bool required_friction = true;
  /// Not a scene key: set by a sweep that keeps no runs (sweep/scenario.hpp). The run is
  /// computed for its summary row alone, and a sample's required friction is settled by an
  /// upper bound where it cannot reach the run's largest (docs/theory/grip.md#in-a-sweep);
  /// such a run is never written to a file.
  bool summary_only = false;
};

/// A default-constructed Scene holds the default of every optional scene key (the key table
/// reads them from here: docs/user/configuration.md); fields of keys a scene must give hold
/// the paper's values only as examples.
struct Scene {
  std::string name = "scene";  ///< name: (default "scene")
  RobotParams robot;
  TerrainParams terrain;
  GaitParams gait;
  MotionParams motion;
  ContactParams contact;
  ReplayParams replay;
  AllocationParams allocation;
  OutputParams output;
  RobustnessParams robustness;  ///< robustness: (a study's worlds; core/robustness_params.hpp)
  std::string resolved_yaml;    ///< the fully resolved configuration, as YAML
  std::string source_path;      ///< the file it was read from
  /// The input files read (scene, inherited files, URDF) with their SHA-256, one line
  /// "SHA256  ABSOLUTE_PATH" each (config/inputs.hpp); /meta input_sha256 of the result.
  std::string input_sha256;
  /// What reading the scene found worth a warning, one line each without the "hexdyn:
  /// warning: " prefix (a URDF robot's stance fallback): `hexdyn run` and `hexdyn validate`
  /// print them.
  std::vector<std::string> warnings;
};

}  // namespace hexdyn
