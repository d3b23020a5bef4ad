// The whole paper scene, end to end (run_scene: planning, kinematics, touchdown transients,
// allocation of every sample, power), as `hexdyn run` computes it before writing: with the
// default active-set allocation (target: under 50 ms) and, for scale, with Ipopt.
#include <benchmark/benchmark.h>

#include "bench_paper.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace {

using namespace hexdyn;

void run_paper(benchmark::State& state, AllocationSolver solver) {
  Scene scene = load_scene(bench::paper_scene_path());
  scene.allocation.solver = solver;
  int samples = 0, relaxed = 0;
  for (auto _ : state) {
    const RunResult r = run_scene(scene);
    samples = r.kin.samples();
    relaxed = 0;
    for (SolverStatus st : r.dyn.solver_status) relaxed += st != SolverStatus::kOptimal;
    benchmark::DoNotOptimize(r.dyn.energy_total_J);
  }
  state.counters["samples"] = samples;
  state.counters["relaxed_samples"] = relaxed;
}

void BM_PaperRun(benchmark::State& state) { run_paper(state, AllocationSolver::kActiveSet); }
BENCHMARK(BM_PaperRun)->Unit(benchmark::kMillisecond);

/// What hexdyn.run(scene) does in C++: read and validate the scene file, then compute it. The
/// denominator of the Python module's cost ratio (bench/bench_python.py).
void BM_PaperLoadAndRun(benchmark::State& state) {
  for (auto _ : state) {
    const Scene scene = load_scene(bench::paper_scene_path());
    const RunResult r = run_scene(scene);
    benchmark::DoNotOptimize(r.dyn.energy_total_J);
  }
}
BENCHMARK(BM_PaperLoadAndRun)->Unit(benchmark::kMillisecond);

void BM_PaperRunIpopt(benchmark::State& state) { run_paper(state, AllocationSolver::kIpopt); }
BENCHMARK(BM_PaperRunIpopt)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
