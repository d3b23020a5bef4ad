// Checkpoints (src/hexdyn/sweep/checkpoint.*): records round-trip a row; the checkpoint
// directory's resume rules, lock and damaged files.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/io/h5io.hpp"
#include "hexdyn/sweep/checkpoint.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

TEST_CASE("sweep: checkpoint files round-trip a row", "[sweep]") {
  TempDir dir;
  std::vector<double> a, b;
  ScenarioSummary s = summarize_run(linear_torque_run(0.0, 1.0, a, b), 42);
  s.wall_time_s = 1.25;
  const std::vector<char> bytes = encode_checkpoint({s, std::nullopt}, dir.path.string());
  const std::string p = dir.write("x.h5", std::string(bytes.begin(), bytes.end()));
  const ScenarioSummary r = read_checkpoint_summary(p);
  CHECK(r.index == 42);
  CHECK(r.status == s.status);
  CHECK(r.message == s.message);
  CHECK(r.samples == s.samples);
  CHECK(r.energy_J == s.energy_J);
  CHECK(r.peak_impact_force_N == s.peak_impact_force_N);
  CHECK(r.peak_torque_Nm == s.peak_torque_Nm);
  CHECK(r.rms_torque_Nm == s.rms_torque_Nm);
  CHECK(r.relaxed_samples == 2);
  CHECK(r.failed_samples == 1);
  CHECK(r.wall_time_s == 1.25);
  const ScenarioSummary f =
      failed_summary(3, ScenarioStatus::kReach, "leg L2 at t = 0.3 s: out of reach");
  const std::vector<char> fb = encode_checkpoint({f, std::nullopt}, dir.path.string());
  const ScenarioSummary g =
      read_checkpoint_summary(dir.write("y.h5", std::string(fb.begin(), fb.end())));
  CHECK(g.status == ScenarioStatus::kReach);
  CHECK(g.message == f.message);
  CHECK(std::isnan(g.energy_J));
  // Nothing is left in the scratch directory but the two files written here.
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 2);
  CHECK_THROWS_AS(read_checkpoint_summary(dir.write("z.h5", "not hdf5")), IoError);
}

TEST_CASE("sweep: checkpoint directory, resume rules and lock", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const std::string out = (dir.path / "out.h5").string();
  auto bytes_of = [&](std::size_t i, ScenarioStatus st) {
    ScenarioSummary s = failed_summary(i, st, st == ScenarioStatus::kOk ? "" : "failed");
    return encode_checkpoint({s, std::nullopt}, dir.path.string());
  };
  {
    Checkpoint cp(out, spec, false, false);
    CHECK(cp.directory() == out + ".checkpoint");
    CHECK(cp.finished().empty());
    CHECK(fs::exists(cp.directory() + "/manifest.h5"));
    // A second sweep on the same checkpoint while this one runs.
    CHECK_THROWS_AS(Checkpoint(out, spec, false, true), IoError);
    cp.store(3, bytes_of(3, ScenarioStatus::kOk));
    cp.store(10, bytes_of(10, ScenarioStatus::kReach));
    CHECK(fs::exists(cp.scenario_path(3)));
    CHECK(fs::path(cp.scenario_path(10)).filename() == "000010.h5");
  }
  // A leftover temporary file and a damaged scenario file, as a kill can leave them.
  dir.write("out.h5.checkpoint/.000011.h5.tmp", "partial");
  dir.write("out.h5.checkpoint/000012.h5", "damaged");
  // Without --resume an existing checkpoint is an error (one line, naming it).
  try {
    Checkpoint cp(out, spec, false, false);
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()) ==
          out +
              ".checkpoint: the checkpoint of an interrupted sweep exists; "
              "continue it with --resume, or remove the directory to start afresh");
  }
  // Another sweep file, or --keep-runs changed: refused.
  const SweepSpec other = load_sweep(sweep_file(dir, kSmallAxes + "name: other\n", "other.yaml"));
  CHECK_THROWS_WITH(Checkpoint(out, other, false, true),
                    Catch::Contains("the sweep file's text differs"));
  CHECK_THROWS_WITH(Checkpoint(out, spec, true, true), Catch::Contains("made without --keep-runs"));
  {
    Checkpoint cp(out, spec, false, true);
    CHECK(cp.finished() == std::vector<std::size_t>{3, 10});
    CHECK_FALSE(fs::exists(cp.directory() + "/.000011.h5.tmp"));
    CHECK_FALSE(fs::exists(cp.directory() + "/000012.h5"));
    cp.remove();
    CHECK_FALSE(fs::exists(cp.directory()));
  }
  // --resume without a checkpoint starts afresh.
  Checkpoint fresh(out, spec, false, true);
  CHECK(fresh.finished().empty());
}
