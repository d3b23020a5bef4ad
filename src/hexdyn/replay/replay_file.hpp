#pragma once
/// \file replay_file.hpp
/// `hexdyn replay RESULT.h5 -o REPLAY.h5`: a result file read as a plan to replay
/// (replay.hpp), and the replay written as a `hexdyn-replay/1` file (io/schema_replay.hpp,
/// docs/user/replay.md).
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/replay/replay.hpp"

namespace hexdyn {

/// A result file read for a replay: its scene (its /meta config_yaml with the overrides
/// applied: replay.*, contact.* …), the plan in the trunk frame B (a URDF robot's /base/*
/// describe its root link: moved back), and what the replay file copies.
struct ReplaySource {
  std::string path;         ///< the result file, as named
  std::string created_utc;  ///< its /meta created_utc
  Scene scene;
  ReplayPlan plan;
  std::string urdf;
  std::vector<std::string> joint_names, leg_names;
  std::vector<InputFile> inputs;  ///< the result file (role "result file") and the scene's URDF
};

/// Reads `result_path` (a hexdyn-result/2 file with dynamics). Throws IoError for a file
/// that is not one (naming the file and what is missing), ConfigError for a bad override.
ReplaySource read_replay_source(const std::string& result_path,
                                const std::vector<Override>& overrides);

/// Writes the replay of `source` to `path` atomically (publish_atomically), after
/// check_output_target(path, source.inputs): the result file is never overwritten.
void write_replay_file(const std::string& path, const ReplaySource& source, const RobotModel& model,
                       const ReplayResult& result);

/// The `hexdyn replay` command (argv[0] = "replay"); returns the exit status.
int replay_command(int argc, char** argv);

}  // namespace hexdyn
