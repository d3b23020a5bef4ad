// Checkpoints (src/hexdyn/sweep/record.*, journal.*, checkpoint.*): records round-trip a
// row; journals detect damaged, truncated and foreign records; the checkpoint directory's
// resume rules, identity and lock.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "hexdyn/sweep/checkpoint.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

namespace {

ScenarioSummary some_row(std::size_t index) {
  ScenarioSummary s;
  s.index = index;
  s.samples = 61;
  s.energy_J = 12.5 + static_cast<double>(index);
  s.cost_of_transport = 0.25;
  s.duration_s = 3.0;
  s.distance_m = 0.25;
  s.peak_impact_force_N = 40.0;
  s.joints = 18;
  for (int k = 0; k < s.joints; ++k) {
    s.peak_torque_Nm[static_cast<std::size_t>(k)] = 0.1 * k;
    s.rms_torque_Nm[static_cast<std::size_t>(k)] = 0.01 * k;
  }
  s.relaxed_samples = 3;
  s.wall_time_s = 0.5;
  return s;
}

std::vector<char> payload_of(const ScenarioSummary& s) { return encode_record({s, {}}); }

std::vector<char> read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void write_all(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string only_journal(const std::string& dir) {
  std::string found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".hxj") found = e.path().string();
  return found;
}

}  // namespace

TEST_CASE("sweep: CRC-32 is zlib's (check value of \"123456789\")", "[sweep]") {
  CHECK(crc32("123456789", 9) == 0xCBF43926u);
  // Incremental = at once.
  CHECK(crc32("56789", 5, crc32("1234", 4)) == 0xCBF43926u);
  CHECK(crc32("", 0) == 0u);
}

TEST_CASE("sweep: a record round-trips a row and its run image", "[sweep]") {
  ScenarioRecord r{some_row(7), {'\0', '\x89', 'H', 'D', 'F'}};
  r.summary.message = "scenario 000007: foothold out of reach";
  const std::vector<char> b = encode_record(r);
  const ScenarioRecord back = decode_record(b.data(), b.size());
  CHECK(back.summary.index == 7);
  CHECK(back.summary.message == r.summary.message);
  CHECK(back.summary.energy_J == r.summary.energy_J);
  REQUIRE(back.summary.joints == 18);
  for (std::size_t k = 0; k < 18; ++k) {
    CHECK(back.summary.peak_torque_Nm[k] == r.summary.peak_torque_Nm[k]);
    CHECK(back.summary.rms_torque_Nm[k] == r.summary.rms_torque_Nm[k]);
  }
  CHECK(back.summary.relaxed_samples == 3);
  CHECK(back.run_image == r.run_image);
  const ScenarioSummary failed = failed_summary(3, ScenarioStatus::kCrashed, "died");
  const std::vector<char> fb = payload_of(failed);
  const ScenarioSummary f = decode_record(fb.data(), fb.size()).summary;
  CHECK(f.status == ScenarioStatus::kCrashed);
  CHECK(std::isnan(f.energy_J));
  CHECK_THROWS_AS(decode_record(b.data(), b.size() - 1), IoError);
}

