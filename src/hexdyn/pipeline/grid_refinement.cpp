#include "hexdyn/pipeline/grid_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <utility>

#include "hexdyn/core/cancel.hpp"
#include "hexdyn/drive/drive.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/planning/grid.hpp"
#include "hexdyn/power/grid_error.hpp"
#include "hexdyn/power/power.hpp"

namespace hexdyn {
namespace {

/// The refinement's limits (docs/theory/output-grid.md#error-control): the shortest interval
/// it splits is 2 kMinRefinedStep_s (a new sample is never closer than kMinRefinedStep_s to
/// another, far above the 1e-9 s at which grid points merge; a shorter interval is taken as a
/// step the series makes), at most kMaxRefinementPasses passes, and at most kMaxRefinedSamples
/// samples in all (the CLI's size guard's count).
constexpr double kMinRefinedStep_s = 1e-7;
constexpr int kMaxRefinementPasses = 40;
constexpr std::size_t kMaxRefinedSamples = 200000;

/// A run's samples while its grid is refined: the batches as computed (the first is the grid
/// as built) and their samples in time order.
struct Batches {
  std::vector<KinematicsResult> kin;
  std::vector<DynamicsResult> dyn;
  std::vector<SampleRef> order;

  const KinematicsResult& kin_of(const SampleRef& r) const { return kin[r.part]; }
  const DynamicsResult& dyn_of(const SampleRef& r) const { return dyn[r.part]; }
  double time(const SampleRef& r) const { return kin[r.part].time_s[r.row]; }

  /// Adds a batch (its samples increasing in time) and merges its samples into the order.
  void add(KinematicsResult k, DynamicsResult d) {
    const int part = static_cast<int>(kin.size());
    std::vector<SampleRef> more;
    for (int r = 0; r < k.samples(); ++r) more.push_back({part, r});
    kin.push_back(std::move(k));
    dyn.push_back(std::move(d));
    std::vector<SampleRef> merged;
    merged.reserve(order.size() + more.size());
    std::merge(order.begin(), order.end(), more.begin(), more.end(), std::back_inserter(merged),
               [this](const SampleRef& a, const SampleRef& b) { return time(a) < time(b); });
    order = std::move(merged);
  }
};

/// The series the output grid controls, gathered in time order: the joint powers τ_k ω_k,
/// whose absolute values and their sum are integrated (the energies), and |τ_k| per joint, the
/// total power and the largest foot force (the peaks); with actuators also the electrical
/// powers P⁺_k drawn (integrated, each and their sum), |τ_drive,k| and the total electrical
/// power (peaks) (docs/theory/output-grid.md#error-control). The mechanical energies are held
/// by the rule they are computed by (energy_rule), the electrical ones by the trapezoid's.
struct ControlledSeries {
  std::vector<double> t_s;
  std::vector<char> jump;  ///< from a left-limit sample to its event
  RowMatrix power;         ///< T×joints, τ_k ω_k [W]
  RowMatrix abs_torque;    ///< T×joints [N m]
  std::vector<double> total_power_W, max_force_N;
  RowMatrix electrical;        ///< with actuators: T×joints, P⁺_k [W]
  RowMatrix abs_drive_torque;  ///< with actuators: T×joints, |τ_drive,k| [N m]
  std::vector<double> total_electrical_W;
  std::vector<SeriesView> terms;
  std::vector<IntegralTarget> integrals;
  std::vector<SeriesView> peaks;

