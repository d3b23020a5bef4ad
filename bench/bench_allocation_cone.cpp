// Cost of the exact friction cone: the outer-approximation cone back end
// (allocation/cone_backend.hpp) against the active-set back end on the 4-sided pyramid and Ipopt on
// the cone, all three on the samples of the paper run (its own grid, touchdown transients
// included), each run in order as the pipeline solves it (warm starts, relaxed runs), in one
// binary.
//
// BM_ConePaperRun reports, per sample: the cone back end's median (median_us_per_sample),
// the active-set pyramid4 median (pyramid4_us_per_sample) and Ipopt's cone median
// (ipopt_cone_us_per_sample), measured in alternation inside the same benchmark run, the
// ratios cone / pyramid4 (target ≤ 3) and Ipopt / cone, the cone back end's total
// allocation time per run [ms] (cone_ms_per_run) and its heap allocations per optimal
// sample after the first pass (relaxed samples build their messages). BM_Pyramid4PaperRun and
// BM_IpoptConePaperRun time whole passes alone.
//
//   build/bench/bench_allocation_cone --benchmark_filter=ConePaperRun
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "bench_paper.hpp"
#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/cone_backend.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

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

/// Every allocation problem of the paper run with friction model `friction`, in order.
std::vector<QpProblem> paper_problems(FrictionModel friction) {
  const bench::PaperSetup& p = bench::paper_setup();
  AllocationParams alloc = p.scene.allocation;
  alloc.friction = friction;
  RobotData data(p.model);
  std::vector<QpProblem> v(static_cast<std::size_t>(p.kin.samples()));
  for (int i = 0; i < p.kin.samples(); ++i) {
    const bench::SampleState s = bench::sample_state(p.kin, i);
    const ContactSplit& split = contact_split(p.model, data, s.base, s.q, s.qd, s.qdd);
    SampleContacts c;
    sample_contacts(p.kin, i, p.plan.terrain, p.touchdowns, c);
    build_allocation_problem(alloc, p.scene.contact, split, c.phase, c.impact_force_N,
                             c.W_R_contact, v[i]);
  }
  return v;
}

const std::vector<QpProblem>& cone_problems() {
  static const std::vector<QpProblem> v = paper_problems(FrictionModel::kCone);
  return v;
}
const std::vector<QpProblem>& pyramid_problems() {
  static const std::vector<QpProblem> v = paper_problems(FrictionModel::kPyramid4);
  return v;
}

const AllocationParams& params() { return bench::paper_setup().scene.allocation; }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// Heap allocations inside solves that ended optimal (status 0), and those solves.
struct AllocationCount {
  long allocations = 0, solves = 0;
};

/// One pass over a run, cold at its start as a run is: per-sample seconds into `s`
/// (appended), and the worst status; allocations of optimal solves into *count if given.
int run_pass(AllocationBackend& backend, const std::vector<QpProblem>& problems,
             std::vector<double>& s, AllocationCount* count = nullptr) {
  backend.reset_warm_start();
  int status = 0;
  for (const QpProblem& qp : problems) {
    const long before = g_allocations.load(std::memory_order_relaxed);
    const QpOutcome& out = backend.solve(qp);
    const long made = g_allocations.load(std::memory_order_relaxed) - before;
    s.push_back(out.seconds);
    status = std::max(status, static_cast<int>(out.status));
    if (count && out.status == SolverStatus::kOptimal) count->allocations += made, ++count->solves;
  }
  return status;
}

double sum(const std::vector<double>& v, std::size_t from) {
  double t = 0.0;
  for (std::size_t i = from; i < v.size(); ++i) t += v[i];
  return t;
}

/// The three back ends over the paper run in alternation (cone, pyramid4 every iteration;
/// Ipopt on the cone once, it takes seconds): per-sample medians and their ratios.
void BM_ConePaperRun(benchmark::State& state) {
  auto cone = make_cone_backend(cone_options_from(params()));
  auto pyramid = make_active_set_backend(active_set_options_from(params()));
  std::vector<double> ipopt_s;
  {
    auto ipopt = make_ipopt_backend(ipopt_options_from(params()));
    run_pass(*ipopt, cone_problems(), ipopt_s);
  }
  std::vector<double> cone_s, pyramid_s, cone_run_ms;
  std::vector<double> pass;
  AllocationCount count;
  int status = 0;
  bool first = true;
  for (auto _ : state) {
    pass.clear();
    status = std::max(status, run_pass(*cone, cone_problems(), pass, first ? nullptr : &count));
    first = false;
    cone_run_ms.push_back(1e3 * sum(pass, 0));
    cone_s.insert(cone_s.end(), pass.begin(), pass.end());
    run_pass(*pyramid, pyramid_problems(), pyramid_s);
  }
  const double c = median(cone_s), p = median(pyramid_s), i = median(ipopt_s);
  state.counters["samples"] = static_cast<double>(cone_problems().size());
  state.counters["median_us_per_sample"] = 1e6 * c;
  state.counters["pyramid4_us_per_sample"] = 1e6 * p;
  state.counters["ipopt_cone_us_per_sample"] = 1e6 * i;
  state.counters["cone_over_pyramid4"] = c / p;
  state.counters["ipopt_over_cone"] = i / c;
  state.counters["cone_ms_per_run"] = median(cone_run_ms);
  state.counters["ipopt_cone_ms_per_run"] = 1e3 * sum(ipopt_s, 0);
  state.counters["allocs_per_optimal_sample"] =
      count.solves ? static_cast<double>(count.allocations) / static_cast<double>(count.solves)
                   : 0.0;
  state.counters["worst_status"] = status;
}
BENCHMARK(BM_ConePaperRun)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_Pyramid4PaperRun(benchmark::State& state) {
  auto backend = make_active_set_backend(active_set_options_from(params()));
  std::vector<double> s;
  for (auto _ : state) run_pass(*backend, pyramid_problems(), s);
  state.counters["median_us_per_sample"] = 1e6 * median(s);
}
BENCHMARK(BM_Pyramid4PaperRun)->Unit(benchmark::kMillisecond);

void BM_ConeOnlyPaperRun(benchmark::State& state) {
  auto backend = make_cone_backend(cone_options_from(params()));
  std::vector<double> s;
  for (auto _ : state) run_pass(*backend, cone_problems(), s);
  state.counters["median_us_per_sample"] = 1e6 * median(s);
}
BENCHMARK(BM_ConeOnlyPaperRun)->Unit(benchmark::kMillisecond);

void BM_IpoptConePaperRun(benchmark::State& state) {
  auto backend = make_ipopt_backend(ipopt_options_from(params()));
  std::vector<double> s;
  for (auto _ : state) run_pass(*backend, cone_problems(), s);
  state.counters["median_us_per_sample"] = 1e6 * median(s);
}
BENCHMARK(BM_IpoptConePaperRun)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
