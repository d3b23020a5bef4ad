// `hexdyn run` and `hexdyn validate`: one scene computed or checked (cli/command.hpp).
#include <iostream>
#include <vector>

#include "hexdyn/cli/subcommands.hpp"
#include "hexdyn/cli/verdict.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/model/stance.hpp"
#include "hexdyn/model/urdf_robot.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/planning/gait.hpp"
#include "hexdyn/sweep/validate.hpp"

namespace hexdyn::cli {
namespace {

/// -v: a URDF robot's leg mapping (the description's chains → L1 … L6) and its stance
/// (model/stance.hpp: each leg's pose and how it was obtained), one line per leg.
void print_leg_mapping(const Scene& scene, std::ostream& os) {
  if (!scene.robot.urdf) return;
  const UrdfRobot& robot = *scene.robot.urdf;
  os << "hexdyn: robot '" << robot.name << "' from " << robot.source_path << ", trunk link "
     << robot.trunk_link << " (forward " << robot.forward_axis << "), legs:\n"
     << leg_mapping_text(robot) << "hexdyn: stance of each leg (robot.nominal_pose):\n"
     << stance_text(scene.robot.stance) << "hexdyn: footholds " << scene.gait.foot_lateral_m
     << " m from the hips along their outward directions (gait.foot_lateral)\n";
}

/// -v: each leg's lift-off phase, from gait.pattern or gait.phases (model/gait_pattern.hpp).
void print_gait_phases(const Scene& scene, std::ostream& os) {
  const std::vector<double> phases =
      liftoff_phases(scene.gait, gait_legs(build_robot_model(scene.robot)));
  const GaitPattern pattern = scene.gait.pattern;
  os << "hexdyn: lift-off phases (fraction of a cycle; gait.pattern " << gait_pattern_word(pattern)
     << (pattern == GaitPattern::kCustom ? ": gait.phases" : "") << ", swings of "
     << 1.0 - scene.gait.duty_factor << " of a cycle):";
  for (std::size_t leg = 0; leg < phases.size(); ++leg)
    os << (leg ? ", " : " ") << leg_name(static_cast<int>(leg)) << " " << phases[leg];
  os << "\n";
}

/// The scene's warnings (Scene::warnings), one line each on stderr.
void print_warnings(const Scene& scene) {
  for (const std::string& w : scene.warnings) std::cerr << "hexdyn: warning: " << w << "\n";
}

}  // namespace

int validate_command(const Args& args) {
  const ValidationReport report = validate_file(args.input, args.overrides);
  if (args.verbose && report.scene) {
    print_leg_mapping(*report.scene, std::cout);
    print_gait_phases(*report.scene, std::cout);
  }
  if (report.scene) print_warnings(*report.scene);
  for (const std::string& line : report.messages) std::cout << line << "\n";
  return 0;
}

/// Every check of the inputs, the output path and the run's size comes before any computing.
int run_command(const Args& args) {
  std::vector<InputFile> inputs;
  const Scene scene = load_scene(args.input, args.overrides, &inputs);
  if (args.verbose) {
    print_leg_mapping(scene, std::cerr);
    print_gait_phases(scene, std::cerr);
  }
  print_warnings(scene);
  // Before any computing: the output is a new path or a regular file that is none of the
  // inputs (the scene, its inherited files, its URDF).
  check_output_target(args.output, inputs);
  // Before the allocation: the grid's size, against the large-run limit.
  const PreparedScene prep = prepare_scene(scene);
  check_run_size(prep.grid.size(), prep.model.legs(), prep.model.joints(), args.allow_large);
  // A line every 5 s while the stages compute (an Ipopt run at a fine tolerance takes minutes).
  const ProgressScope progress(std::cerr, "run", args.progress_s);
  const RunResult result = run_prepared_scene(scene, prep, &std::cerr);
  write_result_file(args.output, result, inputs);
  std::cerr << "hexdyn: wrote " << args.output << " (" << result.kin.samples() << " samples, "
            << result.wall_time_s << " s)\n"
            << run_verdict(result) << "\n";
  return 0;
}

}  // namespace hexdyn::cli