  /// `joints`, `legs`: the robot's counts (RobotModel::joints(), legs()).
  ControlledSeries(const Batches& b, const DriveTrainParams& drive, Quadrature rule, int joints,
                   int legs) {
    const int J = joints;
    const std::size_t T = b.order.size();
    const auto rows = static_cast<Eigen::Index>(T);
    t_s.resize(T);
    jump.assign(T, 0);
    power.resize(rows, J);
    abs_torque.resize(rows, J);
    total_power_W.resize(T);
    max_force_N.assign(T, 0.0);
    for (std::size_t i = 0; i < T; ++i) {
      const SampleRef& r = b.order[i];
      const KinematicsResult& k = b.kin_of(r);
      const DynamicsResult& d = b.dyn_of(r);
      t_s[i] = k.time_s[r.row];
      jump[i] = !k.sample_kind.empty() && k.sample_kind[r.row] == kSampleLeftLimit;
      const double* tau = d.joint_torque.data() + static_cast<std::size_t>(r.row) * J;
      const double* omega = k.joint_velocity.data() + static_cast<std::size_t>(r.row) * J;
      double* p = power.data() + i * J;
      double* a = abs_torque.data() + i * J;
      double sum = 0.0;
      for (int j = 0; j < J; ++j) {
        p[j] = tau[j] * omega[j];
        a[j] = std::abs(tau[j]);
        sum += std::abs(p[j]);
      }
      total_power_W[i] = sum;
      const double* F = d.contact_force.data() + static_cast<std::size_t>(r.row) * 3 * legs;
      double f2 = 0.0;
      for (int l = 0; l < legs; ++l)
        f2 = std::max(
            f2, F[3 * l] * F[3 * l] + F[3 * l + 1] * F[3 * l + 1] + F[3 * l + 2] * F[3 * l + 2]);
      max_force_N[i] = std::sqrt(f2);
    }
    // Each joint's energy is held to the larger of its own value and the mean joint's: a
    // joint that does almost no work is not refined to the rounding of its tiny energy.
    const double total = trapezoid(t_s, total_power_W.data());
    IntegralTarget all{{}, total};
    const RowMatrix abs_power = power.cwiseAbs();
    for (int j = 0; j < J; ++j) {
      terms.push_back({power.data() + j, J});
      const double energy = trapezoid(t_s, abs_power.data() + j, J);
      integrals.push_back({{j}, std::max(energy, total / J), rule});
      all.terms.push_back(j);
    }
    all.rule = rule;
    integrals.push_back(std::move(all));
    for (int j = 0; j < J; ++j) peaks.push_back({abs_torque.data() + j, J});
    peaks.push_back({total_power_W.data(), 1});
    peaks.push_back({max_force_N.data(), 1});
    if (drive.present) add_drive_train(b, drive, J);
  }

