// The run's verdict line (cli/verdict.hpp).
#include "hexdyn/cli/verdict.hpp"

#include <cmath>

#include "hexdyn/core/common.hpp"
#include "hexdyn/sweep/scenario.hpp"

namespace hexdyn::cli {

std::string run_verdict(const RunResult& run) {
  const ScenarioSummary s = summarize_run(run, 0);
  auto num = [](double x) { return format_number(x, 6); };
  std::string line = "hexdyn: verdict: " + std::to_string(s.samples) + " samples, " +
                     std::to_string(s.relaxed_gait_samples) + " relaxed outside touchdowns (" +
                     std::to_string(s.relaxed_samples - s.relaxed_gait_samples) + " in them)";
  if (s.failed_samples > 0) line += ", " + std::to_string(s.failed_samples) + " failed";
  if (s.no_friction_samples < 0) {
    line += ", required friction not computed (output.required_friction is false)";
  } else if (std::isnan(s.required_friction_support)) {
    line += ", no required friction outside touchdowns";
  } else {
    const int leg = s.required_friction_support_leg;
    line += ", largest required friction " + num(s.required_friction_support) + " (" +
            (leg >= 0 ? leg_name(leg) : std::string("no leg")) +
            " at t = " + num(s.required_friction_support_time_s) + " s) outside touchdowns";
  }
  if (s.no_friction_samples > 0)
    line +=
        ", no friction coefficient admits " + std::to_string(s.no_friction_samples) + " samples";
  return line + ", " + std::to_string(s.slip_samples) + " slip samples";
}

}  // namespace hexdyn::cli
