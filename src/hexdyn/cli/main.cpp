// hexdyn command line: thin driver over the library (pipeline.hpp).
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "hexdyn/io/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/mpi/mpi_sweep.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/version.hpp"

namespace {

constexpr const char* kUsage = R"(hexdyn — inverse dynamics of a legged robot on stairs

usage:
  hexdyn run CONFIG -o FILE [--set key.path=value ...]   run a scene, write hexdyn-result/1
  hexdyn validate CONFIG [--set key.path=value ...]      check a scene file and exit
  hexdyn sweep SWEEP -o FILE [--keep-runs] [--resume] [-v] [--progress SECONDS]
                                                         run a parameter sweep, write hexdyn-sweep/1
  hexdyn --help | --version

CONFIG is a YAML scene (see configs/paper.yaml for every key). --set overrides one key
by dotted path, the value parsed as YAML (e.g. --set gait.duty_factor=0.75,
--set motion.cycle_durations=[3,2.6,3]). Exit status: 0 success, 2 bad input (config,
arguments, output path), 3 a scene that cannot be computed (unreachable foothold, ...).

SWEEP is a sweep file (see configs/sweeps/stairs.yaml): a base scene and axes over its
keys; every combination is a scenario. Run it under `mpirun -np N` or plainly (one
rank). Scenarios that cannot be computed are rows with a status and a message; the exit
status is 0 once FILE is written. --keep-runs also stores each scenario's full result
under /runs/<id>. Finished scenarios are kept in FILE.checkpoint/ until FILE is
complete; --resume continues an interrupted sweep from there. -v prints one line per
scenario; progress lines come at most every --progress seconds (default 5).
)";

struct Args {
  std::string command, config, output;
  std::vector<hexdyn::Override> overrides;
  bool keep_runs = false, resume = false, verbose = false, progress_given = false;
  double progress_s = 5.0;
};

double parse_seconds(const std::string& text) {
  std::size_t used = 0;
  double v = -1.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(v >= 0.0 && v <= 86400.0))
    throw hexdyn::ConfigError("--progress: got " + text + ", expected seconds in [0, 86400]");
  return v;
}

Args parse_args(int argc, char** argv) {
  Args a;
  if (argc < 2) throw hexdyn::ConfigError("missing command; run 'hexdyn --help'");
  a.command = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) {
      if (i + 1 >= argc) throw hexdyn::ConfigError(std::string(flag) + ": missing value");
      return std::string(argv[++i]);
    };
    if (arg == "-o" || arg == "--output") a.output = value("-o");
    else if (arg == "--set") a.overrides.push_back(hexdyn::parse_override(value("--set")));
    else if (arg.rfind("--set=", 0) == 0) a.overrides.push_back(hexdyn::parse_override(arg.substr(6)));
    else if (arg == "--keep-runs") a.keep_runs = true;
    else if (arg == "--resume") a.resume = true;
    else if (arg == "-v" || arg == "--verbose") a.verbose = true;
    else if (arg == "--progress") {
      a.progress_s = parse_seconds(value("--progress"));
      a.progress_given = true;
    }
    else if (!arg.empty() && arg[0] == '-') throw hexdyn::ConfigError("unknown option " + arg + "; run 'hexdyn --help'");
    else if (a.config.empty()) a.config = arg;
    else throw hexdyn::ConfigError("unexpected argument " + arg + "; run 'hexdyn --help'");
  }
  if (a.config.empty())
    throw hexdyn::ConfigError(a.command + ": missing " + (a.command == "sweep" ? "SWEEP" : "CONFIG") + " file");
  const bool sweep_flags = a.keep_runs || a.resume || a.verbose || a.progress_given;
  if (a.command == "sweep" && !a.overrides.empty())
    throw hexdyn::ConfigError("sweep: --set is not available; fix keys with set: in the sweep file");
  if (a.command != "sweep" && sweep_flags)
    throw hexdyn::ConfigError(a.command + ": --keep-runs, --resume, -v and --progress belong to 'hexdyn sweep'");
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))) {
    std::cout << kUsage;
    return 0;
  }
  if (argc >= 2 && !std::strcmp(argv[1], "--version")) {
    std::cout << "hexdyn " << hexdyn::kVersion << " (" << hexdyn::kGitCommit << ")\n";
    return 0;
  }
  try {
    const Args args = parse_args(argc, argv);
    if (args.command == "validate") {
      const hexdyn::Scene scene = hexdyn::load_scene(args.config, args.overrides);
      std::cout << args.config << ": valid scene '" << scene.name << "'\n";
      return 0;
    }
    if (args.command == "run") {
      if (args.output.empty()) throw hexdyn::ConfigError("run: missing -o FILE");
      const hexdyn::Scene scene = hexdyn::load_scene(args.config, args.overrides);
      hexdyn::check_output_path_writable(args.output);
      const hexdyn::RunResult result = hexdyn::run_scene(scene, &std::cerr);
      hexdyn::write_result_file(args.output, result);
      std::cerr << "hexdyn: wrote " << args.output << " (" << result.kin.samples() << " samples, "
                << result.wall_time_s << " s)\n";
      return 0;
    }
    if (args.command == "sweep") {
      if (args.output.empty()) throw hexdyn::ConfigError("sweep: missing -o FILE");
      return hexdyn::run_sweep({args.config, args.output, args.keep_runs, args.resume,
                                args.verbose, args.progress_s});
    }
    throw hexdyn::ConfigError("unknown command '" + args.command + "'; run 'hexdyn --help'");
  } catch (const hexdyn::Error& e) {
    if (!hexdyn::launched_as_secondary_rank()) std::cerr << "hexdyn: error: " << e.what() << "\n";
    return e.exit_status();
  } catch (const std::exception& e) {
    std::cerr << "hexdyn: internal error: " << e.what() << "\n";
    return 4;
  }
}
