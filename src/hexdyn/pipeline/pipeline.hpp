#pragma once
/// \file pipeline.hpp
/// One scene, end to end: the library call behind `hexdyn run` and every sweep
/// scenario (run_scene, pipeline/run.hpp). The stages run in one direction, each reading
/// what the ones before made:
///
///   robot model (model/) → plan: terrain, trunk motion, gait (planning/plan.hpp)
///     → touchdowns and their transients (contact/touchdowns.hpp)
///     → output grid (planning/grid.hpp, refined at the plan's and touchdowns' events)
///     → kinematics on the grid (kinematics/) → contact schedule (contact/touchdowns.hpp)
///     → dynamics, allocation and power (pipeline/solve_dynamics.hpp).
///
/// Throws a hexdyn::Error subclass when the scene cannot be computed.
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <vector>

#include "hexdyn/balance/balance.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/run.hpp"  // IWYU pragma: export (run_scene)
#include "hexdyn/pipeline/solve_dynamics.hpp"
#include "hexdyn/pipeline/stage_times.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

/// Everything a scene determines before the per-sample loop: the model, the plan, the
/// touchdown transients and the output grid (refined at every lift-off and touchdown, with
/// the left limit of every contact event on the adaptive grid, extended past the end of the
/// motion when a final transient outlasts it).
struct PreparedScene {
  RobotModel model;
  MotionPlan plan;
  std::vector<Touchdown> touchdowns;
  std::vector<double> grid;              ///< [s], strictly increasing
  std::vector<std::int8_t> sample_kind;  ///< per grid point: planning/grid.hpp kSample*
  /// motion.trunk: balanced: what planning the offset found (balance/balance.hpp).
  std::optional<BalanceReport> balance;
};
/// `times` (may be null) receives the time of each stage (stage_times.hpp).
PreparedScene prepare_scene(const Scene& scene, StageTimes* times = nullptr);

/// Samples and solves a scene prepared by prepare_scene(scene): what run_scene does after
/// the preparation, so that a caller can look at the grid first (the CLI's size guard).
/// wall_time_s counts from this call.
RunResult run_prepared_scene(const Scene& scene, const PreparedScene& prep,
                             std::ostream* log = nullptr, StageTimes* times = nullptr);

/// The allocation problem of the instant t_s of a prepared scene, as the run solves it
/// (solve_dynamics.hpp SampleProblem, docs/theory/grip.md#one-samples-rows): for second
/// computations of the allocation or the required friction, and for inspection.
SampleProblem sample_problem(const Scene& scene, const PreparedScene& prep, double t_s);

}  // namespace hexdyn
