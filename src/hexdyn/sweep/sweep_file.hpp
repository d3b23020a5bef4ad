#pragma once
/// \file sweep_file.hpp
/// The `hexdyn-sweep/5` file: the layout is declared in io/schema.hpp (paths, units,
/// shapes: N scenarios, A axes), which this writer follows for every path and units string.
#include <cstddef>
#include <string>
#include <vector>

#include "hexdyn/sweep/checkpoint.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

/// Facts about the run that produced a sweep file, stored in /meta. All of them are
/// allowed to differ between otherwise identical sweeps.
struct SweepRunInfo {
  int ranks = 1;
  double wall_time_s = 0.0;
  std::size_t resumed_scenarios = 0;  ///< rows taken from an earlier run's checkpoint
};

/// Writes the `hexdyn-sweep/5` file atomically (temporary name, fsync, rename):
/// /meta, /axes/<i>/{key,values,labels}, /joint_names, /scenarios/* (one row per
/// scenario, index order) and, when `runs_from` is given, each computed scenario's
/// run image copied from the checkpoint's journals (Checkpoint::run_image, flushed) to
/// /runs/<id>. `rows` holds every
/// scenario, rows[i].index == i. `robot`: the scenarios' robot shape (sweep_robot_shape),
/// whose joints are /joint_names (positional, core/common.hpp joint_name) and the columns of
/// the per-joint tables; a row of a computed scenario has as many (ScenarioSummary::joints).
/// Throws IoError.
void write_sweep_file(const std::string& path, const SweepSpec& spec,
                      const std::vector<ScenarioSummary>& rows, const RobotShape& robot,
                      const Checkpoint* runs_from, const SweepRunInfo& info);

}  // namespace hexdyn