TEST_CASE("sweep: a journal finds damaged, truncated and foreign records", "[sweep]") {
  std::vector<InputFile> inputs(1);
  inputs[0].role = "sweep file";
  inputs[0].path = inputs[0].absolute = "/s.yaml";
  inputs[0].sha256 = std::string(64, 'a');
  const SweepIdentity id = make_identity(inputs, "base", "build", 10, false);
  std::vector<char> j = journal_header(id);
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < 4; ++i) {
    starts.push_back(j.size());
    const auto p = payload_of(some_row(i));
    append_journal_record(j, RecordKind::kRow, i, id, p.data(), p.size());
  }
  SECTION("intact") {
    const JournalScan s = scan_journal(j.data(), j.size(), "J", id);
    CHECK(s.header_ok);
    CHECK(s.header.id == id.id);
    CHECK(id.difference(s.header).empty());  // the inputs read back from the header
    REQUIRE(s.header.inputs.size() == 1);
    CHECK(s.header.inputs[0].sha256 == inputs[0].sha256);
    CHECK(s.damage.empty());
    REQUIRE(s.entries.size() == 4);
    CHECK(s.entries[3].index == 3);
  }
  SECTION("a flipped byte in a payload: that record only, named") {
    j[starts[1] + 40] ^= 0x5A;
    const JournalScan s = scan_journal(j.data(), j.size(), "J", id);
    REQUIRE(s.entries.size() == 3);
    CHECK(s.entries[1].index == 2);
    REQUIRE(s.damage.size() == 1);
    CHECK_THAT(s.damage[0], Catch::Contains("scenario 000001") && Catch::Contains("checksum"));
  }
  SECTION("a flipped byte in a length field: found again at the next record") {
    j[starts[2] + 24 + 5] ^= 0x01;
    const JournalScan s = scan_journal(j.data(), j.size(), "J", id);
    CHECK(s.entries.size() == 3);
    CHECK(s.damage.size() == 1);
  }
  SECTION("a cut-off last record") {
    j.resize(j.size() - 7);
    const JournalScan s = scan_journal(j.data(), j.size(), "J", id);
    CHECK(s.entries.size() == 3);
    REQUIRE(s.damage.size() == 1);
    CHECK_THAT(s.damage[0], Catch::Contains("truncated"));
  }
  SECTION("a damaged header: records still checked one by one") {
    j[3] ^= 0x20;
    const JournalScan s = scan_journal(j.data(), j.size(), "J", id);
    CHECK_FALSE(s.header_ok);
    CHECK(s.entries.size() == 4);
  }
  SECTION("records of another sweep") {
    std::vector<InputFile> changed = inputs;
    changed[0].sha256 = std::string(64, 'b');
    const SweepIdentity other = make_identity(changed, "base", "build", 10, false);
    CHECK_THAT(other.difference(id),
               Catch::Contains("the sweep file /s.yaml changed since the checkpoint was made"));
    const JournalScan s = scan_journal(j.data(), j.size(), "J", other);
    CHECK(s.foreign_record);
    CHECK(s.entries.empty());
  }
}

TEST_CASE("sweep: checkpoint directory, resume rules, identity and lock", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const std::string out = (dir.path / "out.h5").string();
  const std::string cpdir = out + ".checkpoint";
  {
    Checkpoint cp(out, spec, false, false);
    CHECK(cp.finished().empty());
    // A second sweep on the same output while this one runs: refused, saying so.
    try {
      Checkpoint second(out, spec, false, true);
      FAIL("a second sweep took a live checkpoint");
    } catch (const IoError& e) {
      CHECK_THAT(std::string(e.what()),
                 Catch::Contains("still running") && !Catch::Contains("remove"));
    }
    for (std::size_t i : {4u, 1u, 6u}) {
      const auto p = payload_of(some_row(i));
      cp.append_row(i, p.data(), p.size());
    }
    cp.append_crash(9, "killed by signal 6");
    cp.flush(true);
    CHECK(cp.journal_count() == 1);
  }
  // Not resumed: an interrupted sweep is not overwritten.
  CHECK_THROWS_WITH(Checkpoint(out, spec, false, false), Catch::Contains("--resume"));
  {
    Checkpoint cp(out, spec, false, true);
    REQUIRE(cp.finished().size() == 3);
    CHECK(cp.finished()[1].index == 1);
    CHECK(cp.finished()[1].energy_J == some_row(1).energy_J);
    CHECK(cp.crash_attempts() == std::vector<std::size_t>{9});
    CHECK(cp.warnings().empty());
    const auto p = payload_of(some_row(2));
    cp.append_row(2, p.data(), p.size());
    cp.flush(false);
    CHECK(cp.journal_count() == 2);  // one journal per run, not per scenario
  }
  // Another sweep, or the same one with another --keep-runs: refused whole.
  const SweepSpec other = load_sweep(sweep_file(dir, kSmallAxes + "# other\n", "t.yaml"));
  CHECK_THROWS_WITH(Checkpoint(out, other, false, true),
                    Catch::Contains("another sweep") && Catch::Contains("sweep file"));
  CHECK_THROWS_WITH(Checkpoint(out, spec, true, true), Catch::Contains("without --keep-runs"));
  // Every journal's header lost: the records still name their sweep.
  for (const auto& e : fs::directory_iterator(cpdir))
    if (e.path().extension() == ".hxj") {
      std::vector<char> b = read_all(e.path().string());
      std::memset(b.data(), 'X', 64);
      write_all(e.path().string(), b);
    }
  CHECK_THROWS_WITH(Checkpoint(out, other, false, true), Catch::Contains("another sweep"));
  {
    Checkpoint cp(out, spec, false, true);
    CHECK(cp.finished().size() == 4);
    CHECK(cp.warnings().size() == 2);  // one damaged header per journal
  }
  // A checkpoint that is done is removed with its lock.
  Checkpoint last(out, spec, false, true);
  last.remove();
  CHECK_FALSE(fs::exists(cpdir));
}

