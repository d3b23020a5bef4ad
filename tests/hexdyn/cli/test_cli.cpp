// The hexdyn command line (src/main.cpp), run as a separate process in a scratch
// directory: exit statuses, one-line error messages naming the key or the file, and
// output files that are either complete or untouched.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <set>
#include <string>
#include <vector>

#include "hexdyn/cli/cli_harness.hpp"
#include "hexdyn/config/config.hpp"

namespace hexdyn {
namespace {

using namespace cli_test;

TEST_CASE("cli: --help and validate succeed", "[cli]") {
  Scratch s;
  const Outcome help = run_cli(s, {"--help"});
  CHECK(help.status == 0);
  CHECK(help.out.find("usage") != std::string::npos);
  const Outcome ok = run_cli(s, {"validate", kPaperConfig});
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(ok.err.empty());
  CHECK(s.listing().empty());
}

TEST_CASE("cli: -v prints the lift-off phases, the pattern's or gait.phases", "[cli]") {
  Scratch s;
  // The tripod of the paper: L2, L3, L6 lift off first.
  const Outcome tripod = run_cli(s, {"validate", kPaperConfig, "-v"});
  INFO(tripod.err);
  REQUIRE(tripod.status == 0);
  CHECK(tripod.out.find("hexdyn: lift-off phases (fraction of a cycle; gait.pattern wave, swings "
                        "of 0.5 of a cycle): L1 0.5, L2 0, L3 0, L4 0.5, L5 0.5, L6 0\n") !=
        std::string::npos);
  // β = 3/4: each side's wave from rear to front a quarter cycle apart, the left half a cycle
  // after the right.
  const Outcome wave =
      run_cli(s, {"validate", kPaperConfig, "-v", "--set", "gait.duty_factor=3/4"});
  CHECK(wave.out.find("gait.pattern wave, swings of 0.25 of a cycle): L1 0, L2 0.5, L3 0.75, L4 "
                      "0.25, L5 0.5, L6 0\n") != std::string::npos);
  const Outcome given =
      run_cli(s, {"validate", kPaperConfig, "-v", "--set",
                  "gait.phases={L1: 0.125, L2: 0.5, L3: 0.5, L4: 0, L5: 0, L6: 0.5}"});
  CHECK(given.out.find("gait.pattern custom: gait.phases, swings of 0.5 of a cycle): L1 0.125, "
                       "L2 0.5, L3 0.5, L4 0, L5 0, L6 0.5\n") != std::string::npos);
  // The trot of six legs is the tripod: alternate ranks, the sides opposite.
  const Outcome trot = run_cli(s, {"validate", kPaperConfig, "-v", "--set", "gait.pattern=trot"});
  CHECK(trot.out.find("gait.pattern trot, swings of 0.5 of a cycle): L1 0.5, L2 0, L3 0, L4 0.5, "
                      "L5 0.5, L6 0\n") != std::string::npos);
  // A bound needs an even number of legs on each side: one line, exit 2.
  const Outcome bound = run_cli(s, {"validate", kPaperConfig, "--set", "gait.pattern=bound"});
  const std::string said = bound.out + bound.err;
  CHECK(bound.status == 2);
  CHECK(said.find("gait.pattern: got bound for a robot of 6 legs (3 on the left, 3 on the "
                  "right)") != std::string::npos);
  CHECK(std::count(said.begin(), said.end(), '\n') == 1);
  const Outcome quiet = run_cli(s, {"validate", kPaperConfig});
  CHECK(quiet.out.find("lift-off") == std::string::npos);
}

/// One bad invocation: the arguments before `-o FILE`, and what stderr must name.
struct BadCase {
  std::string what;
  std::vector<std::string> args;
  std::string names;
};

TEST_CASE("cli: bad input exits 2 with one line and leaves output files alone", "[cli]") {
  Scratch s;
  const std::string known_bytes =
      std::string("previous result \x01\x02\x03\n") + std::string(100, 'x');
  write_file(s.work / "existing.h5", known_bytes);
  // A scene file with a YAML syntax error.
  std::string text = read_text_file(kPaperConfig);
  const std::string key = "  stroke: 0.125";
  const auto at = text.find(key);
  REQUIRE(at != std::string::npos);
  text.replace(at, key.size(), "  stroke: 0.125: 0.2");
  write_file(s.work / "broken.yaml", text);

  const std::vector<BadCase> cases = {
      {"out of range", {"run", kPaperConfig, "--set", "gait.duty_factor=1.5"}, "gait.duty_factor"},
      {"unknown key", {"run", kPaperConfig, "--set", "gait.bogus=1"}, "gait.bogus"},
      {"mistyped", {"run", kPaperConfig, "--set", "contact.stiffness=abc"}, "contact.stiffness"},
      {"non-finite", {"run", kPaperConfig, "--set", "robot.trunk.mass=.nan"}, "robot.trunk.mass"},
      {"missing file", {"run", "no-such-scene.yaml"}, "no-such-scene.yaml"},
      {"YAML syntax", {"run", "broken.yaml"}, "broken.yaml:"},
  };
  const std::set<std::string> before = s.listing();
  for (const BadCase& c : cases) {
    for (const std::string& target : {std::string("fresh.h5"), std::string("existing.h5")}) {
      const Outcome o = run_cli(s, concat(c.args, {"-o", target}));
      INFO(c.what << " -> " << target << "\nstderr: " << o.err);
      CHECK(o.status == 2);
      CHECK(o.err.find(c.names) != std::string::npos);
      REQUIRE(!o.err.empty());
      CHECK(o.err.find('\n') == o.err.size() - 1);  // exactly one line
      CHECK_FALSE(fs::exists(s.work / "fresh.h5"));
      CHECK(read_file(s.work / "existing.h5") == known_bytes);
      CHECK(s.listing() == before);
    }
  }
  // The YAML syntax error gives line and column.
  const Outcome yaml = run_cli(s, {"validate", "broken.yaml"});
  CHECK(yaml.status == 2);
  CHECK(yaml.err.find("broken.yaml:") != std::string::npos);
  std::size_t colon = yaml.err.find("broken.yaml:") + std::string("broken.yaml:").size();
  CHECK(std::isdigit(static_cast<unsigned char>(yaml.err[colon])));
  // validate refuses the same bad keys.
  const Outcome v = run_cli(s, {"validate", kPaperConfig, "--set", "gait.duty_factor=1.5"});
  CHECK(v.status == 2);
  CHECK(v.err.find("gait.duty_factor") != std::string::npos);

  // An output path in a directory that does not exist.
  const Outcome nodir =
      run_cli(s, concat({"run", kPaperConfig, "-o", "no-such-dir/out.h5"}, kCoarse));
  INFO("stderr: " << nodir.err);
  CHECK(nodir.status == 2);
  CHECK(nodir.err.find("no-such-dir/out.h5") != std::string::npos);
  CHECK(nodir.err.find('\n') == nodir.err.size() - 1);
  CHECK_FALSE(fs::exists(s.work / "no-such-dir"));
  CHECK(read_file(s.work / "existing.h5") == known_bytes);
  CHECK(s.listing() == before);
}

TEST_CASE("cli: a good run writes the result file and nothing else", "[cli]") {
  Scratch s;
  const Outcome o = run_cli(s, concat({"run", kPaperConfig, "-o", "OUT.h5"}, kCoarse));
  INFO("stderr: " << o.err);
  REQUIRE(o.status == 0);
  REQUIRE(fs::exists(s.work / "OUT.h5"));
  const std::string bytes = read_file(s.work / "OUT.h5");
  CHECK(bytes.size() > 1000);
  CHECK(bytes.substr(0, 8) == std::string("\x89HDF\r\n\x1a\n", 8));
  CHECK(s.listing() == std::set<std::string>{"OUT.h5"});
}

}  // namespace
}  // namespace hexdyn
