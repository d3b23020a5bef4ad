// The table of subcommands (cli/command.hpp): a row each, with its help text.
#include <array>

#include "hexdyn/cli/command.hpp"
#include "hexdyn/cli/subcommands.hpp"

namespace hexdyn::cli {
namespace {

constexpr const char* kRunHelp =
    R"(  Runs a scene and writes its hexdyn-result/5 file to FILE. -v prints a URDF robot's
  leg mapping (which chain of the description is L1 ... L6). While the stages compute, a
  progress line comes at most every --progress seconds (default 5). The run ends with a
  verdict line: samples, relaxed samples outside touchdowns, the largest required friction
  with its leg and time, and slip samples (docs/user/output.md#the-runs-verdict).

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

constexpr const char* kValidateHelp =
    R"(  Checks a scene file, or a sweep file, and exits without computing anything.

A file with a top-level `axes:` key is a sweep file: it is checked as `hexdyn sweep`
would check it (its keys, axes and base scene), and each scenario's scene is validated;
scenarios with a value out of range are counted (exit status 0: `hexdyn sweep` records
them as rows with status config). --set applies to scene files only.
)";

constexpr const char* kSweepHelp =
    R"(  Runs a parameter sweep and writes its hexdyn-sweep/5 file to FILE.

SWEEP is a sweep file (see configs/sweeps/stairs.yaml): a base scene and axes over its
keys; every combination is a scenario. Run it under `mpirun -np N` or plainly (one
rank). Scenarios that cannot be computed are rows with a status and a message; the exit
status is 0 once FILE is written. --keep-runs also stores each scenario's full result
under /runs/<id>. Finished scenarios are kept in FILE.checkpoint/ until FILE is
complete; --resume continues an interrupted sweep from there. -v prints one line per
scenario; progress lines come at most every --progress seconds (default 5).
)";

constexpr const char* kEnvelopeHelp =
    R"(  Finds the largest stair riser the robot climbs, per tread depth, duty factor and peak
  speed (and per case: a design of `cases:`), under the kinematic, torque and friction
  criteria, and writes the hexdyn-envelope/2 file FILE (docs/user/envelope.md;
  configs/envelope/paper.yaml documents the keys). With `search: friction` it finds
  instead the least friction coefficient per riser of the scan. -v prints one line per
  cell and criterion.
)";

constexpr const char* kRobustnessHelp =
    R"(  Plans the scene CONFIG once, as `hexdyn run` plans it (or takes the stored plan of
  CONFIG, a result file of `hexdyn run`, whose scene --set may change in its replay.*,
  contact.* and robustness.* keys), then replays the plan (as `hexdyn replay`) on
  robustness.replays worlds whose risers, treads, nosings, friction,
  masses, payload, actuators, foot placement and contact stiffness differ from the plan's by
  errors drawn from the distributions of its robustness: section, and writes the
  hexdyn-robustness/1 file FILE: each replay's outcome (reached the top, or slipped, stubbed a
  toe, saturated, fell or drifted), its drawn errors, the probability of success with its
  Wilson 95 % interval and, with robustness.tolerance, the largest error of each kind the plan
  tolerates (docs/user/robustness.md; configs/robustness/paper.yaml shows the keys). The draws
  depend on robustness.seed and the replay's index alone: FILE is the same for any --jobs
  (default: one thread per core) but for its timing fields.
)";

constexpr const char* kReplayHelp =
    R"(  Replays a result's joint torques through the forward dynamics of the robot on its
  terrain, with compliant contact and friction, and writes a hexdyn-replay/3 file to FILE
  (docs/user/replay.md).

Each joint is driven by its stored torque plus a PD on the planned angle and rate (gains
replay.kp [N m/rad] and replay.kd [N m s/rad]; auto by default: 10 and 0.1, or 1.1 m g l and
a hundredth of it for a robot whose weight moment m g l exceeds 50 N m; 0 and 0 is open
loop). The integrator's largest step is replay.step [s]. The contact's friction law is contact.friction_law:
stick_slip (default; contact.tangential_stiffness and contact.tangential_damping) or
regularised (contact.stiction_velocity and contact.friction_velocity), both with
contact.static_friction and contact.dynamic_friction. --set
changes a key of replay.* or contact.* for the replay (--set contact.static_friction=0.2);
any other key would not change the stored plan and is refused. With actuators: the joints
are driven through them (the planned drive torques, the armature and the joints' friction,
each drive bounded by its torque-speed envelope unless replay.saturate is false), and the
electrical energy and saturation are reported. The robot and the scene are
the result's own (/meta config_yaml, /model/urdf): files edited since the run are not read.
A progress line comes at most every --progress seconds (default 5). The report (trunk
drift per gait cycle, tracking error, slip and touchdown energy, whether the robot reached
the plan's end) is in /replay of FILE and printed on stderr.
)";

int sweep_row(const Args& args) { return args.program->sweep(args); }

// clang-format off
constexpr std::array kCommands{
    Command{"run", "CONFIG", kOutput | kSet | kAllowLarge | kVerbose | kProgress, kOutput,
            "run a scene, write hexdyn-result/5", kRunHelp, run_command, true},
    Command{"validate", "FILE", kSet | kVerbose, 0,
            "check a scene or sweep file and exit", kValidateHelp, validate_command},
    Command{"sweep", "SWEEP", kOutput | kKeepRuns | kResume | kVerbose | kProgress, kOutput,
            "run a parameter sweep, write hexdyn-sweep/5", kSweepHelp, sweep_row, false,
            "fix keys with set: in the sweep file"},
    Command{"envelope", "ENVELOPE", kOutput | kVerbose, kOutput,
            "find the climbable riser, write hexdyn-envelope/2", kEnvelopeHelp, envelope_command,
            true},
    Command{"replay", "RESULT", kOutput | kSet | kProgress, kOutput,
            "replay a result's torques, write hexdyn-replay/3", kReplayHelp, replay_command, true},
    Command{"robustness", "CONFIG", kOutput | kSet | kProgress | kJobs, kOutput,
            "replay a plan on perturbed worlds, write hexdyn-robustness/1", kRobustnessHelp,
            robustness_command, true},
};
// clang-format on

}  // namespace

std::span<const Command> commands() { return kCommands; }

}  // namespace hexdyn::cli
