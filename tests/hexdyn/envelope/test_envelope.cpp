// The climbable envelope (envelope/envelope.hpp): its boundaries checked by runs of the
// pipeline made here, not through the envelope's own probes: just below a boundary the
// run succeeds, just above it it fails for the reason the envelope names; the file it
// writes holds the declared layout.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/envelope/envelope.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";

std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// A one-cell envelope file in a temporary directory.
struct TempSpec {
  fs::path dir;
  std::string path;
  explicit TempSpec(const std::string& body) {
    static int count = 0;
    dir = fs::temp_directory_path() /
          ("hexdyn_envelope_test_" + std::to_string(::getpid()) + "_" + std::to_string(count++));
    fs::create_directories(dir);
    path = (dir / "envelope.yaml").string();
    std::ofstream(path) << "base: " << kConfigs << "/sweeps/stairs_base.yaml\n" << body;
  }
  ~TempSpec() { fs::remove_all(dir); }
};

Scene stairs(double riser, double tread, double beta, double speed,
             std::vector<Override> extra = {}) {
  extra.push_back({"terrain.riser_height", exact(riser)});
  extra.push_back({"terrain.tread_depth", exact(tread)});
  extra.push_back({"gait.duty_factor", exact(beta)});
  extra.push_back({"motion.peak_speed", exact(speed)});
  return load_scene(kConfigs + "/sweeps/stairs_base.yaml", extra);
}

/// Relaxed or failed allocation samples while no leg is in a touchdown transient, and
/// the message of the first.
int support_relaxed(const RunResult& run, std::string* first) {
  int n = 0;
  for (int i = 0; i < run.kin.samples(); ++i) {
    if (run.dyn.solver_status[i] == SolverStatus::kOptimal) continue;
    bool impact = false;
    for (int leg = 0; leg < run.kin.contact_phase.cols(); ++leg)
      impact = impact || run.kin.contact_phase(i, leg) == 1;
    if (!impact && n++ == 0 && first) *first = run.dyn.solver_messages[i];
  }
  return n;
}

TEST_CASE(
    "envelope: kinematic boundary at the paper tread: below it runs, above it is out of reach",
    "[envelope]") {
  TempSpec t(
      "riser: {from: 0.06, to: 0.20, step: 0.02, tolerance: 0.001}\n"
      "tread_depth: [0.25]\nduty_factor: [1/2]\npeak_speed: [0.1]\ncriteria: [kinematic]\n");
  const EnvelopeSpec spec = load_envelope_spec(t.path);
  const EnvelopeResult r = compute_envelope(spec, nullptr);
  REQUIRE(r.boundary.size() == 1);
  const EnvelopeBoundary& b = r.boundary[0];
  INFO("riser_max " << b.riser_max_m << " riser_fail " << b.riser_fail_m << ": " << b.message);
  // The paper robot's reach: nothing kinematic forbids risers below 6 cm at 0.25 m treads.
  REQUIRE(std::isfinite(b.riser_max_m));
  CHECK(b.riser_max_m >= 0.06);
  REQUIRE(std::isfinite(b.riser_fail_m));
  CHECK(b.riser_fail_m - b.riser_max_m <= 0.001 + 1e-12);
  // Just below: the whole pipeline runs (no reach error on its adaptive grid).
  const RunResult below = run_scene(stairs(b.riser_max_m, 0.25, 0.5, 0.1));
  CHECK(below.kin.samples() > 100);
  // Just above: the run is refused, naming the leg and the constraint the envelope names.
  const std::string constraint = b.limit.substr(b.limit.find(' ', 4) + 1);  // after "leg Lx "
  try {
    (void)run_scene(stairs(b.riser_fail_m, 0.25, 0.5, 0.1));
    FAIL("riser " << b.riser_fail_m << " ran");
  } catch (const ReachError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK(m.find(b.limit.substr(0, 6)) != std::string::npos);  // "leg Lx"
    CHECK(m.find(constraint) != std::string::npos);
  }
}

