#pragma once
/// \file command.hpp
/// The command line of hexdyn in one table: every subcommand is a row of kCommands
/// (commands.cpp) naming its operand, the options it takes (one table of options,
/// kOptions), its help text and its function. One parser (options.cpp) reads every
/// command's arguments, one wrapper (dispatch.cpp) turns every error into one line and an
/// exit status, and `hexdyn --help` and `hexdyn CMD --help` are written from the rows. A
/// new subcommand is one row and its function (docs/dev/extending.md#add-a-subcommand).
///
/// The libraries own no command: this folder calls them (run_prepared_scene, run_sweep,
/// compute_envelope, replay_plan, ...) and prints their reports.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"

namespace hexdyn::cli {

/// One option of the command line; a command takes a set of them (Command::options).
enum Option : std::uint32_t {
  kOutput = 1u << 0,      ///< -o FILE, --output FILE
  kSet = 1u << 1,         ///< --set key.path=value, --set=key.path=value (repeatable)
  kAllowLarge = 1u << 2,  ///< --allow-large
  kKeepRuns = 1u << 3,    ///< --keep-runs
  kResume = 1u << 4,      ///< --resume
  kVerbose = 1u << 5,     ///< -v, --verbose
  kProgress = 1u << 6,    ///< --progress SECONDS
  kJobs = 1u << 7,        ///< -j N, --jobs N: threads of a command that computes in parallel
};

/// How an option is written: its name, an alias, and its value's name (nullptr for a flag).
struct OptionSpec {
  Option option;
  const char* name;        ///< "-o"
  const char* alias;       ///< "--output", or nullptr
  const char* value_name;  ///< "FILE", or nullptr for a flag
  bool repeatable = false;
};

/// Every option, in the order the usage lines list them.
std::span<const OptionSpec> options();

struct Args;
struct Program;

/// One subcommand: a row of the table.
struct Command {
  const char* name;            ///< "run"
  const char* operand;         ///< the one positional argument, "CONFIG"
  std::uint32_t options = 0;   ///< the options it takes (Option bits)
  std::uint32_t required = 0;  ///< those it cannot do without (kOutput)
  const char* summary;         ///< one line for `hexdyn --help`
  const char* help;            ///< the paragraphs below its usage line
  int (*run)(const Args&);     ///< the command itself; returns the exit status
  /// Installs the exit-at-once interrupt handlers naming -o FILE (a command that writes one
  /// file and keeps nothing to resume: docs/user/faults.md#signals).
  bool exits_on_interrupt = false;
  /// Why --set is refused, when the command has a better way ("" : the generic refusal).
  const char* set_refusal = "";
};

/// Every subcommand, in the order `hexdyn --help` lists them.
std::span<const Command> commands();
/// The row named `name`; nullptr for none.
const Command* find_command(const std::string& name);

/// The parsed arguments of one command.
struct Args {
  const Command* command = nullptr;
  std::string input;   ///< the operand
  std::string output;  ///< -o FILE
  std::vector<Override> overrides;
  bool allow_large = false, keep_runs = false, resume = false, verbose = false;
  double progress_s = 5.0;
  int jobs = 0;  ///< --jobs; 0: one per core (std::thread::hardware_concurrency)
  const Program* program = nullptr;
  int argc = 0;
  char** argv = nullptr;  ///< the process's arguments, as given
};

/// What differs between the two programs built from this folder (src/CMakeLists.txt):
/// `hexdyn` (no MPI) execs `hexdyn-sweep` for a sweep, `hexdyn-sweep` runs it over MPI.
struct Program {
  int (*sweep)(const Args&);
};

/// Parses argv[2 …] for `command` (argv[1]): every option it takes, its operand and its
/// required options. Throws ConfigError naming the option or argument at fault.
Args parse_args(const Command& command, int argc, char** argv);

/// Whether argv[2 …] asks for help (--help or -h, not as the value of an option).
bool asks_for_help(int argc, char** argv);

/// The full help of a command: its usage line, written from the option table, and its text.
std::string usage(const Command& command);
/// `hexdyn --help`: every command's usage line and summary, exit statuses, then each help.
std::string overview();

/// The whole command line: dispatches argv[1] to its row, prints help and the version,
/// and turns every error into one line and an exit status (0, 2 bad input, 3 a scene that
/// cannot be computed, 4 internal).
int main(int argc, char** argv, const Program& program);

}  // namespace hexdyn::cli
