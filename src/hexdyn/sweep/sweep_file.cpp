#include "hexdyn/sweep/sweep_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "hexdyn/config/key_units.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/labels.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

[[noreturn]] void io_fail(const std::string& path, const std::string& what) {
  throw IoError("cannot write '" + path + "': " + what);
}

/// Copies `/run` of each kept run image (from the checkpoint's journals) to `/runs/<id>`
/// of the open file `dst` (the writer's in-memory file, so that only H5Writer::close()
/// meets the disk). An image is opened in memory (HDF5 core driver). Every identifier
/// opened here is closed here, on every path.
void copy_runs(hid_t dst, const std::string& dst_path, const SweepSpec& spec,
               const std::vector<ScenarioSummary>& rows, const Checkpoint& cp) {
  silence_hdf5_errors();
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  std::string error;
  for (const ScenarioSummary& row : rows) {
    if (row.status != ScenarioStatus::kOk) continue;
    if (interrupted()) break;
    std::vector<char> image;
    try {
      image = cp.run_image(row.index);
    } catch (const Error& e) {
      error = e.what();
      break;
    }
    if (image.empty()) continue;
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_core(fapl, 1 << 20, 0);
    H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    H5Pset_file_image(fapl, image.data(), image.size());
    const std::string name = "run-" + scenario_id(spec, row.index) + ".h5";
    const hid_t src = H5Fopen(name.c_str(), H5F_ACC_RDONLY, fapl);
    H5Pclose(fapl);
    if (src < 0) {
      error = "cannot open the kept run of scenario " + scenario_id(spec, row.index);
      break;
    }
    if (H5Lexists(src, kRunImageGroup, H5P_DEFAULT) > 0) {
      const std::string to = schema::at(schema::kRunGroup, scenario_id(spec, row.index));
      if (H5Ocopy(src, kRunImageGroup, dst, to.c_str(), H5P_DEFAULT, lcpl) < 0)
        error = "cannot copy the run of scenario " + scenario_id(spec, row.index);
    }
    H5Fclose(src);
    if (!error.empty()) break;
  }
  H5Pclose(lcpl);
  H5Eclear2(H5E_DEFAULT);
  check_interrupt();
  if (!error.empty()) io_fail(dst_path, error);
}

namespace s = schema;

void set_attribute(H5Writer& w, const s::AttributeSpec& a, const std::string& value) {
  w.set_string_attribute(a.object, a.name, value);
}
void set_attribute(H5Writer& w, const s::AttributeSpec& a, std::int64_t value) {
  w.set_int_attribute(a.object, a.name, value);
}

void write_doubles(H5Writer& w, const s::DatasetSpec& d, const std::vector<std::size_t>& dims,
                   const std::vector<double>& values) {
  w.write_doubles(d.path, dims, values, d.units);
}
void write_int32(H5Writer& w, const s::DatasetSpec& d, const std::vector<std::size_t>& dims,
                 const std::vector<std::int32_t>& values) {
  w.write_int32(d.path, dims, values, d.units);
}

void write_meta(H5Writer& w, const SweepSpec& spec, bool keep_runs, const SweepRunInfo& info) {
  write_meta_header(w, s::kMetaGroup, s::kSweepSchema, s::kSweepSchemaVersion);
  set_attribute(w, s::kMetaSweepName, spec.name);
  set_attribute(w, s::kMetaSweepYaml, spec.sweep_yaml);
  set_attribute(w, s::kMetaBaseConfigYaml, spec.base_config_yaml);
  set_attribute(w, s::kMetaScenarios, static_cast<std::int64_t>(spec.scenario_count()));
  set_attribute(w, s::kMetaKeepRuns, std::int64_t{keep_runs ? 1 : 0});
  w.set_double_attribute(s::kMetaWallTime.object, s::kMetaWallTime.name, info.wall_time_s);
  set_attribute(w, s::kMetaRanks, std::int64_t{info.ranks});
  set_attribute(w, s::kMetaResumedScenarios, static_cast<std::int64_t>(info.resumed_scenarios));
  set_attribute(w, s::kMetaInputSha256, input_sha256_text(spec.inputs));
}

