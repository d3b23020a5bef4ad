// Inputs the command line must refuse at once: duplicate keys in scenes,
// inherited files and sweep files; configuration paths that are not regular files or
// are too large; inheritance cycles; a top level that is not a map; deep nesting. Each
// gives exit status 2, exactly one line on stderr naming the cause, no output file and
// every file of the scratch directory unchanged. Also: per-command --help, validate on
// sweep files, and --set with p/q.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/cli/cli_harness.hpp"

namespace hexdyn {
namespace {

using namespace cli_test;

/// 1-based number of the first line of `text` that starts with `prefix`; 0 if none.
int line_of(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.rfind(prefix, 0) == 0) return n;
  return 0;
}

int line_count(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

/// `text` with `extra` inserted as a new line after line `after` (1-based).
std::string insert_after(const std::string& text, int after, const std::string& extra) {
  std::istringstream in(text);
  std::string line, out;
  for (int n = 1; std::getline(in, line); ++n) {
    out += line + "\n";
    if (n == after) out += extra + "\n";
  }
  return out;
}

/// Runs `args` (a command that would write out.h5) and checks the refusal: status 2,
/// one line on stderr containing every string of `names`, nothing created or changed.
void check_refused(const Scratch& s, const std::string& what, const std::vector<std::string>& args,
                   const std::vector<std::string>& names, int limit_s = 120) {
  const auto before = s.snapshot();
  const Outcome o = run_cli(s, args, limit_s);
  INFO(what << "\nstderr: " << o.err);
  CHECK(o.status == 2);
  REQUIRE(!o.err.empty());
  CHECK(o.err.find('\n') == o.err.size() - 1);  // exactly one line
  CHECK(o.err.rfind("hexdyn: error: ", 0) == 0);
  for (const auto& n : names) CHECK(o.err.find(n) != std::string::npos);
  CHECK_FALSE(fs::exists(s.work / "out.h5"));
  CHECK_FALSE(fs::exists(s.work / "out.h5.checkpoint"));
  CHECK(s.snapshot() == before);
}

std::string dup_message(const std::string& path, int first, int again) {
  return path + ": duplicate key, first at line " + std::to_string(first) + ", again at line " +
         std::to_string(again);
}

TEST_CASE("cli inputs: duplicate keys in scenes, inherited files and sweep files",
          "[cli][inputs]") {
  Scratch s;
  const std::string paper = read_file(kPaperConfig);
  write_file(s.work / "paper.yaml", paper);

  // gait.duty_factor twice, on consecutive lines.
  const int duty = line_of(paper, "  duty_factor:");
  REQUIRE(duty > 0);
  write_file(s.work / "duty.yaml", insert_after(paper, duty, "  duty_factor: 0.75"));
  const std::string duty_msg = dup_message("gait.duty_factor", duty, duty + 1);
  check_refused(s, "scene", {"run", "duty.yaml", "-o", "out.h5"}, {"duty.yaml: " + duty_msg});
  check_refused(s, "scene, validate", {"validate", "duty.yaml"}, {"duty.yaml: " + duty_msg});

  // A second terrain: section at the end of the file.
  const int terrain = line_of(paper, "terrain:");
  REQUIRE(terrain > 0);
  write_file(s.work / "terrain.yaml", paper + "terrain:\n  type: flat\n");
  check_refused(s, "second section", {"run", "terrain.yaml", "-o", "out.h5"},
                {"terrain.yaml: " + dup_message("terrain", terrain, line_count(paper) + 1)});

  // The duplicate is in an inherited file.
  write_file(s.work / "child.yaml", "inherit: duty.yaml\nname: child\n");
  check_refused(s, "inherited file", {"run", "child.yaml", "-o", "out.h5"},
                {"duty.yaml: " + duty_msg});

  // Sweep files: axes: twice, a set: key twice, a key twice inside an axis; and a base
  // scene with a duplicate.
  const std::string axis = "  - key: gait.duty_factor\n    values: [1/2, 3/4]\n";
  write_file(s.work / "axes2.yaml", "base: paper.yaml\naxes:\n" + axis + "axes:\n" + axis);
  check_refused(s, "sweep axes twice", {"sweep", "axes2.yaml", "-o", "out.h5"},
                {"axes2.yaml: " + dup_message("axes", 2, 5)});
  write_file(s.work / "set2.yaml",
             "base: paper.yaml\nset:\n  gait.duty_factor: 0.6\n  gait.duty_factor: 0.7\naxes:\n"
             "  - key: gait.stroke\n    values: [0.125]\n");
  check_refused(s, "sweep set key twice", {"sweep", "set2.yaml", "-o", "out.h5"},
                {"set2.yaml: " + dup_message("set.gait.duty_factor", 3, 4)});
  write_file(s.work / "axkey2.yaml",
             "base: paper.yaml\naxes:\n  - key: gait.duty_factor\n    key: gait.stroke\n    "
             "values: [0.5]\n");
  check_refused(s, "sweep axis key twice", {"sweep", "axkey2.yaml", "-o", "out.h5"},
                {"axkey2.yaml: " + dup_message("axes[0].key", 3, 4)});
  write_file(s.work / "terrain_base.yaml", "base: terrain.yaml\naxes:\n" + axis);
  check_refused(s, "sweep base scene", {"sweep", "terrain_base.yaml", "-o", "out.h5"},
                {"terrain.yaml: " + dup_message("terrain", terrain, line_count(paper) + 1)});
  check_refused(s, "sweep base scene, validate", {"validate", "terrain_base.yaml"},
                {"terrain.yaml: " + dup_message("terrain", terrain, line_count(paper) + 1)});
}

TEST_CASE("cli inputs: configuration paths that are not regular files, or too large",
          "[cli][inputs]") {
  Scratch s;
  fs::create_directories(s.work / "dir");
  REQUIRE(::mkfifo((s.work / "fifo.yaml").c_str(), 0644) == 0);
  // 2 MiB of a comment: valid YAML, refused by size alone.
  write_file(s.work / "big.yaml", "# " + std::string(2 * 1024 * 1024, 'x') + "\n");
  write_file(s.work / "inherit_dir.yaml", "inherit: dir\n");
  // The time limit turns a hang (FIFO) or an endless read (/dev/zero) into a failure.
  const int limit = 20;
  for (const char* cmd : {"run", "validate"}) {
    std::vector<std::string> tail;
    if (std::string(cmd) == "run") tail = {"-o", "out.h5"};
    check_refused(s, "directory", concat({cmd, "dir"}, tail), {"dir: is a directory"}, limit);
    check_refused(s, "FIFO", concat({cmd, "fifo.yaml"}, tail), {"fifo.yaml: is a FIFO"}, limit);
    check_refused(s, "/dev/zero", concat({cmd, "/dev/zero"}, tail), {"/dev/zero: is a device"},
                  limit);
    check_refused(s, "2 MiB", concat({cmd, "big.yaml"}, tail),
                  {"big.yaml: larger than 1048576 bytes"}, limit);
    check_refused(s, "inherit: dir", concat({cmd, "inherit_dir.yaml"}, tail),
                  {"inherit_dir.yaml: inherit: got dir, which is a directory"}, limit);
  }
  check_refused(s, "sweep of a FIFO", {"sweep", "fifo.yaml", "-o", "out.h5"},
                {"fifo.yaml: is a FIFO"}, limit);
  check_refused(s, "sweep of a directory", {"sweep", "dir", "-o", "out.h5"},
                {"dir: is a directory"}, limit);
}

TEST_CASE("cli inputs: inheritance cycles are found by canonical path", "[cli][inputs]") {
  Scratch s;
  fs::create_directories(s.work / "a");
  fs::create_directories(s.work / "b");
  write_file(s.work / "cfg.yaml", "inherit: ./cfg.yaml\nname: x\n");
  write_file(s.work / "a" / "cfg.yaml", "inherit: ../b/cfg.yaml\n");
  write_file(s.work / "b" / "cfg.yaml", "inherit: ../a/cfg.yaml\n");
  check_refused(s, "self", {"run", "cfg.yaml", "-o", "out.h5"},
                {"inherit: cycle cfg.yaml -> cfg.yaml"}, 20);
  check_refused(s, "two files through ../", {"run", "a/cfg.yaml", "-o", "out.h5"},
                {"inherit: cycle a/cfg.yaml -> b/cfg.yaml -> a/cfg.yaml"}, 20);
  // The same cycle entered through a path that names the file differently.
  check_refused(s, "two files, other spelling", {"validate", "b/../a/cfg.yaml"},
                {"inherit: cycle a/cfg.yaml -> b/cfg.yaml -> a/cfg.yaml"}, 20);
}

TEST_CASE("cli inputs: a top level that is not a map, and deep nesting, give one line",
          "[cli][inputs]") {
  Scratch s;
  write_file(s.work / "list.yaml", "- robot: {}\n- terrain: {}\n- gait:\n    duty_factor: 0.5\n");
  check_refused(s, "list", {"run", "list.yaml", "-o", "out.h5"},
                {"list.yaml: top level: got a list, expected a map of sections"});
  write_file(s.work / "scalar.yaml", "just words\n");
  check_refused(s, "scalar", {"validate", "scalar.yaml"},
                {"scalar.yaml: top level: got a single value"});
  // 200 nested flow lists and 100 nested block maps.
  write_file(s.work / "deep.yaml", "gait: " + std::string(200, '[') + std::string(200, ']') + "\n");
  check_refused(s, "deep lists", {"run", "deep.yaml", "-o", "out.h5"},
                {"deep.yaml:1: gait...: maps and lists nested deeper than 64 levels"});
  std::string maps;
  for (int i = 0; i < 100; ++i) maps += std::string(2 * i, ' ') + "k:\n";
  write_file(s.work / "deepmap.yaml", maps);
  check_refused(s, "deep maps", {"validate", "deepmap.yaml"},
                {"deepmap.yaml:65: ", "nested deeper than 64 levels"});
  // The same cap inside a --set value.
  check_refused(
      s, "deep --set",
      {"validate", kPaperConfig, "--set", "gait=" + std::string(100, '[') + std::string(100, ']')},
      {"--set gait=", "nested deeper than 64 levels"});
}

TEST_CASE("cli inputs: per-command --help", "[cli][inputs]") {
  Scratch s;
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"run", "usage: hexdyn run CONFIG -o FILE"},
      {"sweep", "usage: hexdyn sweep SWEEP -o FILE"},
      {"validate", "usage: hexdyn validate FILE"}};
  for (const auto& [command, usage] : commands) {
    for (const auto& args : std::vector<std::vector<std::string>>{
             {command, "--help"}, {command, "-h"}, {command, "x.yaml", "--set", "a=1", "--help"}}) {
      const Outcome o = run_cli(s, args);
      INFO(command << ": " << o.err);
      CHECK(o.status == 0);
      CHECK(o.out.rfind(usage, 0) == 0);
      CHECK(o.err.empty());
    }
  }
  // A flag's value that reads "--help" is a value, not a request for help.
  check_refused(s, "--set --help", {"validate", kPaperConfig, "--set", "--help"},
                {"--set --help: expected key.path=value"});
  CHECK(s.listing().empty());
}

