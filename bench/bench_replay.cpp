// The forward replay of the paper scene (replay/replay.hpp, docs/validation/replay.md): the
// paper run is computed once and written to a temporary result file, read back as `hexdyn
// replay` reads it (read_replay_source), and replay_plan is timed on its plan with the scene's
// gains. Args: replay.step in microseconds and replay.tolerance in thousandths, the defaults
// (1000, 50) and the settings docs/validation/replay.md#speed-against-error recommends (250,
// 10); issue target: at most 2 s on one core at the recommended settings. Each iteration also runs
// the paper scene (run_scene, what `hexdyn run` computes), timed on its own: counter `over_run` is
// the replay's time over the run's, both measured in the same iterations; `run_ms` the run's time.
// The reported time is the replay's alone (manual time).
//   cmake --build build --target bench_replay && build/bench/bench_replay --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "bench_paper.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/replay/replay_file.hpp"

namespace {

using namespace hexdyn;

/// The paper run as a replay reads it: written to a temporary file, read back, file removed.
ReplaySource paper_replay_source() {
  const Scene scene = load_scene(bench::paper_scene_path());
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("hexdyn_bench_replay_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  write_result_file(path, run_scene(scene));
  ReplaySource src = read_replay_source(path, {});
  std::filesystem::remove(path);
  return src;
}

void BM_ReplayPaper(benchmark::State& state) {
  const ReplaySource src = paper_replay_source();
  const RobotModel model = build_robot_model(src.scene.robot);
  ReplayParams params = src.scene.replay;
  params.step_s = 1e-6 * static_cast<double>(state.range(0));
  params.tolerance = 1e-3 * static_cast<double>(state.range(1));
  double run_s = 0.0, replay_s = 0.0;
  ReplayResult r;
  for (auto _ : state) {
    const auto t0 = bench::Clock::now();
    const RunResult plan = run_scene(src.scene);
    benchmark::DoNotOptimize(plan.dyn.energy_total_J);
    run_s += bench::since(t0);
    const auto t1 = bench::Clock::now();
    r = replay_plan(model, src.scene.contact, params, src.scene.terrain, src.plan);
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
