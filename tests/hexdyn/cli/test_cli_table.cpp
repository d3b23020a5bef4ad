// The command table (src/hexdyn/cli/command.hpp) against the program built from it: each
// row's help, operand, required -o and options, and the refusal of every option a row does
// not take, naming exactly the rows that do.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/cli/cli_harness.hpp"
#include "hexdyn/cli/command.hpp"

namespace hexdyn {
namespace {

using namespace cli_test;

TEST_CASE("cli table: every row's help, operand and -o come from the table", "[cli][table]") {
  Scratch s;
  const Outcome all = run_cli(s, {"--help"});
  CHECK(all.status == 0);
  CHECK(all.out == cli::overview());
  for (const cli::Command& c : cli::commands()) {
    INFO("command " << c.name);
    CHECK(all.out.find(c.summary) != std::string::npos);
    const Outcome help = run_cli(s, {c.name, "--help"});
    CHECK(help.status == 0);
    CHECK(help.out == cli::usage(c));
    CHECK(help.out.rfind(std::string("usage: hexdyn ") + c.name + " " + c.operand, 0) == 0);
    CHECK(all.out.find(help.out) != std::string::npos);
    for (const cli::OptionSpec& o : cli::options())
      CHECK((help.out.find(std::string("[") + o.name) != std::string::npos ||
             help.out.find(std::string(" ") + o.name + " ") != std::string::npos) ==
            static_cast<bool>(c.options & o.option));
    const Outcome bare = run_cli(s, {c.name});
    CHECK(bare.status == 2);
    CHECK(bare.err ==
          std::string("hexdyn: error: ") + c.name + ": missing " + c.operand + " file\n");
    if (c.required & cli::kOutput) {
      const Outcome no_output = run_cli(s, {c.name, "x.yaml"});
      CHECK(no_output.status == 2);
      CHECK(no_output.err == std::string("hexdyn: error: ") + c.name + ": missing -o FILE\n");
    }
  }
  CHECK(s.listing().empty());
}

TEST_CASE("cli table: an option a row does not take is refused, naming the rows that do",
          "[cli][table]") {
  Scratch s;
  for (const cli::Command& c : cli::commands()) {
    for (const cli::OptionSpec& o : cli::options()) {
      if (c.options & o.option) continue;
      std::vector<std::string> args = {c.name, "x.yaml", o.name};
      if (o.value_name) args.push_back("a=1");
      const Outcome r = run_cli(s, args);
      INFO(c.name << " " << o.name << ": " << r.err);
      CHECK(r.status == 2);
      CHECK(r.err.find('\n') == r.err.size() - 1);
      if (o.option == cli::kSet && *c.set_refusal) {
        CHECK(r.err.find(c.set_refusal) != std::string::npos);
        continue;
      }
      CHECK(r.err.find(std::string(c.name) + ": " + o.name + " belongs to ") != std::string::npos);
      for (const cli::Command& other : cli::commands())
        CHECK((r.err.find(std::string("'hexdyn ") + other.name + "'") != std::string::npos) ==
              static_cast<bool>(other.options & o.option));
    }
  }
  CHECK(s.listing().empty());
}

}  // namespace
}  // namespace hexdyn
