// Where a stair-study scenario's time goes, stage by stage: every 11th
// scenario of the 1,000-scenario grid of bench/sweep_1000.yaml (riser x speed x duty factor on
// configs/sweeps/stairs_base.yaml; 11, not 10, so that the 91 scenarios cover every duty
// factor, the fastest-varying axis), each computed as a sweep's scenario process computes it
// (scene from the base tree, prepare_scene, run_prepared_scene, summary row, record), with the
// pipeline's own stage clocks (pipeline/stage_times.hpp). The counters give each stage in
// microseconds per scenario and its share of the scenario, and `other_share`: the share of
// everything except the touchdown transients, the inverse dynamics (rnea) and the allocation.
//
// `/11` is every 11th scenario; `/1` every scenario of the grid (the stage sums over the whole
// grid, for instance the required friction's (grip) against the allocation's).
//
//   build/bench/bench_sweep_stages --benchmark_filter='StairScenarioStages/11'
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "bench_common.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/record.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/scenario_process.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace {

using hexdyn::bench::Clock;
using hexdyn::bench::since;

std::string bench_file(const char* name) {
  return hexdyn::bench::source_file(std::string("bench/") + name);
}

void BM_StairScenarioStages(benchmark::State& state) {
  const hexdyn::SweepSpec spec = hexdyn::load_sweep(bench_file("sweep_1000.yaml"));
  const hexdyn::ScenarioFactory factory(spec);
  hexdyn::keep_freed_memory();  // as the sweep's scenario process does
  hexdyn::StageTimes times;
  double config = 0, summary = 0, record = 0;
  std::size_t scenarios = 0, ok = 0, evaluations = 0, samples = 0;
  for (auto _ : state) {
    const auto stride = static_cast<std::size_t>(state.range(0));
    for (std::size_t i = 0; i < spec.scenario_count(); i += stride) {
      auto t = Clock::now();
      hexdyn::ScenarioSummary row;
      try {
        hexdyn::Scene scene = factory.scene(i, false);  // as without --keep-runs
        scene.output.summary_only = true;               // (sweep/scenario.cpp run_scenario)
        config += since(t);
        const hexdyn::PreparedScene prep = hexdyn::prepare_scene(scene, &times);
        const hexdyn::RunResult run = hexdyn::run_prepared_scene(scene, prep, nullptr, &times);
        evaluations += prep.plan.posture.evaluations;
        samples += run.kin.samples();
        t = Clock::now();
        row = hexdyn::summarize_run(run, i);
        summary += since(t);
        ++ok;
      } catch (const std::exception& e) {
        t = Clock::now();  // the stage that threw has its time; the row is the summary's
        row = hexdyn::failed_summary(i, hexdyn::classify_exception(e), e.what());
        summary += since(t);
      }
      t = Clock::now();
      benchmark::DoNotOptimize(hexdyn::encode_record({row, {}}));
      record += since(t);
      ++scenarios;
    }
  }
  double total = config + summary + record;
  for (double s : times.seconds) total += s;
  const double n = static_cast<double>(scenarios);
  auto put = [&](const std::string& name, double s) {
    state.counters[name + "_us"] = 1e6 * s / n;
    state.counters[name + "_share"] = s / total;
  };
  put("config", config);
  for (int k = 0; k < static_cast<int>(hexdyn::Stage::kCount); ++k)
    put(std::string(hexdyn::kStageNames[k]), times.seconds[k]);
  put("summary", summary);
  put("record", record);
  using hexdyn::Stage;
  const double physics =
      times[Stage::kTouchdowns] + times[Stage::kRnea] + times[Stage::kAllocation];
  state.counters["scenario_us"] = 1e6 * total / n;
  state.counters["other_share"] = 1.0 - physics / total;
  state.counters["ok_scenarios"] = static_cast<double>(ok);
  // Per computed scenario: candidate postures the automatic posture search evaluated, and
  // output samples.
  state.counters["posture_evaluations"] =
      static_cast<double>(evaluations) / static_cast<double>(ok);
  state.counters["samples"] = static_cast<double>(samples) / static_cast<double>(ok);
  state.counters["scenarios"] = n;
}
BENCHMARK(BM_StairScenarioStages)->Unit(benchmark::kMillisecond)->Iterations(1)->Arg(11)->Arg(1);

/// The `config` stage alone over all scenarios of a sweep: each scenario's scene from the base
/// tree, as a scenario process makes it (counter config_us: µs per scene). Sweeps: the 1,000
/// scenarios of the grid, and the 60 of configs/sweeps/kraby_risers.yaml (a URDF robot).
void BM_ScenarioScenes(benchmark::State& state) {
  const char* sweeps[] = {"bench/sweep_1000.yaml", "configs/sweeps/kraby_risers.yaml"};
  const hexdyn::SweepSpec spec =
      hexdyn::load_sweep(hexdyn::bench::source_file(sweeps[state.range(0)]));
  const hexdyn::ScenarioFactory factory(spec);
  double config = 0;
  std::size_t scenes = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < spec.scenario_count(); ++i) {
      const auto t = Clock::now();
      try {
        benchmark::DoNotOptimize(factory.scene(i, false));
      } catch (const std::exception&) {
      }
      config += since(t);
      ++scenes;
    }
  }
  state.counters["config_us"] = 1e6 * config / static_cast<double>(scenes);
}
BENCHMARK(BM_ScenarioScenes)->Unit(benchmark::kMillisecond)->Iterations(3)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
