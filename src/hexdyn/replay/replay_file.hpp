#pragma once
/// \file replay_file.hpp
/// A result file read as a plan to replay (replay.hpp), and the replay written as a
/// `hexdyn-replay/3` file (io/schema_replay.hpp, docs/user/replay.md); the command
/// `hexdyn replay` is cli/replay_command.cpp.
#include <cstdint>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/replay/replay.hpp"

namespace hexdyn {

/// Largest |‖q‖ − 1| of a stored /base/orientation quaternion (the writer stores unit
/// quaternions to rounding, ~1e-16).
inline constexpr double kReplayQuaternionTolerance = 1e-6;
/// Largest distance between a stored foot (/feet/center of a sphere foot, else
/// /feet/position) and the foot that forward kinematics of the stored trunk and joints
/// places [m]. The run's IK meets its targets to ~1e-10 m; a scene or robot other than the
/// run's misplaces the feet by millimetres or more.
inline constexpr double kReplayFootTolerance_m = 1e-6;

/// A result file read for a replay: the run's scene (its /meta config_yaml with the
/// overrides applied, which may name only replay.* and contact.* keys), its robot built from
/// the result's own description (a URDF robot from /model/urdf, never the file on disk), the
/// plan in the trunk frame B (a URDF robot's /base/* describe its root link: moved back), and
/// what the replay file copies.
struct ReplaySource {
  std::string path;         ///< the result file, as named
  std::string created_utc;  ///< its /meta created_utc
  Scene scene;
  ReplayPlan plan;
  std::string urdf;
  std::vector<std::string> joint_names, leg_names;
  /// Each leg's joints (/model/leg_joint_counts, the model's leg table for a result of
  /// layout version 2 or 3).
  std::vector<std::int32_t> leg_joint_counts;
  /// The result file (role "result file"), then the inputs its /meta input_sha256 records:
  /// an output may be none of them (io/output.hpp check_output_target).
  std::vector<InputFile> inputs;
  /// One line per recorded input that is gone or changed on disk since the run (not read).
  std::vector<std::string> warnings;
};

/// Reads `result_path` (a hexdyn-result/5 file with dynamics, or of versions 2 and 3) while an
/// InputFreeze lives (config/inputs.hpp: the stored URDF is kept as an input). Every series the
/// replay reads is checked: finite, of the right shape, /time increasing, unit quaternions
/// (kReplayQuaternionTolerance), and the stored feet where the model puts them
/// (kReplayFootTolerance_m). Throws IoError for a file that is not such a result (naming the
/// file, the dataset, the sample and the value), ConfigError for a bad override or a key
/// outside replay.* and contact.* (and robustness.*, with `robustness`: a robustness study of
/// the stored plan, robustness/robustness.hpp).
ReplaySource read_replay_source(const std::string& result_path,
                                const std::vector<Override>& overrides, bool robustness = false);

/// Writes the replay of `source` to `path` atomically (publish_atomically), after
/// check_output_target(path, source.inputs): the result file is never overwritten.
void write_replay_file(const std::string& path, const ReplaySource& source, const RobotModel& model,
                       const ReplayResult& result);

}  // namespace hexdyn
