// The whole paper scene, end to end (run_scene: planning, kinematics, touchdown transients,
// allocation of every sample, power), as `hexdyn run` computes it before writing: with the
// default active-set allocation (target: under 50 ms), with MX-64 actuators on every joint
// (target: at most 1.2 times the time without, BM_ActuatorCostRatio) and, for scale, with Ipopt.
#include <benchmark/benchmark.h>

#include <chrono>

#include "bench_paper.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/stage_times.hpp"

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

/// The paper scene with MX-64 servos on every joint (actuators.default.model): drive torques,
/// bounds, currents and electrical energies on top of the run.
Scene paper_with_actuators() {
  return load_scene(bench::paper_scene_path(),
                    {parse_override("actuators.default.model=dynamixel_mx64")});
}

void BM_PaperRunActuators(benchmark::State& state) {
  const Scene scene = paper_with_actuators();
  for (auto _ : state) {
    const RunResult r = run_scene(scene);
    benchmark::DoNotOptimize(r.dyn.electrical.energy_J);
  }
}
BENCHMARK(BM_PaperRunActuators)->Unit(benchmark::kMillisecond);

/// The cost of the drive train: the paper scene without and with actuators run alternately,
/// each timed on its own, so that both see the same machine; counter `ratio` is the time with
/// actuators over the time without (issue target: at most 1.2).
void BM_ActuatorCostRatio(benchmark::State& state) {
  const Scene plain = load_scene(bench::paper_scene_path());
  const Scene driven = paper_with_actuators();
  using Clock = std::chrono::steady_clock;
  double without_s = 0.0, with_s = 0.0;
  for (auto _ : state) {
    for (const bool drive : {false, true}) {
      const auto t0 = Clock::now();
      const RunResult r = run_scene(drive ? driven : plain);
      benchmark::DoNotOptimize(r.dyn.energy_total_J);
      (drive ? with_s : without_s) += std::chrono::duration<double>(Clock::now() - t0).count();
    }
  }
  state.counters["ratio"] = with_s / without_s;
  state.counters["without_ms"] = 1e3 * without_s / static_cast<double>(state.iterations());
  state.counters["with_ms"] = 1e3 * with_s / static_cast<double>(state.iterations());
}
BENCHMARK(BM_ActuatorCostRatio)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// The cost of the required friction (docs/theory/grip.md#cost): the stage times of the paper
/// scene's run, counter `ratio` the grip stage (utilised friction, slip flags, required
/// friction) over the allocation stage, both timed in the same runs (issue target: at most
/// 1.5). Arg 0: the scene's pyramid; 1: the exact cone. Counters `newton_share` and
/// `probes_per_sample` say how the required friction was found.
void BM_RequiredFrictionCost(benchmark::State& state) {
  Scene scene = load_scene(bench::paper_scene_path());
  if (state.range(0) == 1) scene.allocation.friction = FrictionModel::kCone;
  const PreparedScene prep = prepare_scene(scene);
  StageTimes times;
  for (auto _ : state) {
    const RunResult r = run_prepared_scene(scene, prep, nullptr, &times);
    benchmark::DoNotOptimize(r.dyn.required_friction.data());
  }
  state.counters["ratio"] = times[Stage::kGrip] / times[Stage::kAllocation];
  state.counters["allocation_ms"] =
      1e3 * times[Stage::kAllocation] / static_cast<double>(state.iterations());
  state.counters["grip_ms"] = 1e3 * times[Stage::kGrip] / static_cast<double>(state.iterations());
}
BENCHMARK(BM_RequiredFrictionCost)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_PaperRunIpopt(benchmark::State& state) { run_paper(state, AllocationSolver::kIpopt); }
BENCHMARK(BM_PaperRunIpopt)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
