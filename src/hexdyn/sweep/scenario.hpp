#pragma once
/// \file scenario.hpp
/// One scenario of a sweep: run (or only validated) as `hexdyn run` would, and reduced
/// to its summary row of /scenarios (schema.hpp, hexdyn-sweep/5). A scenario that cannot
/// be computed is a row with a status and a message, never an exception.
#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

struct RobotModel;

/// The shape of a robot: its legs and each leg's joint count (RobotModel::legs(),
/// leg(l).n_joints). The scenarios of a sweep have robots of one shape: its per-joint
/// tables have a column per joint (docs/user/sweeps.md).
struct RobotShape {
  int legs = 0;                ///< 0: not known (no scenario's robot was built)
  LegArray<int> leg_joints{};  ///< the first `legs` entries
  int joints() const;
  bool operator==(const RobotShape& other) const;
  /// "6 legs of 3 joints", "4 legs of 3, 3, 4, 3 joints".
  std::string text() const;
};
RobotShape robot_shape(const RobotModel& model);

/// Outcome of a scenario, stored in /scenarios/status (int8).
enum class ScenarioStatus : std::int8_t {
  kOk = 0,        ///< computed (relaxed samples are counted, not failures)
  kConfig = 1,    ///< a value out of range for its key (ConfigError)
  kReach = 2,     ///< a foothold or foot target out of reach (ReachError)
  kPlanning = 3,  ///< PlanningError
  kSolver = 4,    ///< SolverError
  kError = 5,     ///< another hexdyn::Error
  kInternal = 6,  ///< any other exception (a bug)
  kCrashed = 7,   ///< its process died twice (signal, abort, out-of-memory kill): not retried
};
/// The largest status code.
inline constexpr ScenarioStatus kLastScenarioStatus = ScenarioStatus::kCrashed;

/// "ok", "config", "reach", "planning", "solver", "error", "internal", "crashed".
const char* status_name(ScenarioStatus status);
/// "0 ok, 1 config, ..." for the `codes` attribute of /scenarios/status.
std::string status_codes_text();

/// One row of /scenarios. Dynamic metrics are NaN when status != kOk.
struct ScenarioSummary {
  std::size_t index = 0;
  ScenarioStatus status = ScenarioStatus::kOk;
  std::string message;      ///< the error's one-line message; "" when ok
  int samples = 0;          ///< T output samples
  double duration_s = 0.0;  ///< last minus first sample time [s]
  double distance_m = 0.0;  ///< trunk travel used by the cost of transport [m]
  double energy_J = 0.0;    ///< E = ∫ Σ|τ ω| dt [J]
  /// /energy/positive_work and /energy/negative_work: E's parts where τ ω > 0 and < 0 [J]
  double positive_work_J = 0.0, negative_work_J = 0.0;
  double cost_of_transport = 0.0;     ///< E / (m g d) [1]
  double peak_impact_force_N = 0.0;   ///< largest touchdown peak; 0 without touchdowns [N]
  double peak_power_W = 0.0;          ///< max over samples of Σ|τ ω| [W]
  double peak_contact_force_N = 0.0;  ///< max over samples and legs of |F| [N]
  double grid_energy_error = 0.0;     ///< the run's estimated relative energy error [1]
  double grid_peak_error = 0.0;       ///< the run's estimated relative peak error [1]
  /// The robot's joints: the entries in use of the per-joint arrays below (0: a row of no
  /// computed run, whose arrays are NaN through their whole capacity).
  int joints = 0;
  JointArray<double> peak_torque_Nm{};  ///< max over samples of |τ_k| [N m]
  JointArray<double> rms_torque_Nm{};   ///< time-weighted RMS of τ_k [N m]
  /// max |τ_k| over the samples outside touchdown transients (no leg in its impact phase),
  /// and inside them; NaN where there is no such sample [N m]
  JointArray<double> peak_torque_gait_Nm{}, peak_torque_transient_Nm{};
  // With actuators (NaN without): electrical energy [J] and cost of transport [1], the peak
  // of the total electrical power [W], the drive torques' split peaks and largest windowed
  // RMS [N m], and the thermal load: max over joints of that RMS / continuous_torque [1].
  double energy_electrical_J = 0.0;
  double energy_copper_loss_J = 0.0, energy_friction_loss_J = 0.0, energy_regenerated_J = 0.0;
  double cost_of_transport_electrical = 0.0;
  double peak_electrical_power_W = 0.0;
  JointArray<double> peak_drive_torque_gait_Nm{}, peak_drive_torque_transient_Nm{};
  JointArray<double> drive_torque_window_rms_Nm{};
  double thermal_load = 0.0;
  // With a thermal model (NaN without; drive/thermal.hpp): per joint the peak winding
  // temperature [°C] and the time it reaches its limit [s] (+inf: never), and over the joints
  // the largest peak and the earliest time.
  JointArray<double> peak_winding_temperature_degC{}, time_to_winding_limit_s{};
  double peak_winding_temperature_max_degC = 0.0, time_to_winding_limit_min_s = 0.0;
  // Grip (docs/theory/grip.md; schema.hpp's kScenarioRequiredFriction* for the contract): the
  // largest required friction over support samples and over touchdown-transient samples
  // [1], each with its binding leg (0..5, −1 none) and time [s] (NaN, −1 where none is
  // finite or output.required_friction is false); the samples where no μ suffices (−1 when
  // not computed); the largest utilised friction over support samples [1]; slip samples.
  double required_friction_support = 0.0, required_friction_support_time_s = 0.0;
  double required_friction_transient = 0.0, required_friction_transient_time_s = 0.0;
  int required_friction_support_leg = -1, required_friction_transient_leg = -1;
  int no_friction_samples = 0;
  double peak_utilized_friction = 0.0;
  int slip_samples = 0;
  int relaxed_samples = 0;  ///< samples with solver status 1
  int failed_samples = 0;   ///< samples with solver status 2
  /// relaxed samples outside touchdown transients (no leg in phase impact): the gait itself
  /// asks for more than the robot can give (a transient's relaxed samples are by design)
  int relaxed_gait_samples = 0;
  // A robustness study per scenario (the scene's robustness: section; docs/user/robustness.md
  // #in-a-sweep): its replays (0 without a study), the success fraction with its Wilson 95 %
  // interval (NaN without), and the replays of each failure class.
  int robust_replays = 0;
  double p_success = std::numeric_limits<double>::quiet_NaN();
  double p_success_low = std::numeric_limits<double>::quiet_NaN();
  double p_success_high = std::numeric_limits<double>::quiet_NaN();
  int replays_slipped = 0, replays_stubbed = 0, replays_saturated = 0, replays_fell = 0,
      replays_drifted = 0;
  double wall_time_s = 0.0;  ///< time to compute the scenario [s] (timing field)
};