  /// The electrical energies and the drive's peaks, as the mechanical ones above.
  void add_drive_train(const Batches& b, const DriveTrainParams& drive, int J) {
    const std::size_t T = b.order.size();
    electrical.resize(static_cast<Eigen::Index>(T), J);
    abs_drive_torque.resize(static_cast<Eigen::Index>(T), J);
    total_electrical_W.assign(T, 0.0);
    for (std::size_t i = 0; i < T; ++i) {
      const SampleRef& r = b.order[i];
      const auto row = static_cast<Eigen::Index>(r.row);
      for (int j = 0; j < J; ++j) {
        const double tau = b.dyn_of(r).drive_torque(row, j);
        const double omega = b.kin_of(r).joint_velocity(row, j);
        const double p = electrical_power(drive.joints[j], tau, omega);
        electrical(static_cast<Eigen::Index>(i), j) = p;
        abs_drive_torque(static_cast<Eigen::Index>(i), j) = std::abs(tau);
        total_electrical_W[i] += std::abs(p);
      }
    }
    const double total = trapezoid(t_s, total_electrical_W.data());
    IntegralTarget all{{}, total};
    const RowMatrix abs_electrical = electrical.cwiseAbs();
    for (int j = 0; j < J; ++j) {
      const int term = static_cast<int>(terms.size());
      terms.push_back({electrical.data() + j, J});
      const double energy = trapezoid(t_s, abs_electrical.data() + j, J);
      integrals.push_back({{term}, std::max(energy, total / J)});
      all.terms.push_back(term);
      peaks.push_back({abs_drive_torque.data() + j, J});
    }
    integrals.push_back(std::move(all));
    peaks.push_back({total_electrical_W.data(), 1});
  }
};

}  // namespace

KinematicsResult sample_with_contacts(const PreparedScene& prep, const std::vector<double>& t_s,
                                      ContactSchedule& contacts, StageTimes* times) {
  std::optional<StageTimer> clock(std::in_place, times, Stage::kKinematics);
  KinematicsResult kin = sample_kinematics(prep.model, prep.plan, t_s);
  if (kin.sample_kind.size() != t_s.size()) kin.sample_kind.assign(t_s.size(), kSampleOrdinary);
  clock.emplace(times, Stage::kContacts);
  contacts = schedule_contacts(kin, prep.plan.terrain, prep.touchdowns);
  kin.contact_phase = contacts.phase;
  return kin;
}

GridAccuracy refine_output_grid(const Scene& scene, const PreparedScene& prep,
                                DynamicsSolver& solver, KinematicsResult& kin, DynamicsResult& dyn,
                                std::ostream* log, StageTimes* times, CubicEstimates* estimates) {
  const double tol = scene.output.tolerance;
  const bool refine = tol > 0.0 && scene.output.grid == OutputGrid::kAdaptive;
  // Without refinement, the estimates are those of the default tolerance's assessment.
  const double assess_tol = refine ? tol : kDefaultOutputTolerance;
  GridAccuracy acc;
  acc.tolerance = refine ? tol : 0.0;
  acc.cubic_energy = energy_rule(scene.output.grid) == Quadrature::kCubic;
  Batches b;
  b.add(std::move(kin), std::move(dyn));
  CubicEstimates own;  // each pass's cubic estimates, for the intervals the next keeps
  CubicEstimates& reuse = estimates ? *estimates : own;
  for (int pass = 0;; ++pass) {
    check_cancelled();
    std::optional<StageTimer> clock(std::in_place, times, Stage::kRefinement);
    GridAssessment a;
    {
      const ControlledSeries series(b, prep.model.drive, energy_rule(scene.output.grid),
                                    prep.model.joints(), prep.model.legs());
      a = assess_grid(series.t_s, series.jump, series.terms, series.integrals, series.peaks,
                      assess_tol, kMinRefinedStep_s, &reuse);
    }
    acc.energy_error = a.integral_error;
    acc.peak_error = a.peak_error;
    if (!refine || a.refine_at_s.empty()) break;
    const std::size_t T = b.order.size();
    if (pass == kMaxRefinementPasses || T + a.refine_at_s.size() > kMaxRefinedSamples) {
      if (log)
        *log << "hexdyn: output grid: output.tolerance " << tol << " not reached after " << pass
             << " refinement passes and " << T << " samples (estimated energy error "
             << acc.energy_error << ", peak error " << acc.peak_error << ")\n";
      break;
    }
    clock.reset();  // the sampling and the solver time their own stages
    ContactSchedule contacts;
    KinematicsResult more = sample_with_contacts(prep, a.refine_at_s, contacts, times);
    DynamicsResult solved =
        solver.solve(more, contacts, times, DynamicsSolver::WarmStart::kSamePhases);
    clock.emplace(times, Stage::kRefinement);
    b.add(std::move(more), std::move(solved));
    ++acc.refinement_passes;
    acc.added_samples += static_cast<int>(a.refine_at_s.size());
  }
  const StageTimer clock(times, Stage::kRefinement);
  if (b.kin.size() == 1) {  // nothing added: the samples as they came
    kin = std::move(b.kin.front());
    dyn = std::move(b.dyn.front());
    return acc;
  }
  std::vector<const KinematicsResult*> kin_parts;
  std::vector<const DynamicsResult*> dyn_parts;
  for (std::size_t p = 0; p < b.kin.size(); ++p) {
    kin_parts.push_back(&b.kin[p]);
    dyn_parts.push_back(&b.dyn[p]);
  }
  kin = gather_samples(kin_parts, b.order);
  dyn = gather_samples(dyn_parts, b.order);
  return acc;
}

}  // namespace hexdyn
