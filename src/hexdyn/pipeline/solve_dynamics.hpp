#pragma once
/// \file solve_dynamics.hpp
/// The dynamics stage's driver (docs/theory/stages.md#inverse-dynamics,
/// docs/theory/allocation.md#measured-violation-flags): for every sample, the affine split of the
/// equations of motion (dynamics/rnea.hpp), the allocation problem (allocation/problem.hpp)
/// solved by the scene's back end, and the foot forces, joint torques and penetrations;
/// then joint power and energy (power/power.hpp), per run and per gait cycle.
#include <iosfwd>
#include <vector>

#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/stage_times.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

/// The dynamics of every sample of `kin` under the contact schedule `contacts` (from
/// schedule_contacts over the same kin and touchdowns). Reads its inputs only; the
/// schedule's phases are the run's /contacts/phase. `log` (may be null) receives one line
/// per truncated touchdown transient and per episode of relaxed or failed samples.
/// `times` (may be null) receives the time of the stages rnea, allocation, verdict and power.
/// Throws SolverError when `contacts` does not match `kin` or an allocation back end
/// cannot start.
DynamicsResult solve_dynamics(const Scene& scene, const RobotModel& model, const MotionPlan& plan,
                              const KinematicsResult& kin, const ContactSchedule& contacts,
                              const std::vector<Touchdown>& touchdowns, std::ostream* log,
                              StageTimes* times = nullptr);

}  // namespace hexdyn
