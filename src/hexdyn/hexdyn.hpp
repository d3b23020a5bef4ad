#pragma once
/// \file hexdyn.hpp
/// hexdyn as a library: the one header a program includes (installed as
/// <hexdyn/hexdyn.hpp>; CMake target hexdyn::hexdyn, pkg-config hexdyn). The stable
/// entry points, the same words as the command line and the Python module:
///
///     hexdyn::Scene scene = hexdyn::load_scene("paper.yaml",
///                                              {hexdyn::parse_override("gait.duty_factor=3/4")});
///     hexdyn::RunResult r = hexdyn::run_scene(scene);     // computes; throws hexdyn::Error
///     double energy_J = r.dyn.energy_total_J;
///     hexdyn::write_result_file("out.h5", r);             // hexdyn-result/5, as `hexdyn run`
///
/// - load_scene(path, overrides) reads, inherits, overrides and validates a scene file
///   (config/config.hpp); parse_override("key.path=value") is one `--set`.
/// - run_scene(scene, log) plans, samples and solves it (pipeline/run.hpp); the
///   RunResult (core/result.hpp) holds every array of the result file, SI units.
/// - write_result_file(path, result, inputs) writes it atomically (io/output.hpp), after
///   check_output_target(path, inputs): `inputs` are the files load_scene(path, overrides,
///   &inputs) read (config/inputs.hpp), which the output must not be; the CLI checks them so
///   before computing.
/// - CancelScope and check_cancelled (core/cancel.hpp) stop a computation from another
///   thread between samples (what Python's Ctrl-C does).
/// - result_layout(result) (io/result_layout.hpp) lists the file's datasets and /meta
///   attributes in memory, as the file would hold them.
/// - read_replay_source(result_path, overrides), replay_plan(...) and write_replay_file
///   (replay/replay_file.hpp, replay/replay.hpp) replay a result's torques forward, as
///   `hexdyn replay` (docs/theory/replay.md).
/// - run_robustness(scene, threads) and write_robustness_file (robustness/robustness.hpp) run
///   a scene's robustness study, as `hexdyn robustness` (docs/user/robustness.md).
/// - Errors (core/errors.hpp): hexdyn::Error and its family ConfigError, IoError (exit
///   status 2), ReachError, PlanningError, SolverError (3); each message is one line.
///
/// Only these headers and what they need are included: the stages behind them (planning,
/// kinematics, the allocation, prepare_scene in pipeline/pipeline.hpp, signal handling in
/// process/, the YAML reader in config/) are included by name where they are used.
///
/// Thread safety: a Scene and a RunResult are plain values; run_scene may be called from
/// several threads at once on different scenes (the library keeps no global state).
/// write_result_file and the HDF5 reader are not thread-safe (serial HDF5): call them from
/// one thread at a time.
#include "hexdyn/config/config.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/cancel.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/pipeline/run.hpp"
#include "hexdyn/replay/replay_file.hpp"
#include "hexdyn/robustness/robustness.hpp"
#include "hexdyn/version.hpp"