TEST_CASE(
    "envelope: torque boundary: below it no relaxed support sample, above it the named torque",
    "[envelope]") {
  // β = 3/4 at 0.2 m/s: near full extension the swing legs need more than 6 N m.
  TempSpec t(
      "riser: {from: 0.15, to: 0.17, step: 0.01, tolerance: 0.001}\n"
      "tread_depth: [0.25]\nduty_factor: [3/4]\npeak_speed: [0.2]\ncriteria: [torque]\n");
  const EnvelopeSpec spec = load_envelope_spec(t.path);
  const EnvelopeResult r = compute_envelope(spec, nullptr);
  const EnvelopeBoundary& b = r.boundary[0];
  INFO("riser_max " << b.riser_max_m << " riser_fail " << b.riser_fail_m << ": " << b.message);
  REQUIRE(std::isfinite(b.riser_max_m));
  REQUIRE(std::isfinite(b.riser_fail_m));
  REQUIRE(b.limit.rfind("torque L", 0) == 0);
  const std::vector<Override> lifted{{"contact.friction_coefficient", "10"}};
  std::string first;
  CHECK(support_relaxed(run_scene(stairs(b.riser_max_m, 0.25, 0.75, 0.2, lifted)), &first) == 0);
  CHECK(support_relaxed(run_scene(stairs(b.riser_fail_m, 0.25, 0.75, 0.2, lifted)), &first) > 0);
  INFO(first);
  CHECK(first.find(b.limit) != std::string::npos);
}

/// Support samples (no leg in a touchdown transient) with a slip flag on some leg.
int support_slips(const RunResult& run) {
  int n = 0;
  for (int i = 0; i < run.kin.samples(); ++i) {
    bool impact = false, slip = false;
    for (int leg = 0; leg < run.kin.contact_phase.cols(); ++leg) {
      impact = impact || run.kin.contact_phase(i, leg) == 1;
      slip = slip || run.dyn.slip(i, leg) != 0;
    }
    n += !impact && slip;
  }
  return n;
}

TEST_CASE("envelope: friction search: the least mu per riser holds the climb, 1e-3 less does not",
          "[envelope]") {
  // The second computation: the scene itself run at the scene's mu just above and just below
  // the searched mu* (the required friction does not depend on the scene's mu, so one run
  // per riser gives it; docs/user/envelope.md#the-least-friction-per-riser).
  TempSpec t(
      "search: friction\nriser: {from: 0.0, to: 0.06, step: 0.06}\n"
      "tread_depth: [0.25]\nduty_factor: [1/2]\npeak_speed: [0.1]\n");
  const EnvelopeSpec spec = load_envelope_spec(t.path);
  REQUIRE(spec.search == EnvelopeSearch::kFriction);
  REQUIRE(spec.scan_risers() == std::vector<double>{0.0, 0.06});
  const EnvelopeResult r = compute_envelope(spec, nullptr);
  REQUIRE(r.required_friction.size() == 2);
  REQUIRE(r.probes.size() == 2);
  const double mu = r.required_friction[1];
  INFO("mu* " << mu << " at t = " << r.required_friction_time_s[1] << " s, leg "
              << r.required_friction_leg[1]);
  REQUIRE(std::isfinite(mu));
  CHECK(mu > 0.0);
  CHECK(r.required_friction_leg[1] >= 0);
  for (const double dmu : {1e-3, -1e-3}) {
    Scene scene = envelope_probe_scene(spec, 0, 0.06, EnvelopeCriterion::kFriction);
    scene.contact.friction_coefficient = mu + dmu;
    const RunResult run = run_scene(scene);
    std::string first;
    const int relaxed = support_relaxed(run, &first), slips = support_slips(run);
    INFO("mu " << mu + dmu << ": " << relaxed << " relaxed, " << slips
               << " slipping support samples; " << first);
    if (dmu > 0) {
      CHECK(relaxed == 0);
      CHECK(slips == 0);
    } else {
      // Below mu* some support sample cannot hold. The allocation's L1 weights let the trunk
      // rows (100) give way before the friction rows (1000), so the sample is relaxed in its
      // trunk rows and need not carry a slip flag (docs/theory/grip.md#slip-onset).
      CHECK(relaxed + slips > 0);
    }
  }
  // The file: the risers and the least mu per cell and riser.
  const std::string file = (t.dir / "friction.h5").string();
  write_envelope_file(file, spec, r);
  const H5Reader h(file);
  CHECK(h.dims(schema::kEnvelopeRequiredFriction.path) == std::vector<std::size_t>{1, 1, 1, 2});
  CHECK(h.read_doubles(schema::kEnvelopeRequiredFriction.path).values[1] == mu);
  CHECK(h.read_doubles(schema::kEnvelopeRisers.path).values == spec.scan_risers());
}

