// hexdyn command line: thin driver over the library (pipeline.hpp).
//
// Built twice (src/CMakeLists.txt): `hexdyn`, which links no MPI and hands `hexdyn sweep` to
// `hexdyn-sweep` (exec, same arguments, same process), and `hexdyn-sweep`
// (HEXDYN_CLI_MPI), which runs the sweep over MPI (mpi/mpi_sweep.hpp). So run, validate
// and envelope start without loading or initialising MPI.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/envelope/envelope.hpp"
#include "hexdyn/model/stance.hpp"
#include "hexdyn/model/urdf_robot.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/process/launch.hpp"
#ifdef HEXDYN_CLI_MPI
#include "hexdyn/mpi/mpi_sweep.hpp"
#endif
#include "hexdyn/io/output.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/replay/replay_file.hpp"
#include "hexdyn/sweep/sweep.hpp"
#include "hexdyn/sweep/validate.hpp"
#include "hexdyn/version.hpp"

namespace {

constexpr const char* kRunUsage =
    R"(usage: hexdyn run CONFIG -o FILE [--set key.path=value ...] [--allow-large] [-v]
                  [--progress SECONDS]
  Runs a scene and writes its hexdyn-result/3 file to FILE. -v prints a URDF robot's
  leg mapping (which chain of the description is L1 ... L6). While the stages compute, a
  progress line comes at most every --progress seconds (default 5).

FILE must be a new path or an existing regular file that is none of the run's inputs
(CONFIG and the files it inherits); devices, FIFOs, directories and symbolic links are
refused, and FILE's folder must take a new file, all checked before computing. A run of
more than 200000 output samples (about 290 MB) stops before computing unless
--allow-large is given.

CONFIG is a YAML scene (see configs/paper.yaml for every key); `inherit: OTHER.yaml`
takes the keys of another scene file. --set overrides one key by dotted path, the value
parsed as YAML: --set gait.duty_factor=0.75, --set gait.duty_factor=3/4 (p/q is p
divided by q, as in sweep files), --set motion.cycle_durations=[3,2.6,3].
)";

constexpr const char* kValidateUsage =
    R"(usage: hexdyn validate FILE [--set key.path=value ...] [-v]
  Checks a scene file, or a sweep file, and exits without computing anything.

A file with a top-level `axes:` key is a sweep file: it is checked as `hexdyn sweep`
would check it (its keys, axes and base scene), and each scenario's scene is validated;
scenarios with a value out of range are counted (exit status 0: `hexdyn sweep` records
them as rows with status config). --set applies to scene files only.
)";

constexpr const char* kSweepUsage =
    R"(usage: hexdyn sweep SWEEP -o FILE [--keep-runs] [--resume] [-v] [--progress SECONDS]
  Runs a parameter sweep and writes its hexdyn-sweep/3 file to FILE.

SWEEP is a sweep file (see configs/sweeps/stairs.yaml): a base scene and axes over its
keys; every combination is a scenario. Run it under `mpirun -np N` or plainly (one
rank). Scenarios that cannot be computed are rows with a status and a message; the exit
status is 0 once FILE is written. --keep-runs also stores each scenario's full result
under /runs/<id>. Finished scenarios are kept in FILE.checkpoint/ until FILE is
complete; --resume continues an interrupted sweep from there. -v prints one line per
scenario; progress lines come at most every --progress seconds (default 5).
)";

constexpr const char* kUsage = R"(hexdyn — inverse dynamics of a legged robot on stairs

usage:
  hexdyn run CONFIG -o FILE [--set key.path=value ...] [--allow-large]
                                                         run a scene, write hexdyn-result/3
  hexdyn validate FILE [--set key.path=value ...]        check a scene or sweep file and exit
  hexdyn sweep SWEEP -o FILE [--keep-runs] [--resume] [-v] [--progress SECONDS]
                                                         run a parameter sweep, write hexdyn-sweep/3
  hexdyn envelope ENVELOPE -o FILE [-v]                  find the climbable riser, write hexdyn-envelope/2
  hexdyn replay RESULT -o FILE [--set key.path=value ...]
                                                         replay a result's torques, write hexdyn-replay/1
  hexdyn COMMAND --help                                  help on one command
  hexdyn --help | --version

Exit status: 0 success, 2 bad input (config, arguments, output path), 3 a scene that
cannot be computed (unreachable foothold, ...). Configuration files must be regular
files of at most 1 MiB, without duplicate keys.

)";

