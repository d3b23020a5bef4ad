// Parameter sweeps without MPI (src/hexdyn/sweep.*): sweep-file validation with
// one-line errors, the row-major grid against nested loops, scenario scenes against
// `--set` overrides of the base, summary metrics against closed-form integrals,
// checkpoint files and directories (resume rules, lock, damaged files), the sweep file
// read back, and the progress lines.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "hexdyn/io/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/io/result_schema.hpp"
#include "hexdyn/sweep/sweep.hpp"

namespace {

namespace fs = std::filesystem;
using namespace hexdyn;

const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";

/// A fresh directory removed with its contents at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("hexdyn_test_sweep_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
};

/// A sweep file in `dir` over the stair base scene (absolute path), with `body` after
/// the base line.
std::string sweep_file(const TempDir& dir, const std::string& body,
                       const std::string& name = "s.yaml") {
  return dir.write(name, "base: " + kConfigs + "/sweeps/stairs_base.yaml\n" + body);
}

const std::string kSmallAxes =
    "set:\n  output.grid: uniform\n  motion.cycles: 1\n"
    "axes:\n"
    "  - key: terrain.riser_height\n    range: {from: 0.03, to: 0.06, count: 4}\n"
    "  - key: gait.duty_factor\n    values: [1/2, 2/3, 0.75]\n"
    "  - key: allocation.friction\n    values: [pyramid4, cone]\n";

