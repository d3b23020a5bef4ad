#pragma once
/// \file spec.hpp
/// The sweep file (`hexdyn sweep SWEEP.yaml`): its validated form SweepSpec, the grid of
/// scenarios it spans, and the scene of one scenario. Nothing here runs a scenario
/// (scenario.hpp) or touches an output file.
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
///       - cases:                       # paired values: each case sets its keys together
///           - {label: phantomx, robot.urdf: ../robots/phantomx_mark4.urdf, robot.forward_axis: +x}
///           - {label: kraby, robot.urdf: ../robots/kraby.urdf, robot.forward_axis: +y}
///         name: robot                  # optional: the axis's dimension (default "case")
///
/// A cases axis (SweepAxis::case_keys non-empty) is an axis of words, its labels: its key is
/// its name, its values and labels the case labels. Every case sets the same keys (the
/// keys of the first case); a robot.urdf value is a path relative to the sweep file. Each
/// case is validated with all its keys on the base scene (with `set:`) before any work: a
/// case that is not valid there is an error of the sweep file, not a row.
///
/// Each axis value is validated once against the base scene (SweepAxis::errors); no work
/// is done per scenario (the cost of load_sweep grows with the number of axis values, not
/// of scenarios). Errors in the sweep file itself — YAML syntax, unknown or missing keys, malformed
/// axes, an axis key the base scene does not have, a base scene (with `set:`) that is
/// not valid on its own — throw ConfigError with one line "FILE: path: got X, expected
/// Y" before any work. A scenario whose value is out of range for its key is not an
/// error of the sweep: it becomes a row with status `kConfig` and the message
/// (scenario.hpp).
#include <cstddef>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/inputs.hpp"

namespace hexdyn {

/// One swept key and its values.
struct SweepAxis {
  std::string key;                  ///< dotted path of a scene key, e.g. "gait.duty_factor"
  std::vector<std::string> values;  ///< YAML scalar text given to apply_override
  std::vector<std::string> labels;  ///< each value as written in the sweep file ("2/3")
  bool numeric = true;              ///< every value is a finite number
  std::vector<double> numbers;      ///< values as numbers when `numeric`, else empty
  /// Per value: why the base scene with only this value set is not valid (the
  /// ConfigError's message), "" when it is. Checked once per value, not per scenario;
  /// a scenario holding such a value fails its own validation (a row with status config).
  std::vector<std::string> errors;
  /// A cases axis: the keys each case sets, in the order of the first case (empty for an
  /// axis of one key).
  std::vector<std::string> case_keys;
  /// case_values[v][k]: the value of case_keys[k] in case v, as YAML text given to
  /// apply_override (p/q evaluated; a robot.urdf path absolute, resolved from the sweep file).
  std::vector<std::vector<std::string>> case_values;
  bool is_cases() const { return !case_keys.empty(); }
  std::size_t size() const { return values.size(); }
  /// The overrides of value `v`: {key, values[v]}, or for a cases axis each of its keys.
  std::vector<Override> overrides(std::size_t v) const;
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
  /// Every input file, hashed (config/inputs.hpp): the sweep file, the base scene, its
  /// inherited files, its URDF and each URDF a robot.urdf axis or a case names. /meta input_sha256,
  /// and part of the checkpoint's identity (journal.hpp).
  std::vector<InputFile> inputs;
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

}  // namespace hexdyn
