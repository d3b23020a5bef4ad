// The whole paper scene, end to end (run_scene: planning, kinematics, touchdowns,
// allocation of every sample, power), as `hexdyn run` computes it before writing.
#include <benchmark/benchmark.h>

#include "bench_paper.hpp"
#include "hexdyn/pipeline.hpp"

namespace {

using namespace hexdyn;

void BM_PaperRun(benchmark::State& state) {
  const Scene scene = load_scene(bench::paper_scene_path());
  int samples = 0, relaxed = 0;
  for (auto _ : state) {
    const RunResult r = run_scene(scene);
    samples = r.kin.samples();
    relaxed = 0;
    for (auto st : r.dyn.solver_status) relaxed += st != 0;
    benchmark::DoNotOptimize(r.dyn.energy_total_J);
  }
  state.counters["samples"] = samples;
  state.counters["relaxed_samples"] = relaxed;
}
BENCHMARK(BM_PaperRun)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
