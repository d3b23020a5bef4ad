// Cost of one foot-force allocation (Ipopt) on real samples of the paper run:
//  - a support-phase sample (tripod 2-3-6 on the ground, t = 2.5 s), warm-started from
//    the solution of the neighbouring sample as in the run, and cold;
//  - a touchdown-transient sample (t = 3.0001 s, legs 1-4-5 impacting), whose trunk rows
//    cannot hold: the relaxed (penalised slack) path.
// Counters: Ipopt iterations per solve and the outcome status (0 optimal, 1 relaxed).
#include <benchmark/benchmark.h>

#include <stdexcept>

#include "bench_paper.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"

namespace {

using namespace hexdyn;

struct Problems {
  QpProblem a, b;  ///< two consecutive samples
  int index = 0;
};

Problems support_problems() {
  const bench::PaperSetup& p = bench::paper_setup();
  RobotData data(p.model);
  Problems pr;
  pr.index = bench::sample_at(p.kin, 2.5);
  if (bench::sample_problem(p, data, pr.index, pr.a) != 0 ||
      bench::sample_problem(p, data, pr.index + 1, pr.b) != 0)
    throw std::logic_error("bench_allocation: the support sample is inside a touchdown transient");
  return pr;
}

void report(benchmark::State& state, long iterations, long solves, int status) {
  state.counters["ipopt_iterations"] =
      benchmark::Counter(static_cast<double>(iterations) / std::max(1L, solves));
  state.counters["status"] = status;
  state.SetItemsProcessed(solves);
}

void BM_AllocationSupportWarm(benchmark::State& state) {
  const Problems pr = support_problems();
  auto backend = make_ipopt_backend(ipopt_options_from(bench::paper_setup().scene.allocation));
  backend->solve(pr.a);  // the previous sample's solution is the warm start
  long iterations = 0, solves = 0;
  int status = 0;
  bool flip = false;
  for (auto _ : state) {
    const QpOutcome& out = backend->solve(flip ? pr.a : pr.b);
    flip = !flip;
    iterations += out.iterations;
    status = std::max(status, static_cast<int>(out.status));
    ++solves;
    benchmark::DoNotOptimize(out.x.data());
  }
  report(state, iterations, solves, status);
}
BENCHMARK(BM_AllocationSupportWarm)->Unit(benchmark::kMillisecond);

void BM_AllocationSupportCold(benchmark::State& state) {
  const Problems pr = support_problems();
  auto backend = make_ipopt_backend(ipopt_options_from(bench::paper_setup().scene.allocation));
  long iterations = 0, solves = 0;
  int status = 0;
  for (auto _ : state) {
    backend->reset_warm_start();
    const QpOutcome& out = backend->solve(pr.a);
    iterations += out.iterations;
    status = std::max(status, static_cast<int>(out.status));
    ++solves;
    benchmark::DoNotOptimize(out.x.data());
  }
  report(state, iterations, solves, status);
}
BENCHMARK(BM_AllocationSupportCold)->Unit(benchmark::kMillisecond);

void BM_AllocationImpactRelaxed(benchmark::State& state) {
  const bench::PaperSetup& p = bench::paper_setup();
  RobotData data(p.model);
  QpProblem qp;
  const int i = bench::sample_at(p.kin, 3.0001);
  if (bench::sample_problem(p, data, i, qp) == 0)
    throw std::logic_error("bench_allocation: the impact sample has no leg in a transient");
  auto backend = make_ipopt_backend(ipopt_options_from(p.scene.allocation));
  long iterations = 0, solves = 0;
  int status = 0;
  for (auto _ : state) {
    backend->reset_warm_start();
    const QpOutcome& out = backend->solve(qp);
    iterations += out.iterations;
    status = std::max(status, static_cast<int>(out.status));
    ++solves;
    benchmark::DoNotOptimize(out.x.data());
  }
  report(state, iterations, solves, status);
}
BENCHMARK(BM_AllocationImpactRelaxed)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
