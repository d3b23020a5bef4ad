#pragma once
/// \file replay.hpp
/// The forward replay of a planned motion (docs/theory/replay.md): the robot on the terrain,
/// driven by the plan's stored joint torques as feedforward plus a joint PD on the planned
/// angles, integrated through the forward dynamics (dynamics/forward_dynamics.hpp) with the
/// compliant contact of simulation (contact/simulation_contact.hpp). What it answers: do the
/// inverse-dynamics torques climb, and how much energy touchdowns and slip take.
///
/// Integrator: linearly implicit Euler (docs/theory/replay.md#integrator). Each step of at
/// most ReplayParams::step_s solves
///   (M − h ∂f/∂ν − h² ∂f/∂q) Δν = h f(q, ν),   ν ← ν + Δν,   q ← q ⊕ h ν
/// where f is the generalised force (torques, contact forces, gravity and velocity terms):
/// the PD and the contact linearised about the step's start (the contact's stiffness and
/// damping, the friction's regularisation), the rest explicit: the gravity and velocity
/// terms and the planned feedforward at the step's start, the PD's targets at its end. It
/// is stable on stiff contact (a loaded foot of 2e6 N/m on a 0.1 kg leg at any step) and
/// first order in h. The plan's instants are step boundaries; each stored sample is a state
/// the integrator reached, with torques, forces and accelerations evaluated at that state.
#include <string>
#include <vector>

#include "hexdyn/core/base_state.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/core/sizes.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// The largest number of steps of replay.step a replay may take over its plan's span (a
/// step of replay.step / 64 at the most halved, so at most 64 times as many in all).
inline constexpr double kMaxReplaySteps = 1e6;
/// The fall test (docs/theory/replay.md#falls): the robot has fallen when its centre of mass
/// is below this fraction of the planned centre of mass's height above the terrain under
/// it, or its trunk is tilted more than kFallTilt_rad from the planned trunk.
inline constexpr double kFallHeightFraction = 0.5;
inline constexpr double kFallTilt_rad = M_PI / 3.0;

/// What the replay follows, at the plan's T instants (a result file's /time, /base/*,
/// /joints/*): T ≥ 2, t_s strictly increasing.
struct ReplayPlan {
  std::vector<double> t_s;            ///< [s]
  std::vector<BaseState> base;        ///< planned trunk pose and twist (accelerations unused)
  std::vector<JointVector> q_rad;     ///< planned joint angles (model.joints() each)
  std::vector<JointVector> qd_radps;  ///< planned joint rates
  std::vector<JointVector> tau_Nm;    ///< stored joint torques (/joints/torque)
  /// With actuators (RobotModel::drive): the planned drive torques τ_drive = τ + J_a q̈ +
  /// τ_c sgn(q̇) + b q̇ (/joints/drive_torque), the feedforward; else empty and tau_Nm is.
  std::vector<JointVector> tau_drive_Nm;
  std::vector<double> cycle_start_s;  ///< start of each gait cycle (/gait/cycle_start)
  /// The terrain's height profile (/terrain/y, /terrain/z; planning/terrain.hpp).
  std::vector<double> terrain_y_m, terrain_z_m;
  /// A height map's grid (/terrain/map_*), which the feet meet instead of the profile; null
  /// on other terrain.
  std::shared_ptr<const HeightMap> terrain_map;
  /// /contacts/phase (T × legs, ContactPhase codes): the feet the plan swings, stands on or
  /// lands at each instant (replay.early_contact, the robustness study's stubbed toes).
  RowMatrixI8 contact_phase;
};

/// The trunk's state (frame B, what dynamics/rnea.hpp takes) from one row of a result's
/// /base/position, /base/orientation (w, x, y, z), /base/linear_velocity and
/// /base/angular_velocity, which describe the URDF root link (model/root_link.hpp).
BaseState trunk_state_from_row(const RobotModel& model, const Vec3& position_m,
                               const Eigen::Vector4d& wxyz, const Vec3& velocity_mps,
                               const Vec3& omega_radps);

/// The plan of a run in memory (what `hexdyn replay` reads from its file): its instants,
/// trunk states (moved from the root link frame of /base/* to the trunk frame), joint angles,
/// rates and torques, cycle starts and terrain profile. Throws ConfigError for a run without
/// its dynamics or with a non-finite torque.
ReplayPlan plan_from_result(const RobotModel& model, const RunResult& result);

/// How far the replayed robot may end from the plan's end and still count as having reached
/// it (docs/theory/replay.md#reaching-the-top): horizontally, vertically, and its trunk's
/// tilt from the planned one.
struct ArrivalTolerance {
  double horizontal_m = 0.125;
  double vertical_m = 0.025;
  double tilt_rad = 0.5;
};
/// Half a tread depth and half a riser on stairs (at least 1 cm), 5 cm on other terrain.
ArrivalTolerance arrival_tolerance(const TerrainParams& terrain);