std::string message_of(const std::string& path) {
  try {
    (void)load_sweep(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

YAML::Node at(const YAML::Node& root, const std::string& dotted) {
  YAML::Node cur = YAML::Clone(root);
  std::stringstream ss(dotted);
  std::string key;
  while (std::getline(ss, key, '.')) {
    YAML::Node next = cur[key];
    cur.reset(next);
  }
  return cur;
}

}  // namespace

TEST_CASE("sweep: a sweep file gives axes, values and the row-major grid", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  CHECK(spec.name == "s");
  REQUIRE(spec.axes.size() == 3);
  CHECK(spec.scenario_count() == 4 * 3 * 2);

  const SweepAxis& riser = spec.axes[0];
  CHECK(riser.key == "terrain.riser_height");
  CHECK(riser.numeric);
  CHECK(riser.values == std::vector<std::string>{"0.03", "0.04", "0.05", "0.06"});
  CHECK(riser.numbers == std::vector<double>{0.03, 0.04, 0.05, 0.06});

  const SweepAxis& duty = spec.axes[1];
  CHECK(duty.labels == std::vector<std::string>{"1/2", "2/3", "0.75"});
  REQUIRE(duty.numbers.size() == 3);
  CHECK(duty.numbers[0] == 0.5);
  CHECK(duty.numbers[1] == 2.0 / 3.0);  // exactly the double nearest to 2/3
  CHECK(duty.numbers[2] == 0.75);

  const SweepAxis& friction = spec.axes[2];
  CHECK_FALSE(friction.numeric);
  CHECK(friction.numbers.empty());

  // Row-major, last axis fastest: the order of three nested loops.
  std::size_t index = 0;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 3; ++b)
      for (std::size_t c = 0; c < 2; ++c, ++index)
        CHECK(grid_point(spec, index) == std::vector<std::size_t>{a, b, c});
  CHECK(scenario_id(spec, 7) == "000007");
  CHECK(scenario_id(spec, 23) == "000023");
  CHECK(spec.fixed.size() == 2);
}

TEST_CASE("sweep: a scenario's scene is the base with --set overrides of its values", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  for (std::size_t index : {std::size_t{0}, std::size_t{5}, std::size_t{17}, std::size_t{23}}) {
    const ScenarioInput in = scenario_input(spec, index);
    CHECK(in.index == index);
    CHECK(in.id == scenario_id(spec, index));
    const auto p = grid_point(spec, index);
    std::vector<Override> overrides = spec.fixed;
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
      overrides.push_back({spec.axes[a].key, spec.axes[a].values[p[a]]});
    const Scene expected = load_scene(kConfigs + "/sweeps/stairs_base.yaml", overrides);
    const Scene got = load_scene_from_string(in.yaml, "scenario " + in.id);
    INFO("scenario " << in.id);
    CHECK(got.resolved_yaml == expected.resolved_yaml);
    const YAML::Node tree = YAML::Load(in.yaml);
    CHECK(at(tree, "allocation.friction").Scalar() == spec.axes[2].values[p[2]]);
    CHECK(at(tree, "terrain.riser_height").as<double>() == spec.axes[0].numbers[p[0]]);
  }
}

TEST_CASE("sweep: the stairs study and the smoke sweep are valid", "[sweep]") {
  const SweepSpec stairs = load_sweep(kConfigs + "/sweeps/stairs.yaml");
  CHECK(stairs.scenario_count() == 80);
  CHECK(stairs.axes[0].numbers == std::vector<double>{0.02, 0.04, 0.06, 0.08, 0.10});
  CHECK(stairs.axes[1].numbers == std::vector<double>{0.05, 0.1, 0.15, 0.2});
  CHECK(stairs.axes[2].numbers == std::vector<double>{0.5, 2.0 / 3.0, 0.75, 5.0 / 6.0});
  // The base scene's motion is given by speed: the paper's cycle durations are removed.
  const YAML::Node base = YAML::Load(stairs.base_config_yaml);
  CHECK_FALSE(base["motion"]["cycle_durations"].IsDefined());
  CHECK(base["motion"]["peak_speed"].as<double>() == 0.1);
  const SweepSpec smoke = load_sweep(kConfigs + "/sweeps/smoke.yaml");
  CHECK(smoke.scenario_count() <= 8);
}

TEST_CASE("sweep: a bad sweep file is one ConfigError line naming file, key and value", "[sweep]") {
  TempDir dir;
  struct Case {
    std::string what, text, names;
  };
  const std::string base = "base: " + kConfigs + "/sweeps/stairs_base.yaml\n";
  const std::string axis = "axes:\n  - key: gait.duty_factor\n    values: [0.5, 0.75]\n";
  const std::vector<Case> cases = {
      {"YAML syntax", base + "axes: [\n", "s.yaml:"},
      {"unknown top-level key", base + axis + "axis: []\n",
       "axis: unknown key, allowed here: axes, base, name, set"},
      {"missing base", axis, "base: missing"},
      {"base not a file", "base: no-such.yaml\n" + axis,
       "base: got no-such.yaml, expected the path of a scene file"},
      {"missing axes", base, "axes: missing"},
      {"empty axes", base + "axes: []\n", "axes: got [], expected a non-empty list"},
      {"axis key unknown", base + "axes:\n  - key: gait.duty\n    values: [0.5]\n",
       "axes[0].key: got gait.duty, expected a key of the base scene"},
      {"axis key is a group", base + "axes:\n  - key: gait\n    values: [0.5]\n",
       "axes[0].key: got gait, expected a key holding a single value (it holds a group of keys)"},
      {"axis key holds a list",
       base + "axes:\n  - key: motion.initial_position\n    values: [0.5]\n",
       "axes[0].key: got motion.initial_position, expected a key holding a single value (it holds "
       "a list)"},
      {"axis key twice", base + axis + "  - key: gait.duty_factor\n    values: [0.6]\n",
       "axes[1].key: got gait.duty_factor, expected each key on one axis only"},
      {"axis key also fixed", base + "set:\n  gait.duty_factor: 0.5\n" + axis,
       "axes[0].key: got gait.duty_factor, expected a key not also fixed by set:"},
      {"unknown axis key", base + "axes:\n  - key: gait.duty_factor\n    vals: [0.5]\n",
       "axes[0].vals: unknown key, allowed here: key, range, values"},
      {"values and range",
       base + "axes:\n  - key: gait.duty_factor\n    values: [0.5]\n    range: {from: 0.5, to: "
              "0.6, count: 2}\n",
       "axes[0]: got both values and range, expected exactly one of them"},
      {"empty values", base + "axes:\n  - key: gait.duty_factor\n    values: []\n",
       "axes[0].values: got [], expected a non-empty list"},
      {"a list as a value", base + "axes:\n  - key: gait.duty_factor\n    values: [[0.5]]\n",
       "axes[0].values[0]: got [0.5], expected a single value"},
      {"duplicate values", base + "axes:\n  - key: gait.duty_factor\n    values: [0.5, 1/2]\n",
       "axes[0].values: got 1/2 twice (values 0 and 1), expected distinct values"},
      {"range count",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: 0.5, to: 0.6, count: 1}\n",
       "axes[0].range.count: got 1, expected an integer in [2, 100000]"},
      {"range bound",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: .nan, to: 0.6, count: 3}\n",
       "axes[0].range.from: got .nan, expected a finite number"},
      {"range empty",
       base + "axes:\n  - key: gait.duty_factor\n    range: {from: 0.6, to: 0.6, count: 3}\n",
       "axes[0].range: got from = to = 0.6, expected from != to"},
      {"set makes the base invalid", base + "set:\n  output.grid: fine\n" + axis,
       "(base " + kConfigs +
           "/sweeps/stairs_base.yaml): output.grid: got fine, expected one of uniform, adaptive"},
      {"set of an unknown key", base + "set:\n  output.gird: uniform\n" + axis,
       "output.gird: unknown key"},
      {"set with a nested map", base + "set:\n  output: {grid: uniform}\n" + axis,
       "set.output: got {grid: uniform}, expected a value or a list"},
      {"too many scenarios",
       base +
           "axes:\n  - key: terrain.riser_height\n    range: {from: 0.01, to: 0.1, count: 100000}\n"
           "  - key: gait.duty_factor\n    range: {from: 0.5, to: 0.9, count: 100}\n",
       "axes: got more than 1000000 scenarios"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("s.yaml", c.text);
    const std::string msg = message_of(path);
    INFO(c.what << ": " << msg);
    CHECK(msg.find(c.names) != std::string::npos);
    CHECK(msg.rfind(path, 0) == 0);  // starts with the sweep file's path
    CHECK(msg.find('\n') == std::string::npos);
  }
}

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
        "0 ok, 1 config, 2 reach, 3 planning, 4 solver, 5 error, 6 internal");
}