struct Args {
  std::string command, config, output;
  std::vector<hexdyn::Override> overrides;
  bool keep_runs = false, resume = false, verbose = false, progress_given = false,
       allow_large = false;
  double progress_s = 5.0;
};

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
    if (arg == "-o" || arg == "--output")
      a.output = value("-o");
    else if (arg == "--set")
      a.overrides.push_back(hexdyn::parse_override(value("--set")));
    else if (arg.rfind("--set=", 0) == 0)
      a.overrides.push_back(hexdyn::parse_override(arg.substr(6)));
    else if (arg == "--keep-runs")
      a.keep_runs = true;
    else if (arg == "--resume")
      a.resume = true;
    else if (arg == "--allow-large")
      a.allow_large = true;
    else if (arg == "-v" || arg == "--verbose")
      a.verbose = true;
    else if (arg == "--progress") {
      a.progress_s = hexdyn::parse_progress_interval(value("--progress"));
      a.progress_given = true;
    } else if (!arg.empty() && arg[0] == '-')
      throw hexdyn::ConfigError("unknown option " + arg + "; run 'hexdyn --help'");
    else if (a.config.empty())
      a.config = arg;
    else
      throw hexdyn::ConfigError("unexpected argument " + arg + "; run 'hexdyn --help'");
  }
  if (a.config.empty())
    throw hexdyn::ConfigError(a.command + ": missing " +
                              (a.command == "sweep"      ? "SWEEP"
                               : a.command == "validate" ? "FILE"
                                                         : "CONFIG") +
                              " file");
  // -v also belongs to run and validate: it prints a URDF robot's leg mapping.
  const bool sweep_flags = a.keep_runs || a.resume || (a.progress_given && a.command != "run");
  if (a.command == "sweep" && !a.overrides.empty())
    throw hexdyn::ConfigError(
        "sweep: --set is not available; fix keys with set: in the sweep file");
  if (a.command != "run" && a.allow_large)
    throw hexdyn::ConfigError(a.command + ": --allow-large belongs to 'hexdyn run'");
  if (a.command != "sweep" && sweep_flags)
    throw hexdyn::ConfigError(a.command +
                              ": --keep-runs and --resume belong to 'hexdyn sweep', "
                              "--progress to 'hexdyn sweep' and 'hexdyn run'");
  return a;
}

/// The usage text of one command; nullptr for an unknown command.
const char* command_usage(const std::string& command) {
  if (command == "run") return kRunUsage;
  if (command == "validate") return kValidateUsage;
  if (command == "sweep") return kSweepUsage;
  return nullptr;
}

bool is_help(const char* arg) { return !std::strcmp(arg, "--help") || !std::strcmp(arg, "-h"); }

/// -v: a URDF robot's leg mapping (the description's chains → L1 … L6) and its stance
/// (model/stance.hpp: each leg's pose and how it was obtained), one line per leg.
void print_leg_mapping(const hexdyn::Scene& scene, std::ostream& os) {
  if (!scene.robot.urdf) return;
  const hexdyn::UrdfRobot& robot = *scene.robot.urdf;
  os << "hexdyn: robot '" << robot.name << "' from " << robot.source_path << ", trunk link "
     << robot.trunk_link << " (forward " << robot.forward_axis << "), legs:\n"
     << hexdyn::leg_mapping_text(robot) << "hexdyn: stance of each leg (robot.nominal_pose):\n"
     << hexdyn::stance_text(scene.robot.stance) << "hexdyn: footholds " << scene.gait.foot_lateral_m
     << " m from the hips along their outward directions (gait.foot_lateral)\n";
}

/// The scene's warnings (Scene::warnings), one line each on stderr.
void print_warnings(const hexdyn::Scene& scene) {
  for (const std::string& w : scene.warnings) std::cerr << "hexdyn: warning: " << w << "\n";
}

/// `hexdyn validate`: the report of validate_file (sweep/validate.hpp), printed.
int validate(const Args& args) {
  const hexdyn::ValidationReport report = hexdyn::validate_file(args.config, args.overrides);
  if (args.verbose && report.scene) print_leg_mapping(*report.scene, std::cout);
  if (report.scene) print_warnings(*report.scene);
  for (const std::string& line : report.messages) std::cout << line << "\n";
  return 0;
}

/// `hexdyn run CONFIG -o FILE`: the scene computed and its result file written; every check
/// of the inputs, the output path and the run's size comes before any computing.
int run(const Args& args) {
  if (args.output.empty()) throw hexdyn::ConfigError("run: missing -o FILE");
  // SIGTERM, SIGINT: the temporary file removed, the process ended at once; a run keeps
  // nothing to resume (docs/user/faults.md#signals).
  hexdyn::install_interrupt_handlers(
      hexdyn::InterruptMode::kExitInHandler,
      "hexdyn: run interrupted by {signal}: nothing written to " + args.output +
          " (an existing file there is kept, no temporary file left); run the command "
          "again to compute it");
  std::vector<hexdyn::InputFile> inputs;
  const hexdyn::Scene scene = hexdyn::load_scene(args.config, args.overrides, &inputs);
  if (args.verbose) print_leg_mapping(scene, std::cerr);
  print_warnings(scene);
  // Before any computing: the output is a new path or a regular file that is none of the
  // inputs (the scene, its inherited files, its URDF).
  hexdyn::check_output_target(args.output, inputs);
  // Before the allocation: the grid's size, against the large-run limit.
  const hexdyn::PreparedScene prep = hexdyn::prepare_scene(scene);
  hexdyn::check_run_size(prep.grid.size(), args.allow_large);
  // A line every 5 s while the stages compute (an Ipopt run at a fine tolerance takes minutes).
  const hexdyn::ProgressScope progress(std::cerr, "run", args.progress_s);
  const hexdyn::RunResult result = hexdyn::run_prepared_scene(scene, prep, &std::cerr);
  hexdyn::write_result_file(args.output, result, inputs);
  std::cerr << "hexdyn: wrote " << args.output << " (" << result.kin.samples() << " samples, "
            << result.wall_time_s << " s)\n";
  return 0;
}

