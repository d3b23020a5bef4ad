// The forward replay of the paper scene (replay/replay.hpp, docs/validation/replay.md): the
// paper run is computed once, outside the timing, and replay_plan is timed on its plan
// (plan_from_result: what `hexdyn replay` reads from the run's file) with the scene's gains.
// Args: replay.step in microseconds and replay.tolerance in thousandths, the defaults (1000,
// 50) and the settings docs/validation/replay.md#speed-against-error recommends (250, 10);
// issue target: at most 2 s on one core at the recommended settings. Each iteration also runs
// the paper scene (run_scene, what `hexdyn run` computes), timed on its own: counter
// `over_run` is the replay's time over the run's, both measured in the same iterations;
// `run_ms` the run's time. The reported time is the replay's alone (manual time).
//   cmake --build build --target bench_replay && build/bench/bench_replay --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "bench_paper.hpp"
#include "hexdyn/replay/replay.hpp"

namespace {

using namespace hexdyn;

void BM_ReplayPaper(benchmark::State& state) {
  const Scene scene = load_scene(bench::paper_scene_path());
  const RobotModel model = build_robot_model(scene.robot);
  const ReplayPlan plan = plan_from_result(model, run_scene(scene));
  ReplayParams params = scene.replay;
  params.step_s = 1e-6 * static_cast<double>(state.range(0));
  params.tolerance = 1e-3 * static_cast<double>(state.range(1));
  double run_s = 0.0, replay_s = 0.0;
  ReplayResult r;
  for (auto _ : state) {
    const auto t0 = bench::Clock::now();
    const RunResult run = run_scene(scene);
    benchmark::DoNotOptimize(run.dyn.energy_total_J);
    run_s += bench::since(t0);
    const auto t1 = bench::Clock::now();
    r = replay_plan(model, scene.contact, params, scene.terrain, plan);
    benchmark::DoNotOptimize(r.energy_J);
    const double s = bench::since(t1);
    replay_s += s;
    state.SetIterationTime(s);
  }
  state.counters["over_run"] = replay_s / run_s;
  state.counters["run_ms"] = 1e3 * run_s / static_cast<double>(state.iterations());
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["forced_steps"] = static_cast<double>(r.forced_steps);
  state.counters["reached_top"] = r.reached_top ? 1.0 : 0.0;
}
BENCHMARK(BM_ReplayPaper)
    ->ArgNames({"step_us", "tolerance_permille"})
    ->Args({1000, 50})
    ->Args({250, 10})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