/// The replayed motion, sample by sample, and its report (schema_replay.hpp names each).
/// Sized by the model: each joint vector has model.joints() entries; of each per-leg array
/// (core/sizes.hpp LegArray) the first model.legs() entries are used, the others zero.
struct ReplayResult {
  // --- per sample (T' ≤ T samples: the plan's instants up to the replay's end) ---
  std::vector<double> t_s;
  std::vector<BaseState> base;  ///< with the accelerations of the forward dynamics
  std::vector<JointVector> q, qd, qdd, tau, tau_ff, tracking_error;
  std::vector<LegArray<Vec3>> force_W, foot_W, slip_velocity_W, slip_displacement_W;
  std::vector<LegArray<double>> normal_N, penetration_m, slip_distance_m;
  std::vector<LegArray<double>> damping_energy_J, slip_energy_J;
  /// Each foot's contact normal: the outward unit normal of the terrain's face nearest to it
  /// (contact/simulation_contact.hpp), in contact or not.
  std::vector<LegArray<Vec3>> normal_W;
  std::vector<double> actuator_energy_J, kinetic_J, potential_J;
  // --- per sample, with actuators only (RobotModel::drive; else empty) ---
  /// The drive torque u the drive gave (feedforward and PD, at its bound when saturated),
  /// and whether it was at its bound (1) or not (0) at the sample.
  std::vector<JointVector> tau_drive, saturated;
  /// Cumulative energies [J]: electrical drawn (electrical_power), copper loss, and the
  /// joints' friction (Coulomb and viscous) dissipated.
  std::vector<double> electrical_J, copper_loss_J, joint_friction_J;
  // --- report ---
  std::vector<double> cycle_end_s;
  std::vector<Vec3> position_drift_m, orientation_drift_rad;
  double max_tracking_error_rad = 0.0;
  int max_tracking_error_joint = 0;
  double max_tracking_error_time_s = 0.0;
  LegArray<double> slip_distance_total_m{}, slip_energy_total_J{}, damping_total_J{};
  double energy_J = 0.0;         ///< ∫ Σ|τ q̇| dt of the replay
  double energy_plan_J = 0.0;    ///< the same of the plan over the replayed span (trapezoid)
  double actuator_work_J = 0.0;  ///< ∫ τ·q̇ dt, signed
  /// actuator_work_J less the gains in kinetic, potential and contact-spring energy and the
  /// contacts' dissipation: zero but for the integrator's error [J].
  double energy_residual_J = 0.0;
  /// With actuators: per joint, the time its drive torque spent at its bound [s]; the
  /// electrical energy of the replay and of the plan's drive torques over the same span
  /// (trapezoid of electrical_power at the plan's samples) [J].
  std::vector<double> saturation_time_s;
  double electrical_energy_J = 0.0, electrical_energy_plan_J = 0.0;
  Vec3 final_position_error_m = Vec3::Zero();
  bool reached_top = false;
  std::string message;  ///< why it ended early, or ""
  bool fell = false;    ///< it ended early because the robot fell (kFallHeightFraction, ...)
  double max_step_s = 0.0;
  long steps = 0;
  /// Steps accepted at the smallest step with the contact force still beyond the tolerance
  /// (a sphere foot rolling over a nosing: the face's normal turns within the step).
  long forced_steps = 0;
  double seconds = 0.0;  ///< wall time of the integration
};

/// Replays `plan` on `model` (its gravity_W) with `contact`'s law and `replay`'s gains and
/// step (docs/theory/replay.md). With actuators (model.drive.present, plan.tau_drive_Nm
/// given) the joints are driven through them (docs/theory/replay.md#driven-by-the-actuators):
/// the feedforward is the planned drive torque, the forward dynamics carry the armature and
/// the joints' viscous and regularised Coulomb friction, and with replay.saturate the drive
/// torque is bounded by its torque–speed envelope. Starts from the plan's first state. Ends at the
/// plan's last instant, or early with `message` when the state stops being finite or the robot
/// falls (kFallHeightFraction, kFallTilt_rad: tested at the plan's instants); the samples up to
/// then are kept. Reports progress (core/progress.hpp). Throws ConfigError for a plan of
/// fewer than 2 samples or mismatched sizes, a replay.step that takes more than
/// kMaxReplaySteps steps, or a robot without a positive definite mass matrix (massless legs:
/// naming robot.leg_inertia).
ReplayResult replay_plan(const RobotModel& model, const ContactParams& contact,
                         const ReplayParams& replay, const TerrainParams& terrain,
                         const ReplayPlan& plan);

/// The robot's weight moment m g l [N m]: model.total_mass_kg, its gravity's magnitude and l
/// the longest leg's reach (longest_leg_reach_m).
double weight_moment_Nm(const RobotModel& model);

/// Whether a joint PD of stiffness kp_Nmprad is weak against a weight moment: its torque at
/// 0.1 rad is below a fiftieth of it (docs/user/replay.md#gains). The paper robot's 10 N m/rad
/// give it 1 N m against 20 N m, a twentieth; ANYmal C's weight moment is 375 N m.
bool weak_joint_pd(double kp_Nmprad, double weight_moment_Nm);

/// replay.kp: auto on a robot for which ReplayParams' default stiffness is weak: this many
/// N m/rad per N m of its weight moment.
inline constexpr double kAutoGainPerWeightMoment = 1.1;

/// The gains a replay of `model` uses (docs/user/replay.md#gains): given ones as given;
/// replay.kp auto: ReplayParams' default 10 N m/rad (the paper robot's) unless that is weak
/// for the robot (weak_joint_pd: a weight moment above 50 N m), then kAutoGainPerWeightMoment
/// times the weight moment per rad; replay.kd auto: the stiffness times 0.01 s. The result's
/// kp_auto and kd_auto stay as given.
ReplayParams resolved_gains(const ReplayParams& replay, const RobotModel& model);

}  // namespace hexdyn