TEST_CASE("sweep: a damaged record is named and its scenario recomputed", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const std::string out = (dir.path / "out.h5").string();
  {
    Checkpoint cp(out, spec, false, false);
    for (std::size_t i = 0; i < 5; ++i) {
      const auto p = payload_of(some_row(i));
      cp.append_row(i, p.data(), p.size());
    }
    cp.flush(false);
  }
  const std::string journal = only_journal(out + ".checkpoint");
  std::vector<char> b = read_all(journal);
  std::uint32_t header = 0;  // the header's size (journal.hpp)
  std::memcpy(&header, b.data() + 8, sizeof header);
  const std::size_t record = (b.size() - header) / 5;  // records of equal size
  b[header + 2 * record + 100] ^= 0x10;                // inside scenario 2's record
  b.resize(b.size() - 3);                              // and the last one cut short
  write_all(journal, b);
  Checkpoint cp(out, spec, false, true);
  std::vector<std::size_t> got;
  for (const auto& r : cp.finished()) got.push_back(r.index);
  CHECK(got == std::vector<std::size_t>{0, 1, 3});
  REQUIRE(cp.warnings().size() == 2);
  CHECK_THAT(cp.warnings()[0], Catch::Contains("scenario 000002"));
  CHECK_THAT(cp.warnings()[1], Catch::Contains("truncated"));
}