namespace {

/// A run with torques τ_k(t) = a_k + b_k t on a grid that is uniform except for a dense
/// cluster of samples (as the adaptive grid has at touchdowns).
RunResult linear_torque_run(double t0, double t1, std::vector<double>& a, std::vector<double>& b) {
  std::vector<double> t;
  const int coarse = 2000;
  for (int i = 0; i <= coarse; ++i) t.push_back(t0 + (t1 - t0) * i / coarse);
  for (int i = 1; i < 400; ++i) t.push_back(t0 + 0.3 * (t1 - t0) + 1e-6 * i);  // dense cluster
  std::sort(t.begin(), t.end());
  const int T = static_cast<int>(t.size());
  RunResult r;
  r.kin.time_s = t;
  r.dyn.present = true;
  r.dyn.joint_torque.resize(T, kJoints);
  a.resize(kJoints);
  b.resize(kJoints);
  for (int k = 0; k < kJoints; ++k) {
    a[k] = 0.3 * (k - 8.5);
    b[k] = 0.1 * ((k * 7) % 5 - 2);
    for (int i = 0; i < T; ++i) r.dyn.joint_torque(i, k) = a[k] + b[k] * t[i];
  }
  r.dyn.solver_status.assign(T, SolverStatus::kOptimal);
  r.dyn.solver_status[3] = SolverStatus::kRelaxed;
  r.dyn.solver_status[4] = SolverStatus::kRelaxed;
  r.dyn.solver_status[9] = SolverStatus::kFailed;
  r.dyn.energy_total_J = 12.5;
  r.dyn.cost_of_transport = 0.8;
  r.dyn.distance_m = 0.25;
  r.dyn.impacts = {{1, 0.1, 1e-3, 40.0, 0.01, 0.1, 0.05}, {3, 0.2, 1e-3, 64.5, 0.01, 0.1, 0.05}};
  return r;
}

}  // namespace

