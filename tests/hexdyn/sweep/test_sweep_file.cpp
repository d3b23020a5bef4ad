// The hexdyn-sweep/5 writer (src/hexdyn/sweep/sweep_file.*): the file read back holds the
// axes, the rows in index order and the kept runs.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/sweep/scenario_process.hpp"
#include "hexdyn/sweep/sweep_file.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

TEST_CASE("sweep: the sweep file holds axes, rows in index order and kept runs", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(
      sweep_file(dir,
                 "set:\n  output.grid: uniform\n  output.sample_step: 0.1\n  motion.cycles: 1\n"
                 "axes:\n  - key: gait.duty_factor\n    values: [1/2, 1.2]\n"
                 "  - key: allocation.friction\n    values: [pyramid4, cone]\n"));
  const std::string out = (dir.path / "sweep.h5").string();
  Checkpoint cp(out, spec, true, false);
  const ScenarioFactory factory(spec);
  std::vector<ScenarioSummary> rows(spec.scenario_count());
  for (std::size_t i = rows.size(); i-- > 0;) {  // completion order need not be index order
    const ScenarioEvent ev = compute_scenario(factory, i, true, dir.path.string());
    cp.append_row(i, ev.payload.data(), ev.payload.size());
    rows[i] = decode_record(ev.payload.data(), ev.payload.size()).summary;
  }
  cp.flush(false);
  write_sweep_file(out, spec, rows, sweep_robot_shape(factory), &cp, {2, 3.5, 1});
  const H5Reader r(out);
  CHECK(r.string_attribute("/meta", "schema") == schema::kSweepSchema);
  CHECK(r.int_attribute("/meta", "schema_version") == 5);
  CHECK(r.string_attribute("/meta", "sweep_yaml") == spec.sweep_yaml);
  CHECK(r.string_attribute("/meta", "base_config_yaml") == spec.base_config_yaml);
  CHECK(r.int_attribute("/meta", "ranks") == 2);
  CHECK(r.int_attribute("/meta", "resumed_scenarios") == 1);
  CHECK(r.read_string("/axes/0/key") == "gait.duty_factor");
  CHECK(r.read_doubles("/axes/0/values").values == std::vector<double>{0.5, 1.2});
  CHECK(r.read_strings("/axes/0/labels") == std::vector<std::string>{"1/2", "1.2"});
  CHECK(r.read_strings("/axes/1/values") == std::vector<std::string>{"pyramid4", "cone"});
  CHECK(r.read_strings("/scenarios/id") ==
        std::vector<std::string>{"000000", "000001", "000002", "000003"});
  CHECK(r.read_doubles("/scenarios/axis_0").values == std::vector<double>{0.5, 0.5, 1.2, 1.2});
  CHECK(r.read_strings("/scenarios/axis_1") ==
        std::vector<std::string>{"pyramid4", "cone", "pyramid4", "cone"});
  CHECK(r.read_ints("/scenarios/axis_index") == std::vector<std::int64_t>{0, 0, 0, 1, 1, 0, 1, 1});
  CHECK(r.read_ints("/scenarios/status") == std::vector<std::int64_t>{0, 0, 1, 1});
  const auto messages = r.read_strings("/scenarios/message");
  CHECK(messages[0].empty());
  CHECK(messages[2] == "scenario 000002: gait.duty_factor: got 1.2, expected a number in [0.5, 1)");
  const auto energy = r.read_doubles("/scenarios/energy").values;
  CHECK(energy[0] == rows[0].energy_J);
  CHECK(std::isnan(energy[3]));
  CHECK(r.dims("/scenarios/peak_torque") == std::vector<std::size_t>{4, 18});
  // Kept runs: computed scenarios only, in the hexdyn-result/5 layout.
  CHECK(r.string_attribute("/runs/000001/meta", "schema") == schema::kResultSchema);
  CHECK(r.read_doubles("/runs/000001/energy/total").values[0] == rows[1].energy_J);
  CHECK_FALSE(r.exists("/runs/000002"));
  // The file is complete: no temporary files next to it (run images are built in
  // hidden temporaries and removed).
  for (const auto& e : fs::directory_iterator(dir.path)) {
    CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
    CHECK(e.path().filename().string().rfind(".hexdyn-run", 0) != 0);
  }
}