/// Every per-joint metric of a row, in record order (sweep/record.cpp writes and reads them in
/// it; failed_summary fills them with NaN). S is ScenarioSummary or const ScenarioSummary.
template <class S>
auto per_joint_metrics(S& s) {
  using Summary = std::remove_const_t<S>;
  static constexpr std::array kMembers{&Summary::peak_torque_Nm,
                                       &Summary::rms_torque_Nm,
                                       &Summary::peak_torque_gait_Nm,
                                       &Summary::peak_torque_transient_Nm,
                                       &Summary::peak_drive_torque_gait_Nm,
                                       &Summary::peak_drive_torque_transient_Nm,
                                       &Summary::drive_torque_window_rms_Nm,
                                       &Summary::peak_winding_temperature_degC,
                                       &Summary::time_to_winding_limit_s};
  std::array<decltype(&s.peak_torque_Nm), kMembers.size()> metrics{};
  for (std::size_t i = 0; i < kMembers.size(); ++i) metrics[i] = &(s.*kMembers[i]);
  return metrics;
}

/// Summary metrics of a computed scenario. RMS is over time, with the trapezoidal
/// rule on the output grid: sqrt(∫ τ² dt / (t_end − t_0)), so that a grid refined near
/// touchdowns does not weigh them more (|τ_0| for a single sample).
ScenarioSummary summarize_run(const RunResult& run, std::size_t index);

/// A row for a scenario that could not be computed: metrics NaN, counts 0.
ScenarioSummary failed_summary(std::size_t index, ScenarioStatus status,
                               const std::string& message);

/// Status of an exception thrown by a scenario (by its hexdyn::Error subclass).
ScenarioStatus classify_exception(const std::exception& e);

/// A scenario run: its row and, when kept and computed, its full result.
struct ScenarioOutcome {
  ScenarioSummary summary;
  std::optional<RunResult> run;
};

/// Validates the scenario's scene (ConfigError → status kConfig) without running it.
/// Returns the failed row, or nothing when the scene is valid.
std::optional<ScenarioSummary> check_scenario(const ScenarioInput& input);

/// Runs one scenario with the same library call as `hexdyn run` (run_scene). Never
/// throws for a scenario that cannot be computed: the exception becomes the row's
/// status and message. `keep_run` keeps the RunResult of a computed scenario.
ScenarioOutcome run_scenario(const ScenarioInput& input, bool keep_run);

class ScenarioFactory;

/// Where a scenario's time went [s]: building and validating its scene, the physics
/// (run_scene), and the summary row.
struct ScenarioTiming {
  double config_s = 0.0, physics_s = 0.0, summary_s = 0.0;
};

/// Runs scenario `index` of a sweep with the scene from `factory` (scenario_factory.hpp);
/// otherwise as above. The row's wall_time_s is the scene's construction plus the physics.
ScenarioOutcome run_scenario(const ScenarioFactory& factory, std::size_t index, bool keep_run,
                             ScenarioTiming* timing = nullptr);

}  // namespace hexdyn