// A worker builds its rows' journal records (mpi/worker.cpp) and rank 0 appends them
// (append_row_record): the journal must be byte for byte the one rank 0 writes when it builds
// the records itself (append_row), resume must read it back, and a record whose header does
// not match (kind, scenario, sweep, length, magic) must be refused before it is appended.
TEST_CASE("sweep: a record built by a worker is appended as rank 0 would build it", "[sweep]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const SweepIdentity id = sweep_identity(spec, false);
  std::vector<std::vector<char>> journals;
  for (bool built_by_worker : {false, true}) {
    const std::string out = (dir.path / (built_by_worker ? "w.h5" : "r.h5")).string();
    {
      Checkpoint cp(out, spec, false, false);
      CHECK(cp.identity().id == id.id);
      for (std::size_t i : {3u, 0u, 5u}) {
        const auto p = payload_of(some_row(i));
        if (!built_by_worker) {
          cp.append_row(i, p.data(), p.size());
          continue;
        }
        std::vector<char> record;
        append_journal_record(record, RecordKind::kRow, i, id, p.data(), p.size());
        const BuiltRecord b = cp.append_row_record(i, record.data(), record.size());
        CHECK(std::vector<char>(b.payload, b.payload + b.size) == p);
      }
      cp.flush(true);
      journals.push_back(read_all(only_journal(out + ".checkpoint")));
    }
    Checkpoint resumed(out, spec, false, true);
    REQUIRE(resumed.finished().size() == 3);
    CHECK(resumed.finished()[2].energy_J == some_row(5).energy_J);
    CHECK(resumed.warnings().empty());
  }
  CHECK(journals[0] == journals[1]);

  const auto p = payload_of(some_row(1));
  std::vector<char> good;
  append_journal_record(good, RecordKind::kRow, 1, id, p.data(), p.size());
  const SweepIdentity other = sweep_identity(spec, true);
  std::vector<char> foreign, crash;
  append_journal_record(foreign, RecordKind::kRow, 1, other, p.data(), p.size());
  append_journal_record(crash, RecordKind::kCrashAttempt, 1, id, p.data(), p.size());
  std::vector<char> bad_magic = good;
  bad_magic[0] ^= 1;
  const char* g = good.data();
  CHECK(check_built_record(g, good.size(), RecordKind::kRow, 1, id).size == p.size());
  CHECK_THROWS_WITH(check_built_record(g, good.size(), RecordKind::kRow, 2, id),
                    Catch::Contains("another scenario"));
  CHECK_THROWS_WITH(check_built_record(g, good.size() - 1, RecordKind::kRow, 1, id),
                    Catch::Contains("wrong length"));
  CHECK_THROWS_WITH(check_built_record(foreign.data(), foreign.size(), RecordKind::kRow, 1, id),
                    Catch::Contains("another sweep"));
  CHECK_THROWS_WITH(check_built_record(crash.data(), crash.size(), RecordKind::kRow, 1, id),
                    Catch::Contains("another kind"));
  CHECK_THROWS_WITH(check_built_record(bad_magic.data(), bad_magic.size(), RecordKind::kRow, 1, id),
                    Catch::Contains("not a record"));
  CHECK_THROWS_WITH(check_built_record(g, 20, RecordKind::kRow, 1, id),
                    Catch::Contains("not a record"));
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// `text` with its first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

// Edited inputs: the checkpoint's identity covers the content of every input. A sweep over a
// scene that inherits the Kraby scene and names its URDF, with a robot.urdf axis over two
// copies of the URDF, is checkpointed; then each input in turn is edited: the resume is
// refused in one line naming that file, and accepted again once the file is restored.
TEST_CASE("sweep: a resume after any input's content changed is refused, naming the file",
          "[sweep]") {
  TempDir dir;
  const std::string urdf_text = read_text(std::string(HEXDYN_SOURCE_DIR) + "/robots/kraby.urdf");
  const std::string urdf = dir.write("kraby.urdf", urdf_text);
  const std::string urdf_b = dir.write("kraby_b.urdf", urdf_text);
  const std::string robot_text = replaced(read_text(kConfigs + "/robots/kraby_stairs.yaml"),
                                          "../../robots/kraby.urdf", "kraby.urdf");
  const std::string robot = dir.write("robot.yaml", robot_text);
  const std::string scene_text = "inherit: robot.yaml\noutput:\n  grid: uniform\n";
  const std::string scene = dir.write("scene.yaml", scene_text);
  const std::string sweep_text = "base: scene.yaml\naxes:\n  - key: robot.urdf\n    values: [" +
                                 urdf + ", " + urdf_b +
                                 "]\n  - key: terrain.riser_height\n    values: [0.02, 0.04]\n";
  const std::string sweep = dir.write("s.yaml", sweep_text);
  const SweepSpec spec = load_sweep(sweep);
  std::vector<std::string> roles;
  for (const InputFile& f : spec.inputs) roles.push_back(f.role);
  CHECK(roles ==
        std::vector<std::string>{"sweep file", "base scene", "inherited scene", "URDF", "URDF"});
  const std::string out = (dir.path / "out.h5").string();
  {
    Checkpoint cp(out, spec, false, false);
    const auto p = payload_of(some_row(1));
    cp.append_row(1, p.data(), p.size());
    cp.flush(true);
  }
  // The URDF's mass edited (`sed -i '25s/0.667/1.667/'`).
  const std::string heavier =
      replaced(urdf_text, "<mass value=\"0.667\" />", "<mass value=\"1.667\" />");
  const struct {
    std::string path, original, edited, role;
  } edits[] = {
      {urdf, urdf_text, heavier, "URDF"},
      {urdf_b, urdf_text, heavier, "URDF"},
      {robot, robot_text, replaced(robot_text, "stroke: 0.025", "stroke: 0.026"),
       "inherited scene"},
      {scene, scene_text, scene_text + "# a comment is content too\n", "base scene"},
      {sweep, sweep_text, sweep_text + "name: renamed\n", "sweep file"},
  };
  for (const auto& e : edits) {
    dir.write(fs::path(e.path).filename().string(), e.edited);
    try {
      Checkpoint cp(out, load_sweep(sweep), false, true);
      FAIL("a resume was accepted after " << e.path << " changed");
    } catch (const ConfigError& err) {
      const std::string what = err.what();
      CHECK(what.find('\n') == std::string::npos);
      CHECK_THAT(what, Catch::Contains("the " + e.role + " " + e.path +
                                       " changed since the "
                                       "checkpoint was made"));
    }
    dir.write(fs::path(e.path).filename().string(), e.original);
  }
  // Every input as it was: the checkpoint is resumed.
  Checkpoint cp(out, load_sweep(sweep), false, true);
  REQUIRE(cp.finished().size() == 1);
  CHECK(cp.finished()[0].index == 1);
}
