// Checkpoint faults (src/hexdyn/sweep/checkpoint.*; docs/user/faults.md#links and
// docs/user/faults.md#lost-checkpoint): links and special files in a checkpoint are
// refused before anything is written through them; a checkpoint removed or taken over
// while a sweep holds it stops the sweep (CheckpointLost) and is never removed by it.
// Whole-program cases with mpirun, FIFOs and a full disk are in tests/faults/.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <string>

#include "hexdyn/sweep/checkpoint.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

namespace {

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string refusal(const std::string& out, const SweepSpec& spec) {
  try {
    Checkpoint cp(out, spec, false, true);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("sweep: nothing in a checkpoint follows a link", "[sweep][faults]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const std::string out = (dir.path / "out.h5").string();
  const std::string cpdir = out + ".checkpoint";
  const std::string victim = (dir.path / "victim.txt").string();
  std::ofstream(victim) << "an input\n";

  SECTION("the lock a symbolic link to a file") {
    fs::create_directory(cpdir);
    fs::create_symlink(victim, cpdir + "/lock");
    CHECK_THAT(refusal(out, spec), Catch::Contains("checkpoint lock '" + cpdir + "/lock'") &&
                                       Catch::Contains("it is a symbolic link"));
  }
  SECTION("the lock a hard link of another file") {
    fs::create_directory(cpdir);
    fs::create_hard_link(victim, cpdir + "/lock");
    CHECK_THAT(refusal(out, spec), Catch::Contains("other (hard) links"));
  }
  SECTION("the lock a FIFO") {
    fs::create_directory(cpdir);
    REQUIRE(::mkfifo((cpdir + "/lock").c_str(), 0644) == 0);
    CHECK_THAT(refusal(out, spec), Catch::Contains("it is a FIFO"));
  }
  SECTION("a journal a symbolic link") {
    fs::create_directory(cpdir);
    fs::create_symlink(victim, cpdir + "/journal-0001.hxj");
    CHECK_THAT(refusal(out, spec),
               Catch::Contains("checkpoint journal") && Catch::Contains("it is a symbolic link"));
  }
  SECTION("the checkpoint folder a symbolic link to another folder") {
    const fs::path other = dir.path / "other";
    fs::create_directory(other);
    fs::create_directory_symlink(other, cpdir);
    CHECK_THAT(refusal(out, spec),
               Catch::Contains("checkpoint directory") && Catch::Contains("it is a symbolic link"));
    CHECK(fs::is_empty(other));
  }
  CHECK(text_of(victim) == "an input\n");
}

TEST_CASE("sweep: a checkpoint removed or taken over stops its sweep", "[sweep][faults]") {
  TempDir dir;
  const SweepSpec spec = load_sweep(sweep_file(dir, kSmallAxes));
  const std::string out = (dir.path / "out.h5").string();
  const std::string cpdir = out + ".checkpoint";
  const std::vector<char> payload = encode_record({ScenarioSummary{}, {}});

  Checkpoint a(out, spec, false, false);
  a.append_row(0, payload.data(), payload.size());
  a.flush(false);
  REQUIRE_NOTHROW(a.verify());

  SECTION("the folder removed, a second sweep started on the output") {
    fs::remove_all(cpdir);
    Checkpoint b(out, spec, false, false);  // admitted: nothing of A is left to find
    CHECK_THROWS_AS(a.append_row(1, payload.data(), payload.size()), CheckpointLost);
    CHECK_THROWS_WITH(a.flush(true), Catch::Contains("is no longer this sweep's"));
    // A never removes B's checkpoint.
    CHECK_THROWS_AS(a.remove(), CheckpointLost);
    CHECK(fs::exists(cpdir + "/lock"));
    b.remove();
    CHECK_FALSE(fs::exists(cpdir));
  }
  SECTION("the lock removed") {
    fs::remove(cpdir + "/lock");
    CHECK_THROWS_WITH(a.flush(false), Catch::Contains("its lock was removed or replaced"));
  }
  SECTION("the journal replaced") {
    fs::remove(cpdir + "/journal-0001.hxj");
    std::ofstream(cpdir + "/journal-0001.hxj") << "x";
    CHECK_THROWS_WITH(a.flush(false), Catch::Contains("journal-0001.hxj was removed or replaced"));
  }
  SECTION("intact: remove() deletes the checkpoint") {
    a.remove();
    CHECK_FALSE(fs::exists(cpdir));
  }
}
