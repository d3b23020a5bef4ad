#pragma once
/// \file progress.hpp
/// Progress lines of a long computation (docs/user/faults.md#progress). A command whose work
/// can last more than a few seconds (`hexdyn run`, `hexdyn replay`) opens a ProgressScope on
/// its computing thread; the stages call report_progress between samples, where they call
/// check_cancelled (core/cancel.hpp), and one line
///   hexdyn: COMMAND: STAGE DONE of TOTAL UNIT (P %), E s elapsed
/// reaches the scope's stream at most once per interval, the first after one interval. A
/// thread without a scope prints nothing (a sweep's scenarios, Python), and the call then
/// costs one thread-local read.
#include <chrono>
#include <ostream>
#include <string>

namespace hexdyn {

/// While it lives, report_progress on this thread writes to `os`. Scopes nest (the inner one
/// counts until it ends).
class ProgressScope {
 public:
  /// `command` names the lines ("run", "replay"); `interval_s` ≥ 0 is the least time between
  /// two lines and before the first; `stage`, when not empty, is the only stage reported (an
  /// envelope reports its cells, not the dynamics of each run it makes).
  ProgressScope(std::ostream& os, std::string command, double interval_s = 5.0,
                std::string stage = "");
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

  /// The line of `stage` at `done` of `total` `unit`, when an interval has passed.
  void report(const char* stage, double done, double total, const char* unit);

 private:
  std::ostream& os_;
  std::string command_, stage_;
  std::chrono::steady_clock::duration interval_;
  std::chrono::steady_clock::time_point start_, next_;
  ProgressScope* previous_;
};

/// The value of a command's --progress SECONDS: a number in [0, 86400] (0: a line at every
/// report); throws ConfigError "--progress: got TEXT, expected seconds in [0, 86400]".
double parse_progress_interval(const std::string& text);

/// Reports progress to this thread's ProgressScope, if any: `done` of `total` `unit`
/// ("samples", "s of motion") in `stage` ("dynamics", "replay").
void report_progress(const char* stage, double done, double total, const char* unit);

}  // namespace hexdyn
