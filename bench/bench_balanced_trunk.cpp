// The balanced trunk's cost (motion.trunk: balanced, docs/theory/balance.md; issue target: at
// most 1.2 times the straight trunk's time on the same scene): each scene is computed with the
// straight and the balanced trunk alternately, the whole scenario timed as `hexdyn run` computes
// it before writing (prepare_scene + run_prepared_scene), and the balance stage (balance_trunk on
// a copy of the straight plan) timed on its own in the same loop.
//
// Counters, per scene, from process CPU time (the pipeline is single-threaded; on a shared
// machine CPU time varies less than wall time): `ratio` the balanced scenario's time over the
// straight one's (sums over the iterations), `ratio_lo` and `ratio_hi` the least and largest of
// the per-pair ratios, `wall_ratio` the same from wall time, `straight_ms` and `balanced_ms` per
// scenario, `balance_ms` the balance stage alone and `balance_share` its share of the balanced
// scenario, `rest_ratio` the balanced scenario without its balance stage over the straight one
// (what the offset costs the later stages: sampling the trunk, the touchdowns, the allocation of
// other forces), `passes` the balance stage's passes. A scene whose balanced run throws is
// skipped with its message.
//
// BM_TrunkOffsetAt and BM_TrunkOffsetBuild time the offset's evaluation and construction
// (planning/trunk_offset.hpp) alone, on pieces like the balanced trot's.
//
//   build/bench/bench_balanced_trunk --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "hexdyn/balance/balance.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/planning/trunk_offset.hpp"

