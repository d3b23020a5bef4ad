#pragma once
/// \file episode_log.hpp
/// The log of a run's relaxed and failed samples (docs/theory/allocation.md#relaxed-samples):
/// runs of consecutive such samples (episodes), told apart by status and by whether a leg is
/// in its touchdown transient. A kind of episode that occurs once is one line with its time
/// span, its count and the message of its worst sample (largest violation); a kind that
/// repeats is one summary line: the episodes and samples counted, the first and last time,
/// and the worst sample's time and row. A required-friction note is cut to its phrase ("no
/// friction coefficient up to 1000 admits the rows"): every sample's full message is in
/// /solver/messages. Before the first relaxed line, once, what a relaxed sample is.
#include <ostream>
#include <string>
#include <vector>

#include "hexdyn/core/result.hpp"

namespace hexdyn {

class EpisodeLog {
 public:
  explicit EpisodeLog(std::ostream* log) : log_(log) {}

  /// One relaxed or failed sample at `t_s`; `touchdown`: some leg is in its impact phase.
  /// Without a log (null), nothing is kept.
  void add(double t_s, SolverStatus status, bool touchdown, double max_violation,
           const std::string& message);
  /// Ends the current episode (at an optimal sample).
  void close();
  /// Ends the current episode and writes the lines, kinds in the order they first occur.
  void flush();

  /// One episode: its span, samples, status, kind and worst sample.
  struct Episode {
    double start_s = 0.0, end_s = 0.0, worst_s = 0.0, worst = -1.0;
    int count = 0, no_friction = 0;
    SolverStatus status = SolverStatus::kOptimal;
    bool touchdown = false;
    std::string message;  ///< the worst sample's
  };

 private:
  std::ostream* log_;
  std::vector<Episode> episodes_;
  bool open_ = false;
};

/// The worst row of an outcome message: its first "NAME by AMOUNT" after the status word
/// ("relaxed: trunk force z by 123, ..." → "trunk force z by 123"), with the legs in impact
/// when the message names them ("(impact L2 L3 L6)").
std::string worst_row(const std::string& message);

/// `message` with a required-friction note cut to its phrase: "...; required friction: no
/// friction coefficient up to 1000 admits the rows (trunk force z by 123, ...)" → "...;
/// required friction: no friction coefficient up to 1000 admits the rows".
std::string brief_message(const std::string& message);

}  // namespace hexdyn
