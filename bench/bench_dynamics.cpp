// Per-sample cost of the inverse dynamics on the paper run's states: one RNEA evaluation
// (with and without foot forces) and one contact split (RNEA without foot forces plus
// the six foot Jacobians), cycling through every sample of the run's output grid.
#include <benchmark/benchmark.h>

#include "bench_paper.hpp"

namespace {

using namespace hexdyn;

std::vector<bench::SampleState> all_states() {
  const bench::PaperSetup& p = bench::paper_setup();
  std::vector<bench::SampleState> out;
  for (int i = 0; i < p.kin.samples(); ++i) out.push_back(bench::sample_state(p.kin, i));
  return out;
}

void BM_Rnea(benchmark::State& state) {
  const RobotModel& model = bench::paper_setup().model;
  const std::vector<bench::SampleState> samples = all_states();
  RobotData data(model);
  LegArray<Vec3> forces;
  for (int l = 0; l < model.legs(); ++l) forces[l] = Vec3(0.5, -0.3, 65.7 / 3.0);
  const bool with_forces = state.range(0) != 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const bench::SampleState& s = samples[i];
    i = i + 1 == samples.size() ? 0 : i + 1;
    benchmark::DoNotOptimize(
        rnea(model, data, s.base, s.q, s.qd, s.qdd, with_forces ? &forces : nullptr).data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Rnea)->ArgName("foot_forces")->Arg(0)->Arg(1);

void BM_ContactSplit(benchmark::State& state) {
  const RobotModel& model = bench::paper_setup().model;
  const std::vector<bench::SampleState> samples = all_states();
  RobotData data(model);
  std::size_t i = 0;
  for (auto _ : state) {
    const bench::SampleState& s = samples[i];
    i = i + 1 == samples.size() ? 0 : i + 1;
    benchmark::DoNotOptimize(contact_split(model, data, s.base, s.q, s.qd, s.qdd).trunk_rhs.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ContactSplit);

}  // namespace

BENCHMARK_MAIN();
