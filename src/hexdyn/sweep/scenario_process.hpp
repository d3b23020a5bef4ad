#pragma once
/// \file scenario_process.hpp
/// Scenarios computed in a child process (fork), so that one that kills its process
/// (segmentation fault, abort, out-of-memory kill) kills only the child: the caller
/// learns which scenario it was and goes on with a new child. The child is long-lived:
/// it is forked once (and again after a crash), receives scenario indices through a
/// pipe and sends back each finished scenario's record (record.hpp) and timing, so a
/// scenario costs a few microseconds of pipe traffic, not a fork. The child never calls
/// MPI and leaves with _exit; it dies with its parent (PR_SET_PDEATHSIG).
///
/// Test-only switch: the environment variable HEXDYN_TEST_CRASH_SCENARIO=k makes the
/// process computing scenario k abort (SIGABRT), to test crash containment; never set
/// it outside tests.
#include <sys/types.h>

#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/sweep/record.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"

namespace hexdyn {

/// A scenario the child finished, or one whose process died.
struct ScenarioEvent {
  std::size_t index = 0;
  bool crashed = false;
  std::string reason;         ///< how the process died, when crashed
  std::vector<char> payload;  ///< encode_record bytes, when not crashed
  ScenarioTiming timing;      ///< when not crashed
  double encode_s = 0.0;      ///< time to encode the record (run image included)
};

/// Makes this process keep the memory it frees for its next allocations (glibc mallopt: no
/// heap trimming, no separate mapping below 64 MiB). A scenario allocates and frees the same
/// few hundred kilobytes of samples again and again; returned to the kernel, they cost page
/// faults at every scenario (docs/dev/benchmarks.md#where-a-scenario-spends-its-time). The
/// scenario child calls it when it starts; it leaves the results unchanged.
void keep_freed_memory();

/// Computes one scenario and encodes its record (what the child does per index).
ScenarioEvent compute_scenario(const ScenarioFactory& factory, std::size_t index, bool keep_runs,
                               const std::string& scratch_dir);

class ScenarioProcess {
 public:
  /// `isolate` false computes in this process, inside wait() (no crash containment).
  ScenarioProcess(const ScenarioFactory& factory, bool keep_runs, std::string scratch_dir,
                  bool isolate = true);
  ~ScenarioProcess();
  ScenarioProcess(const ScenarioProcess&) = delete;
  ScenarioProcess& operator=(const ScenarioProcess&) = delete;

  /// Queues scenarios; they are computed in order.
  void submit(const std::vector<std::size_t>& indices);
  /// Scenarios submitted and not yet reported.
  std::size_t outstanding() const { return pending_.size(); }
  /// Waits up to `timeout_ms` (0: do not wait; without isolation one scenario is
  /// computed) and returns what finished, in order. After a crash the scenarios queued
  /// behind the crashed one continue in a new child. Throws hexdyn::Error when no child
  /// can be started.
  std::vector<ScenarioEvent> wait(int timeout_ms);
  /// Number of children started (1 + crashes), for tests and benchmarks.
  int children_started() const { return children_; }

 private:
  void start_child();
  void stop_child();
  std::vector<ScenarioEvent> read_frames();
  std::string reap_child();

  const ScenarioFactory& factory_;
  bool keep_runs_;
  std::string scratch_;
  bool isolate_;
  std::deque<std::size_t> pending_;
  pid_t child_ = -1;
  int to_child_ = -1, from_child_ = -1;
  std::vector<char> inbox_;
  int children_ = 0;
};

}  // namespace hexdyn
