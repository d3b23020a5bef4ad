// Where a sweep scenario's time goes: the physics (run_scene) against
// everything else a scenario costs in `hexdyn sweep` — building and validating its scene
// from the base tree (ScenarioFactory), the summary row, encoding its record, the
// journal append, the messages to and from the coordinator, the coordinator's
// bookkeeping — measured per scenario over the 1,000-scenario grid of bench/sweep_1000.yaml
// (every 10th scenario, so the mix of fast, slow and failing ones is the grid's).
// The counters give each part in microseconds per scenario and overhead / physics.
//
//   build/bench/bench_sweep_overhead --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "hexdyn/mpi/messages.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/coordinator.hpp"
#include "hexdyn/sweep/journal.hpp"
#include "hexdyn/sweep/record.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace {

using hexdyn::bench::Clock;
using hexdyn::bench::since;

std::string bench_file(const char* name) {
  return hexdyn::bench::source_file(std::string("bench/") + name);
}

void BM_SweepScenarioOverhead(benchmark::State& state) {
  const hexdyn::SweepSpec spec = hexdyn::load_sweep(bench_file("sweep_1000.yaml"));
  const hexdyn::ScenarioFactory factory(spec);
  std::vector<std::size_t> sizes;
  for (const auto& a : spec.axes) sizes.push_back(a.size());
  const hexdyn::SweepIdentity id =
      hexdyn::make_identity(spec.inputs, spec.base_config_yaml, "bench", 1000, false);
  double config = 0, physics = 0, summary = 0, encode = 0, journal = 0, messages = 0, coord = 0;
  double ok_config = 0, ok_physics = 0;
  std::size_t scenarios = 0, ok = 0;
  std::vector<char> journal_buffer;
  for (auto _ : state) {
    hexdyn::SweepCoordinator c(spec.scenario_count(), sizes, 1);
    std::vector<hexdyn::Assignment> out;
    c.on_ready(0, out);
    for (std::size_t i = 0; i < spec.scenario_count(); i += 10) {
      auto t = Clock::now();
      std::vector<char> work = hexdyn::pack_work({i});
      (void)hexdyn::unpack_work(work);
      messages += since(t);

      t = Clock::now();
      hexdyn::ScenarioSummary row;
      try {
        const hexdyn::Scene scene = factory.scene(i, false);  // as without --keep-runs
        const double c = since(t);
        config += c;
        t = Clock::now();
        const hexdyn::RunResult run = hexdyn::run_scene(scene, nullptr);
        const double p = since(t);
        physics += p;
        ok_config += c;
        ok_physics += p;
        ++ok;
        t = Clock::now();
        row = hexdyn::summarize_run(run, i);
        summary += since(t);
      } catch (const std::exception& e) {
        config += since(t);  // a scenario that fails its validation or planning: no physics
        t = Clock::now();
        row = hexdyn::failed_summary(i, hexdyn::classify_exception(e), e.what());
        summary += since(t);
      }
      t = Clock::now();
      const std::vector<char> payload = hexdyn::encode_record({row, {}});
      encode += since(t);

      t = Clock::now();
      hexdyn::Finished f;
      f.index = i;
      f.cost_s = 0.01;
      f.payload = payload;
      std::vector<char> msg;
      hexdyn::append_result(msg, f);
      const auto back = hexdyn::unpack_results(msg);
      const hexdyn::ScenarioRecord r =
          hexdyn::decode_record(back[0].payload.data(), back[0].payload.size(), false);
      messages += since(t);

      t = Clock::now();
      hexdyn::append_journal_record(journal_buffer, hexdyn::RecordKind::kRow, i, id, payload.data(),
                                    payload.size());
      if (journal_buffer.size() > (1u << 20)) journal_buffer.clear();
      journal += since(t);

      t = Clock::now();
      out.clear();
      c.on_result(0, r.summary.index, 0.01, out);
      coord += since(t);
      ++scenarios;
    }
  }
  const double n = static_cast<double>(scenarios);
  const double overhead = config + summary + encode + journal + messages + coord;
  state.counters["physics_us"] = 1e6 * physics / n;
  state.counters["config_us"] = 1e6 * config / n;
  state.counters["summary_us"] = 1e6 * summary / n;
  state.counters["record_us"] = 1e6 * encode / n;
  state.counters["journal_us"] = 1e6 * journal / n;
  state.counters["messages_us"] = 1e6 * messages / n;
  state.counters["coordinator_us"] = 1e6 * coord / n;
  state.counters["overhead_ratio"] = overhead / physics;
  // The computed scenarios alone (those that fail fail in their validation or planning).
  state.counters["ok_scenarios"] = static_cast<double>(ok);
  state.counters["ok_physics_us"] = 1e6 * ok_physics / static_cast<double>(ok);
  state.counters["ok_config_us"] = 1e6 * ok_config / static_cast<double>(ok);
  state.counters["ok_overhead_ratio"] =
      (ok_config + (overhead - config) * static_cast<double>(ok) / n) / ok_physics;
}
BENCHMARK(BM_SweepScenarioOverhead)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
