// The sweep's scheduling (src/hexdyn/sweep/coordinator.*), driven by scripted workers:
// every scenario is handed out exactly once (twice after a first crash), batches follow
// the measured cost and shrink at the end, costly scenarios go first once their cost can
// be predicted, and workers stop only when everything is finished.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <vector>

#include "hexdyn/sweep/coordinator.hpp"

using namespace hexdyn;

namespace {

/// Runs `workers` simulated workers in virtual time over a coordinator: each computes
/// its assignments in order, scenario i costing cost(i) seconds, and reports each result
/// at once. Returns the order in which scenarios were started and checks the invariants.
struct Simulation {
  SweepCoordinator& c;
  std::function<double(std::size_t)> cost;
  std::vector<std::deque<std::size_t>> queue;
  std::vector<double> busy_until;
  std::vector<bool> stopped;
  std::vector<int> handed;  ///< times each scenario was handed out
  std::vector<std::size_t> started;
  std::vector<std::size_t> batch_sizes;
  double now = 0.0;

  Simulation(SweepCoordinator& coord, int workers, std::function<double(std::size_t)> f)
      : c(coord),
        cost(std::move(f)),
        queue(static_cast<std::size_t>(workers)),
        busy_until(static_cast<std::size_t>(workers), 0.0),
        stopped(static_cast<std::size_t>(workers), false),
        handed(coord.count(), 0) {}

  void take(std::vector<Assignment>& out) {
    for (const Assignment& a : out) {
      if (a.stop) {
        CHECK(queue[static_cast<std::size_t>(a.worker)].empty());
        stopped[static_cast<std::size_t>(a.worker)] = true;
        continue;
      }
      batch_sizes.push_back(a.indices.size());
      const auto w = static_cast<std::size_t>(a.worker);
      if (queue[w].empty()) busy_until[w] = std::max(busy_until[w], now);  // was idle
      for (std::size_t i : a.indices) {
        ++handed[i];
        queue[static_cast<std::size_t>(a.worker)].push_back(i);
      }
    }
    out.clear();
  }

  /// Runs to the end; `crash_once` scenarios crash on their first attempt, `crash_always`
  /// on every attempt. Returns the virtual wall time.
  double run(const std::vector<std::size_t>& crash_once = {},
             const std::vector<std::size_t>& crash_always = {}) {
    std::vector<Assignment> out;
    for (int w = 0; w < static_cast<int>(queue.size()); ++w) c.on_ready(w, out);
    take(out);
    std::map<std::size_t, int> attempts;
    for (int guard = 0; guard < 1000000; ++guard) {
      // The worker that finishes next.
      int next = -1;
      for (std::size_t w = 0; w < queue.size(); ++w)
        if (!queue[w].empty() &&
            (next < 0 || busy_until[w] + cost(queue[w].front()) <
                             busy_until[static_cast<std::size_t>(next)] +
                                 cost(queue[static_cast<std::size_t>(next)].front())))
          next = static_cast<int>(w);
      if (next < 0) break;
      auto& q = queue[static_cast<std::size_t>(next)];
      const std::size_t i = q.front();
      q.pop_front();
      started.push_back(i);
      busy_until[static_cast<std::size_t>(next)] += cost(i);
      now = std::max(now, busy_until[static_cast<std::size_t>(next)]);
      const int attempt = ++attempts[i];
      const bool crash = std::count(crash_always.begin(), crash_always.end(), i) > 0 ||
                         (attempt == 1 && std::count(crash_once.begin(), crash_once.end(), i) > 0);
      if (crash)
        c.on_crash(next, i, out);
      else
        c.on_result(next, i, cost(i), out);
      take(out);
    }
    return now;
  }
};

}  // namespace

TEST_CASE("coordinator: every scenario once, workers stopped at the end", "[sweep]") {
  SweepCoordinator c(60, {5, 12}, 3);
  Simulation s(c, 3, [](std::size_t i) { return 0.01 * (1 + static_cast<double>(i % 7)); });
  s.run();
  CHECK(c.finished());
  for (int h : s.handed) CHECK(h == 1);
  for (bool st : s.stopped) CHECK(st);
}

TEST_CASE("coordinator: batches follow the measured cost and shrink at the end", "[sweep]") {
  CoordinatorOptions o;
  o.target_batch_s = 0.1;
  SweepCoordinator c(4000, {4000}, 2, o);
  Simulation s(c, 2, [](std::size_t) { return 0.001; });  // 1 ms each: 100 per batch
  s.run();
  REQUIRE(s.batch_sizes.size() > 4);
  CHECK(*std::max_element(s.batch_sizes.begin(), s.batch_sizes.end()) == 100);
  CHECK(s.batch_sizes.back() == 1);
  CHECK(s.batch_sizes.front() == 2);  // before any cost is known
}

TEST_CASE("coordinator: the costly scenarios of the tail go first", "[sweep]") {
  // Cost grows with the value of the second axis (like a slower speed): the last
  // quarter is handed out costliest first, as predicted from the first three quarters.
  SweepCoordinator c(400, {20, 20}, 1);
  const auto cost = [](std::size_t i) { return 0.001 * (1.0 + static_cast<double>(i % 20)); };
  Simulation s(c, 1, cost);
  s.run();
  const std::vector<std::size_t> tail(s.started.end() - 100, s.started.end());
  for (std::size_t k = 1; k < tail.size(); ++k) CHECK(cost(tail[k - 1]) >= cost(tail[k]));
  // The first three quarters in index order.
  for (std::size_t k = 1; k < 250; ++k) CHECK(s.started[k] > s.started[k - 1]);
}

TEST_CASE("coordinator: a crash is retried once, a second crash is final", "[sweep]") {
  SweepCoordinator c(30, {30}, 2);
  Simulation s(c, 2, [](std::size_t) { return 0.01; });
  s.run({5}, {11});
  CHECK(c.finished());
  CHECK(s.handed[5] == 2);
  CHECK(s.handed[11] == 2);  // handed out twice, then recorded as crashed
  for (std::size_t i = 0; i < 30; ++i)
    if (i != 5 && i != 11) CHECK(s.handed[i] == 1);
}

TEST_CASE("coordinator: finished and once-crashed scenarios of an earlier run", "[sweep]") {
  SweepCoordinator c(10, {10}, 1);
  for (std::size_t i : {0u, 3u, 9u}) c.mark_finished(i);
  c.mark_crashed_once(4);
  Simulation s(c, 1, [](std::size_t) { return 0.01; });
  s.run({}, {4});
  CHECK(c.finished());
  CHECK(s.handed[0] == 0);
  CHECK(s.handed[9] == 0);
  CHECK(s.handed[4] == 1);  // its second crash is final
}
