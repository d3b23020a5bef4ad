#pragma once
/// \file sweep.hpp
/// Parameter sweeps without MPI: the sweep file, its grid of scenarios, one scenario
/// run as a summary row, per-scenario checkpoint files, and the `hexdyn-sweep/1` file
/// (DESIGN.md §4). The distribution over ranks is in mpi_sweep.hpp.
///
/// A sweep file (see configs/sweeps/stairs.yaml):
///
///     name: stairs                     # optional
///     base: stairs_base.yaml           # a scene file, relative to the sweep file
///     set:                             # optional: keys fixed for every scenario
///       output.grid: uniform
///     axes:                            # the grid is the product, last axis fastest
///       - key: terrain.riser_height    # any key of the base scene, by dotted path
///         range: {from: 0.02, to: 0.10, count: 5}
///       - key: gait.duty_factor
///         values: [1/2, 2/3, 3/4, 5/6] # scalars; p/q is the number p divided by q
///
/// Errors in the sweep file itself — YAML syntax, unknown or missing keys, malformed
/// axes, an axis key the base scene does not have, a base scene (with `set:`) that is
/// not valid on its own — throw ConfigError with one line "FILE: path: got X, expected
/// Y" before any work. A scenario whose value is out of range for its key is not an
/// error of the sweep: it becomes a row with status `kConfig` and the message.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/io/config.hpp"
#include "hexdyn/core/result.hpp"

namespace hexdyn {

/// One swept key and its values.
struct SweepAxis {
  std::string key;                  ///< dotted path of a scene key, e.g. "gait.duty_factor"
  std::vector<std::string> values;  ///< YAML scalar text given to apply_override
  std::vector<std::string> labels;  ///< each value as written in the sweep file ("2/3")
  bool numeric = true;              ///< every value is a finite number
  std::vector<double> numbers;      ///< values as numbers when `numeric`, else empty
  std::size_t size() const { return values.size(); }
};

/// A validated sweep file.
struct SweepSpec {
  std::string name;              ///< `name:` or the file's stem
  std::string sweep_yaml;        ///< the sweep file's text, stored in /meta
  std::string base_path;         ///< the base scene file, as resolved from the sweep file
  std::vector<Override> fixed;   ///< `set:` entries, in file order
  std::vector<SweepAxis> axes;   ///< at least one
  std::string base_tree_yaml;    ///< base scene after `inherit:` and `set:`, unvalidated YAML
  std::string base_config_yaml;  ///< the same, validated and fully resolved (defaults filled)
  /// Number of scenarios: the product of the axis sizes.
  std::size_t scenario_count() const;
};

/// Reads and validates a sweep file and its base scene (inherit: resolved). Throws
/// ConfigError (one line naming file, path, value and what is allowed).
SweepSpec load_sweep(const std::string& path);

/// Upper bound on the number of scenarios of one sweep.
inline constexpr std::size_t kMaxScenarios = 1000000;

/// Index into each axis's values of scenario `index` < scenario_count(), row-major:
/// the last axis varies fastest.
std::vector<std::size_t> grid_point(const SweepSpec& spec, std::size_t index);

/// Scenario id: the index zero-padded to at least 6 digits ("000012"); names /runs/<id>.
std::string scenario_id(const SweepSpec& spec, std::size_t index);

/// What one scenario is made of: the base scene tree with the axis values applied.
struct ScenarioInput {
  std::size_t index = 0;
  std::string id;
  std::string yaml;  ///< the scene as YAML text (unvalidated; validated when it runs)
};

ScenarioInput scenario_input(const SweepSpec& spec, std::size_t index);

/// Name of a scenario in its messages: "scenario 000012" (independent of paths and
/// rank counts, so that files compare equal).
std::string scenario_source_name(const std::string& id);

/// Outcome of a scenario, stored in /scenarios/status (int8).
enum class ScenarioStatus : std::int8_t {
  kOk = 0,        ///< computed (relaxed samples are counted, not failures)
  kConfig = 1,    ///< a value out of range for its key (ConfigError)
  kReach = 2,     ///< a foothold or foot target out of reach (ReachError)
  kPlanning = 3,  ///< PlanningError
  kSolver = 4,    ///< SolverError
  kError = 5,     ///< another hexdyn::Error
  kInternal = 6,  ///< any other exception (a bug)
};

/// "ok", "config", "reach", "planning", "solver", "error", "internal".
const char* status_name(ScenarioStatus status);
/// "0 ok, 1 config, ..." for the `codes` attribute of /scenarios/status.
std::string status_codes_text();

/// One row of /scenarios. Dynamic metrics are NaN when status != kOk.
struct ScenarioSummary {
  std::size_t index = 0;
  ScenarioStatus status = ScenarioStatus::kOk;
  std::string message;               ///< the error's one-line message; "" when ok
  int samples = 0;                   ///< T output samples
  double duration_s = 0.0;           ///< last minus first sample time [s]
  double distance_m = 0.0;           ///< trunk travel used by the cost of transport [m]
  double energy_J = 0.0;             ///< E = ∫ Σ|τ ω| dt [J]
  double cost_of_transport = 0.0;    ///< E / (m g d) [1]
  double peak_impact_force_N = 0.0;  ///< largest touchdown peak; 0 without touchdowns [N]
  std::array<double, kJoints> peak_torque_Nm{};  ///< max over samples of |τ_k| [N m]
  std::array<double, kJoints> rms_torque_Nm{};   ///< time-weighted RMS of τ_k [N m]
  int relaxed_samples = 0;                       ///< samples with solver status 1
  int failed_samples = 0;                        ///< samples with solver status 2
  double wall_time_s = 0.0;  ///< time to compute the scenario [s] (timing field)
};

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

// ---------------------------------------------------------------- checkpoints

/// A scenario as a checkpoint file (`hexdyn-sweep-checkpoint/1`, HDF5): /meta (schema,
/// index), /summary/* (the row) and, when the run is kept, /run/* in the
/// `hexdyn-result/1` layout. Built in a temporary file under `scratch_dir` (which must
/// be writable) and returned as the file's bytes, so that it can travel between ranks.
std::vector<char> encode_checkpoint(const ScenarioOutcome& outcome, const std::string& scratch_dir);

/// Reads the row of a checkpoint file; throws IoError if it is not one.
ScenarioSummary read_checkpoint_summary(const std::string& path);

/// The checkpoint directory of a sweep output, `<output>.checkpoint/`: a manifest
/// naming the sweep it belongs to, one `<id>.h5` per finished scenario (written to a
/// temporary name and renamed, so a file present is complete) and a lock held while
/// a sweep runs. Not thread-safe; store() does not call HDF5.
class Checkpoint {
 public:
  /// Opens the checkpoint of `output_path` for `spec` (rank 0, before any work).
  /// Without `resume`: an existing directory is an error (an interrupted sweep would
  /// be lost). With `resume`: an existing directory must have been made by the same
  /// sweep (same sweep file text, same resolved base scene, same --keep-runs, same
  /// hexdyn version and commit), else ConfigError; a missing one starts afresh.
  /// Leftover temporary files are removed; unreadable scenario files are removed and
  /// recomputed. Throws IoError if the directory is locked by a running sweep.
  Checkpoint(const std::string& output_path, const SweepSpec& spec, bool keep_runs, bool resume);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  const std::string& directory() const { return dir_; }
  /// Indices found finished when the checkpoint was opened, ascending.
  const std::vector<std::size_t>& finished() const { return finished_; }
  /// Path of scenario `index`'s file.
  std::string scenario_path(std::size_t index) const;
  /// Writes a scenario's checkpoint bytes atomically (temporary name, fsync, rename).
  void store(std::size_t index, const std::vector<char>& bytes);
  /// Removes the directory (after the sweep file is complete) and releases the lock.
  void remove();

