#pragma once
/// \file solve_dynamics.hpp
/// The dynamics stage's driver (docs/theory/stages.md#inverse-dynamics,
/// docs/theory/allocation.md#measured-violation-flags): for every sample, the affine split of the
/// equations of motion (dynamics/rnea.hpp), the allocation problem (allocation/problem.hpp)
/// solved by the scene's back end, and the foot forces, joint torques and penetrations;
/// then joint power and energy (power/power.hpp), per run and per gait cycle.
#include <array>
#include <iosfwd>
#include <limits>
#include <memory>
#include <vector>

#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/stage_times.hpp"
#include "hexdyn/planning/plan.hpp"
#include "hexdyn/power/quadrature.hpp"

namespace hexdyn {

class SampleSolver;

/// One sample's allocation problem as the run solves it: its rows at the scene's μ
/// (allocation/qp.hpp), the variable layout, the contact phases, and the answers of the
/// allocation and of the required friction (docs/theory/grip.md#one-samples-rows).
struct SampleProblem {
  QpProblem qp;
  AllocationLayout layout;
  int legs = 0;                    ///< the robot's legs: the first entries of phase
  LegArray<ContactPhase> phase{};  ///< each leg's contact phase
  Eigen::VectorXd x;               ///< the allocation's solution (contact-frame forces [N])
  SolverStatus status = SolverStatus::kOptimal;
  double required_friction = 0.0;  ///< NaN where none suffices (or not computed)
  int required_friction_leg = -1;
};

/// Sample i of `kin` under contacts `c`, solved alone (cold back ends).
SampleProblem solve_sample_problem(const Scene& scene, const RobotModel& model,
                                   const KinematicsResult& kin, int i, const SampleContacts& c);

/// The per-sample part of the dynamics stage with the workspace it keeps between calls: the
/// dynamics buffers, the allocation problem and the back end, whose warm start carries from one
/// solve to the next, also from one call to the next (the output grid's refinement solves its
/// new samples with the same solver, pipeline/pipeline.hpp).
class DynamicsSolver {
 public:
  /// Throws SolverError when the scene's allocation back end cannot start.
  DynamicsSolver(const Scene& scene, const RobotModel& model);
  ~DynamicsSolver();
  DynamicsSolver(const DynamicsSolver&) = delete;
  DynamicsSolver& operator=(const DynamicsSolver&) = delete;

  /// Where a sample's warm start comes from: the solve before it (samples in time order, the
  /// grid as built), or the last solve of a sample with the same contact phases (samples spread
  /// over a run, the refinement's: the nearest such sample before it is alike, the one solved
  /// just before may be in another phase of the gait).
  enum class WarmStart { kPrevious, kSamePhases };

  /// The per-sample fields of the result for every sample of `kin` under `contacts` (from
  /// schedule_contacts over the same kin): torques, forces, penetrations, solver status,
  /// iterations, objective, seconds, messages and the largest measured violations; the power
  /// and energy fields are left empty (finish_dynamics). `times` as solve_dynamics.
  DynamicsResult solve(const KinematicsResult& kin, const ContactSchedule& contacts,
                       StageTimes* times = nullptr, WarmStart warm = WarmStart::kPrevious);

 private:
  const Scene& scene_;
  const RobotModel& model_;
  std::unique_ptr<SampleSolver> solver_;
  /// Solvers by contact phases (WarmStart::kSamePhases), key: the legs' phases in base 3.
  std::vector<std::pair<int, std::unique_ptr<SampleSolver>>> by_phases_;
  /// The largest required friction found so far (not a bound), of samples outside touchdown
  /// transients [0] and inside them [1]; −inf before the first.
  std::array<double, 2> largest_mu_{-std::numeric_limits<double>::infinity(),
                                    -std::numeric_limits<double>::infinity()};
  /// With output.summary_only, the required friction a sample of this kind needs exactly only
  /// from here up (RequiredFrictionSolver::solve's `enough`); else −inf.
  double enough(bool transient) const;
};

/// What solve_dynamics does after the per-sample solves, on a result whose samples are final:
/// the touchdowns' records and log lines, the episodes of relaxed or failed samples
/// (pipeline/episode_log.hpp), the power and energies over the samples (power/power.hpp) and, with
/// actuators, the electrical side (drive/drive.hpp). `log` may be null. `estimates` (may be
/// null): refine_output_grid's last, whose interval energies compute_power takes.
void finish_dynamics(const Scene& scene, const RobotModel& model, const MotionPlan& plan,
                     const KinematicsResult& kin, const std::vector<Touchdown>& touchdowns,
                     DynamicsResult& dyn, std::ostream* log, StageTimes* times = nullptr,
                     const CubicEstimates* estimates = nullptr);

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
