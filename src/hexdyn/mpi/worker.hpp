#pragma once
/// \file worker.hpp
/// The computing side of a sweep, independent of how messages travel: a worker takes
/// batches of scenario indices, computes them in a child process (ScenarioProcess, so a
/// crash kills only the child) and returns the finished scenarios in result messages
/// (messages.hpp). It sends its results when it is down to its last scenario (which asks
/// the coordinator for more while that one computes) or every `flush_interval_s`, so a
/// worker never waits idle for a round trip and the coordinator sees one message per
/// batch, not per scenario. Between events it blocks in poll(2) or sleeps with backoff:
/// an idle worker does not spin.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/sweep/journal.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"

namespace hexdyn {

/// How a worker talks to the coordinator (MPI for a rank, a queue for rank 0's thread).
struct WorkerLink {
  /// Non-blocking: a work message if one has arrived (unpack_work form: nothing = stop).
  std::function<std::optional<std::optional<std::vector<std::size_t>>>()> poll_work;
  /// Sends a result message (append_result bytes).
  std::function<void(std::vector<char>&&)> send_results;
  /// Sends the first "ready" message.
  std::function<void()> send_ready;
};

struct WorkerOptions {
  bool keep_runs = false;
  bool isolate = true;            ///< compute in a child process (crash containment)
  double flush_interval_s = 0.5;  ///< longest time a finished scenario waits to be sent
  std::string scratch_dir;        ///< for kept runs' temporary files
  /// The sweep's identity (rank 0's checkpoint's, sent with the spec): a finished scenario is sent
  /// as its complete journal record (journal.hpp, checksum included), built here rather than on
  /// rank 0, whose time per result bounds the sweep's scale.
  SweepIdentity identity;
};

/// Runs until the stop message; throws hexdyn::Error if no scenario process can start.
void run_worker(const ScenarioFactory& factory, const WorkerOptions& options, WorkerLink& link);

/// True when HEXDYN_SWEEP_ISOLATION is not "none" (the default: isolated).
bool isolation_from_environment();

}  // namespace hexdyn