TEST_CASE("envelope: the file holds the declared layout and the boundaries", "[envelope]") {
  TempSpec t(
      "riser: {from: 0.0, to: 0.04, step: 0.02, tolerance: 0.01}\n"
      "duty_factor: [1/2, 3/4]\npeak_speed: [0.1]\ncriteria: [kinematic, friction]\n");
  const EnvelopeSpec spec = load_envelope_spec(t.path);
  CHECK(spec.tread_depth_m == std::vector<double>{0.25});  // the base scene's
  const EnvelopeResult r = compute_envelope(spec, nullptr);
  const std::string file = (t.dir / "envelope.h5").string();
  write_envelope_file(file, spec, r);
  const H5Reader h(file);
  CHECK(h.string_attribute("/meta", "schema") == schema::kEnvelopeSchema);
  for (const auto& d : schema::kEnvelopeDatasets) {
    INFO(d.path);
    CHECK(h.exists(d.path));
  }
  CHECK(h.dims(schema::kEnvelopeRiserMax.path) == std::vector<std::size_t>{1, 2, 1, 2});
  const auto rmax = h.read_doubles(schema::kEnvelopeRiserMax.path).values;
  for (std::size_t i = 0; i < rmax.size(); ++i) CHECK(rmax[i] == 0.04);  // nothing fails up to 4 cm
  CHECK(h.read_strings(schema::kProbeMessage.path).size() == r.probes.size());
}

