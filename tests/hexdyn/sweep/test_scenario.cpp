// Scenarios (src/hexdyn/sweep/scenario.*): out-of-range values as failed rows, statuses of
// exceptions, summary metrics against closed-form integrals, a scenario against `hexdyn run`.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

TEST_CASE("sweep: a value out of range fails its scenario only, naming key and value", "[sweep]") {
  TempDir dir;
  const SweepSpec spec =
      load_sweep(sweep_file(dir, "axes:\n  - key: gait.duty_factor\n    values: [0.5, 1.2]\n"));
  CHECK_FALSE(check_scenario(scenario_input(spec, 0)).has_value());
  const auto bad = check_scenario(scenario_input(spec, 1));
  REQUIRE(bad.has_value());
  CHECK(bad->status == ScenarioStatus::kConfig);
  CHECK(bad->index == 1);
  CHECK(bad->message ==
        "scenario 000001: gait.duty_factor: got 1.2, expected a number in [0.5, 1)");
  CHECK(std::isnan(bad->energy_J));
  CHECK(std::isnan(bad->peak_torque_Nm[17]));
  const ScenarioOutcome run = run_scenario(scenario_input(spec, 1), true);
  CHECK(run.summary.status == ScenarioStatus::kConfig);
  CHECK(run.summary.message == bad->message);
  CHECK_FALSE(run.run.has_value());
}

TEST_CASE("sweep: exceptions map to statuses", "[sweep]") {
  CHECK(classify_exception(ConfigError("x")) == ScenarioStatus::kConfig);
  CHECK(classify_exception(ReachError("x")) == ScenarioStatus::kReach);
  CHECK(classify_exception(PlanningError("x")) == ScenarioStatus::kPlanning);
  CHECK(classify_exception(SolverError("x")) == ScenarioStatus::kSolver);
  CHECK(classify_exception(IoError("x")) == ScenarioStatus::kError);
  CHECK(classify_exception(std::runtime_error("x")) == ScenarioStatus::kInternal);
  CHECK(status_codes_text() ==
        "0 ok, 1 config, 2 reach, 3 planning, 4 solver, 5 error, 6 internal, 7 crashed");
  // The names the schema declares (and the Python reader parses) are the program's.
  REQUIRE(schema::kScenarioStatusNames.size() == static_cast<std::size_t>(kLastScenarioStatus) + 1);
  for (std::size_t c = 0; c < schema::kScenarioStatusNames.size(); ++c)
    CHECK(std::string(schema::kScenarioStatusNames[c]) ==
          status_name(static_cast<ScenarioStatus>(c)));
}

TEST_CASE("sweep: summary metrics against closed forms", "[sweep]") {
  const double t0 = 0.5, t1 = 3.0;
  std::vector<double> a, b;
  // A hexapod's 18 joints and a quadruped's 12: the summary has one entry per joint.
  const int J = GENERATE(18, 12);
  CAPTURE(J);
  const RunResult run = linear_torque_run(t0, t1, a, b, J);
  const ScenarioSummary s = summarize_run(run, 7);
  CHECK(s.joints == J);
  CHECK(s.index == 7);
  CHECK(s.status == ScenarioStatus::kOk);
  CHECK(s.message.empty());
  CHECK(s.samples == run.kin.samples());
  CHECK(s.duration_s == Approx(t1 - t0));
  CHECK(s.energy_J == 12.5);
  CHECK(s.cost_of_transport == 0.8);
  CHECK(s.distance_m == 0.25);
  CHECK(s.peak_impact_force_N == 64.5);
  CHECK(s.relaxed_samples == 2);
  CHECK(s.failed_samples == 1);
  for (int k = 0; k < J; ++k) {
    // |a + b t| is largest at an end of the interval.
    const double peak = std::max(std::abs(a[k] + b[k] * t0), std::abs(a[k] + b[k] * t1));
    // ∫ (a + b t)² dt = [(a + b t)³ / (3 b)] or a² (t1 − t0) when b = 0.
    const double integral =
        b[k] == 0.0 ? a[k] * a[k] * (t1 - t0)
                    : (std::pow(a[k] + b[k] * t1, 3) - std::pow(a[k] + b[k] * t0, 3)) / (3 * b[k]);
    const double rms = std::sqrt(integral / (t1 - t0));
    INFO("joint " << k);
    CHECK(s.peak_torque_Nm[k] == Approx(peak).epsilon(1e-12));
    CHECK(s.rms_torque_Nm[k] == Approx(rms).epsilon(1e-6));
  }
}

TEST_CASE("sweep: summary of a constant torque and of a single sample", "[sweep]") {
  RunResult r;
  r.kin.time_s = {0.0, 0.1, 0.35, 1.0};
  r.dyn.present = true;
  const int J = 18;
  r.dyn.joint_torque = RowMatrix::Constant(4, J, -1.5);
  r.dyn.solver_status.assign(4, SolverStatus::kOptimal);
  const ScenarioSummary s = summarize_run(r, 0);
  CHECK(s.peak_impact_force_N == 0.0);
  for (int k = 0; k < J; ++k) {
    CHECK(s.peak_torque_Nm[k] == 1.5);
    CHECK(s.rms_torque_Nm[k] == Approx(1.5).epsilon(1e-14));
  }
  r.kin.time_s = {0.2};
  r.dyn.joint_torque = RowMatrix::Constant(1, J, 2.0);
  r.dyn.solver_status.assign(1, SolverStatus::kOptimal);
  const ScenarioSummary one = summarize_run(r, 0);
  CHECK(one.duration_s == 0.0);
  CHECK(one.rms_torque_Nm[0] == 2.0);
}

TEST_CASE("sweep: a scenario is the same computation as hexdyn run with --set", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(
      sweep_file(dir,
                 "set:\n  output.grid: uniform\n  output.sample_step: 0.1\n  motion.cycles: 1\n"
                 "axes:\n  - key: motion.peak_speed\n    values: [0.15]\n"));
  const ScenarioOutcome out = run_scenario(scenario_input(spec, 0), true);
  REQUIRE(out.summary.status == ScenarioStatus::kOk);
  REQUIRE(out.run.has_value());
  const Scene scene =
      load_scene(kConfigs + "/sweeps/stairs_base.yaml", {{"output.grid", "uniform"},
                                                         {"output.sample_step", "0.1"},
                                                         {"motion.cycles", "1"},
                                                         {"motion.peak_speed", "0.15"}});
  const RunResult direct = run_scene(scene);
  CHECK(out.run->config_yaml == direct.config_yaml);
  CHECK(out.run->dyn.joint_torque == direct.dyn.joint_torque);
  CHECK(out.summary.energy_J == direct.dyn.energy_total_J);
  CHECK(out.summary.cost_of_transport == direct.dyn.cost_of_transport);
  CHECK(out.summary.wall_time_s > 0.0);
}