/// /axes/{i}, /joint_names and the coordinates: one per axis at /{key}, /axis, /joint.
void write_axes(H5Writer& w, Labeller& labels, const SweepSpec& spec, const RobotShape& robot) {
  w.create_group(s::kAxesGroup);
  std::vector<std::string> keys;
  for (std::size_t a = 0; a < spec.axes.size(); ++a) {
    const SweepAxis& ax = spec.axes[a];
    const std::string i = std::to_string(a);
    keys.push_back(ax.key);
    w.write_string(s::at(s::kAxisKey.path, i), ax.key, s::kAxisKey.units);
    labels.add(s::kAxisKey, s::at(s::kAxisKey.path, i));
    const std::string coordinate = s::at(s::kAxisCoordinateNumbers.path, ax.key);
    if (ax.numeric) {
      const std::string units = scene_key_units(ax.key);
      w.write_doubles(s::at(s::kAxisNumbers.path, i), {ax.size()}, ax.numbers, units);
      w.write_doubles(coordinate, {ax.size()}, ax.numbers, units);
      labels.add(s::kAxisNumbers, s::at(s::kAxisNumbers.path, i), ax.key);
      labels.add(s::kAxisCoordinateNumbers, coordinate, ax.key);
    } else {
      w.write_strings(s::at(s::kAxisWords.path, i), ax.values, s::kAxisWords.units);
      w.write_strings(coordinate, ax.values, s::kAxisCoordinateWords.units);
      labels.add(s::kAxisWords, s::at(s::kAxisWords.path, i), ax.key);
      labels.add(s::kAxisCoordinateWords, coordinate, ax.key);
    }
    w.write_strings(s::at(s::kAxisLabels.path, i), ax.labels, s::kAxisLabels.units);
    labels.add(s::kAxisLabels, s::at(s::kAxisLabels.path, i), ax.key);
    if (ax.is_cases()) {
      const std::size_t K = ax.case_keys.size();
      std::vector<std::string> table;
      for (const auto& values : ax.case_values)
        table.insert(table.end(), values.begin(), values.end());
      const std::string keys_path = s::at(s::kAxisCaseKeys.path, i);
      const std::string values_path = s::at(s::kAxisCaseValues.path, i);
      const std::string key_coordinate = s::at(s::kCaseKeyCoordinate.path, ax.key);
      w.write_strings(keys_path, {K}, ax.case_keys, s::kAxisCaseKeys.units);
      w.write_strings(values_path, {ax.size(), K}, table, s::kAxisCaseValues.units);
      w.write_strings(key_coordinate, {K}, ax.case_keys, s::kCaseKeyCoordinate.units);
      labels.add(s::kAxisCaseKeys, keys_path, ax.key);
      labels.add(s::kAxisCaseValues, values_path, ax.key);
      labels.add(s::kCaseKeyCoordinate, key_coordinate, ax.key);
    }
  }
  std::vector<std::string> joints;
  for (int leg = 0; leg < robot.legs; ++leg)
    for (int j = 0; j < robot.leg_joints[leg]; ++j)
      joints.push_back(joint_name(leg, j, robot.leg_joints[leg]));
  w.write_strings(s::kSweepJointNames.path, joints, s::kSweepJointNames.units);
  labels.add(s::kSweepJointNames);
  w.write_strings(s::kSweepJointCoordinate.path, joints, s::kSweepJointCoordinate.units);
  labels.add(s::kSweepJointCoordinate);
  w.write_strings(s::kAxisCoordinate.path, keys, s::kAxisCoordinate.units);
  labels.add(s::kAxisCoordinate);
}

