// Cost of one foot-force allocation with the dual active-set back end against Ipopt, on
// the samples of bench_allocation.cpp, both back ends in this binary:
//  - a support-phase sample (tripod 2-3-6, t = 2.5 s) and its neighbour, solved in turn,
//    each warm-started from the other's solution as in a run;
//  - a touchdown-transient sample (t = 3.0001 s, legs 1-4-5 impacting) and its neighbour,
//    whose trunk rows cannot hold: the relaxed (penalised) path, warm as well;
//  - the whole paper run, sample after sample as the run solves them: per-sample median.
// Counters: active-set changes (or Ipopt iterations) per solve, the worst status, heap
// allocations per solve, and on the active-set benchmarks `ipopt_ratio`, Ipopt's median
// time per solve over the active-set median (both measured here, per solve).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <new>
#include <stdexcept>
#include <vector>

#include "bench_paper.hpp"
#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"

// Heap allocations of this program, counted to show that a warm solve makes none.
namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// The replacements pair malloc with free; GCC cannot tell once they are inlined.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpragmas"
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace {

using namespace hexdyn;

/// Two consecutive samples of the paper run, starting at the first sample at or after t.
struct Pair {
  QpProblem a, b;
};

Pair sample_pair(double t, bool impact) {
  const bench::PaperSetup& p = bench::paper_setup();
  RobotData data(p.model);
  Pair pr;
  const int i = bench::sample_at(p.kin, t);
  const int legs_a = bench::sample_problem(p, data, i, pr.a);
  const int legs_b = bench::sample_problem(p, data, i + 1, pr.b);
  if (impact != (legs_a > 0 && legs_b > 0))
    throw std::logic_error("bench_allocation_active_set: unexpected contact phases near t");
  return pr;
}

const Pair& support_pair() {
  static const Pair pr = sample_pair(2.5, false);
  return pr;
}
const Pair& impact_pair() {
  static const Pair pr = sample_pair(3.0001, true);
  return pr;
}

std::unique_ptr<AllocationBackend> make_backend(bool active_set) {
  const AllocationParams& params = bench::paper_setup().scene.allocation;
  if (active_set) return make_active_set_backend(active_set_options_from(params));
  return make_ipopt_backend(ipopt_options_from(params));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// Median wall time of one warm solve of a pair (alternating), `solves` solves after one
/// to warm up.
double median_solve_seconds(const Pair& pr, bool active_set, int solves) {
  auto backend = make_backend(active_set);
  backend->solve(pr.a);
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(solves));
  for (int k = 0; k < solves; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    backend->solve(k % 2 ? pr.a : pr.b);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return median(t);
}

/// Ipopt's median per warm solve of a pair, measured once per pair.
double ipopt_median(const Pair& pr) {
  static std::map<const Pair*, double> cache;
  auto it = cache.find(&pr);
  if (it == cache.end()) it = cache.emplace(&pr, median_solve_seconds(pr, false, 200)).first;
  return it->second;
}

/// Warm solves of a pair, alternating; per-solve times recorded for the median.
void run_pair(benchmark::State& state, const Pair& pr, bool active_set) {
  const double ipopt = active_set ? ipopt_median(pr) : 0.0;
  auto backend = make_backend(active_set);
  backend->solve(pr.a);  // the previous sample's solution is the warm start
  std::vector<double> times;
  times.reserve(
      static_cast<std::size_t>(std::min<benchmark::IterationCount>(state.max_iterations, 1 << 22)));
  long iterations = 0, solves = 0, allocations = 0;
  int status = 0;
  bool flip = false;
  for (auto _ : state) {
    const long before = g_allocations.load(std::memory_order_relaxed);
    const auto t0 = std::chrono::steady_clock::now();
    const QpOutcome& out = backend->solve(flip ? pr.a : pr.b);
    const auto t1 = std::chrono::steady_clock::now();
    allocations += g_allocations.load(std::memory_order_relaxed) - before;
    if (times.size() < times.capacity())
      times.push_back(std::chrono::duration<double>(t1 - t0).count());
    flip = !flip;
    iterations += out.iterations;
    status = std::max(status, static_cast<int>(out.status));
    ++solves;
    benchmark::DoNotOptimize(out.x.data());
  }
  const double n = static_cast<double>(std::max(1L, solves));
  state.counters[active_set ? "changes" : "ipopt_iterations"] = iterations / n;
  state.counters["status"] = status;
  state.counters["allocs_per_solve"] = allocations / n;
  state.counters["median_us"] = 1e6 * median(times);
  if (active_set) state.counters["ipopt_ratio"] = ipopt / median(times);
  state.SetItemsProcessed(solves);
}

void BM_ActiveSetSupportWarm(benchmark::State& state) { run_pair(state, support_pair(), true); }
BENCHMARK(BM_ActiveSetSupportWarm)->Unit(benchmark::kMicrosecond);

void BM_IpoptSupportWarm(benchmark::State& state) { run_pair(state, support_pair(), false); }
BENCHMARK(BM_IpoptSupportWarm)->Unit(benchmark::kMicrosecond);

void BM_ActiveSetImpactWarm(benchmark::State& state) { run_pair(state, impact_pair(), true); }
BENCHMARK(BM_ActiveSetImpactWarm)->Unit(benchmark::kMicrosecond);

void BM_IpoptImpactWarm(benchmark::State& state) { run_pair(state, impact_pair(), false); }
BENCHMARK(BM_IpoptImpactWarm)->Unit(benchmark::kMicrosecond);

/// Cold solves of the support sample (reset before each).
void BM_ActiveSetSupportCold(benchmark::State& state) {
  const Pair& pr = support_pair();
  auto backend = make_backend(true);
  long iterations = 0, solves = 0;
  for (auto _ : state) {
    backend->reset_warm_start();
    const QpOutcome& out = backend->solve(pr.a);
    iterations += out.iterations;
    ++solves;
    benchmark::DoNotOptimize(out.x.data());
  }
  state.counters["changes"] = static_cast<double>(iterations) / std::max(1L, solves);
  state.SetItemsProcessed(solves);
}
BENCHMARK(BM_ActiveSetSupportCold)->Unit(benchmark::kMicrosecond);

/// Every allocation problem of the paper run, in order.
const std::vector<QpProblem>& paper_problems() {
  static const std::vector<QpProblem> problems = [] {
    const bench::PaperSetup& p = bench::paper_setup();
    RobotData data(p.model);
    std::vector<QpProblem> v(static_cast<std::size_t>(p.kin.samples()));
    for (int i = 0; i < p.kin.samples(); ++i) bench::sample_problem(p, data, i, v[i]);
    return v;
  }();
  return problems;
}

/// Solves the whole run with one back end; the outcomes' per-sample seconds.
std::vector<double> run_seconds(AllocationBackend& backend) {
  std::vector<double> s;
  s.reserve(paper_problems().size());
  for (const QpProblem& qp : paper_problems()) s.push_back(backend.solve(qp).seconds);
  return s;
}

/// The paper run's allocations (1073 samples, most of them relaxed inside touchdown
/// transients), as a run solves them; one iteration = the whole run. Ipopt's per-sample
/// median comes from one Ipopt pass over the same run (several seconds).
void BM_ActiveSetPaperRun(benchmark::State& state) {
  static const double ipopt = [] {
    auto ipopt_backend = make_backend(false);
    return median(run_seconds(*ipopt_backend));
  }();
  auto backend = make_backend(true);
  std::vector<double> medians;
  for (auto _ : state) {
    backend->reset_warm_start();
    medians.push_back(median(run_seconds(*backend)));
  }
  const double per_sample = median(medians);
  state.counters["samples"] = static_cast<double>(paper_problems().size());
  state.counters["median_us_per_sample"] = 1e6 * per_sample;
  state.counters["ipopt_median_us_per_sample"] = 1e6 * ipopt;
  state.counters["ipopt_ratio"] = ipopt / per_sample;
}
BENCHMARK(BM_ActiveSetPaperRun)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