namespace {

using hexdyn::bench::Clock;
using hexdyn::bench::since;

/// The balanced scenes of the issue: the two crawls on flat ground and up stairs and the two
/// trots, each balanced in its file (a run that throws is reported as the benchmark's error).
const char* const kScenes[] = {"configs/robots/solo12_crawl_balanced.yaml",
                               "configs/robots/anymal_c_crawl_balanced.yaml",
                               "configs/robots/solo12_trot_balanced.yaml",
                               "configs/robots/anymal_c_trot_balanced.yaml",
                               "configs/robots/solo12_crawl_stairs_balanced.yaml",
                               "configs/robots/anymal_c_crawl_stairs_balanced.yaml"};

hexdyn::Scene scene_with(const char* file, const char* trunk) {
  return hexdyn::load_scene(hexdyn::bench::source_file(file),
                            {hexdyn::parse_override(std::string("motion.trunk=") + trunk)});
}

/// Process CPU time [s]: the pipeline runs on one thread, and on a shared machine its CPU time
/// varies less than its wall time.
double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Wall and CPU seconds of a piece of work.
struct Spent {
  double wall = 0.0, cpu = 0.0;
  Spent& operator+=(const Spent& o) {
    wall += o.wall;
    cpu += o.cpu;
    return *this;
  }
};

template <class F>
Spent timed(F&& work) {
  const auto t = Clock::now();
  const double c = cpu_now();
  work();
  return {since(t), cpu_now() - c};
}

/// One whole scenario (`hexdyn run` without its file); its passes of the balance stage out.
Spent time_scenario(const hexdyn::Scene& scene, int& passes) {
  return timed([&] {
    const hexdyn::PreparedScene prep = hexdyn::prepare_scene(scene);
    const hexdyn::RunResult run = hexdyn::run_prepared_scene(scene, prep);
    benchmark::DoNotOptimize(run.dyn.energy_total_J);
    passes = prep.balance ? prep.balance->iterations : 0;
  });
}

/// balance_trunk alone on the balanced scene's plan at the straight scene's posture (its swings
/// kept out of the standing spans at the ends, as plan_motion_with plans a balanced scene).
Spent time_balance(const hexdyn::Scene& scene, const hexdyn::PreparedScene& straight) {
  hexdyn::MotionPlan plan = hexdyn::plan_motion_with(
      scene, straight.model, straight.plan.posture.p0_W, straight.plan.posture.foot_lateral_m);
  hexdyn::BalanceOptions options;
  options.margin_m = scene.motion.balance_margin_m;
  return timed([&] { benchmark::DoNotOptimize(balance_trunk(straight.model, plan, options)); });
}

void BM_BalancedOverStraight(benchmark::State& state) {
  const char* file = kScenes[state.range(0)];
  state.SetLabel(file);
  hexdyn::Scene straight, balanced;
  int passes = 0;
  try {  // a scene the balanced trunk cannot run is skipped, with the reason
    straight = scene_with(file, "straight");
    balanced = scene_with(file, "balanced");
    time_scenario(balanced, passes);
  } catch (const std::exception& e) {
    state.SkipWithError((std::string("balanced run throws: ") + e.what()).c_str());
    return;
  }
  const hexdyn::PreparedScene straight_prep = hexdyn::prepare_scene(straight);
  Spent plain, balanced_run, balance;
  std::vector<double> ratios;
  int none = 0;
  for (auto _ : state) {
    const Spent a = time_scenario(straight, none);
    const Spent b = time_scenario(balanced, passes);
    balance += time_balance(balanced, straight_prep);
    plain += a;
    balanced_run += b;
    ratios.push_back(b.cpu / a.cpu);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["ratio"] = balanced_run.cpu / plain.cpu;
  state.counters["ratio_lo"] = *std::min_element(ratios.begin(), ratios.end());
  state.counters["ratio_hi"] = *std::max_element(ratios.begin(), ratios.end());
  state.counters["wall_ratio"] = balanced_run.wall / plain.wall;
  state.counters["straight_ms"] = 1e3 * plain.cpu / n;
  state.counters["balanced_ms"] = 1e3 * balanced_run.cpu / n;
  state.counters["balance_ms"] = 1e3 * balance.cpu / n;
  state.counters["balance_share"] = balance.cpu / balanced_run.cpu;
  state.counters["rest_ratio"] = (balanced_run.cpu - balance.cpu) / plain.cpu;
  state.counters["passes"] = passes;
}
BENCHMARK(BM_BalancedOverStraight)
    ->DenseRange(0, static_cast<int>(std::size(kScenes)) - 1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

/// Pieces as the balanced trot of Solo-12 makes them (solo12_trot_flat.yaml: 114 pieces of
/// 0.02–0.06 s, 9 Chebyshev coefficients of s, ω near 7.3 rad/s), with random values.
std::vector<hexdyn::OffsetPiece> trot_like_pieces() {
  std::mt19937 rng(44u);
  std::uniform_real_distribution<double> len(0.02, 0.06), val(-0.03, 0.03);
  std::vector<hexdyn::OffsetPiece> p(114);
  double t = 0.0;
  for (hexdyn::OffsetPiece& piece : p) {
    piece.t0_s = t;
    t += len(rng);
    piece.t1_s = t;
    piece.w0 = hexdyn::Vec2(val(rng), val(rng));
    piece.w1 = hexdyn::Vec2(val(rng), val(rng));
    for (int j = 0; j < 9; ++j)
      piece.r_cheb.push_back(hexdyn::Vec2(val(rng), val(rng)) / (1.0 + j * j));
  }
  return p;
}

/// TrunkOffset::at alone: 9 instants per piece (the balance passes' nodes), per call.
void BM_TrunkOffsetAt(benchmark::State& state) {
  const hexdyn::TrunkOffset offset(7.3, trot_like_pieces());
  std::vector<double> times;
  for (const hexdyn::OffsetPiece& p : offset.pieces())
    for (int j = 0; j < 9; ++j)
      times.push_back(p.t0_s + (p.t1_s - p.t0_s) * 0.5 * (1.0 + std::cos(M_PI * j / 8.0)));
  for (auto _ : state)
    for (double t : times) benchmark::DoNotOptimize(offset.at(t));
  state.counters["per_call"] = benchmark::Counter(
      static_cast<double>(times.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TrunkOffsetAt);

/// TrunkOffset's constructor (the sweeps of ξ and ζ, and what it keeps per piece) on the same
/// pieces: once per balance pass.
void BM_TrunkOffsetBuild(benchmark::State& state) {
  const std::vector<hexdyn::OffsetPiece> pieces = trot_like_pieces();
  for (auto _ : state) {
    const hexdyn::TrunkOffset offset(7.3, pieces);
    benchmark::DoNotOptimize(offset.xi().front());
  }
}
BENCHMARK(BM_TrunkOffsetBuild)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
