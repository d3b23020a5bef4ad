#pragma once
/// \file progress.hpp
/// Progress lines of a running sweep for logs (stderr of rank 0).
#include <chrono>
#include <cstddef>
#include <optional>
#include <string>

namespace hexdyn {

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
