// The output grid (planning/grid.hpp) against its definition: the uniform grid holds the
// multiples of the step and the end and nothing else; the adaptive grid holds, besides,
// every event, its transient's points and peak, and the finest step on both sides.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/run_size.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/grid.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {
namespace {

const std::string kPaperConfig = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";

struct Planned {
  Scene scene;
  RobotModel model;
  MotionPlan plan;
};

Planned plan_scene() {
  Scene scene = load_scene(kPaperConfig);
  RobotModel model = build_robot_model(scene.robot);
  MotionPlan plan = plan_motion(scene, model);
  return Planned{std::move(scene), model, std::move(plan)};
}

bool contains(const std::vector<double>& grid, double t, double tol) {
  const auto it = std::lower_bound(grid.begin(), grid.end(), t - tol);
  return it != grid.end() && *it <= t + tol;
}

void check_increasing(const std::vector<double>& grid, double T) {
  REQUIRE(!grid.empty());
  CHECK(grid.front() == 0.0);
  CHECK(grid.back() == T);
  for (std::size_t i = 1; i < grid.size(); ++i) {
    INFO("i " << i << " " << grid[i - 1] << " " << grid[i]);
    REQUIRE(grid[i] > grid[i - 1]);
  }
}

TEST_CASE("output grid: uniform", "[grid]") {
  OutputParams out;
  out.grid = OutputGrid::kUniform;
  out.sample_step_s = 0.05;
  for (double T : {8.6, 1.234, 0.05, 3.0}) {
    INFO("T " << T);
    const std::vector<double> grid = build_output_grid(out, T, {{1.0, 0.01, 0.002}});
    check_increasing(grid, T);
    int multiples = 0;
    for (int k = 0; k * 0.05 <= T + 1e-9; ++k) {
      ++multiples;
      CHECK(contains(grid, k * 0.05, 1e-9));
    }
    // Nothing else: every point is a multiple of the step or the end time.
    for (double t : grid) {
      const double r = t / 0.05 - std::round(t / 0.05);
      CHECK((std::abs(r) <= 1e-9 || t == T));
    }
    const bool T_is_multiple = std::abs(T / 0.05 - std::round(T / 0.05)) <= 1e-9;
    CHECK(grid.size() == static_cast<std::size_t>(multiples + (T_is_multiple ? 0 : 1)));
  }
}

TEST_CASE("output grid: adaptive contains every event and is strictly increasing", "[grid]") {
  const Planned p = plan_scene();
  const double T = p.plan.trunk.duration_s();
  std::vector<GridEvent> events;
  for (const LegPlan& leg : p.plan.gait.legs)
    for (const Swing& sw : leg.swings) {
      events.push_back({sw.t_liftoff_s, 0.0, 0.0});
      events.push_back({sw.t_touchdown_s, 0.004, 0.0015});
    }
  events.push_back({2.02, 0.0, 0.0});  // on a uniform point of the grid
  OutputParams out = p.scene.output;
  REQUIRE(out.grid == OutputGrid::kAdaptive);
  const std::vector<double> grid = build_output_grid(out, T, events);
  check_increasing(grid, T);
  for (int k = 0; k * out.sample_step_s <= T + 1e-9; ++k)
    CHECK(contains(grid, k * out.sample_step_s, 1e-9));
  for (const GridEvent& e : events) {
    INFO("event " << e.t_s);
    CHECK(contains(grid, e.t_s, 1e-9));
    // Points of a transient that ends after T are cut off.
    if (e.duration_s > 0.0) {
      if (e.t_s + e.peak_offset_s <= T) CHECK(contains(grid, e.t_s + e.peak_offset_s, 1e-9));
      for (int j = 0; j <= out.impact_samples; ++j)
        if (e.t_s + e.duration_s * j / out.impact_samples <= T)
          CHECK(contains(grid, e.t_s + e.duration_s * j / out.impact_samples, 1e-9));
    }
    // The finest step next to the event (on each side that lies inside the run).
    if (e.t_s - out.event_step_s >= 0.0) CHECK(contains(grid, e.t_s - out.event_step_s, 1e-9));
    if (e.t_s + e.duration_s + out.event_step_s <= T)
      CHECK(contains(grid, e.t_s + e.duration_s + out.event_step_s, 1e-9));
  }
  // Refinement only adds points: it is denser than the uniform grid.
  OutputParams uniform = out;
  uniform.grid = OutputGrid::kUniform;
  CHECK(grid.size() > build_output_grid(uniform, T, events).size());
}

TEST_CASE("output grid: a left-limit point 1e-10 s before every contact event", "[grid]") {
  OutputParams out;
  out.sample_step_s = 0.05;
  out.event_step_s = 0.01;
  out.impact_samples = 4;
  const double T = 2.0;
  // A touchdown with a transient (events at 0.5 and 0.504), a lift-off on a uniform point
  // (1.0), two events 5e-10 s apart (merged: one left limit, before the earlier), a lift-off
  // at 0 (no left limit) and two more 2e-9 s apart (two left limits).
  const std::vector<GridEvent> events{{0.5, 0.004, 0.0015},    {1.0, 0.0, 0.0}, {1.3, 0.0, 0.0},
                                      {1.3 + 5e-10, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.7, 0.0, 0.0},
                                      {1.7 + 2e-9, 0.0, 0.0}};
  std::vector<std::int8_t> kind;
  const std::vector<double> grid = build_output_grid(out, T, events, &kind);
  check_increasing(grid, T);
  REQUIRE(kind.size() == grid.size());
  std::vector<double> expected_left{0.5 - 1e-10, 0.504 - 1e-10, 1.0 - 1e-10,
                                    1.3 - 1e-10, 1.7 - 1e-10,   1.7 + 2e-9 - 1e-10};
  std::vector<double> left;
  for (std::size_t i = 0; i < grid.size(); ++i)
    if (kind[i] == kSampleLeftLimit)
      left.push_back(grid[i]);
    else
      CHECK(kind[i] == kSampleOrdinary);
  REQUIRE(left.size() == expected_left.size());
  for (std::size_t k = 0; k < left.size(); ++k) {
    INFO("left limit " << k);
    CHECK(left[k] == Approx(expected_left[k]).margin(1e-15));
  }
  // The event itself follows its left limit, nothing in between.
  for (std::size_t i = 0; i + 1 < grid.size(); ++i)
    if (kind[i] == kSampleLeftLimit) {
      INFO("t " << grid[i]);
      CHECK(kind[i + 1] == kSampleOrdinary);
      CHECK(grid[i + 1] - grid[i] >= 1e-10 - 1e-15);
      CHECK(grid[i + 1] - grid[i] <= 6e-10 + 1e-15);
    }
  CHECK(build_output_grid(out, T, events) == grid);  // the same grid without `kind`
  // The uniform grid adds no event samples.
  OutputParams uniform = out;
  uniform.grid = OutputGrid::kUniform;
  std::vector<std::int8_t> uniform_kind;
  const std::vector<double> u = build_output_grid(uniform, T, events, &uniform_kind);
  CHECK(uniform_kind == std::vector<std::int8_t>(u.size(), kSampleOrdinary));
}

// The size bound (core/run_size.hpp) is an upper bound of the grid as built, on the planned
// events of the paper scene with transients and on the scene's own bound before planning, for
// both grids and several steps; a grid beyond kMaxRunSamples is refused before any point is
// made, whatever its count in an int (4e-9 s over 8.6 s: 2.15e9 > 2^31).
TEST_CASE("output grid: its size bound holds, and a grid beyond the limit is refused",
          "[grid][sizes]") {
  const Planned p = plan_scene();
  const double T = p.plan.trunk.duration_s();
  std::vector<GridEvent> events;
  double liftoffs = 0.0, touchdowns = 0.0;
  for (const LegPlan& leg : p.plan.gait.legs)
    for (const Swing& sw : leg.swings) {
      events.push_back({sw.t_liftoff_s, 0.0, 0.0});
      events.push_back({sw.t_touchdown_s, 0.004, 0.0015});
      liftoffs += 1.0;
      touchdowns += 1.0;
    }
  for (OutputGrid kind : {OutputGrid::kUniform, OutputGrid::kAdaptive})
    for (double step : {0.05, 0.013, 1e-3}) {
      OutputParams out = p.scene.output;
      out.grid = kind;
      out.sample_step_s = step;
      out.event_step_s = std::min(out.event_step_s, step);
      const std::size_t built = build_output_grid(out, T, events).size();
      const GridSizeBound b = output_grid_bound(out, T, liftoffs, touchdowns, touchdowns);
      INFO("step " << step << " built " << built << " bound " << b.total());
      CHECK(static_cast<double>(built) <= b.total());
      Scene scene = p.scene;
      scene.output = out;
      CHECK(b.total() <= planned_grid_bound(scene).total());  // the bound before planning
    }
  REQUIRE(kMaxRunSamples == 1000000);
  OutputParams out = p.scene.output;
  out.grid = OutputGrid::kUniform;
  out.sample_step_s = T / 999998.0;  // floor(T / step) + 2 = 10^6 points at most: built
  CHECK(build_output_grid(out, T, {}).size() <= 1000000u);
  for (double step : {T / 999999.0, 4e-9, 1e-12}) {
    out.sample_step_s = step;
    INFO("step " << step);
    CHECK_THROWS_WITH(build_output_grid(out, T, {}),
                      Catch::StartsWith("output.sample_step: the output grid of the 8.6 s run "
                                        "would have up to") &&
                          Catch::EndsWith("samples, expected at most 1000000"));
  }
  out.grid = OutputGrid::kAdaptive;
  out.sample_step_s = 0.05;
  out.impact_samples = 100000;
  CHECK_THROWS_WITH(build_output_grid(out, T, events), Catch::StartsWith("output.impact_samples"));
}

}  // namespace
}  // namespace hexdyn
