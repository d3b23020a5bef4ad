// `hexdyn robustness CONFIG -o FILE`, CONFIG a scene or a result file (cli/command.hpp;
// robustness/robustness.hpp).
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "hexdyn/cli/subcommands.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/replay/replay_file.hpp"
#include "hexdyn/robustness/robustness.hpp"

namespace hexdyn::cli {
namespace {

/// " m", " kg", or "" for a relative error or a friction coefficient.
std::string unit_text(Perturbation p) {
  const std::string unit = perturbation_unit(p);
  return unit == "1" ? "" : " " + unit;
}

/// The report on stderr: the success probability, the failures by class, the tolerances.
void print_report(const Scene& scene, const RobustnessResult& r, std::ostream& os) {
  os << "hexdyn: robustness: " << r.successes << " of " << r.outcomes.size()
     << " replays reached the top: P(success) = " << r.p_success << ", 95 % Wilson interval ["
     << r.interval.low << ", " << r.interval.high << "]\n";
  os << "hexdyn: robustness: failures:";
  bool any = false;
  for (int c = 1; c < kFailureClassCount; ++c)
    if (r.counts[static_cast<std::size_t>(c)] > 0) {
      os << (any ? ", " : " ") << failure_class_name(static_cast<FailureClass>(c)) << " "
         << r.counts[static_cast<std::size_t>(c)];
      any = true;
    }
  os << (any ? "\n" : " none\n");
  for (const ToleranceResult& t : r.tolerance)
    os << "hexdyn: robustness: " << perturbation_name(t.perturbation) << " tolerated "
       << (t.censored ? "at least " : "") << "up to scale " << t.scale << " (errors up to "
       << t.magnitude << unit_text(t.perturbation) << ", P = " << t.p_success << " on "
       << scene.robustness.search.replays << " replays)\n";
}

/// The last line: the file written, its replays, threads and time.
void print_written(const std::string& path, const RobustnessResult& r, int threads) {
  std::cerr << "hexdyn: wrote " << path << " (" << r.outcomes.size() << " replays on " << threads
            << (threads == 1 ? " thread, " : " threads, ") << r.seconds << " s)\n";
}

/// Whether `path` is a regular file that starts with HDF5's signature (a result file).
bool is_hdf5_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  in.read(head, sizeof head);
  return in.gcount() == 8 && std::memcmp(head, "\x89HDF\r\n\x1a\n", 8) == 0;
}

}  // namespace

int robustness_command(const Args& args) {
  const int threads = args.jobs > 0
                          ? args.jobs
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (is_hdf5_file(args.input)) {  // a result file: its stored plan, replayed as it is
    const ReplaySource src = read_replay_source(args.input, args.overrides, true);
    check_output_target(args.output, src.inputs);
    for (const std::string& w : src.warnings)
      std::cerr << "hexdyn: warning: robustness: " << w << "\n";
    const StudyPlan plan{build_robot_model(src.scene.robot), src.plan, src.joint_names};
    const ProgressScope progress(std::cerr, "robustness", args.progress_s, "replays");
    const RobustnessResult r = run_robustness(src.scene, plan, threads);
    write_robustness_file(args.output, src.scene, src.inputs, r);
    print_report(src.scene, r, std::cerr);
    print_written(args.output, r, threads);
    return 0;
  }
  std::vector<InputFile> inputs;
  const Scene scene = load_scene(args.input, args.overrides, &inputs);
  for (const std::string& w : scene.warnings) std::cerr << "hexdyn: warning: " << w << "\n";
  check_output_target(args.output, inputs);
  const ProgressScope progress(std::cerr, "robustness", args.progress_s, "replays");
  const RobustnessResult r = run_robustness(scene, threads);
  write_robustness_file(args.output, scene, inputs, r);
  print_report(scene, r, std::cerr);
  print_written(args.output, r, threads);
  return 0;
}

}  // namespace hexdyn::cli