TEST_CASE("sweep: summary metrics against closed forms", "[sweep]") {
  const double t0 = 0.5, t1 = 3.0;
  std::vector<double> a, b;
  const RunResult run = linear_torque_run(t0, t1, a, b);
  const ScenarioSummary s = summarize_run(run, 7);
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
  for (int k = 0; k < kJoints; ++k) {
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
  r.dyn.joint_torque = RowMatrix::Constant(4, kJoints, -1.5);
  r.dyn.solver_status.assign(4, SolverStatus::kOptimal);
  const ScenarioSummary s = summarize_run(r, 0);
  CHECK(s.peak_impact_force_N == 0.0);
  for (int k = 0; k < kJoints; ++k) {
    CHECK(s.peak_torque_Nm[k] == 1.5);
    CHECK(s.rms_torque_Nm[k] == Approx(1.5).epsilon(1e-14));
  }
  r.kin.time_s = {0.2};
  r.dyn.joint_torque = RowMatrix::Constant(1, kJoints, 2.0);
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

TEST_CASE("sweep: the sweep file holds axes, rows in index order and kept runs", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(
      sweep_file(dir,
                 "set:\n  output.grid: uniform\n  output.sample_step: 0.1\n  motion.cycles: 1\n"
                 "axes:\n  - key: gait.duty_factor\n    values: [1/2, 1.2]\n"
                 "  - key: allocation.friction\n    values: [pyramid4, cone]\n"));
  const std::string out = (dir.path / "sweep.h5").string();
  Checkpoint cp(out, spec, true, false);
  std::vector<ScenarioSummary> rows(spec.scenario_count());
  for (std::size_t i = rows.size(); i-- > 0;) {  // completion order need not be index order
    const ScenarioOutcome o = run_scenario(scenario_input(spec, i), true);
    cp.store(i, encode_checkpoint(o, dir.path.string()));
    rows[i] = read_checkpoint_summary(cp.scenario_path(i));
  }
  write_sweep_file(out, spec, rows, &cp, {2, 3.5, 1});
  const H5Reader r(out);
  CHECK(r.string_attribute("/meta", "schema") == schema::kSweepSchema);
  CHECK(r.int_attribute("/meta", "schema_version") == 1);
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
  // Kept runs: computed scenarios only, in the hexdyn-result/1 layout.
  CHECK(r.string_attribute("/runs/000001/meta", "schema") == schema::kResultSchema);
  CHECK(r.read_doubles("/runs/000001/energy/total").values[0] == rows[1].energy_J);
  CHECK_FALSE(r.exists("/runs/000002"));
  // The file is complete: no temporary files next to it.
  for (const auto& e : fs::directory_iterator(dir.path))
    CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
}

TEST_CASE("sweep: progress lines are throttled and give rate and time left", "[sweep]") {
  using Clock = ProgressMeter::Clock;
  const Clock::time_point t0{};
  ProgressMeter m(100, 20, 5.0, t0);
  CHECK_FALSE(m.update(25, 0, t0 + std::chrono::seconds(2)).has_value());  // too soon
  const auto line = m.update(30, 1, t0 + std::chrono::seconds(5));
  REQUIRE(line.has_value());
  // 10 computed in 5 s: 2 per second, 70 left: 35 s.
  CHECK(*line == "hexdyn: sweep: 30/100 done, 1 failed, 2 scenarios/s, 35 s left, 5 s elapsed");
  CHECK_FALSE(m.update(30, 1, t0 + std::chrono::seconds(20)).has_value());  // nothing new
  CHECK_FALSE(m.update(31, 1, t0 + std::chrono::seconds(9)).has_value());   // too soon again
  CHECK(m.update(100, 1, t0 + std::chrono::seconds(40)).value() ==
        "hexdyn: sweep: 100/100 done, 1 failed, 2 scenarios/s, 40 s elapsed");
  CHECK(format_duration(125) == "2 min 05 s");
  CHECK(format_duration(7300) == "2 h 01 min");
}
