#include "hexdyn/sweep/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/robustness/robustness.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"

namespace hexdyn {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

const char* status_name(ScenarioStatus status) {
  switch (status) {
    case ScenarioStatus::kOk:
      return "ok";
    case ScenarioStatus::kConfig:
      return "config";
    case ScenarioStatus::kReach:
      return "reach";
    case ScenarioStatus::kPlanning:
      return "planning";
    case ScenarioStatus::kSolver:
      return "solver";
    case ScenarioStatus::kError:
      return "error";
    case ScenarioStatus::kInternal:
      return "internal";
    case ScenarioStatus::kCrashed:
      return "crashed";
  }
  return "internal";
}

std::string status_codes_text() {
  std::string s;
  for (int c = 0; c <= static_cast<int>(kLastScenarioStatus); ++c)
    s += (s.empty() ? "" : ", ") + std::to_string(c) + " " +
         status_name(static_cast<ScenarioStatus>(c));
  return s;
}

ScenarioStatus classify_exception(const std::exception& e) {
  if (dynamic_cast<const ConfigError*>(&e)) return ScenarioStatus::kConfig;
  if (dynamic_cast<const ReachError*>(&e)) return ScenarioStatus::kReach;
  if (dynamic_cast<const PlanningError*>(&e)) return ScenarioStatus::kPlanning;
  if (dynamic_cast<const SolverError*>(&e)) return ScenarioStatus::kSolver;
  if (dynamic_cast<const Error*>(&e)) return ScenarioStatus::kError;
  return ScenarioStatus::kInternal;
}

int RobotShape::joints() const {
  int n = 0;
  for (int l = 0; l < legs; ++l) n += leg_joints[l];
  return n;
}

bool RobotShape::operator==(const RobotShape& other) const {
  if (legs != other.legs) return false;
  for (int l = 0; l < legs; ++l)
    if (leg_joints[l] != other.leg_joints[l]) return false;
  return true;
}

std::string RobotShape::text() const {
  bool equal = true;
  for (int l = 1; l < legs; ++l) equal = equal && leg_joints[l] == leg_joints[0];
  std::string counts;
  for (int l = 0; l < (equal ? std::min(legs, 1) : legs); ++l)
    counts += (l ? ", " : "") + std::to_string(leg_joints[l]);
  return std::to_string(legs) + " legs of " + counts + " joints";
}

RobotShape robot_shape(const RobotModel& model) {
  RobotShape shape;
  shape.legs = model.legs();
  for (int l = 0; l < model.legs(); ++l) shape.leg_joints[l] = model.leg(l).n_joints;
  return shape;
}

namespace {

/// The thermal model's metrics of a row without one: NaN.
void no_thermal_metrics(ScenarioSummary& s) {
  s.peak_winding_temperature_max_degC = s.time_to_winding_limit_min_s = kNaN;
  s.peak_winding_temperature_degC.fill(kNaN);
  s.time_to_winding_limit_s.fill(kNaN);
}

/// The drive train's metrics of a row without actuators: NaN.
void no_drive_metrics(ScenarioSummary& s) {
  s.energy_electrical_J = s.cost_of_transport_electrical = s.peak_electrical_power_W = kNaN;
  s.energy_copper_loss_J = s.energy_friction_loss_J = s.energy_regenerated_J = kNaN;
  s.thermal_load = kNaN;
  for (auto* a : {&s.peak_drive_torque_gait_Nm, &s.peak_drive_torque_transient_Nm,
                  &s.drive_torque_window_rms_Nm})
    a->fill(kNaN);
  no_thermal_metrics(s);
}

/// The thermal model's metrics of e (ElectricalResult; NaN without a thermal model).
void thermal_metrics(const ElectricalResult& e, ScenarioSummary& s) {
  if (!e.has_thermal()) return no_thermal_metrics(s);
  s.peak_winding_temperature_max_degC = -kInfinity;
  s.time_to_winding_limit_min_s = kInfinity;
  for (std::size_t k = 0; k < e.peak_winding_temperature_degC.size(); ++k) {
    s.peak_winding_temperature_degC[k] = e.peak_winding_temperature_degC[k];
    s.time_to_winding_limit_s[k] = e.time_to_limit_s[k];
    if (std::isnan(e.peak_winding_temperature_degC[k])) continue;
    s.peak_winding_temperature_max_degC =
        std::max(s.peak_winding_temperature_max_degC, e.peak_winding_temperature_degC[k]);
    s.time_to_winding_limit_min_s = std::min(s.time_to_winding_limit_min_s, e.time_to_limit_s[k]);
  }
}

/// True when some leg of sample i is in its touchdown transient (phase impact); false for a
/// run without phases (a result built by hand).
bool in_transient(const RowMatrixI8& phase, int i) {
  if (i >= phase.rows()) return false;
  for (int l = 0; l < phase.cols(); ++l)
    if (phase(i, l) == static_cast<std::int8_t>(ContactPhase::kImpact)) return true;
  return false;
}

/// max |x_k| over the samples outside touchdown transients (`gait`) and inside them
/// (`transient`); NaN where no sample is of the kind.
void split_peaks(const RowMatrix& x, const RowMatrixI8& phase, JointArray<double>& gait,
                 JointArray<double>& transient) {
  gait.fill(kNaN);
  transient.fill(kNaN);
  for (int i = 0; i < x.rows(); ++i) {
    auto& peak = in_transient(phase, i) ? transient : gait;
    for (int k = 0; k < x.cols(); ++k)
      peak[k] = std::isnan(peak[k]) ? std::abs(x(i, k)) : std::max(peak[k], std::abs(x(i, k)));
  }
}

/// The drive train's metrics of a computed run with actuators.
void drive_metrics(const RunResult& run, ScenarioSummary& s) {
  const DynamicsResult& d = run.dyn;
  const ElectricalResult& e = d.electrical;
  s.energy_electrical_J = e.energy_J;
  s.energy_copper_loss_J = e.copper_loss_J;
  s.energy_friction_loss_J = e.friction_loss_J;
  s.energy_regenerated_J = e.regenerated_J;
  s.cost_of_transport_electrical = e.cost_of_transport;
  s.peak_electrical_power_W = e.total_power_W.empty() ? kNaN : -kInfinity;
  for (double p : e.total_power_W)
    s.peak_electrical_power_W = std::max(s.peak_electrical_power_W, p);
  split_peaks(d.drive_torque, run.kin.contact_phase, s.peak_drive_torque_gait_Nm,
              s.peak_drive_torque_transient_Nm);
  std::copy(e.window_rms_torque_Nm.begin(), e.window_rms_torque_Nm.end(),
            s.drive_torque_window_rms_Nm.begin());
  thermal_metrics(e, s);
  s.thermal_load = kNaN;  // NaN when no joint has a continuous rating
  for (int k = 0; k < static_cast<int>(e.continuous_torque_Nm.size()); ++k)
    if (std::isfinite(e.continuous_torque_Nm[k])) {
      const double load = e.window_rms_torque_Nm[k] / e.continuous_torque_Nm[k];
      s.thermal_load = std::isnan(s.thermal_load) ? load : std::max(s.thermal_load, load);
    }
}

/// The grip metrics of a row that has none: NaN, legs −1, counts 0 (no_friction_samples −1:
/// not computed).
void no_grip_metrics(ScenarioSummary& s) {
  s.required_friction_support = s.required_friction_support_time_s = kNaN;
  s.required_friction_transient = s.required_friction_transient_time_s = kNaN;
  s.required_friction_support_leg = s.required_friction_transient_leg = -1;
  s.no_friction_samples = -1;
  s.peak_utilized_friction = kNaN;
  s.slip_samples = 0;
}

/// The largest finite required friction over the samples where some leg is in its touchdown
/// transient (`transient`) or none is, with its binding leg and time; the NaN samples counted.
void required_friction_peaks(const RunResult& run, ScenarioSummary& s) {
  const DynamicsResult& d = run.dyn;
  s.no_friction_samples = 0;
  for (int i = 0; i < static_cast<int>(d.required_friction.size()); ++i) {
    const double mu = d.required_friction[i];
    if (std::isnan(mu)) {
      ++s.no_friction_samples;
      continue;
    }
    const bool transient = in_transient(run.kin.contact_phase, i);
    double& peak = transient ? s.required_friction_transient : s.required_friction_support;
    if (!std::isnan(peak) && mu <= peak) continue;
    peak = mu;
    const int leg =
        i < static_cast<int>(d.required_friction_leg.size()) ? d.required_friction_leg[i] : -1;
    (transient ? s.required_friction_transient_leg : s.required_friction_support_leg) = leg;
    (transient ? s.required_friction_transient_time_s : s.required_friction_support_time_s) =
        run.kin.time_s[i];
  }
}

/// The grip metrics of a computed run (docs/theory/grip.md): required friction peaks when
/// the run has them, the largest utilised friction over support samples, the slip samples.
void grip_metrics(const RunResult& run, ScenarioSummary& s) {
  const DynamicsResult& d = run.dyn;
  no_grip_metrics(s);
  if (!d.required_friction.empty()) required_friction_peaks(run, s);
  for (int i = 0; i < d.utilized_friction.rows(); ++i) {
    if (in_transient(run.kin.contact_phase, i)) continue;
    for (int l = 0; l < d.utilized_friction.cols(); ++l) {
      const double u = d.utilized_friction(i, l);
      if (!std::isnan(u) && !(u <= s.peak_utilized_friction)) s.peak_utilized_friction = u;
    }
  }
  for (int i = 0; i < d.slip.rows(); ++i)
    if ((d.slip.row(i).array() != 0).any()) ++s.slip_samples;
}

}  // namespace

ScenarioSummary failed_summary(std::size_t index, ScenarioStatus status,
                               const std::string& message) {
  ScenarioSummary s;
  s.index = index;
  s.status = status;
  s.message = message;
  s.duration_s = s.distance_m = s.energy_J = s.cost_of_transport = s.peak_impact_force_N = kNaN;
  s.peak_power_W = s.peak_contact_force_N = s.grid_energy_error = s.grid_peak_error = kNaN;
  s.positive_work_J = s.negative_work_J = kNaN;
  for (auto* a : per_joint_metrics(s)) a->fill(kNaN);
  no_drive_metrics(s);
  no_grip_metrics(s);
  return s;
}

ScenarioSummary summarize_run(const RunResult& run, std::size_t index) {
  ScenarioSummary s;
  s.index = index;
  const auto& t = run.kin.time_s;
  const int T = run.kin.samples();
  s.samples = T;
  s.duration_s = T > 0 ? t.back() - t.front() : 0.0;
  const DynamicsResult& d = run.dyn;
  const int J = static_cast<int>(d.joint_torque.cols());  // the robot's joints
  if (!d.present || d.joint_torque.rows() != T || J > kMaxJoints) {
    ScenarioSummary f = failed_summary(index, ScenarioStatus::kOk, "");
    f.samples = T;
    f.duration_s = s.duration_s;
    return f;
  }
  s.distance_m = d.distance_m;
  s.energy_J = d.energy_total_J;
  s.positive_work_J = d.positive_work_J;
  s.negative_work_J = d.negative_work_J;
  s.cost_of_transport = d.cost_of_transport;
  for (const ImpactRecord& im : d.impacts)
    s.peak_impact_force_N = std::max(s.peak_impact_force_N, im.peak_force_N);
  for (double p : d.total_power_W) s.peak_power_W = std::max(s.peak_power_W, p);
  for (int i = 0; i < d.contact_force.rows(); ++i)
    for (int l = 0; l < d.contact_force.cols() / 3; ++l)
      s.peak_contact_force_N =
          std::max(s.peak_contact_force_N, d.contact_force.row(i).segment<3>(3 * l).norm());
  s.grid_energy_error = run.grid.energy_error;
  s.grid_peak_error = run.grid.peak_error;
  s.joints = J;
  for (int k = 0; k < J; ++k) {
    double peak = 0.0, integral = 0.0;
    for (int i = 0; i < T; ++i) peak = std::max(peak, std::abs(d.joint_torque(i, k)));
    for (int i = 0; i + 1 < T; ++i) {
      const double a = d.joint_torque(i, k), b = d.joint_torque(i + 1, k);
      integral += 0.5 * (a * a + b * b) * (t[i + 1] - t[i]);
    }
    s.peak_torque_Nm[k] = peak;
    s.rms_torque_Nm[k] = (T >= 2 && s.duration_s > 0.0)
                             ? std::sqrt(integral / s.duration_s)
                             : (T > 0 ? std::abs(d.joint_torque(0, k)) : 0.0);
  }
  split_peaks(d.joint_torque, run.kin.contact_phase, s.peak_torque_gait_Nm,
              s.peak_torque_transient_Nm);
  if (d.has_drive())
    drive_metrics(run, s);
  else
    no_drive_metrics(s);
  grip_metrics(run, s);
  for (int i = 0; i < static_cast<int>(d.solver_status.size()); ++i) {
    const SolverStatus st = d.solver_status[i];
    if (st == SolverStatus::kRelaxed) ++s.relaxed_samples;
    if (st == SolverStatus::kRelaxed && !in_transient(run.kin.contact_phase, i))
      ++s.relaxed_gait_samples;
    if (st == SolverStatus::kFailed) ++s.failed_samples;
  }
  return s;
}

std::optional<ScenarioSummary> check_scenario(const ScenarioInput& input) {
  const std::string source = scenario_source_name(input.id);
  try {
    (void)scene_from_yaml(parse_yaml_text(input.yaml, source), source);
    return std::nullopt;
  } catch (const std::exception& e) {
    return failed_summary(input.index, classify_exception(e), e.what());
  }
}

namespace {

/// The scenario's run; with a robustness: section, its study too (on one thread: the sweep's
/// ranks are its parallelism), whose outcome fills the row's robustness columns.
RunResult run_scenario_scene(const Scene& scene, std::optional<RobustnessResult>& study) {
  if (scene.robustness.replays == 0) return run_scene(scene, nullptr);
  RunResult run;
  study = run_robustness(scene, 1, &run);
  run.summary_only = scene.output.summary_only;
  return run;
}

void add_study(ScenarioSummary& s, const std::optional<RobustnessResult>& study) {
  if (!study) return;
  s.robust_replays = static_cast<int>(study->outcomes.size());
  s.p_success = study->p_success;
  s.p_success_low = study->interval.low;
  s.p_success_high = study->interval.high;
  const auto count = [&](FailureClass c) {
    return static_cast<int>(study->counts[static_cast<std::size_t>(c)]);
  };
  s.replays_slipped = count(FailureClass::kSlipped);
  s.replays_stubbed = count(FailureClass::kStubbed);
  s.replays_saturated = count(FailureClass::kSaturated);
  s.replays_fell = count(FailureClass::kFell);
  s.replays_drifted = count(FailureClass::kDrifted);
}

}  // namespace

ScenarioOutcome run_scenario(const ScenarioInput& input, bool keep_run) {
  const auto start = std::chrono::steady_clock::now();
  const std::string source = scenario_source_name(input.id);
  ScenarioOutcome out;
  try {
    Scene scene = scene_from_yaml(parse_yaml_text(input.yaml, source), source);
    scene.output.summary_only = !keep_run;  // only its row is kept
    std::optional<RobustnessResult> study;
    RunResult run = run_scenario_scene(scene, study);
    out.summary = summarize_run(run, input.index);
    add_study(out.summary, study);
    if (keep_run) out.run = std::move(run);
  } catch (const std::exception& e) {
    out.summary = failed_summary(input.index, classify_exception(e), e.what());
    out.run.reset();
  }
  out.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ScenarioOutcome run_scenario(const ScenarioFactory& factory, std::size_t index, bool keep_run,
                             ScenarioTiming* timing) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto t1 = t0, t2 = t0;
  ScenarioOutcome out;
  try {
    Scene scene = factory.scene(index, keep_run);
    scene.output.summary_only = !keep_run;  // only its row is kept
    t1 = Clock::now();
    std::optional<RobustnessResult> study;
    RunResult run = run_scenario_scene(scene, study);
    t2 = Clock::now();
    out.summary = summarize_run(run, index);
    add_study(out.summary, study);
    if (keep_run) out.run = std::move(run);
  } catch (const std::exception& e) {
    if (t1 == t0) t1 = Clock::now();
    t2 = Clock::now();
    out.summary = failed_summary(index, classify_exception(e), e.what());
    out.run.reset();
  }
  const auto t3 = Clock::now();
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  out.summary.wall_time_s = seconds(t2 - t0);
  if (timing) *timing = {seconds(t1 - t0), seconds(t2 - t1), seconds(t3 - t2)};
  return out;
}

}  // namespace hexdyn