TEST_CASE("cli inputs: validate checks sweep files without running them", "[cli][inputs]") {
  Scratch s;
  fs::create_directories(s.work / "sweeps");
  write_file(s.work / "paper.yaml", read_file(kPaperConfig));
  for (const char* name : {"smoke.yaml", "stairs_base.yaml"})
    write_file(s.work / "sweeps" / name, read_file(kSourceDir + "/configs/sweeps/" + name));
  const auto before = s.snapshot();
  const Outcome ok = run_cli(s, {"validate", "sweeps/smoke.yaml"});
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(ok.err.empty());
  CHECK(ok.out.find("sweeps/smoke.yaml: valid sweep 'smoke'") != std::string::npos);
  CHECK(ok.out.find("8 scenarios") != std::string::npos);
  CHECK(s.snapshot() == before);
  // Scenarios out of range are counted, as the sweep records them as rows.
  write_file(
      s.work / "sweeps" / "partly.yaml",
      "base: stairs_base.yaml\naxes:\n  - key: gait.duty_factor\n    values: [1/2, 3/4, 1.2]\n");
  const Outcome partly = run_cli(s, {"validate", "sweeps/partly.yaml"});
  CHECK(partly.status == 0);
  CHECK(partly.out.find("1 of 3 scenarios have a value out of range") != std::string::npos);
  CHECK(partly.out.find("gait.duty_factor: got 1.2") != std::string::npos);
  // Errors of the sweep file itself.
  write_file(s.work / "sweeps" / "bad.yaml",
             "base: stairs_base.yaml\naxes:\n  - key: gait.duty\n    values: [0.5]\n");
  check_refused(s, "unknown axis key", {"validate", "sweeps/bad.yaml"},
                {"sweeps/bad.yaml: axes[0].key: got gait.duty"});
  check_refused(s, "--set with a sweep file",
                {"validate", "sweeps/smoke.yaml", "--set", "gait.stroke=0.1"},
                {"--set applies to scene files"});
}

TEST_CASE("cli inputs: --set accepts p/q as sweep files do", "[cli][inputs]") {
  Scratch s;
  const Outcome ok = run_cli(s, {"validate", kPaperConfig, "--set", "gait.duty_factor=3/4"});
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(ok.err.empty());
  // 1/3 becomes a number, then is out of range for the key.
  check_refused(s, "1/3", {"validate", kPaperConfig, "--set", "gait.duty_factor=1/3"},
                {"gait.duty_factor: got 0.333333333333333", "expected a number in [0.5, 1)"});
  // Not a fraction: refused as a value, by name.
  check_refused(s, "3/0", {"validate", kPaperConfig, "--set", "gait.duty_factor=3/0"},
                {"gait.duty_factor: got 3/0, expected"});
}

}  // namespace
}  // namespace hexdyn
