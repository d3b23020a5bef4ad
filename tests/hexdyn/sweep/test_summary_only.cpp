// A sweep that keeps no runs computes each scenario for its summary row alone
// (OutputParams::summary_only): a sample's required friction may end as an upper bound where
// it cannot reach the run's largest. Checked against the full computation of the same scene:
// the same row (largest required friction with its leg and time, outside and inside touchdown
// transients, the samples without one, the slip samples), every bound above the sample's own
// μ* and below the largest, and such a run refused by the writer.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "sweep_test_support.hpp"

using namespace sweep_test;

namespace {

bool same_or_both_nan(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 2e-7 * std::max(1.0, std::abs(b));
}

void check_summary_only(const std::vector<Override>& set) {
  Scene scene = load_scene(kConfigs + "/sweeps/stairs_base.yaml", set);
  const RunResult full = run_scene(scene);
  scene.output.summary_only = true;
  const RunResult fast = run_scene(scene);
  const ScenarioSummary a = summarize_run(full, 0), b = summarize_run(fast, 0);
  CHECK(same_or_both_nan(b.required_friction_support, a.required_friction_support));
  CHECK(same_or_both_nan(b.required_friction_transient, a.required_friction_transient));
  CHECK(b.required_friction_support_leg == a.required_friction_support_leg);
  CHECK(b.required_friction_transient_leg == a.required_friction_transient_leg);
  CHECK(b.required_friction_support_time_s == a.required_friction_support_time_s);
  CHECK(b.required_friction_transient_time_s == a.required_friction_transient_time_s);
  CHECK(b.no_friction_samples == a.no_friction_samples);
  CHECK(b.slip_samples == a.slip_samples);
  CHECK(b.energy_J == a.energy_J);
  // Sample by sample: equal, or a bound between the sample's own μ* and the largest.
  REQUIRE(fast.dyn.required_friction.size() == full.dyn.required_friction.size());
  const double largest = std::fmax(a.required_friction_support, a.required_friction_transient);
  int bounds = 0;
  for (std::size_t i = 0; i < full.dyn.required_friction.size(); ++i) {
    const double exact = full.dyn.required_friction[i], got = fast.dyn.required_friction[i];
    if (std::isnan(exact)) {
      CHECK(std::isnan(got));
      continue;
    }
    REQUIRE(std::isfinite(got));
    if (std::abs(got - exact) <= 2e-7) continue;
    ++bounds;
    CHECK(got >= exact - 1e-9);
    CHECK(got < largest);
  }
  INFO("samples settled by a bound: " << bounds);
  CHECK(bounds > 0);  // the scenes below have samples that need it
  TempDir dir;
  CHECK_THROWS_AS(write_result_file((dir.path / "r.h5").string(), fast), IoError);
  CHECK_FALSE(fs::exists(dir.path / "r.h5"));
}

}  // namespace

TEST_CASE("sweep: a summary-only run gives the full run's row, its bounds above μ*", "[sweep]") {
  SECTION("a fast tripod on high risers") {
    check_summary_only({{"motion.peak_speed", "0.2"},
                        {"terrain.riser_height", "0.09"},
                        {"gait.duty_factor", "1/2"}});
  }
  SECTION("a slow wave gait") {
    check_summary_only({{"motion.peak_speed", "0.08"},
                        {"terrain.riser_height", "0.04"},
                        {"gait.duty_factor", "5/6"}});
  }
}