TEST_CASE("envelope: a bad envelope file is refused with the key named", "[envelope]") {
  TempSpec t("riser: {from: 0.1, to: 0.05}\nduty_factor: [1/2]\npeak_speed: [0.1]\n");
  try {
    (void)load_envelope_spec(t.path);
    FAIL("accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("riser.to: got 0.05") != std::string::npos);
  }
  TempSpec u(
      "riser: {from: 0.0, to: 0.1}\nduty_factor: [1/2]\npeak_speed: [0.1]\ncriteria: [grip]\n");
  CHECK_THROWS_AS(load_envelope_spec(u.path), ConfigError);
}

/// "[a, a + d, …]" of n values.
std::string values(double a, double d, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + exact(a + d * i);
  return s + "]";
}

/// The ConfigError message of loading `t`, "" when it loads.
std::string load_error(const TempSpec& t) {
  try {
    (void)load_envelope_spec(t.path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The cells (D × W × B × V) and the probes they plan are counted in 64-bit arithmetic and
// refused beyond kMaxEnvelopeCells and kMaxEnvelopeProbes before anything is made per cell,
// in one line naming the key; at the limits the file loads (every cell validated).
TEST_CASE("envelope: cells and probes are bounded before any cell is made", "[envelope][sizes]") {
  REQUIRE(kMaxEnvelopeCells == 10000);
  REQUIRE(kMaxEnvelopeProbes == 1000000);
  const std::string riser = "riser: {from: 0.0, to: 0.1, step: 0.01, tolerance: 0.001}\n";
  // 100 × 100 cells of one criterion: 10,000 cells, 10,000 × (11 + 5) probes at most.
  TempSpec inside(riser + "duty_factor: " + values(0.5, 0.002, 100) +
                  "\npeak_speed: " + values(0.05, 0.001, 100) + "\ncriteria: [kinematic]\n");
  const auto start = std::chrono::steady_clock::now();
  const std::string ok = load_error(inside);
  INFO(ok);
  CHECK(ok.empty());
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(30));
  TempSpec beyond(riser + "duty_factor: " + values(0.5, 0.002, 101) +
                  "\npeak_speed: " + values(0.05, 0.001, 100) + "\ncriteria: [kinematic]\n");
  std::string msg = load_error(beyond);
  CHECK(msg.rfind(beyond.path + ": duty_factor: got 101 values, 10100 cells (cases 1 x "
                                "tread_depth 1 x duty_factor 101 x peak_speed 100), expected at "
                                "most 10000 cells",
                  0) == 0);
  // 2^32 cells (an int wrapped it to 0) and 1300^3 (an int wrapped it negative).
  for (const auto& [w, b, v] : {std::tuple{4096, 1024, 1024}, std::tuple{1300, 1300, 1300}}) {
    TempSpec big(riser + "tread_depth: " + values(0.2, 1e-5, w) + "\nduty_factor: " +
                 values(0.5, 1e-4, b) + "\npeak_speed: " + values(0.05, 1e-5, v) + "\n");
    msg = load_error(big);
    INFO(msg);
    const std::string cells = std::to_string(std::uint64_t(w) * b * v);
    CHECK(msg.rfind(
              big.path + ": tread_depth: got " + std::to_string(w) + " values, " + cells + " cells",
              0) == 0);
  }
  // One list longer than the limit is refused before its values are compared pairwise.
  TempSpec long_list(riser + "duty_factor: [1/2]\npeak_speed: " + values(0.05, 1e-6, 10001) + "\n");
  CHECK(load_error(long_list) ==
        long_list.path +
            ": peak_speed: got 10001 values, expected at most 10000 (an envelope has "
            "at most 10000 cells)");
  // Probes: a fine riser scan over the paper's 64 cells and 3 criteria.
  const std::string grid =
      "tread_depth: [0.2, 0.25, 0.3, 0.35]\nduty_factor: [1/2, 2/3, 3/4, "
      "5/6]\npeak_speed: [0.05, 0.1, 0.15, 0.2]\n";
  TempSpec fine("riser: {from: 0.0, to: 0.3, step: 0.00001, tolerance: 0.000001}\n" + grid);
  msg = load_error(fine);
  INFO(msg);
  CHECK(msg.rfind(fine.path + ": riser.step: got 1e-05 m, up to 5.76115e+06 planned probes (64 "
                              "cells x 3 criteria x (30001 scan steps + 5 halvings)), expected at "
                              "most 1000000",
                  0) == 0);
  const auto at = msg.find("a step of at least ");
  REQUIRE(at != std::string::npos);
  const double step = std::stod(msg.substr(at + 19));
  TempSpec coarser("riser: {from: 0.0, to: 0.3, step: " + exact(step) + ", tolerance: 0.000001}\n" +
                   grid);
  CHECK(load_error(coarser).empty());
}

TEST_CASE("envelope: cases are designs, each probe's scene the base with its keys", "[envelope]") {
  const std::string grid =
      "riser: {from: 0.0, to: 0.1}\nduty_factor: [1/2, 2/3]\npeak_speed: [0.1]\n";
  TempSpec t(grid +
             "cases:\n  - {label: light, robot.payload.mass: 0.5}\n"
             "  - {label: heavy, robot.payload.mass: 2.0}\n");
  const EnvelopeSpec spec = load_envelope_spec(t.path);
  REQUIRE(spec.cases.labels == std::vector<std::string>{"light", "heavy"});
  CHECK(spec.cell_count() == 2 * 1 * 2 * 1);
  // Cell (case, tread, duty, speed), row-major: cell 3 is heavy at β = 2/3.
  const Scene probe = envelope_probe_scene(spec, 3, 0.04, EnvelopeCriterion::kKinematic);
  const Scene expected =
      stairs(0.04, spec.tread_depth_m[0], 2.0 / 3.0, 0.1, {{"robot.payload.mass", "2.0"}});
  CHECK(probe.robot.payload.mass_kg == expected.robot.payload.mass_kg);
  CHECK(probe.gait.duty_factor == expected.gait.duty_factor);

  struct Bad {
    std::string cases, names;
  };
  for (const Bad& b : std::vector<Bad>{
           {"cases: [{label: a, gait.duty_factor: 0.5}]\n",
            "cases: got key gait.duty_factor, expected a key the envelope does not set itself"},
           {"cases: [{label: a, robot.payload.mass: 1}, {label: a, robot.payload.mass: 2}]\n",
            "cases[1].label: got a, expected a label no other case has"},
           {"cases: [{label: a, robot.payload.mass: -1}]\n",
            "cases[0] (a: robot.payload.mass=-1): robot.payload.mass: got -1"}}) {
    TempSpec bad(grid + b.cases);
    try {
      (void)load_envelope_spec(bad.path);
      FAIL("accepted: " << b.cases);
    } catch (const ConfigError& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(b.names) != std::string::npos);
      CHECK(std::string(e.what()).find('\n') == std::string::npos);
    }
  }
}

}  // namespace
}  // namespace hexdyn
