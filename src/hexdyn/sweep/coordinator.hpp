#pragma once
/// \file coordinator.hpp
/// Who computes which scenario next: the sweep's scheduling as a plain class, messages
/// in (a worker is ready, finished a scenario, lost a scenario to a crash), assignments
/// out. No MPI, no threads, no files: mpi/mpi_sweep.cpp drives it with MPI messages,
/// bench/bench_coordinator.cpp with simulated workers, the unit tests with scripts.
///
/// Scheduling:
/// - Batches that adapt to the measured cost: a worker gets about `target_batch_s` of
///   work (estimated from the mean cost of the scenarios finished so far), at most
///   `max_batch`, and never more than 1/(2 × workers) of what is left, so the batches
///   shrink to single scenarios at the end. A worker is refilled while it still has one
///   scenario in hand, so it never waits for the coordinator.
/// - Costly ones first where the cost can be predicted: scenarios are handed out in
///   index order until the last quarter (at least 8 per worker) is left; then the rest
///   is sorted by a cost predicted from the measured costs of the scenarios sharing each
///   axis value (log cost additive over the axes), costliest first, so that no long
///   scenario starts last.
/// - A scenario whose process died is handed out once more (first, to any worker); when
///   it dies again on_crash() says it is final (the caller records status `crashed`).
/// Work is O(axes) per event and O(1) memory per scenario (a byte of state).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace hexdyn {

struct CoordinatorOptions {
  double target_batch_s = 0.25;  ///< work per batch aimed at [s]
  std::size_t max_batch = 4096;  ///< largest batch
};

/// Scenarios for one worker, or the order to stop (`stop`, no indices).
struct Assignment {
  int worker = 0;
  std::vector<std::size_t> indices;
  bool stop = false;
};

class SweepCoordinator {
 public:
  /// `count` scenarios on the grid `axis_sizes` (row-major, last axis fastest; their
  /// product is `count`), `workers` workers numbered 0..workers−1.
  SweepCoordinator(std::size_t count, std::vector<std::size_t> axis_sizes, int workers,
                   CoordinatorOptions options = {});

  /// Before any event: a scenario finished in an earlier run (not handed out).
  void mark_finished(std::size_t index);
  /// Before any event: a scenario whose process died once in an earlier run (its next
  /// crash is final).
  void mark_crashed_once(std::size_t index);

  /// Worker `w` starts and asks for work.
  void on_ready(int w, std::vector<Assignment>& out);
  /// Worker `w` finished scenario `index` (any status), which took `cost_s` seconds.
  void on_result(int w, std::size_t index, double cost_s, std::vector<Assignment>& out);
  /// Worker `w`'s process died computing `index`. True when the crash is final (second
  /// crash): the scenario counts as finished and the caller records it as crashed;
  /// false when it will be handed out again.
  bool on_crash(int w, std::size_t index, std::vector<Assignment>& out);

  /// Every scenario finished (ok, failed or crashed).
  bool finished() const { return finished_count_ == count_; }
  std::size_t count() const { return count_; }
  /// Batch size the next assignment would have.
  std::size_t batch_size() const;
  /// Scenarios handed out and not yet finished, of worker `w`.
  std::size_t outstanding(int w) const { return workers_[static_cast<std::size_t>(w)].outstanding; }

 private:
  enum State : std::uint8_t { kPending = 0, kOut = 1, kDone = 2 };
  struct Worker {
    std::size_t outstanding = 0;
    bool ready = false, stopped = false;
  };
  bool take(std::size_t& index);
  void refill(int w, std::vector<Assignment>& out, std::size_t at_least = 1);
  void finish(std::size_t index);
  void stop_idle(std::vector<Assignment>& out);
  void sort_tail();
  /// Log cost of `index` predicted from the axis values seen; `axis_mean`: each axis's mean
  /// log cost, for values not seen yet.
  double predicted_log_cost(std::size_t index, const std::vector<double>& axis_mean) const;

  std::size_t count_;
  std::vector<std::size_t> axis_sizes_;
  CoordinatorOptions options_;
  std::vector<Worker> workers_;
  std::vector<std::uint8_t> state_;
  std::vector<std::uint8_t> crashed_once_;
  std::size_t cursor_ = 0;  ///< next index to consider in index order
  bool tail_sorted_ = false;
  std::vector<std::size_t> tail_;  ///< sorted rest, costliest last (taken from the back)
  std::deque<std::size_t> retry_;  ///< crashed once, handed out first
  std::size_t undispatched_ = 0, finished_count_ = 0;
  std::size_t costs_seen_ = 0;
  double ema_cost_ = 0.0;
  /// Per axis, per value: sum of log cost and count (the cost model).
  std::vector<std::vector<double>> log_sum_;
  std::vector<std::vector<std::uint32_t>> log_n_;
};

}  // namespace hexdyn