/// /scenarios' identity columns for n scenarios: each scenario's id, its index on every
/// axis, and per axis its value (in the key's units, or as words).
void write_scenario_grid(H5Writer& w, Labeller& labels, const SweepSpec& spec, std::size_t n) {
  const std::size_t A = spec.axes.size();
  std::vector<std::string> ids(n);
  std::vector<std::int32_t> axis_index(n * A);
  for (std::size_t i = 0; i < n; ++i) {
    ids[i] = scenario_id(spec, i);
    const auto gp = grid_point(spec, i);
    for (std::size_t a = 0; a < A; ++a) axis_index[i * A + a] = static_cast<std::int32_t>(gp[a]);
  }
  w.write_strings(s::kScenarioId.path, ids, s::kScenarioId.units);
  labels.add(s::kScenarioId);
  write_int32(w, s::kScenarioAxisIndex, {n, A}, axis_index);
  labels.add(s::kScenarioAxisIndex);
  for (std::size_t a = 0; a < A; ++a) {
    const SweepAxis& ax = spec.axes[a];
    const std::string d = s::at(s::kScenarioAxisNumbers.path, std::to_string(a));
    if (ax.numeric) {
      std::vector<double> v(n);
      for (std::size_t i = 0; i < n; ++i)
        v[i] = ax.numbers[static_cast<std::size_t>(axis_index[i * A + a])];
      w.write_doubles(d, {n}, v, scene_key_units(ax.key));
      labels.add(s::kScenarioAxisNumbers, d);
    } else {
      std::vector<std::string> v(n);
      for (std::size_t i = 0; i < n; ++i)
        v[i] = ax.values[static_cast<std::size_t>(axis_index[i * A + a])];
      w.write_strings(d, v, s::kScenarioAxisWords.units);
      labels.add(s::kScenarioAxisWords, d);
    }
    w.set_string_attribute(d, s::kScenarioAxisKey.name, ax.key);
  }
}

/// /scenarios' outcome columns: each scenario's status (with the codes' meanings) and
/// message.
void write_scenario_outcomes(H5Writer& w, Labeller& labels,
                             const std::vector<ScenarioSummary>& rows) {
  const std::size_t n = rows.size();
  std::vector<std::string> messages(n);
  std::vector<std::int8_t> status(n);
  for (std::size_t i = 0; i < n; ++i) {
    messages[i] = rows[i].message;
    status[i] = static_cast<std::int8_t>(rows[i].status);
  }
  w.write_int8(s::kScenarioStatus.path, {n}, status, s::kScenarioStatus.units);
  labels.add(s::kScenarioStatus);
  set_attribute(w, s::kScenarioStatusCodes, status_codes_text());
  w.write_strings(s::kScenarioMessage.path, messages, s::kScenarioMessage.units);
  labels.add(s::kScenarioMessage);
}

/// One column of a summary field, in scenario order.
void double_column(H5Writer& w, Labeller& labels, const std::vector<ScenarioSummary>& rows,
                   const s::DatasetSpec& d, double ScenarioSummary::*field) {
  std::vector<double> v(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) v[i] = rows[i].*field;
  write_doubles(w, d, {rows.size()}, v);
  labels.add(d);
}
void count_column(H5Writer& w, Labeller& labels, const std::vector<ScenarioSummary>& rows,
                  const s::DatasetSpec& d, int ScenarioSummary::*field) {
  std::vector<std::int32_t> v(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) v[i] = rows[i].*field;
  write_int32(w, d, {rows.size()}, v);
  labels.add(d);
}

/// /scenarios' robustness columns (a scene with robustness:; docs/user/robustness.md#in-a-sweep).
void write_study_columns(H5Writer& w, Labeller& labels, const std::vector<ScenarioSummary>& rows) {
  const auto doubles = [&](const s::DatasetSpec& d, double ScenarioSummary::*field) {
    double_column(w, labels, rows, d, field);
  };
  const auto counts = [&](const s::DatasetSpec& d, int ScenarioSummary::*field) {
    count_column(w, labels, rows, d, field);
  };
  counts(s::kScenarioReplays, &ScenarioSummary::robust_replays);
  doubles(s::kScenarioPSuccess, &ScenarioSummary::p_success);
  doubles(s::kScenarioPSuccessLow, &ScenarioSummary::p_success_low);
  doubles(s::kScenarioPSuccessHigh, &ScenarioSummary::p_success_high);
  counts(s::kScenarioReplaysSlipped, &ScenarioSummary::replays_slipped);
  counts(s::kScenarioReplaysStubbed, &ScenarioSummary::replays_stubbed);
  counts(s::kScenarioReplaysSaturated, &ScenarioSummary::replays_saturated);
  counts(s::kScenarioReplaysFell, &ScenarioSummary::replays_fell);
  counts(s::kScenarioReplaysDrifted, &ScenarioSummary::replays_drifted);
}