#ifndef HEXDYN_CLI_MPI
/// `hexdyn sweep ...`: replaces this process by hexdyn-sweep with the same arguments, found
/// next to this program (the build tree) or in ../libexec/hexdyn/ (an installation).
/// Returns only when it cannot, with the exit status of an internal error.
int exec_sweep_program(char** argv) {
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  std::string dir = ".";
  if (n > 0) {
    self[n] = '\0';
    dir = std::string(self);
    dir = dir.substr(0, dir.find_last_of('/'));
  }
  std::string tried;
  for (const std::string& path : {dir + "/hexdyn-sweep", dir + "/../libexec/hexdyn/hexdyn-sweep"}) {
    ::execv(path.c_str(), argv);
    tried += (tried.empty() ? "" : ", ") + path + " (" + std::strerror(errno) + ")";
  }
  if (!hexdyn::launched_as_secondary_rank())
    std::cerr << "hexdyn: internal error: sweep: cannot start hexdyn-sweep: " << tried << "\n";
  return 4;
}
#endif

}  // namespace

int main(int argc, char** argv) {
#ifndef HEXDYN_CLI_MPI
  if (argc >= 2 && !std::strcmp(argv[1], "sweep")) return exec_sweep_program(argv);
#endif
  if (argc >= 2 && is_help(argv[1])) {
    std::cout << kUsage << kRunUsage << "\n" << kValidateUsage << "\n" << kSweepUsage;
    return 0;
  }
  if (argc >= 2 && !std::strcmp(argv[1], "--version")) {
    std::cout << "hexdyn " << hexdyn::kVersion << " (" << hexdyn::kGitCommit << ")\n";
    return 0;
  }
  // `hexdyn envelope` parses its own arguments (envelope/envelope.hpp).
  if (argc >= 2 && !std::strcmp(argv[1], "envelope"))
    return hexdyn::envelope_command(argc - 1, argv + 1);
  // `hexdyn replay` too (replay/replay_file.hpp).
  if (argc >= 2 && !std::strcmp(argv[1], "replay"))
    return hexdyn::replay_command(argc - 1, argv + 1);
  // `hexdyn COMMAND ... --help` prints that command's usage, whatever else is given.
  if (argc >= 2 && command_usage(argv[1])) {
    for (int i = 2; i < argc; ++i) {
      if (!std::strcmp(argv[i], "--set") || !std::strcmp(argv[i], "-o") ||
          !std::strcmp(argv[i], "--output") || !std::strcmp(argv[i], "--progress")) {
        ++i;  // a flag's value is not a request for help
        continue;
      }
      if (is_help(argv[i])) {
        std::cout << command_usage(argv[1]);
        return 0;
      }
    }
  }
  try {
    // Every input file is read once for the whole command (config/inputs.hpp).
    const hexdyn::InputFreeze freeze;
    const Args args = parse_args(argc, argv);
    if (args.command == "validate") return validate(args);
    if (args.command == "run") return run(args);
    if (args.command == "sweep") {
      if (args.output.empty()) throw hexdyn::ConfigError("sweep: missing -o FILE");
        // The output is checked against every input of the sweep by run_sweep, before any work.
#ifdef HEXDYN_CLI_MPI
      return hexdyn::run_sweep(
          {args.config, args.output, args.keep_runs, args.resume, args.verbose, args.progress_s});
#endif
    }
    throw hexdyn::ConfigError("unknown command '" + args.command + "'; run 'hexdyn --help'");
  } catch (const hexdyn::Error& e) {
    if (!hexdyn::launched_as_secondary_rank())
      std::cerr << "hexdyn: error: " << hexdyn::one_line(e.what()) << "\n";
    return e.exit_status();
  } catch (const YAML::Exception& e) {
    // A YAML lookup that a reader did not guard (e.g. a missing key read as a scalar) still
    // comes from the user's file: bad input, not a crash. Each such case is a reader bug to
    // fix where it is thrown; this keeps the exit status and the one line meanwhile.
    if (!hexdyn::launched_as_secondary_rank())
      std::cerr << "hexdyn: error: " << hexdyn::one_line(argc >= 3 ? argv[2] : "input")
                << ": unexpected YAML structure: " << hexdyn::one_line(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "hexdyn: internal error: " << hexdyn::one_line(e.what()) << "\n";
    return 4;
  }
}
