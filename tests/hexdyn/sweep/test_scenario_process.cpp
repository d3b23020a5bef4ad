// Scenarios in a child process (src/hexdyn/sweep/scenario_process.*): the child's records
// equal the same scenarios computed in this process, and a scenario that aborts its
// process is reported as a crash while the scenarios behind it go on in a new child.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>
#include <vector>

#include "hexdyn/sweep/scenario_process.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;

namespace {

std::vector<ScenarioEvent> run_all(ScenarioProcess& p) {
  std::vector<ScenarioEvent> all;
  for (int guard = 0; p.outstanding() > 0 && guard < 100000; ++guard)
    for (ScenarioEvent& e : p.wait(100)) all.push_back(std::move(e));
  return all;
}

}  // namespace

TEST_CASE("sweep: a child process computes what this process computes", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const ScenarioFactory factory(spec);
  ScenarioProcess p(factory, false, dir.path.string(), true);
  p.submit({3, 0, 17});
  const auto events = run_all(p);
  REQUIRE(events.size() == 3);
  for (const ScenarioEvent& e : events) {
    CHECK_FALSE(e.crashed);
    const ScenarioSummary child = decode_record(e.payload.data(), e.payload.size()).summary;
    const ScenarioEvent here = compute_scenario(factory, e.index, false, dir.path.string());
    const ScenarioSummary mine = decode_record(here.payload.data(), here.payload.size()).summary;
    CHECK(child.index == e.index);
    CHECK(child.status == mine.status);
    CHECK(child.energy_J == mine.energy_J);
    REQUIRE(child.joints == mine.joints);
    for (int k = 0; k < mine.joints; ++k)
      CHECK(child.peak_torque_Nm[static_cast<std::size_t>(k)] ==
            mine.peak_torque_Nm[static_cast<std::size_t>(k)]);
  }
  CHECK(events[0].index == 3);
  CHECK(events[2].index == 17);
  CHECK(p.children_started() == 1);
}

TEST_CASE("sweep: a scenario that aborts its process is a crash, the rest goes on", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const ScenarioFactory factory(spec);
  ::setenv("HEXDYN_TEST_CRASH_SCENARIO", "2", 1);  // test-only switch: scenario 2 aborts
  ScenarioProcess p(factory, false, dir.path.string(), true);
  p.submit({1, 2, 4});
  const auto events = run_all(p);
  ::unsetenv("HEXDYN_TEST_CRASH_SCENARIO");
  REQUIRE(events.size() == 3);
  CHECK_FALSE(events[0].crashed);
  CHECK(events[1].index == 2);
  CHECK(events[1].crashed);
  CHECK_THAT(events[1].reason, Catch::Contains("signal 6"));
  CHECK(events[2].index == 4);
  CHECK_FALSE(events[2].crashed);
  CHECK(p.children_started() == 2);
}
