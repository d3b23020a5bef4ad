// Outputs the command line must refuse before computing: devices, FIFOs,
// directories and symbolic links as -o; any input of the run (the config, an inherited
// file, a hard link to the config, the sweep file, its base scene and the base's
// inherited file), compared by identity; unwritable folders. Also the plausibility
// ranges of the gait timing and the size guard of `run`. Each refusal: exit status 2, one
// line naming the path or key and the reason, and every file unchanged.
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/cli/cli_harness.hpp"
#include "hexdyn/core/common.hpp"
#include "hexdyn/io/output.hpp"

namespace hexdyn {
namespace {

using namespace cli_test;

/// Runs `args` and checks the refusal: status 2, one line on stderr with every string of
/// `names`, every entry of the scratch directory unchanged (types and bytes).
void check_refused(const Scratch& s, const std::string& what, const std::vector<std::string>& args,
                   const std::vector<std::string>& names) {
  const auto before = s.snapshot();
  const Outcome o = run_cli(s, args, 120);
  INFO(what << "\nstderr: " << o.err);
  CHECK(o.status == 2);
  REQUIRE(!o.err.empty());
  CHECK(o.err.find('\n') == o.err.size() - 1);
  CHECK(o.err.rfind("hexdyn: error: ", 0) == 0);
  for (const auto& n : names) CHECK(o.err.find(n) != std::string::npos);
  CHECK(s.snapshot() == before);
}

bool is_char_device(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

TEST_CASE("cli outputs: special files are never replaced", "[cli][outputs]") {
  Scratch s;
  write_file(s.work / "cfg.yaml", read_file(kPaperConfig));
  fs::create_directories(s.work / "dir");
  REQUIRE(::mkfifo((s.work / "fifo.h5").c_str(), 0644) == 0);
  write_file(s.work / "target.h5", "old bytes");
  fs::create_symlink("target.h5", s.work / "link.h5");
  const auto run = [&](const std::string& out) {
    return concat({"run", "cfg.yaml", "-o", out}, kCoarse);
  };
  check_refused(s, "directory", run("dir"), {"'dir'", "is a directory"});
  check_refused(s, "FIFO", run("fifo.h5"), {"'fifo.h5'", "is a FIFO"});
  check_refused(s, "symbolic link", run("link.h5"), {"'link.h5'", "is a symbolic link"});
  for (const std::string dev : {"/dev/null", "/dev/full"}) {
    REQUIRE(is_char_device(dev));
    check_refused(s, dev, run(dev), {"'" + dev + "'", "is a character device"});
    CHECK(is_char_device(dev));  // still the device, not a file
  }
  // A device made with mknod (root only).
  if (::geteuid() == 0) {
    REQUIRE(::mknod((s.work / "dev.h5").c_str(), S_IFCHR | 0644, makedev(1, 3)) == 0);
    check_refused(s, "mknod device", run("dev.h5"), {"'dev.h5'", "is a character device"});
    CHECK(is_char_device((s.work / "dev.h5").string()));
  }
}

TEST_CASE("cli outputs: no input of the run is ever the output", "[cli][outputs]") {
  Scratch s;
  write_file(s.work / "cfg.yaml", read_file(kPaperConfig));
  write_file(s.work / "child.yaml", "inherit: cfg.yaml\nname: child\n");
  fs::create_hard_link(s.work / "cfg.yaml", s.work / "hard.yaml");
  fs::create_directories(s.work / "sub");
  write_file(s.work / "sub" / "sweep.yaml",
             "base: ../child.yaml\nset: {output.grid: uniform, output.sample_step: 0.5}\n"
             "axes:\n  - key: gait.duty_factor\n    values: [1/2]\n");
  const std::string same = "same device and inode";
  const auto run = [&](const std::string& cfg, const std::string& out) {
    return concat({"run", cfg, "-o", out}, kCoarse);
  };
  check_refused(s, "the config itself", run("cfg.yaml", "cfg.yaml"), {"'cfg.yaml'", same});
  check_refused(s, "the config by another path", run("cfg.yaml", "sub/../cfg.yaml"), {same});
  check_refused(s, "an inherited file", run("child.yaml", "cfg.yaml"), {"'cfg.yaml'", same});
  check_refused(s, "a hard link to the config", run("cfg.yaml", "hard.yaml"),
                {"'hard.yaml'", same});
  check_refused(s, "the sweep file", {"sweep", "sub/sweep.yaml", "-o", "sub/sweep.yaml"}, {same});
  check_refused(s, "the sweep's base scene", {"sweep", "sub/sweep.yaml", "-o", "child.yaml"},
                {same});
  check_refused(s, "the base's inherited file", {"sweep", "sub/sweep.yaml", "-o", "hard.yaml"},
                {same});
  // A regular file that is no input is replaced, as before.
  write_file(s.work / "old.h5", "old bytes");
  const Outcome o = run_cli(s, run("child.yaml", "old.h5"));
  INFO(o.err);
  CHECK(o.status == 0);
  CHECK(read_file(s.work / "old.h5").rfind("\x89HDF", 0) == 0);
}

TEST_CASE("cli outputs: unwritable destinations are found before computing", "[cli][outputs]") {
  Scratch s;
  write_file(s.work / "cfg.yaml", read_file(kPaperConfig));
  // A scene that takes long to compute: a refusal within seconds shows nothing was computed.
  const auto run = [&](const std::string& out) {
    return std::vector<std::string>{"run", "cfg.yaml", "-o", out};
  };
  check_refused(s, "/proc", run("/proc/x.h5"), {"'/proc/x.h5'", "directory '/proc'"});
  check_refused(s, "missing folder", run("no/such/x.h5"),
                {"'no/such/x.h5'", "directory 'no/such' does not exist"});
  check_refused(s, "300-character name", run(std::string(300, 'a') + ".h5"),
                {"File name too long"});
  check_refused(s, "path through a file", run("cfg.yaml/x.h5"), {"not a directory"});
  if (fs::exists("/sys/kernel"))
    check_refused(s, "/sys", run("/sys/kernel/x.h5"), {"'/sys/kernel/x.h5'", "/sys/kernel"});
}

TEST_CASE("cli outputs: physically impossible timings are refused with the bound",
          "[cli][outputs][plausibility]") {
  Scratch s;
  write_file(s.work / "cfg.yaml", read_file(kPaperConfig));
  const auto run = [&](const std::string& set) {
    return std::vector<std::string>{"run", "cfg.yaml", "-o", "out.h5", "--set", set};
  };
  // The swing of the paper scene: (1 - β) 2.6 s; the bounds follow from 100 g, the 2 mm
  // clearance and the stride s0/β (src/hexdyn/config/plausibility.hpp).
  check_refused(
      s, "duty factor", run("gait.duty_factor=0.99999"),
      {"gait.duty_factor: got 0.99999", "swing of 2.6e-05 s", "100 g", "a duty factor of at most"});
  check_refused(s, "cycle durations", run("motion.cycle_durations=[2e-9,1e-9,2e-9]"),
                {"motion.cycle_durations: got a cruise cycle of 1e-09 s", "100 g"});
  check_refused(
      s, "lift fraction", run("gait.lift_fraction=1e-9"),
      {"gait.lift_fraction: got 1e-09", "clearance 0.002 m", "a lift fraction of at least"});
  check_refused(s, "lower fraction", run("gait.lower_fraction=1e-9"),
                {"gait.lower_fraction: got 1e-09", "a lower fraction of at least"});
  check_refused(s, "speed ramp", run("motion.cycle_durations=[2.60001,2.6,2.60001]"),
                {"motion.cycle_durations: got a speed ramp of 2e-05 s", "1.875 v / ramp"});
  check_refused(s, "tolerance", run("allocation.tolerance=1e-2"),
                {"allocation.tolerance: got 0.01", "(0, 1e-05]", "violation threshold"});
}

TEST_CASE("cli outputs: a run of more than 200000 samples needs --allow-large",
          "[cli][outputs][size]") {
  Scratch s;
  write_file(s.work / "cfg.yaml", read_file(kPaperConfig));
  // 474,010 samples: within hexdyn's hard limit (core/run_size.hpp), beyond the guard.
  check_refused(s, "impact samples",
                {"run", "cfg.yaml", "-o", "out.h5", "--set", "output.impact_samples=30000"},
                {" output samples", "0.69 GB", "--allow-large"});
  // Beyond the hard limit of 1,000,000 samples, --allow-large does not help.
  check_refused(
      s, "hard limit",
      {"run", "cfg.yaml", "-o", "out.h5", "--set", "output.impact_samples=100000", "--allow-large"},
      {"output.impact_samples: got 100000", "expected at most 1000000 samples",
       "--allow-large does not lift it"});
  check_refused(s, "--allow-large elsewhere", {"validate", "cfg.yaml", "--allow-large"},
                {"--allow-large belongs to"});
  // Under the limit the flag changes nothing (the paper run, 594 samples).
  const Outcome o = run_cli(s, {"run", "cfg.yaml", "-o", "out.h5", "--allow-large"});
  CHECK(o.status == 0);
  REQUIRE(fs::exists(s.work / "out.h5"));
  // The estimate behind the guard, against the written file: its samples are on stderr ("wrote
  // out.h5 (N samples, ...)").
  const auto at = o.err.find("wrote out.h5 (");
  REQUIRE(at != std::string::npos);
  const std::size_t samples = std::stoul(o.err.substr(at + 14));
  const double estimate = estimated_result_file_bytes(samples, 6, 18);  // the paper robot
  const double actual = static_cast<double>(fs::file_size(s.work / "out.h5"));
  INFO(samples << " samples: estimate " << estimate << " B, file " << actual << " B");
  // Uncompressed, the estimate bounds the compressed file from above, by less than 3 times.
  CHECK(actual <= estimate);
  CHECK(estimate <= 3 * actual);
}

}  // namespace
}  // namespace hexdyn
