#pragma once
/// \file schema_sweep.hpp
/// The `hexdyn-sweep/5` contract, part of io/schema.hpp (which includes this header at
/// its end; the generated Python schema holds it too). Same conventions as there.
#include <array>

#include "hexdyn/io/schema.hpp"

namespace hexdyn::schema {
// ======================================================================= hexdyn-sweep/5
// One row per scenario (N = product of the axis sizes, scenario i at the row-major grid
// point, last axis fastest); metrics are NaN where /scenarios/status != 0.

// ---- /meta: the result's identification attributes, then the sweep's ----
inline constexpr AttributeSpec kMetaSweepName{kMetaGroup, "name", Element::kString};
/// The sweep file's text.
inline constexpr AttributeSpec kMetaSweepYaml{kMetaGroup, "sweep_yaml", Element::kString};
/// The base scene after `inherit:` and `set:`, validated and fully resolved.
inline constexpr AttributeSpec kMetaBaseConfigYaml{kMetaGroup, "base_config_yaml",
                                                   Element::kString};
inline constexpr AttributeSpec kMetaScenarios{kMetaGroup, "scenarios", Element::kInt64};  ///< N
/// 1 when /runs holds each computed scenario's result, else 0.
inline constexpr AttributeSpec kMetaKeepRuns{kMetaGroup, "keep_runs", Element::kInt64};
inline constexpr AttributeSpec kMetaRanks{kMetaGroup, "ranks", Element::kInt64};  ///< MPI ranks
/// Rows taken from an earlier run's checkpoint (--resume).
inline constexpr AttributeSpec kMetaResumedScenarios{kMetaGroup, "resumed_scenarios",
                                                     Element::kInt64};
/// Every /meta attribute of a sweep file (wall_time_s: the whole sweep [s]).
inline constexpr std::array kSweepMetaAttributes{
    kMetaSchema,    kMetaSchemaVersion, kMetaVersion,          kMetaGitCommit,  kMetaCreatedUtc,
    kMetaSweepName, kMetaSweepYaml,     kMetaBaseConfigYaml,   kMetaScenarios,  kMetaKeepRuns,
    kMetaWallTime,  kMetaRanks,         kMetaResumedScenarios, kMetaInputSha256};

// ---- /axes/{i}: axis i = 0..A−1 of the sweep file, in file order ----
/// The declared long name of an axis's values: written as the quantity its key sweeps
/// (io/labels.hpp swept_quantity).
inline constexpr const char* kSweptQuantityName = "swept quantity";
inline constexpr const char* kAxesGroup = "/axes";
/// Dotted scene key of the axis, e.g. "gait.duty_factor".
inline constexpr DatasetSpec kAxisKey{"/axes/{i}/key", "", Shape::kText, Element::kString,
                                      "dotted scene key of the axis"};
/// Values of an axis of numbers (p/q evaluated), in the SI unit of the key. Its long_name
/// is written as the quantity the key sweeps, the key's last word (io/labels.hpp
/// swept_quantity: "riser height" for terrain.riser_height).
inline constexpr DatasetSpec kAxisNumbers{"/axes/{i}/values", "key", Shape::kAxisValues,
                                          Element::kFloat64, kSweptQuantityName};
/// Values of an axis of words (an axis whose values are not all numbers); long_name as above.
inline constexpr DatasetSpec kAxisWords{"/axes/{i}/values", "", Shape::kAxisValues,
                                        Element::kString, kSweptQuantityName};
/// Values as written in the sweep file ("2/3").
inline constexpr DatasetSpec kAxisLabels{"/axes/{i}/labels", "", Shape::kAxisValues,
                                         Element::kString, "values as written in the sweep file"};
/// A cases axis (`cases:`, docs/user/sweeps.md#cases): its key is its name ("case"), its
/// values and labels the case labels; the keys its cases set, in the order of the first
/// case, and each case's value of each key as YAML text (p/q evaluated, a robot.urdf path
/// absolute).
inline constexpr DatasetSpec kAxisCaseKeys{"/axes/{i}/case_keys", "", Shape::kCaseKeys,
                                           Element::kString, "keys each case sets"};
inline constexpr DatasetSpec kAxisCaseValues{"/axes/{i}/case_values", "", Shape::kCaseValues,
                                             Element::kString, "value of each key in each case"};
inline constexpr DatasetSpec kSweepJointNames{"/joint_names", "", Shape::kJointNames,
                                              Element::kString, "joint names, leg-major"};

// ---- coordinate variables (dimension_names): one dimension per axis, named by its key
// ("terrain.riser_height"), its values as coordinate; scenario, axis and joint ----
/// Long name: the quantity the key sweeps, as for /axes/{i}/values.
inline constexpr DatasetSpec kAxisCoordinateNumbers{"/{key}", "key", Shape::kAxisValues,
                                                    Element::kFloat64, kSweptQuantityName};
inline constexpr DatasetSpec kAxisCoordinateWords{"/{key}", "", Shape::kAxisValues,
                                                  Element::kString, kSweptQuantityName};
/// A cases axis's keys: the coordinate of its dimension "{key}_key".
inline constexpr DatasetSpec kCaseKeyCoordinate{"/{key}_key", "", Shape::kCaseKeys,
                                                Element::kString, "keys each case sets"};
inline constexpr DatasetSpec kScenarioCoordinate{"/scenario", "1", Shape::kScenarios,
                                                 Element::kInt32, "scenario index"};
inline constexpr DatasetSpec kAxisCoordinate{"/axis", "", Shape::kAxes, Element::kString,
                                             "dotted scene key of the axis"};
inline constexpr DatasetSpec kSweepJointCoordinate{"/joint", "", Shape::kJointNames,
                                                   Element::kString, "joint name, leg-major"};
inline constexpr std::array kSweepCoordinates{kScenarioCoordinate, kAxisCoordinate,
                                              kSweepJointCoordinate};

// ---- /scenarios: the table ----
inline constexpr const char* kScenariosGroup = "/scenarios";
inline constexpr AttributeSpec kScenariosMissingValues{kScenariosGroup, "missing_values",
                                                       Element::kString};
/// Scenario id: the index zero-padded to at least 6 digits ("000012").
inline constexpr DatasetSpec kScenarioId{"/scenarios/id", "", Shape::kScenarios, Element::kString,
                                         "scenario id"};
/// Index of each scenario's value into each axis.
inline constexpr DatasetSpec kScenarioAxisIndex{"/scenarios/axis_index", "1", Shape::kScenarioAxes,
                                                Element::kInt32,
                                                "index of the scenario's value into each axis"};
/// Each scenario's value of axis i: numbers (SI) or words, as /axes/{i}/values.
inline constexpr DatasetSpec kScenarioAxisNumbers{"/scenarios/axis_{i}", "key", Shape::kScenarios,
                                                  Element::kFloat64, "value of the swept key"};
inline constexpr DatasetSpec kScenarioAxisWords{"/scenarios/axis_{i}", "", Shape::kScenarios,
                                                Element::kString, "value of the swept key"};
/// The axis key, on each /scenarios/axis_{i}: the name of the axis's dimension.
inline constexpr AttributeSpec kScenarioAxisKey{"/scenarios/axis_{i}", "key", Element::kString};
/// 0 ok, 1 config, 2 reach, 3 planning, 4 solver, 5 error, 6 internal, 7 crashed
/// (ScenarioStatus; kScenarioStatusNames).
inline constexpr DatasetSpec kScenarioStatus{"/scenarios/status", "", Shape::kScenarios,
                                             Element::kInt8, "scenario status"};
/// The name of each status code, by code: 7 `crashed` is a scenario whose process died
/// twice (signal, abort, out-of-memory kill) and was not tried again.
inline constexpr std::array kScenarioStatusNames{"ok",     "config", "reach",    "planning",
                                                 "solver", "error",  "internal", "crashed"};
inline constexpr FlagSpec kScenarioStatusFlags{
    "/scenarios/status", "ok config reach planning solver error internal crashed"};
/// "0 ok, 1 config, ...", on /scenarios/status.
inline constexpr AttributeSpec kScenarioStatusCodes{"/scenarios/status", "codes", Element::kString};
/// The error's one-line message; "" when ok.
inline constexpr DatasetSpec kScenarioMessage{"/scenarios/message", "", Shape::kScenarios,
                                              Element::kString, "error message of the scenario"};
inline constexpr DatasetSpec kScenarioSamples{"/scenarios/samples", "1", Shape::kScenarios,
                                              Element::kInt32, "output samples"};
inline constexpr DatasetSpec kScenarioDuration{"/scenarios/duration", "s", Shape::kScenarios,
                                               Element::kFloat64, "duration of the run"};
inline constexpr DatasetSpec kScenarioDistance{"/scenarios/distance", "m", Shape::kScenarios,
                                               Element::kFloat64,
                                               "distance travelled by the trunk"};
inline constexpr DatasetSpec kScenarioEnergy{"/scenarios/energy", "J", Shape::kScenarios,
                                             Element::kFloat64,
                                             "energy: integral of total absolute joint power"};
inline constexpr DatasetSpec kScenarioCostOfTransport{"/scenarios/cost_of_transport", "1",
                                                      Shape::kScenarios, Element::kFloat64,
                                                      "cost of transport E/(m g d)"};
inline constexpr DatasetSpec kScenarioPeakImpactForce{"/scenarios/peak_impact_force", "N",
                                                      Shape::kScenarios, Element::kFloat64,
                                                      "largest touchdown peak force"};
/// Max over samples of /power/total.
inline constexpr DatasetSpec kScenarioPeakPower{"/scenarios/peak_power", "W", Shape::kScenarios,
                                                Element::kFloat64,
                                                "peak total absolute joint power"};
/// Max over samples and legs of the norm of /contacts/force.
inline constexpr DatasetSpec kScenarioPeakContactForce{"/scenarios/peak_contact_force", "N",
                                                       Shape::kScenarios, Element::kFloat64,
                                                       "peak contact force on a foot"};
/// The run's /meta grid_energy_error (docs/theory/output-grid.md#error-control).
inline constexpr DatasetSpec kScenarioGridEnergyError{"/scenarios/grid_energy_error", "1",
                                                      Shape::kScenarios, Element::kFloat64,
                                                      "estimated relative error of the energies"};
/// The run's /meta grid_peak_error.
inline constexpr DatasetSpec kScenarioGridPeakError{"/scenarios/grid_peak_error", "1",
                                                    Shape::kScenarios, Element::kFloat64,
                                                    "estimated relative error of the peaks"};
/// Max over samples of |τ_k|.
inline constexpr DatasetSpec kScenarioPeakTorque{"/scenarios/peak_torque", "N m",
                                                 Shape::kScenarioJoints, Element::kFloat64,
                                                 "peak absolute joint torque"};
/// Time-weighted RMS of τ_k (trapezoidal ∫τ² dt over the duration).
inline constexpr DatasetSpec kScenarioRmsTorque{"/scenarios/rms_torque", "N m",
                                                Shape::kScenarioJoints, Element::kFloat64,
                                                "time-weighted RMS joint torque"};
/// Max of |τ_k| over the samples outside touchdown transients (no leg in phase impact), and
/// over those inside them: the gait's own peaks and the transients' (NaN: no such sample).
inline constexpr DatasetSpec kScenarioPeakTorqueGait{"/scenarios/peak_torque_gait", "N m",
                                                     Shape::kScenarioJoints, Element::kFloat64,
                                                     "peak joint torque outside touchdowns"};
inline constexpr DatasetSpec kScenarioPeakTorqueTransient{
    "/scenarios/peak_torque_transient", "N m", Shape::kScenarioJoints, Element::kFloat64,
    "peak joint torque in touchdown transients"};
// The drive train's metrics (a scene with actuators; NaN without): the run's
// /energy/electrical, /energy/cost_of_transport_electrical, max of /power/electrical_total,
// the split peaks of /joints/drive_torque and /joints/drive_torque_window_rms, and the
// thermal load: the largest ratio of the windowed RMS to the joint's continuous_torque.
inline constexpr DatasetSpec kScenarioEnergyElectrical{"/scenarios/energy_electrical", "J",
                                                       Shape::kScenarios, Element::kFloat64,
                                                       "electrical energy drawn"};
/// The run's /energy/positive_work and /energy/negative_work (≤ 0): on the way down the
/// joints brake, and the negative part grows.
inline constexpr DatasetSpec kScenarioPositiveWork{
    "/scenarios/positive_work", "J", Shape::kScenarios, Element::kFloat64, "positive joint work"};
inline constexpr DatasetSpec kScenarioNegativeWork{
    "/scenarios/negative_work", "J", Shape::kScenarios, Element::kFloat64, "negative joint work"};
/// The run's /energy/copper_loss, /energy/friction_loss and /energy/regenerated: with
/// /scenarios/energy, the energy breakdown of each scenario.
inline constexpr DatasetSpec kScenarioEnergyCopperLoss{"/scenarios/energy_copper_loss", "J",
                                                       Shape::kScenarios, Element::kFloat64,
                                                       "copper loss R I^2"};
inline constexpr DatasetSpec kScenarioEnergyFrictionLoss{"/scenarios/energy_friction_loss", "J",
                                                         Shape::kScenarios, Element::kFloat64,
                                                         "joint friction loss"};
inline constexpr DatasetSpec kScenarioEnergyRegenerated{"/scenarios/energy_regenerated", "J",
                                                        Shape::kScenarios, Element::kFloat64,
                                                        "energy regenerated"};
inline constexpr DatasetSpec kScenarioCostOfTransportElectrical{
    "/scenarios/cost_of_transport_electrical", "1", Shape::kScenarios, Element::kFloat64,
    "electrical cost of transport"};
inline constexpr DatasetSpec kScenarioPeakElectricalPower{"/scenarios/peak_electrical_power", "W",
                                                          Shape::kScenarios, Element::kFloat64,
                                                          "peak total electrical power"};
inline constexpr DatasetSpec kScenarioPeakDriveTorqueGait{
    "/scenarios/peak_drive_torque_gait", "N m", Shape::kScenarioJoints, Element::kFloat64,
    "peak drive torque outside touchdowns"};
inline constexpr DatasetSpec kScenarioPeakDriveTorqueTransient{
    "/scenarios/peak_drive_torque_transient", "N m", Shape::kScenarioJoints, Element::kFloat64,
    "peak drive torque in touchdown transients"};
inline constexpr DatasetSpec kScenarioDriveTorqueWindowRms{
    "/scenarios/drive_torque_window_rms", "N m", Shape::kScenarioJoints, Element::kFloat64,
    "largest RMS drive torque over a thermal window"};
inline constexpr DatasetSpec kScenarioThermalLoad{
    "/scenarios/thermal_load", "1", Shape::kScenarios, Element::kFloat64,
    "largest windowed RMS drive torque over the continuous rating"};
// The thermal model's metrics (actuators with a thermal model; NaN without, and for a joint
// without one): the run's /thermal/peak_winding_temperature and /thermal/time_to_limit per
// joint (+inf: never reached), /thermal/peak and /thermal/first_time_to_limit over them.
inline constexpr DatasetSpec kScenarioPeakWindingTemperature{
    "/scenarios/peak_winding_temperature", "degC", Shape::kScenarioJoints, Element::kFloat64,
    "peak winding temperature"};
inline constexpr DatasetSpec kScenarioTimeToWindingLimit{"/scenarios/time_to_winding_limit", "s",
                                                         Shape::kScenarioJoints, Element::kFloat64,
                                                         "time the winding reaches its limit"};
inline constexpr DatasetSpec kScenarioPeakWindingTemperatureMax{
    "/scenarios/peak_winding_temperature_max", "degC", Shape::kScenarios, Element::kFloat64,
    "peak winding temperature over the joints"};
inline constexpr DatasetSpec kScenarioTimeToWindingLimitMin{
    "/scenarios/time_to_winding_limit_min", "s", Shape::kScenarios, Element::kFloat64,
    "first time a winding reaches its limit"};
// Grip (docs/theory/grip.md): the largest /contacts/required_friction over the support samples
// (no leg in phase impact) and over the touchdown-transient samples (some leg in phase
// impact), NaN samples skipped (NaN when none is finite, and with output.required_friction
// false), each with its binding leg (0-based index into the run's legs, −1 where none) and
// its time; the samples whose required friction is NaN (no μ suffices; −1 with
// output.required_friction false); the largest /contacts/utilized_friction over the support
// samples (NaN without any); the samples with a /contacts/slip flag.
inline constexpr DatasetSpec kScenarioRequiredFrictionSupport{
    "/scenarios/required_friction_support", "1", Shape::kScenarios, Element::kFloat64,
    "largest required friction over support samples"};
inline constexpr DatasetSpec kScenarioRequiredFrictionSupportLeg{
    "/scenarios/required_friction_support_leg", "", Shape::kScenarios, Element::kInt32,
    "leg binding the largest support required friction, 0-based (0 is L1), -1 none"};
inline constexpr DatasetSpec kScenarioRequiredFrictionSupportTime{
    "/scenarios/required_friction_support_time", "s", Shape::kScenarios, Element::kFloat64,
    "time of the largest support required friction"};
inline constexpr DatasetSpec kScenarioRequiredFrictionTransient{
    "/scenarios/required_friction_transient", "1", Shape::kScenarios, Element::kFloat64,
    "largest required friction over touchdown-transient samples"};
inline constexpr DatasetSpec kScenarioRequiredFrictionTransientLeg{
    "/scenarios/required_friction_transient_leg", "", Shape::kScenarios, Element::kInt32,
    "leg binding the largest transient required friction, 0-based (0 is L1), -1 none"};
inline constexpr DatasetSpec kScenarioRequiredFrictionTransientTime{
    "/scenarios/required_friction_transient_time", "s", Shape::kScenarios, Element::kFloat64,
    "time of the largest transient required friction"};
inline constexpr DatasetSpec kScenarioNoFrictionSamples{
    "/scenarios/no_friction_samples", "1", Shape::kScenarios, Element::kInt32,
    "samples for which no friction coefficient suffices"};
inline constexpr DatasetSpec kScenarioPeakUtilizedFriction{
    "/scenarios/peak_utilized_friction", "1", Shape::kScenarios, Element::kFloat64,
    "largest utilised friction over support samples"};
inline constexpr DatasetSpec kScenarioSlipSamples{"/scenarios/slip_samples", "1", Shape::kScenarios,
                                                  Element::kInt32, "samples with a slip flag"};
inline constexpr DatasetSpec kScenarioRelaxedSamples{
    "/scenarios/relaxed_samples", "1", Shape::kScenarios, Element::kInt32, "relaxed samples"};
inline constexpr DatasetSpec kScenarioFailedSamples{
    "/scenarios/failed_samples", "1", Shape::kScenarios, Element::kInt32, "failed samples"};
/// Relaxed samples outside touchdown transients (no leg in phase impact): where the gait
/// itself asks for more than the robot can give (a transient's are by design,
/// docs/theory/allocation.md#relaxed-samples).
inline constexpr DatasetSpec kScenarioRelaxedGaitSamples{"/scenarios/relaxed_gait_samples", "1",
                                                         Shape::kScenarios, Element::kInt32,
                                                         "relaxed samples outside touchdowns"};
// A robustness study per scenario (scenes with robustness:, docs/user/robustness.md#in-a-sweep):
// its replays (0 without a study), the success fraction and its Wilson 95 % interval (NaN
// without), the replays of each failure class (robustness/outcome.hpp).
inline constexpr DatasetSpec kScenarioReplays{"/scenarios/replays", "1", Shape::kScenarios,
                                              Element::kInt32, "replays of the robustness study"};
inline constexpr DatasetSpec kScenarioPSuccess{"/scenarios/p_success", "1", Shape::kScenarios,
                                               Element::kFloat64,
                                               "success fraction of the replays"};
inline constexpr DatasetSpec kScenarioPSuccessLow{"/scenarios/p_success_low", "1",
                                                  Shape::kScenarios, Element::kFloat64,
                                                  "lower end of the 95 % Wilson interval"};
inline constexpr DatasetSpec kScenarioPSuccessHigh{"/scenarios/p_success_high", "1",
                                                   Shape::kScenarios, Element::kFloat64,
                                                   "upper end of the 95 % Wilson interval"};
inline constexpr DatasetSpec kScenarioReplaysSlipped{
    "/scenarios/replays_slipped", "1", Shape::kScenarios, Element::kInt32, "replays that slipped"};
inline constexpr DatasetSpec kScenarioReplaysStubbed{"/scenarios/replays_stubbed", "1",
                                                     Shape::kScenarios, Element::kInt32,
                                                     "replays that stubbed a toe"};
inline constexpr DatasetSpec kScenarioReplaysSaturated{"/scenarios/replays_saturated", "1",
                                                       Shape::kScenarios, Element::kInt32,
                                                       "replays that saturated"};
inline constexpr DatasetSpec kScenarioReplaysFell{"/scenarios/replays_fell", "1", Shape::kScenarios,
                                                  Element::kInt32, "replays that fell"};
inline constexpr DatasetSpec kScenarioReplaysDrifted{
    "/scenarios/replays_drifted", "1", Shape::kScenarios, Element::kInt32, "replays that drifted"};
/// Time to compute each scenario [s] (timing: differs between runs).
inline constexpr DatasetSpec kScenarioWallTime{"/scenarios/wall_time_s", "s", Shape::kScenarios,
                                               Element::kFloat64, "time to compute the scenario"};
/// The columns of /scenarios other than the per-axis /scenarios/axis_{i}, in file order
/// (status, then message, after the axis columns).
// clang-format off
inline constexpr std::array kScenarioDatasets{
    kScenarioId, kScenarioAxisIndex, kScenarioStatus, kScenarioMessage, kScenarioSamples,
    kScenarioDuration, kScenarioDistance, kScenarioEnergy, kScenarioCostOfTransport,
    kScenarioPeakImpactForce, kScenarioPeakPower, kScenarioPeakContactForce, kScenarioPeakTorque,
    kScenarioRmsTorque, kScenarioPeakTorqueGait, kScenarioPeakTorqueTransient,
    kScenarioEnergyElectrical, kScenarioEnergyCopperLoss, kScenarioEnergyFrictionLoss,
    kScenarioEnergyRegenerated, kScenarioPositiveWork, kScenarioNegativeWork,
    kScenarioCostOfTransportElectrical, kScenarioPeakElectricalPower,
    kScenarioPeakDriveTorqueGait, kScenarioPeakDriveTorqueTransient, kScenarioDriveTorqueWindowRms,
    kScenarioThermalLoad, kScenarioPeakWindingTemperature, kScenarioTimeToWindingLimit,
    kScenarioPeakWindingTemperatureMax, kScenarioTimeToWindingLimitMin,
    kScenarioRequiredFrictionSupport, kScenarioRequiredFrictionSupportLeg,
    kScenarioRequiredFrictionSupportTime, kScenarioRequiredFrictionTransient,
    kScenarioRequiredFrictionTransientLeg, kScenarioRequiredFrictionTransientTime,
    kScenarioNoFrictionSamples, kScenarioPeakUtilizedFriction, kScenarioSlipSamples,
    kScenarioGridEnergyError, kScenarioGridPeakError, kScenarioRelaxedSamples, kScenarioFailedSamples, kScenarioRelaxedGaitSamples,
    kScenarioReplays, kScenarioPSuccess, kScenarioPSuccessLow, kScenarioPSuccessHigh,
    kScenarioReplaysSlipped, kScenarioReplaysStubbed, kScenarioReplaysSaturated,
    kScenarioReplaysFell, kScenarioReplaysDrifted, kScenarioWallTime};
// clang-format on

// ---- /runs/{id}: with --keep-runs, each computed scenario in the hexdyn-result/5 layout
// (its own /meta, /model, kinematic and dynamic datasets below the group) ----
inline constexpr const char* kRunsGroup = "/runs";
inline constexpr const char* kRunGroup = "/runs/{id}";

}  // namespace hexdyn::schema
