#pragma once
/// \file robustness.hpp
/// A robustness study (docs/user/robustness.md): a scene planned once, as `hexdyn run` plans
/// it, then its plan replayed (replay/replay.hpp) on the perturbed worlds of the scene's
/// `robustness:` section (core/robustness_params.hpp, world.hpp), each replay's outcome
/// classified (outcome.hpp), and the probability of success with its Wilson interval;
/// optionally, per perturbation, the largest scale of its distribution at which the plan still
/// climbs with the target probability. `hexdyn robustness` runs one study on a scene's threads;
/// a sweep whose scenes have `robustness:` runs one per scenario (sweep/scenario.hpp).
#include <array>
#include <string>
#include <vector>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/replay/replay.hpp"
#include "hexdyn/robustness/outcome.hpp"
#include "hexdyn/robustness/perturbation.hpp"

namespace hexdyn {

/// One perturbation's tolerated error (ToleranceSearch).
struct ToleranceResult {
  Perturbation perturbation = Perturbation::kRiserHeight;
  double scale = 0.0;      ///< the largest scale found to pass [1]
  double magnitude = 0.0;  ///< its largest error: scale × the distribution's largest_magnitude
  double p_success = 1.0;  ///< the success fraction at `scale`
  /// The largest scale searched: robustness.tolerance.max_scale, or less where a larger one
  /// could draw an unphysical world (config/robustness_bounds.hpp).
  double max_scale = 0.0;
  bool censored = false;  ///< it passes at max_scale: the tolerance is at least that
  int probes = 0;         ///< scales evaluated
};

/// What a study found.
struct RobustnessResult {
  DrawSizes sizes;
  std::vector<std::string> joint_names;  ///< J; the link of joint j is the body it moves
  std::vector<WorldDraw> draws;          ///< per replay
  std::vector<ReplayOutcome> outcomes;   ///< per replay
  long successes = 0;
  std::array<long, kFailureClassCount> counts{};  ///< replays per failure class
  double p_success = 0.0;
  WilsonInterval interval;                 ///< 95 %
  FailureBounds bounds;                    ///< as applied (drift_m resolved)
  std::vector<ToleranceResult> tolerance;  ///< per active perturbation, with the search
  double plan_seconds = 0.0;               ///< the planning run [s]
  double seconds = 0.0;                    ///< the whole study [s]
};

/// The replays of a study of `scene`: its robustness.replays, or kDefaultRobustnessReplays for
/// a scene without the section.
int study_replays(const Scene& scene);

/// The plan a study replays: the robot, the plan in the trunk frame (replay.hpp, with its
/// contact phases) and joint names (J).
struct StudyPlan {
  RobotModel model;
  ReplayPlan plan;
  std::vector<std::string> joint_names;
};
/// The plan of a computed run of `model`'s robot.
StudyPlan plan_of_run(const RobotModel& model, const RunResult& run);

/// Runs the study of `scene.robustness` with `threads` ≥ 1 threads; the result does not depend
/// on `threads` (counter-based draws). Reports progress in replays (core/progress.hpp) and
/// stops at check_cancelled. `plan`, when given, receives the planning run (its summary is a
/// sweep row's). Throws what run_scene and replay_plan throw for the plan (a scene that cannot
/// be planned, a plan that cannot be replayed).
RobustnessResult run_robustness(const Scene& scene, int threads, RunResult* plan = nullptr);

/// The study of a given plan (a result file's: replay/replay_file.hpp read_replay_source with
/// robustness) under `scene`'s robustness: section, its robot `plan.model`; as above.
RobustnessResult run_robustness(const Scene& scene, const StudyPlan& plan, int threads);

/// The `hexdyn-robustness/1` file of the study of `scene` in memory (io/result_layout.hpp):
/// its /meta attributes (created_utc = now) and datasets, as write_robustness_file writes them.
ResultLayout robustness_layout(const Scene& scene, const std::vector<InputFile>& inputs,
                               const RobustnessResult& result);

/// Writes the `hexdyn-robustness/1` file (io/schema_robustness.hpp) of the study of `scene`
/// atomically, after check_output_target against `inputs` (the scene's files).
void write_robustness_file(const std::string& path, const Scene& scene,
                           const std::vector<InputFile>& inputs, const RobustnessResult& result);

}  // namespace hexdyn
