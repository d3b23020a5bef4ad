#pragma once
/// \file result.hpp
/// Per-run result arrays, one row per output sample, in the units and frames of the
/// `hexdyn-result/5` contract (io/schema.hpp). Matrices are row-major so that a
/// (T, n) dataset is written straight from `.data()`; (T, legs, 3) datasets are stored
/// as T × 3 legs with leg-major columns (3 l + axis).
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/height_map.hpp"

namespace hexdyn {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowMatrixI8 = Eigen::Matrix<std::int8_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Contact phase per leg and sample (/contacts/phase).
enum class ContactPhase : std::int8_t { kSwing = 0, kImpact = 1, kSupport = 2 };

/// Outcome of one allocation solve (/solver/status, the values are the file's codes):
/// optimal; relaxed (some rows or cones gave way, or an approximate answer; the message
/// says which); failed (a finite fallback answer).
enum class SolverStatus : std::int8_t { kOptimal = 0, kRelaxed = 1, kFailed = 2 };

/// "optimal", "relaxed" or "failed".
std::ostream& operator<<(std::ostream& os, SolverStatus status);

/// The file codes of `status` (0, 1, 2 per SolverStatus), for /solver/status.
std::vector<std::int8_t> solver_status_codes(const std::vector<SolverStatus>& status);

/// Output of the kinematic stages (gait, motion, IK) sampled on the output grid.
struct KinematicsResult {
  std::vector<double> time_s;           ///< T
  RowMatrix base_position;              ///< T×3, P0 in G0 [m]
  RowMatrix base_orientation_wxyz;      ///< T×4, quaternion body → world
  RowMatrix base_linear_velocity;       ///< T×3, world [m/s]
  RowMatrix base_angular_velocity;      ///< T×3, world [rad/s]
  RowMatrix base_linear_acceleration;   ///< T×3, world [m/s²]
  RowMatrix base_angular_acceleration;  ///< T×3, world [rad/s²]
  RowMatrix joint_position;             ///< T×joints [rad]
  RowMatrix joint_velocity;             ///< T×joints [rad/s]
  RowMatrix joint_acceleration;         ///< T×joints [rad/s²]
  RowMatrix foot_position;              ///< T×3 legs = (T,legs,3), world [m]
  RowMatrix foot_velocity;              ///< T×3 legs = (T,legs,3), world [m/s]
  /// T×3 legs = (T,legs,3), world [m]: the foot points the IK placed, a sphere foot's centre
  /// (foot_position + r n); foot_position itself for a point foot.
  RowMatrix foot_center;
  RowMatrix com_position;  ///< T×3, whole-robot COM in G0 [m]
  /// T×legs, ContactPhase values: swing/support from the gait (sample_kinematics); in a
  /// RunResult, the contact schedule's phases with the touchdown transients (kImpact).
  RowMatrixI8 contact_phase;
  /// T (or empty: every sample ordinary), /sample_kind: 0 an ordinary sample, 1 the left
  /// limit of a contact event (docs/theory/output-grid.md#event-samples).
  std::vector<std::int8_t> sample_kind;
  int samples() const { return static_cast<int>(time_s.size()); }
  /// Sizes every dataset to `samples` rows for a robot of `legs` legs and `joints` joints
  /// (joint datasets: joints columns; foot datasets: 3 legs; contact_phase: legs), with zero
  /// values; or, with zero = false, with values unset (but sample_kind zero) for a caller that
  /// writes every row.
  void resize(int samples, int legs, int joints, bool zero = true);
};

/// One touchdown transient (/impacts/*).
struct ImpactRecord {
  int leg = 0;  ///< 0-based leg index (written 1-based)
  double t_start_s = 0.0;
  double duration_s = 0.0;
  double peak_force_N = 0.0;
  double impulse_Ns = 0.0;
  double effective_mass_kg = 0.0;
  double approach_speed_mps = 0.0;
};

/// The electrical side of a run with actuators (drive/drive.hpp compute_electrical;
/// docs/theory/drive-train.md#current-and-electrical-power).
struct ElectricalResult {
  RowMatrix current_A;  ///< T×joints, I [A]
  RowMatrix power_W;    ///< T×joints, P⁺ (P = c R I² + G k_t q̇ I; r P when P < 0) [W]
  std::vector<double> total_power_W;   ///< T, Σ_k P⁺_k [W]
  double energy_J = 0.0;               ///< trapezoid of total_power_W over the samples [J]
  std::vector<double> energy_joint_J;  ///< joints, trapezoid of P⁺_k [J]
  double copper_loss_J = 0.0;          ///< trapezoid of Σ c R I² [J]
  double friction_loss_J = 0.0;        ///< trapezoid of Σ (τ_c |q̇| + b q̇²) [J]
  double regenerated_J = 0.0;          ///< trapezoid of Σ r max(0, −P) [J]
  double cost_of_transport = 0.0;      ///< energy_J / (m g d)
  std::vector<double> rms_torque_Nm;   ///< joints, RMS of τ_drive over the run [N m]
  /// joints, the largest RMS of τ_drive over any window of thermal_window_s in the run (the
  /// run's RMS when the window is longer than the run) [N m].
  std::vector<double> window_rms_torque_Nm;
  /// joints, each joint's continuous_torque (+inf: none), the rating the windowed RMS is against.
  std::vector<double> continuous_torque_Nm;
  /// With a thermal model on some joint (ActuatorParams::thermal; drive/thermal.hpp), else
  /// empty: T×joints winding and housing temperatures [°C], NaN for a joint without one.
  RowMatrix winding_temperature_degC, housing_temperature_degC;
  /// joints: the largest winding temperature over the run, between samples too [°C] (NaN:
  /// no thermal model), and the first time it reaches the joint's limit [s] (+inf: never,
  /// limit_reached 0; NaN: no thermal model).
  std::vector<double> peak_winding_temperature_degC, time_to_limit_s;
  std::vector<std::int8_t> limit_reached;
  bool has_thermal() const { return winding_temperature_degC.rows() > 0; }
};

/// Output of the dynamic stages (inverse dynamics, contact, allocation, power).
struct DynamicsResult {
  RowMatrix joint_torque;   ///< T×joints [N m]
  RowMatrix contact_force;  ///< T×3 legs = (T,legs,3), terrain on foot, world [N]
  RowMatrix penetration;    ///< T×legs [m]
  /// T×legs, |F_t| / F_n of the chosen force in the contact frame of each support or impact leg,
  /// NaN on a swing leg and where a real force does not press the foot (F_n ≤ 0), 0 for a
  /// round-off force; never infinite (docs/theory/grip.md#utilised-friction).
  RowMatrix utilized_friction;
  /// T×legs, 1 where the leg cannot hold at the scene's μ: its friction held only with slack, or
  /// the sample needs more than μ and the leg is at its friction limit or binds the required
  /// friction (docs/theory/grip.md#slip-onset); 0 elsewhere.
  RowMatrixI8 slip;
  /// T, the least μ for which the sample's rows admit a force distribution, NaN where none
  /// does (docs/theory/grip.md#required-friction); empty when output.required_friction is
  /// false.
  std::vector<double> required_friction;
  /// T, the leg whose friction binds at the required friction (0 … legs − 1), −1 where none does;
  /// empty with required_friction.
  std::vector<std::int8_t> required_friction_leg;
  std::vector<ImpactRecord> impacts;
  RowMatrix joint_power;               ///< T×joints [W]
  std::vector<double> total_power_W;   ///< T, Σ|τ ω|
  double energy_total_J = 0.0;         ///< trapezoid of total_power_W over the samples
  std::vector<double> energy_joint_J;  ///< joints, trapezoid of |τ_k ω_k| over the samples
  /// Joints: ∫max(0, τ_k ω_k) (≥ 0) and ∫min(0, τ_k ω_k) (≤ 0) by the energies' rule, so that
  /// positive − negative = energy_joint_J and positive + negative = the net work [J].
  std::vector<double> positive_work_joint_J, negative_work_joint_J;
  double positive_work_J = 0.0, negative_work_J = 0.0;  ///< their sums over the joints [J]
  std::vector<double> energy_cycle_J;        ///< Y, per gait cycle, sums to energy_total_J
  double distance_m = 0.0;                   ///< trunk travel for the cost of transport
  double cost_of_transport = 0.0;            ///< E / (m g d)
  std::vector<SolverStatus> solver_status;   ///< T
  std::vector<double> solver_iterations;     ///< T
  std::vector<double> solver_objective;      ///< T [N² m²]
  std::vector<double> solver_seconds;        ///< T
  std::vector<std::string> solver_messages;  ///< one per relaxed/failed sample
  /// T, the largest measured violation of each sample [N or N m] (not written: it picks
  /// the message of an episode's worst sample for the log).
  std::vector<double> solver_max_violation;
  /// With actuators (RobotModel::drive), else empty: the drive torques τ_drive = τ + J_a q̈ +
  /// τ_c sgn(q̇) + b q̇ (T×joints) [N m] and their bounds at each sample, lower ≤ τ_drive ≤
  /// limit (T×joints) [N m] (docs/theory/drive-train.md).
  RowMatrix drive_torque;
  RowMatrix drive_torque_limit;
  RowMatrix drive_torque_lower_limit;
  ElectricalResult electrical;  ///< with actuators, after finish_dynamics
  bool has_drive() const { return drive_torque.rows() > 0; }
  bool present = false;
};

/// A sample of one of several results: row `row` of part `part`.
struct SampleRef {
  int part = 0;
  int row = 0;
};

/// Every per-sample field of the samples `order` names, in that order, from the results
/// `parts` (the output grid's refinement computes its samples in batches and gathers them once,
/// pipeline/grid_refinement.hpp). A part's sample_kind may be empty (every sample ordinary).
KinematicsResult gather_samples(const std::vector<const KinematicsResult*>& parts,
                                const std::vector<SampleRef>& order);
/// The per-sample fields of DynamicsResult (torques, forces, penetrations, solver fields) of
/// the samples `order` names; the others are left empty.
DynamicsResult gather_samples(const std::vector<const DynamicsResult*>& parts,
                              const std::vector<SampleRef>& order);

/// The automatic posture of a run (motion.posture.height: auto, planning/posture.hpp), which
/// /meta config_yaml records as the values used
/// (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration).
struct ChosenPosture {
  bool automatic = false;       ///< the height was searched
  double height_m = 0.0;        ///< the height chosen [m]
  double foot_lateral_m = 0.0;  ///< gait.foot_lateral used [m]
};

/// How accurate the output grid is (docs/theory/output-grid.md#error-control): /meta
/// grid_tolerance, grid_energy_error, grid_peak_error.
struct GridAccuracy {
  double tolerance = 0.0;     ///< output.tolerance the grid was refined to (0: not refined)
  double energy_error = 0.0;  ///< estimated relative error of the energies, the largest
  double peak_error = 0.0;    ///< estimated relative error of the peaks, the largest
  int refinement_passes = 0;  ///< passes that added samples
  int added_samples = 0;      ///< samples the refinement added to the grid as built
  bool cubic_energy = false;  ///< energies by the piecewise-cubic rule (else the trapezoid)
};

/// What a run produces: the arrays and the provenance for /meta.
struct RunResult {
  KinematicsResult kin;
  DynamicsResult dyn;
  std::string config_yaml;   ///< fully resolved, automatic choices included
  std::string input_sha256;  ///< "SHA256  PATH" per input file (Scene::input_sha256)
  ChosenPosture posture;     ///< written into /meta config_yaml (config/config.hpp)
  GridAccuracy grid;         ///< the output grid's accuracy (/meta grid_*)
  bool compress = true;      ///< output.compression: deflate (io/h5io.hpp)
  std::string urdf;          ///< robot exactly as simulated
  /// /model/joint_names: the description's joint names in flat joint order (a URDF
  /// robot's own names; empty: hexdyn's L{i}_coxa … names).
  std::vector<std::string> joint_names;
  /// /model/leg_joint_counts: each leg's joints, hip to foot, in leg order (empty: legs of
  /// equal counts).
  std::vector<int> leg_joint_counts;
  /// /model/leg_mapping (URDF robots only, else empty): one entry per leg
  /// (model/urdf_robot.hpp leg_mapping_entries).
  std::vector<std::string> leg_mapping;
  /// Some foot is a sphere (RobotModel::foot_radius_m): /feet/center is written.
  bool sphere_feet = false;
  double total_mass_kg = 0.0;
  double wall_time_s = 0.0;
  /// /gait/cycle_start: Y start times of the gait cycles [s], the first 0 (empty: not
  /// written).
  std::vector<double> cycle_start_s;
  /// /terrain: the height profile z(y) as a polyline in G0 [m] (K vertices; a vertical riser
  /// is two vertices of equal y) and the terrain type "flat", "slope" or "stairs" (empty:
  /// not written).
  std::vector<double> terrain_y_m, terrain_z_m;
  std::string terrain_type;
  /// The height map the run stood on (terrain.type height_map), else null: /terrain/map_*.
  std::shared_ptr<const HeightMap> terrain_map;
  /// Computed for a sweep's summary row alone (OutputParams::summary_only): some required
  /// friction values are upper bounds; write_result_file refuses it.
  bool summary_only = false;
};

}  // namespace hexdyn