/// /scenarios' metrics, one column per summary field in scenario order (per joint: n ×
/// joints), with the units their declarations state.
void write_scenario_metrics(H5Writer& w, Labeller& labels, const std::vector<ScenarioSummary>& rows,
                            int joints) {
  const std::size_t n = rows.size();
  const auto J = static_cast<std::size_t>(joints);
  const auto doubles = [&](const s::DatasetSpec& d, double ScenarioSummary::*field) {
    double_column(w, labels, rows, d, field);
  };
  const auto counts = [&](const s::DatasetSpec& d, int ScenarioSummary::*field) {
    count_column(w, labels, rows, d, field);
  };
  const auto per_joint = [&](const s::DatasetSpec& d, JointArray<double> ScenarioSummary::*field) {
    // A row of no computed run (joints 0) has no values: NaN.
    std::vector<double> v(n * J, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < n; ++i)
      if (rows[i].joints == joints)
        std::copy((rows[i].*field).begin(), (rows[i].*field).begin() + joints,
                  v.begin() + static_cast<std::ptrdiff_t>(i * J));
    write_doubles(w, d, {n, J}, v);
    labels.add(d);
  };
  counts(s::kScenarioSamples, &ScenarioSummary::samples);
  doubles(s::kScenarioDuration, &ScenarioSummary::duration_s);
  doubles(s::kScenarioDistance, &ScenarioSummary::distance_m);
  doubles(s::kScenarioEnergy, &ScenarioSummary::energy_J);
  doubles(s::kScenarioCostOfTransport, &ScenarioSummary::cost_of_transport);
  doubles(s::kScenarioPeakImpactForce, &ScenarioSummary::peak_impact_force_N);
  doubles(s::kScenarioPeakPower, &ScenarioSummary::peak_power_W);
  doubles(s::kScenarioPeakContactForce, &ScenarioSummary::peak_contact_force_N);
  per_joint(s::kScenarioPeakTorque, &ScenarioSummary::peak_torque_Nm);
  per_joint(s::kScenarioRmsTorque, &ScenarioSummary::rms_torque_Nm);
  per_joint(s::kScenarioPeakTorqueGait, &ScenarioSummary::peak_torque_gait_Nm);
  per_joint(s::kScenarioPeakTorqueTransient, &ScenarioSummary::peak_torque_transient_Nm);
  doubles(s::kScenarioPositiveWork, &ScenarioSummary::positive_work_J);
  doubles(s::kScenarioNegativeWork, &ScenarioSummary::negative_work_J);
  doubles(s::kScenarioEnergyElectrical, &ScenarioSummary::energy_electrical_J);
  doubles(s::kScenarioEnergyCopperLoss, &ScenarioSummary::energy_copper_loss_J);
  doubles(s::kScenarioEnergyFrictionLoss, &ScenarioSummary::energy_friction_loss_J);
  doubles(s::kScenarioEnergyRegenerated, &ScenarioSummary::energy_regenerated_J);
  doubles(s::kScenarioCostOfTransportElectrical, &ScenarioSummary::cost_of_transport_electrical);
  doubles(s::kScenarioPeakElectricalPower, &ScenarioSummary::peak_electrical_power_W);
  per_joint(s::kScenarioPeakDriveTorqueGait, &ScenarioSummary::peak_drive_torque_gait_Nm);
  per_joint(s::kScenarioPeakDriveTorqueTransient, &ScenarioSummary::peak_drive_torque_transient_Nm);
  per_joint(s::kScenarioDriveTorqueWindowRms, &ScenarioSummary::drive_torque_window_rms_Nm);
  doubles(s::kScenarioThermalLoad, &ScenarioSummary::thermal_load);
  per_joint(s::kScenarioPeakWindingTemperature, &ScenarioSummary::peak_winding_temperature_degC);
  per_joint(s::kScenarioTimeToWindingLimit, &ScenarioSummary::time_to_winding_limit_s);
  doubles(s::kScenarioPeakWindingTemperatureMax,
          &ScenarioSummary::peak_winding_temperature_max_degC);
  doubles(s::kScenarioTimeToWindingLimitMin, &ScenarioSummary::time_to_winding_limit_min_s);
  doubles(s::kScenarioRequiredFrictionSupport, &ScenarioSummary::required_friction_support);
  counts(s::kScenarioRequiredFrictionSupportLeg, &ScenarioSummary::required_friction_support_leg);
  doubles(s::kScenarioRequiredFrictionSupportTime,
          &ScenarioSummary::required_friction_support_time_s);
  doubles(s::kScenarioRequiredFrictionTransient, &ScenarioSummary::required_friction_transient);
  counts(s::kScenarioRequiredFrictionTransientLeg,
         &ScenarioSummary::required_friction_transient_leg);
  doubles(s::kScenarioRequiredFrictionTransientTime,
          &ScenarioSummary::required_friction_transient_time_s);
  counts(s::kScenarioNoFrictionSamples, &ScenarioSummary::no_friction_samples);
  doubles(s::kScenarioPeakUtilizedFriction, &ScenarioSummary::peak_utilized_friction);
  counts(s::kScenarioSlipSamples, &ScenarioSummary::slip_samples);
  doubles(s::kScenarioGridEnergyError, &ScenarioSummary::grid_energy_error);
  doubles(s::kScenarioGridPeakError, &ScenarioSummary::grid_peak_error);
  counts(s::kScenarioRelaxedSamples, &ScenarioSummary::relaxed_samples);
  counts(s::kScenarioFailedSamples, &ScenarioSummary::failed_samples);
  counts(s::kScenarioRelaxedGaitSamples, &ScenarioSummary::relaxed_gait_samples);
  write_study_columns(w, labels, rows);
  doubles(s::kScenarioWallTime, &ScenarioSummary::wall_time_s);
}

