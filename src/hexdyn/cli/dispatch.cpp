// The dispatcher and the one error-and-exit wrapper of every command (cli/command.hpp).
#include <yaml-cpp/yaml.h>

#include <cstring>
#include <iostream>

#include "hexdyn/cli/command.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/process/launch.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn::cli {
namespace {

/// One line on stderr, unless this process is a secondary rank of an mpirun (the first
/// rank says it for all).
void say(const std::string& line) {
  if (!launched_as_secondary_rank()) std::cerr << line << "\n";
}

/// Parses and runs one command while its inputs are frozen (every input file read once for
/// the whole command, config/inputs.hpp).
int parse_and_run(const Command& c, int argc, char** argv, const Program& program,
                  std::string& input) {
  const InputFreeze freeze;
  Args args = parse_args(c, argc, argv);
  args.program = &program;
  input = args.input;
  if (c.exits_on_interrupt)
    install_interrupt_handlers(InterruptMode::kExitInHandler,
                               std::string("hexdyn: ") + c.name + " interrupted by {signal}: " +
                                   "nothing written to " + args.output +
                                   " (an existing file there is kept, no temporary file left); "
                                   "run the command again to compute it");
  return c.run(args);
}

}  // namespace

int main(int argc, char** argv, const Program& program) {
  if (argc >= 2 && (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))) {
    std::cout << overview();
    return 0;
  }
  if (argc >= 2 && !std::strcmp(argv[1], "--version")) {
    std::cout << "hexdyn " << kVersion << " (" << kGitCommit << ")\n";
    return 0;
  }
  const Command* command = argc >= 2 ? find_command(argv[1]) : nullptr;
  // `hexdyn COMMAND ... --help` prints that command's usage, whatever else is given.
  if (command && asks_for_help(argc, argv)) {
    std::cout << usage(*command);
    return 0;
  }
  std::string input = "input";
  try {
    if (argc < 2) throw ConfigError("missing command; run 'hexdyn --help'");
    if (!command)
      throw ConfigError(std::string("unknown command '") + argv[1] + "'; run 'hexdyn --help'");
    return parse_and_run(*command, argc, argv, program, input);
  } catch (const ConfigErrors& e) {
    for (const std::string& line : e.lines()) say("hexdyn: error: " + one_line(line));
    return e.exit_status();
  } catch (const Error& e) {
    say("hexdyn: error: " + one_line(e.what()));
    return e.exit_status();
  } catch (const YAML::Exception& e) {
    // A YAML lookup that a reader did not guard (e.g. a missing key read as a scalar) still
    // comes from the user's file: bad input, not a crash. Each such case is a reader bug to
    // fix where it is thrown; this keeps the exit status and the one line meanwhile.
    say("hexdyn: error: " + one_line(input) + ": unexpected YAML structure: " + one_line(e.what()));
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "hexdyn: internal error: " << one_line(e.what()) << "\n";
    return 4;
  }
}

}  // namespace hexdyn::cli
