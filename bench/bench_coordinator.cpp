// The sweep coordinator at cluster scale: the real SweepCoordinator,
// with the real work and result messages, row decoding and journal records, driven by
// simulated workers in virtual time. Each worker computes fake scenarios of 10 ms ± 30 %
// and talks to the coordinator as mpi/worker.cpp does (each row sent as its complete
// journal record, checksum included; results sent when down to the
// last scenario in hand, a message latency of 5 µs each way). The coordinator is one
// server: every message it handles occupies it for the CPU time its handling really
// takes here (measured per message), so a coordinator too slow for the workers shows as
// idle workers. Not measured: MPI's own cost per message (about a microsecond per
// message on shared memory; one message per batch of results, not per scenario).
// Reported per worker count W (N = 60 W scenarios): the coordinator's measured cost per
// result and per dispatch, its busy fraction, and the parallel efficiency
// Σ cost / (W × makespan); and the largest W held at ≥ 90 % efficiency.
//
//   build/bench/bench_coordinator              (about a minute)
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <queue>
#include <vector>

#include "hexdyn/mpi/messages.hpp"
#include "hexdyn/sweep/coordinator.hpp"
#include "hexdyn/sweep/journal.hpp"
#include "hexdyn/sweep/record.hpp"

namespace {

/// The coordinator's own CPU time [s] (CLOCK_THREAD_CPUTIME_ID): what its handling costs
/// on a core of its own, whatever else runs on this machine.
double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

constexpr double kLatency_s = 5e-6;

double fake_cost(std::size_t i) {  // 10 ms ± 30 %, fixed per scenario
  const std::uint64_t h = (i + 1) * 0x9E3779B97F4A7C15ULL;
  return 0.010 * (0.7 + 0.6 * static_cast<double>(h >> 11) / 9007199254740992.0);
}

struct Event {
  double t;
  int kind;  // 0: a worker finishes its scenario; 1: work arrives at a worker
  int worker;
  std::size_t seq;
  bool operator>(const Event& o) const { return t > o.t || (t == o.t && seq > o.seq); }
};

struct Outcome {
  double efficiency = 0, busy = 0, per_result_us = 0, per_dispatch_us = 0, makespan = 0;
};

Outcome simulate(int workers, std::size_t n) {
  const std::size_t side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  n = side * side;
  hexdyn::SweepCoordinator coord(n, {side, side}, workers);
  const hexdyn::SweepIdentity id = hexdyn::make_identity({}, "b", "bench", n, false);
  hexdyn::ScenarioSummary row = hexdyn::failed_summary(0, hexdyn::ScenarioStatus::kOk, "");
  row.energy_J = 10.0;
  std::vector<char> journal;
  journal.reserve(1 << 22);

  struct W {
    std::deque<std::size_t> queue;
    bool busy = false;
    std::vector<char> results;
    std::size_t in_hand = 0;  // assigned, not yet reported
  };
  std::vector<W> w(static_cast<std::size_t>(workers));
  std::priority_queue<Event, std::vector<Event>, std::greater<>> events;
  std::vector<std::vector<std::vector<char>>> inbox(static_cast<std::size_t>(workers));
  std::size_t seq = 0;
  double coord_free = 0.0, coord_busy = 0.0, result_time = 0.0, dispatch_time = 0.0;
  std::size_t results = 0, dispatches = 0;
  double total_cost = 0.0, makespan = 0.0;

  // The coordinator handles one message arriving at `t` (results or ready): real code,
  // timed, then its work messages leave.
  std::vector<hexdyn::Assignment> out;
  const auto handle = [&](double t, int from, const std::vector<char>* msg) {
    const double t0 = cpu_now();
    if (msg == nullptr) {
      coord.on_ready(from, out);
    } else {
      for (const hexdyn::Finished& f : hexdyn::unpack_results(*msg)) {
        // As Checkpoint::append_row_record: the worker built the journal record.
        const hexdyn::BuiltRecord b = hexdyn::check_built_record(
            f.payload.data(), f.payload.size(), hexdyn::RecordKind::kRow, f.index, id);
        journal.insert(journal.end(), f.payload.begin(), f.payload.end());
        const hexdyn::ScenarioRecord r = hexdyn::decode_record(b.payload, b.size, false);
        if (journal.size() > (1u << 22)) journal.clear();  // written out by flush()
        coord.on_result(from, f.index, f.cost_s, out);
        (void)r;
        ++results;
      }
    }
    const double t1 = cpu_now();
    std::vector<std::pair<int, std::vector<char>>> sends;
    for (const hexdyn::Assignment& a : out)
      if (!a.stop) sends.emplace_back(a.worker, hexdyn::pack_work(a.indices));
    const double t2 = cpu_now();
    out.clear();
    const double h1 = t1 - t0, h2 = t2 - t1;
    result_time += h1;
    dispatch_time += h2;
    dispatches += sends.size();
    const double start = std::max(t, coord_free);
    coord_free = start + h1 + h2;
    coord_busy += h1 + h2;
    for (auto& [to, bytes] : sends) {
      inbox[static_cast<std::size_t>(to)].push_back(std::move(bytes));
      events.push({coord_free + kLatency_s, 1, to, seq++});
    }
  };
  const auto start_next = [&](int k, double t) {
    W& x = w[static_cast<std::size_t>(k)];
    if (x.busy || x.queue.empty()) return;
    x.busy = true;
    events.push({t + fake_cost(x.queue.front()), 0, k, seq++});
  };
  // Messages to the coordinator wait in arrival order.
  std::priority_queue<Event, std::vector<Event>, std::greater<>> to_coord;
  std::vector<std::vector<char>> coord_msgs;
  for (int k = 0; k < workers; ++k) handle(kLatency_s, k, nullptr);

  hexdyn::Finished f;
  const std::vector<char> payload = hexdyn::encode_record({row, {}});
  while (!events.empty()) {
    const Event e = events.top();
    events.pop();
    W& x = w[static_cast<std::size_t>(e.worker)];
    if (e.kind == 1) {
      for (const auto& m : inbox[static_cast<std::size_t>(e.worker)]) {
        const auto idx = hexdyn::unpack_work(m);
        for (std::size_t i : *idx) x.queue.push_back(i);
        x.in_hand += idx->size();
      }
      inbox[static_cast<std::size_t>(e.worker)].clear();
      start_next(e.worker, e.t);
      continue;
    }
    const std::size_t i = x.queue.front();
    x.queue.pop_front();
    x.busy = false;
    total_cost += fake_cost(i);
    makespan = std::max(makespan, e.t);
    f.index = i;
    f.cost_s = fake_cost(i);
    f.payload.clear();  // the worker's side (mpi/worker.cpp): the row's journal record
    hexdyn::append_journal_record(f.payload, hexdyn::RecordKind::kRow, i, id, payload.data(),
                                  payload.size());
    hexdyn::append_result(x.results, f);
    --x.in_hand;
    start_next(e.worker, e.t);
    if (x.in_hand <= 1) {
      const std::vector<char> msg = std::move(x.results);
      x.results.clear();
      handle(e.t + kLatency_s, e.worker, &msg);
    }
  }
  Outcome o;
  o.makespan = makespan;
  o.efficiency = total_cost / (static_cast<double>(workers) * makespan);
  o.busy = coord_busy / makespan;
  o.per_result_us = 1e6 * result_time / static_cast<double>(results);
  o.per_dispatch_us =
      1e6 * dispatch_time / static_cast<double>(std::max<std::size_t>(dispatches, 1));
  return o;
}

void BM_CoordinatorScale(benchmark::State& state) {
  const int workers = static_cast<int>(state.range(0));
  Outcome o;
  for (auto _ : state) o = simulate(workers, 60 * static_cast<std::size_t>(workers));
  state.counters["workers"] = workers;
  state.counters["efficiency"] = o.efficiency;
  state.counters["coordinator_busy"] = o.busy;
  state.counters["per_result_us"] = o.per_result_us;
  state.counters["per_dispatch_us"] = o.per_dispatch_us;
  state.counters["makespan_s"] = o.makespan;
}
BENCHMARK(BM_CoordinatorScale)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(5000)
    ->Arg(10000)
    ->Arg(15000)
    ->Arg(20000)
    ->Arg(40000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
