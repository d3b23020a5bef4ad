#pragma once
/// \file grid_refinement.hpp
/// The output grid's error control (docs/theory/output-grid.md#error-control): a run's grid as
/// built (planning/grid.hpp) refined, pass by pass, where its energies and peaks need it, until
/// the estimates of power/grid_error.hpp are within `output.tolerance`. The samples it adds are
/// computed as every other: kinematics, contact schedule, inverse dynamics and allocation, the
/// latter with the run's solver and its warm start.
#include <iosfwd>
#include <vector>

#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/solve_dynamics.hpp"

namespace hexdyn {

/// The kinematics at the instants t_s (increasing) with their contact phases (the schedule's,
/// touchdown transients included; `contacts` receives the schedule itself). Every sample is
/// ordinary (/sample_kind 0). `times` (may be null): the kinematics and contacts stage clocks.
KinematicsResult sample_with_contacts(const PreparedScene& prep, const std::vector<double>& t_s,
                                      ContactSchedule& contacts, StageTimes* times = nullptr);

/// Refines the samples (kin, dyn) of a run on the grid as built, in place: while the estimated
/// relative error of the energies (each joint's, held to the larger of its own energy and the
/// mean joint's, and the total) or of the peaks (each joint's |τ|, the total power, the largest
/// foot force) exceeds output.tolerance, the intervals that carry it are split, their new
/// samples solved by `solver` and taken into the run in time order. Only on the adaptive grid
/// with output.tolerance > 0; otherwise (the uniform grid, tolerance 0) the samples are left as
/// they are and only assessed. Stops, with one line on `log` (may be null), when a pass limit
/// or the sample limit comes first. dyn holds the per-sample fields only (DynamicsSolver::solve);
/// returns what the grid achieved. `times` (may be null): the stage clocks. `estimates` (may be
/// null): receives the last assessment's piecewise-cubic interval integrals, those of the
/// returned samples, for finish_dynamics.
GridAccuracy refine_output_grid(const Scene& scene, const PreparedScene& prep,
                                DynamicsSolver& solver, KinematicsResult& kin, DynamicsResult& dyn,
                                std::ostream* log, StageTimes* times = nullptr,
                                CubicEstimates* estimates = nullptr);

}  // namespace hexdyn