/// /scenarios: one row per scenario; rows[i].index == i.
void write_scenarios(H5Writer& w, Labeller& labels, const SweepSpec& spec,
                     const std::vector<ScenarioSummary>& rows, int joints) {
  write_scenario_grid(w, labels, spec, rows.size());
  write_scenario_outcomes(w, labels, rows);
  write_scenario_metrics(w, labels, rows, joints);
  set_attribute(w, s::kScenariosMissingValues,
                std::string("metrics are NaN for scenarios whose status is not 0 (ok)"));
}

}  // namespace

void write_sweep_file(const std::string& path, const SweepSpec& spec,
                      const std::vector<ScenarioSummary>& rows, const RobotShape& robot,
                      const Checkpoint* runs_from, const SweepRunInfo& info) {
  const std::size_t n = spec.scenario_count();
  if (rows.size() != n)
    throw IoError("cannot write '" + path + "': " + std::to_string(rows.size()) + " rows for " +
                  std::to_string(n) + " scenarios");
  for (std::size_t i = 0; i < n; ++i)
    if (rows[i].index != i)
      throw IoError("cannot write '" + path + "': row " + std::to_string(i) + " holds scenario " +
                    std::to_string(rows[i].index));
    else if (rows[i].joints != 0 && rows[i].joints != robot.joints())
      throw IoError("cannot write '" + path + "': scenario " + scenario_id(spec, i) + " has " +
                    std::to_string(rows[i].joints) + " joints, the sweep's robot " +
                    std::to_string(robot.joints()));
  check_output_target(path, spec.inputs);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer w(tmp, compressed_output(spec.base_config_yaml));
    write_meta(w, spec, runs_from != nullptr, info);
    Labeller labels(w, "");
    write_axes(w, labels, spec, robot);
    write_scenarios(w, labels, spec, rows, robot.joints());
    labels.finish();
    if (runs_from != nullptr) {
      w.create_group(schema::kRunsGroup);
      copy_runs(w.id(), tmp, spec, rows, *runs_from);
      // The images carry no dimension scales (HDF5 cannot copy their references).
      for (const ScenarioSummary& row : rows)
        if (const std::string run = schema::at(schema::kRunGroup, scenario_id(spec, row.index));
            row.status == ScenarioStatus::kOk && H5Lexists(w.id(), run.c_str(), H5P_DEFAULT) > 0)
          label_result_group(w, run);
    }
    w.close();
  });
}

}  // namespace hexdyn