 private:
  /// Checks or writes the manifest and lists the finished scenarios (lock held).
  void scan(const SweepSpec& spec, bool keep_runs);

  std::string dir_;
  const SweepSpec* spec_;
  std::vector<std::size_t> finished_;
  int lock_fd_ = -1;
};

// ---------------------------------------------------------------- sweep file

/// Facts about the run that produced a sweep file, stored in /meta. All of them are
/// allowed to differ between otherwise identical sweeps.
struct SweepRunInfo {
  int ranks = 1;
  double wall_time_s = 0.0;
  std::size_t resumed_scenarios = 0;  ///< rows taken from an earlier run's checkpoint
};

/// Writes the `hexdyn-sweep/1` file atomically (temporary name, fsync, rename):
/// /meta, /axes/<i>/{key,values,labels}, /joint_names, /scenarios/* (one row per
/// scenario, index order) and, when `runs_from` is given, each computed scenario's
/// /run group copied from its checkpoint file to /runs/<id>. `rows` holds every
/// scenario, rows[i].index == i. Throws IoError.
void write_sweep_file(const std::string& path, const SweepSpec& spec,
                      const std::vector<ScenarioSummary>& rows, const Checkpoint* runs_from,
                      const SweepRunInfo& info);

// ---------------------------------------------------------------- progress

/// Progress lines for a log: done/total, failures, rate, time left; at most one line
/// per `interval_s` (cluster logs stay readable).
class ProgressMeter {
 public:
  using Clock = std::chrono::steady_clock;
  /// `total` scenarios of which `already_done` were finished before this run started.
  ProgressMeter(std::size_t total, std::size_t already_done, double interval_s,
                Clock::time_point start);
  /// Records the current counts; returns a line when `interval_s` has passed since the
  /// last one (or since the start) and something changed.
  std::optional<std::string> update(std::size_t done, std::size_t failed, Clock::time_point now);
  /// The line for the current counts, unconditionally.
  std::string line(Clock::time_point now) const;

 private:
  std::size_t total_, already_done_, done_, failed_ = 0;
  double interval_s_;
  Clock::time_point start_, last_line_;
  std::size_t done_at_last_line_;
};

/// "42 s", "3 min 05 s", "2 h 07 min".
std::string format_duration(double seconds);

}  // namespace hexdyn
