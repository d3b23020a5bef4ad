#pragma once
/// \file schema.hpp
/// The HDF5 contracts of hexdyn in one place (described in docs/user/output.md, whose
/// tables are generated from this header): `hexdyn-result/1` (one
/// run), `hexdyn-sweep/1` (a parameter sweep) and `hexdyn-envelope/1` (the climbable
/// envelope, envelope/envelope.hpp), each with its schema name and version,
/// every /meta attribute, and for every dataset its path, shape, element type and
/// `units` attribute. The writers (io/result_layout.cpp, sweep/sweep_file.cpp,
/// envelope/envelope_file.cpp) take every path and units string from here; the Python
/// reader hexdyn.results (bindings/python/hexdyn/results.py) parses this header at import (the
/// `inline constexpr` lines below, and the shape comments of `Shape`), so the layout is
/// typed once. Keep declarations on the regular pattern
///     inline constexpr DatasetSpec kName{"path", "units", Shape::kX, Element::kY};
/// (a name of a `const char*` constant may stand for a string). A change of layout is a
/// new schema version.
///
/// Shapes: T output samples, 6 legs, 18 joints, n touchdowns, m solver messages; in a
/// sweep file N scenarios, A axes, V values of one axis. (T,6,3) datasets are leg-major
/// (index [t][leg][axis]); all vectors are in the world frame G0 unless the name says
/// otherwise. Units strings: "1" marks dimensionless numbers (quaternions, status codes,
/// counts, ratios) and text; "SI" marks an axis value in the SI unit of its scene key.
/// Paths with "{i}" (axis number 0..A−1) or "{id}" (scenario id) are templates: at().
#include <array>
#include <cstdint>
#include <string>

namespace hexdyn::schema {

inline constexpr const char* kResultSchema = "hexdyn-result/1";  ///< /meta attr `schema`
inline constexpr std::int64_t kResultSchemaVersion = 1;          ///< /meta attr `schema_version`
inline constexpr const char* kSweepSchema = "hexdyn-sweep/1";    ///< sweep files' `schema`
inline constexpr std::int64_t kSweepSchemaVersion = 1;           ///< sweep files' `schema_version`
inline constexpr const char* kEnvelopeSchema = "hexdyn-envelope/1";  ///< envelope files' `schema`
inline constexpr std::int64_t kEnvelopeSchemaVersion = 1;  ///< envelope files' `schema_version`

/// Shape of a dataset in terms of the run's sizes.
enum class Shape {
  kScalar,            ///< ()
  kText,              ///< () variable-length UTF-8 string
  kTextList,          ///< (m) variable-length UTF-8 strings, m may be 0
  kJointNames,        ///< (18) strings
  kLegNames,          ///< (6) strings
  kJ,                 ///< (18)
  kT,                 ///< (T)
  kT3,                ///< (T,3)
  kT4,                ///< (T,4)
  kT6,                ///< (T,6)
  kT18,               ///< (T,18)
  kT6x3,              ///< (T,6,3)
  kN,                 ///< (n), one entry per touchdown, n may be 0
  kScenarios,         ///< (N), one entry per scenario, index order
  kScenarioAxes,      ///< (N,A), one row per scenario, one column per axis
  kScenarioJoints,    ///< (N,18), one row per scenario, one column per joint
  kAxisValues,        ///< (V), one entry per value of an axis
  kEnvelopeTreads,    ///< (W), tread depths of an envelope
  kEnvelopeDuties,    ///< (B), duty factors of an envelope
  kEnvelopeSpeeds,    ///< (S), peak speeds of an envelope
  kEnvelopeCriteria,  ///< (C), criteria of an envelope
  kEnvelopeCells,     ///< (W,B,S), one entry per tread, duty factor and speed
  kEnvelopeGrid,      ///< (W,B,S,C), one entry per cell and criterion
  kEnvelopeGridText,  ///< (G) strings, G = W·B·S·C: the (W,B,S,C) grid flattened row-major
  kEnvelopeProbes,    ///< (P), one entry per probe (a criterion evaluated at one riser)
  kCycles,            ///< (Y), one entry per gait cycle
  kTerrainPoints,     ///< (K), one entry per vertex of the terrain's height profile
};

/// Element type stored in the file.
enum class Element { kFloat64, kInt8, kInt32, kInt64, kString };

/// One dataset of the contract.
struct DatasetSpec {
  const char* path;   ///< absolute HDF5 path
  const char* units;  ///< value of the mandatory `units` attribute
  Shape shape = Shape::kScalar;
  Element element = Element::kFloat64;
  const char* long_name = "";  ///< CF `long_name`: what the values are, in words
};

/// One attribute of the contract: on the object `object`, named `name`.
struct AttributeSpec {
  const char* object;  ///< absolute HDF5 path of the group or dataset (may be a template)
  const char* name;
  Element element = Element::kString;  ///< stored as a scalar of this type
};

/// `path` with its placeholder "{i}" or "{id}" replaced by `value` ("/axes/{i}/key", "2"
/// → "/axes/2/key"); `path` unchanged when it has none.
inline std::string at(const char* path, const std::string& value) {
  std::string s(path);
  for (const char* placeholder : {"{i}", "{id}"}) {
    const auto p = s.find(placeholder);
    if (p != std::string::npos)
      return s.replace(p, std::char_traits<char>::length(placeholder), value);
  }
  return s;
}

// ======================================================================= hexdyn-result/1

// ---- /meta: a group with attributes only ----
inline constexpr const char* kMetaGroup = "/meta";
inline constexpr const char* kAttrSchema = "schema";  ///< string, kResultSchema
inline constexpr const char* kAttrSchemaVersion =
    "schema_version";                                          ///< int64, kResultSchemaVersion
inline constexpr const char* kAttrVersion = "version";         ///< string, hexdyn release
inline constexpr const char* kAttrGitCommit = "git_commit";    ///< string
inline constexpr const char* kAttrCreatedUtc = "created_utc";  ///< string, ISO 8601 "…Z"
inline constexpr const char* kAttrConfigYaml = "config_yaml";  ///< string, fully resolved
inline constexpr const char* kAttrWallTime = "wall_time_s";    ///< double [s]
/// string, one line "SHA256  ABSOLUTE_PATH" per input file read (scene, inherited files,
/// URDF; a sweep's and an envelope's own file first), as `sha256sum` writes them
/// (docs/user/output.md#provenance-of-the-inputs)
inline constexpr const char* kAttrInputSha256 = "input_sha256";
inline constexpr const char* kUnitsAttribute = "units";  ///< on every dataset

inline constexpr AttributeSpec kMetaSchema{kMetaGroup, kAttrSchema, Element::kString};
inline constexpr AttributeSpec kMetaSchemaVersion{kMetaGroup, kAttrSchemaVersion, Element::kInt64};
inline constexpr AttributeSpec kMetaVersion{kMetaGroup, kAttrVersion, Element::kString};
inline constexpr AttributeSpec kMetaGitCommit{kMetaGroup, kAttrGitCommit, Element::kString};
inline constexpr AttributeSpec kMetaCreatedUtc{kMetaGroup, kAttrCreatedUtc, Element::kString};
inline constexpr AttributeSpec kMetaConfigYaml{kMetaGroup, kAttrConfigYaml, Element::kString};
inline constexpr AttributeSpec kMetaWallTime{kMetaGroup, kAttrWallTime, Element::kFloat64};
inline constexpr AttributeSpec kMetaInputSha256{kMetaGroup, kAttrInputSha256, Element::kString};
/// Every /meta attribute of a result file.
inline constexpr std::array kResultMetaAttributes{
    kMetaSchema,     kMetaSchemaVersion, kMetaVersion,  kMetaGitCommit,
    kMetaCreatedUtc, kMetaConfigYaml,    kMetaWallTime, kMetaInputSha256};

// ---- /model ----
inline constexpr DatasetSpec kModelUrdf{"/model/urdf", "1", Shape::kText, Element::kString};
inline constexpr DatasetSpec kModelJointNames{"/model/joint_names", "1", Shape::kJointNames,
                                              Element::kString};
inline constexpr DatasetSpec kModelLegNames{"/model/leg_names", "1", Shape::kLegNames,
                                            Element::kString};
inline constexpr DatasetSpec kModelTotalMass{"/model/total_mass", "kg", Shape::kScalar};
/// A URDF robot's legs L1 … L6: "L1: JOINT1 JOINT2 JOINT3 foot FOOT", the description's
/// joint names hip to foot and the foot's link (or "offset X Y Z LINK", m in that link's
/// frame). Written only for a robot read from a URDF (kUrdfRobotDatasets).
inline constexpr DatasetSpec kModelLegMapping{"/model/leg_mapping", "1", Shape::kLegNames,
                                              Element::kString};

// ---- kinematics: always written ----
inline constexpr DatasetSpec kTime{"/time", "s", Shape::kT};
inline constexpr DatasetSpec kBasePosition{"/base/position", "m", Shape::kT3};
/// Quaternion w, x, y, z of the rotation body → world.
inline constexpr DatasetSpec kBaseOrientation{"/base/orientation", "1", Shape::kT4};
inline constexpr DatasetSpec kBaseLinearVelocity{"/base/linear_velocity", "m/s", Shape::kT3};
inline constexpr DatasetSpec kBaseAngularVelocity{"/base/angular_velocity", "rad/s", Shape::kT3};
inline constexpr DatasetSpec kBaseLinearAcceleration{"/base/linear_acceleration", "m/s^2",
                                                     Shape::kT3};
inline constexpr DatasetSpec kBaseAngularAcceleration{"/base/angular_acceleration", "rad/s^2",
                                                      Shape::kT3};
inline constexpr DatasetSpec kJointPosition{"/joints/position", "rad", Shape::kT18};
inline constexpr DatasetSpec kJointVelocity{"/joints/velocity", "rad/s", Shape::kT18};
inline constexpr DatasetSpec kJointAcceleration{"/joints/acceleration", "rad/s^2", Shape::kT18};
inline constexpr DatasetSpec kFeetPosition{"/feet/position", "m", Shape::kT6x3};
inline constexpr DatasetSpec kFeetVelocity{"/feet/velocity", "m/s", Shape::kT6x3};
inline constexpr DatasetSpec kComPosition{"/com/position", "m", Shape::kT3};
/// 0 swing, 1 impact, 2 support (ContactPhase).
inline constexpr DatasetSpec kContactPhase{"/contacts/phase", "1", Shape::kT6, Element::kInt8};

// ---- dynamics: written only when the dynamic stages ran ----
inline constexpr DatasetSpec kJointTorque{"/joints/torque", "N m", Shape::kT18};
/// Force of the terrain on the foot, world frame.
inline constexpr DatasetSpec kContactForce{"/contacts/force", "N", Shape::kT6x3};
inline constexpr DatasetSpec kContactPenetration{"/contacts/penetration", "m", Shape::kT6};
/// Leg of each touchdown, 1-based (1..6) as in the leg names.
inline constexpr DatasetSpec kImpactLeg{"/impacts/leg", "1", Shape::kN, Element::kInt32};
inline constexpr DatasetSpec kImpactStart{"/impacts/t_start", "s", Shape::kN};
inline constexpr DatasetSpec kImpactDuration{"/impacts/duration", "s", Shape::kN};
inline constexpr DatasetSpec kImpactPeakForce{"/impacts/peak_force", "N", Shape::kN};
inline constexpr DatasetSpec kImpactImpulse{"/impacts/impulse", "N s", Shape::kN};
inline constexpr DatasetSpec kImpactEffectiveMass{"/impacts/effective_mass", "kg", Shape::kN};
inline constexpr DatasetSpec kImpactApproachSpeed{"/impacts/approach_speed", "m/s", Shape::kN};
inline constexpr DatasetSpec kJointPower{"/power/joint", "W", Shape::kT18};
inline constexpr DatasetSpec kTotalPower{"/power/total", "W", Shape::kT};
inline constexpr DatasetSpec kEnergyTotal{"/energy/total", "J", Shape::kScalar};
inline constexpr DatasetSpec kEnergyJoint{"/energy/joint", "J", Shape::kJ};
inline constexpr DatasetSpec kCostOfTransport{"/energy/cost_of_transport", "1", Shape::kScalar};
inline constexpr DatasetSpec kEnergyDistance{"/energy/distance", "m", Shape::kScalar};
/// 0 optimal, 1 relaxed (slack used), 2 failed.
inline constexpr DatasetSpec kSolverStatus{"/solver/status", "1", Shape::kT, Element::kInt8};
inline constexpr DatasetSpec kSolverIterations{"/solver/iterations", "1", Shape::kT};
inline constexpr DatasetSpec kSolverObjective{"/solver/objective", "N^2 m^2", Shape::kT};
inline constexpr DatasetSpec kSolverSeconds{"/solver/seconds", "s", Shape::kT};
/// One message per relaxed or failed sample.
inline constexpr DatasetSpec kSolverMessages{"/solver/messages", "1", Shape::kTextList,
                                             Element::kString};

/// Every dataset present in every result file.
inline constexpr std::array kModelDatasets{kModelUrdf, kModelJointNames, kModelLegNames,
                                           kModelTotalMass};
inline constexpr std::array kKinematicDatasets{kTime,
                                               kBasePosition,
                                               kBaseOrientation,
                                               kBaseLinearVelocity,
                                               kBaseAngularVelocity,
                                               kBaseLinearAcceleration,
                                               kBaseAngularAcceleration,
                                               kJointPosition,
                                               kJointVelocity,
                                               kJointAcceleration,
                                               kFeetPosition,
                                               kFeetVelocity,
                                               kComPosition,
                                               kContactPhase};
/// Datasets present when the robot was read from a URDF.
inline constexpr std::array kUrdfRobotDatasets{kModelLegMapping};
/// Datasets present when the dynamic stages ran.
inline constexpr std::array kDynamicsDatasets{
    kJointTorque,         kContactForce,        kContactPenetration, kImpactLeg,
    kImpactStart,         kImpactDuration,      kImpactPeakForce,    kImpactImpulse,
    kImpactEffectiveMass, kImpactApproachSpeed, kJointPower,         kTotalPower,
    kEnergyTotal,         kEnergyJoint,         kCostOfTransport,    kEnergyDistance,
    kSolverStatus,        kSolverIterations,    kSolverObjective,    kSolverSeconds,
    kSolverMessages};

// ======================================================================= hexdyn-sweep/1
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
inline constexpr const char* kAxesGroup = "/axes";
/// Dotted scene key of the axis, e.g. "gait.duty_factor".
inline constexpr DatasetSpec kAxisKey{"/axes/{i}/key", "1", Shape::kText, Element::kString};
/// Values of an axis of numbers (p/q evaluated), in the SI unit of the key.
inline constexpr DatasetSpec kAxisNumbers{"/axes/{i}/values", "SI", Shape::kAxisValues};
/// Values of an axis of words (an axis whose values are not all numbers).
inline constexpr DatasetSpec kAxisWords{"/axes/{i}/values", "1", Shape::kAxisValues,
                                        Element::kString};
/// Values as written in the sweep file ("2/3").
inline constexpr DatasetSpec kAxisLabels{"/axes/{i}/labels", "1", Shape::kAxisValues,
                                         Element::kString};
inline constexpr DatasetSpec kSweepJointNames{"/joint_names", "1", Shape::kJointNames,
                                              Element::kString};

// ---- /scenarios: the table ----
inline constexpr const char* kScenariosGroup = "/scenarios";
inline constexpr AttributeSpec kScenariosMissingValues{kScenariosGroup, "missing_values",
                                                       Element::kString};
/// Scenario id: the index zero-padded to at least 6 digits ("000012").
inline constexpr DatasetSpec kScenarioId{"/scenarios/id", "1", Shape::kScenarios, Element::kString};
/// Index of each scenario's value into each axis.
inline constexpr DatasetSpec kScenarioAxisIndex{"/scenarios/axis_index", "1", Shape::kScenarioAxes,
                                                Element::kInt32};
/// Each scenario's value of axis i: numbers (SI) or words, as /axes/{i}/values.
inline constexpr DatasetSpec kScenarioAxisNumbers{"/scenarios/axis_{i}", "SI", Shape::kScenarios};
inline constexpr DatasetSpec kScenarioAxisWords{"/scenarios/axis_{i}", "1", Shape::kScenarios,
                                                Element::kString};
/// The axis key, on each /scenarios/axis_{i}.
inline constexpr AttributeSpec kScenarioAxisKey{"/scenarios/axis_{i}", "key", Element::kString};
/// 0 ok, 1 config, 2 reach, 3 planning, 4 solver, 5 error, 6 internal, 7 crashed
/// (ScenarioStatus; kScenarioStatusNames).
inline constexpr DatasetSpec kScenarioStatus{"/scenarios/status", "1", Shape::kScenarios,
                                             Element::kInt8};
/// The name of each status code, by code: 7 `crashed` is a scenario whose process died
/// twice (signal, abort, out-of-memory kill) and was not tried again.
inline constexpr std::array kScenarioStatusNames{"ok",     "config", "reach",    "planning",
                                                 "solver", "error",  "internal", "crashed"};
/// "0 ok, 1 config, ...", on /scenarios/status.
inline constexpr AttributeSpec kScenarioStatusCodes{"/scenarios/status", "codes", Element::kString};
/// The error's one-line message; "" when ok.
inline constexpr DatasetSpec kScenarioMessage{"/scenarios/message", "1", Shape::kScenarios,
                                              Element::kString};
inline constexpr DatasetSpec kScenarioSamples{"/scenarios/samples", "1", Shape::kScenarios,
                                              Element::kInt32};
inline constexpr DatasetSpec kScenarioDuration{"/scenarios/duration", "s", Shape::kScenarios};
inline constexpr DatasetSpec kScenarioDistance{"/scenarios/distance", "m", Shape::kScenarios};
inline constexpr DatasetSpec kScenarioEnergy{"/scenarios/energy", "J", Shape::kScenarios};
inline constexpr DatasetSpec kScenarioCostOfTransport{"/scenarios/cost_of_transport", "1",
                                                      Shape::kScenarios};
inline constexpr DatasetSpec kScenarioPeakImpactForce{"/scenarios/peak_impact_force", "N",
                                                      Shape::kScenarios};
/// Max over samples of |τ_k|.
inline constexpr DatasetSpec kScenarioPeakTorque{"/scenarios/peak_torque", "N m",
                                                 Shape::kScenarioJoints};
/// Time-weighted RMS of τ_k (trapezoidal ∫τ² dt over the duration).
inline constexpr DatasetSpec kScenarioRmsTorque{"/scenarios/rms_torque", "N m",
                                                Shape::kScenarioJoints};
inline constexpr DatasetSpec kScenarioRelaxedSamples{"/scenarios/relaxed_samples", "1",
                                                     Shape::kScenarios, Element::kInt32};
inline constexpr DatasetSpec kScenarioFailedSamples{"/scenarios/failed_samples", "1",
                                                    Shape::kScenarios, Element::kInt32};
/// Time to compute each scenario [s] (timing: differs between runs).
inline constexpr DatasetSpec kScenarioWallTime{"/scenarios/wall_time_s", "s", Shape::kScenarios};
/// The columns of /scenarios other than the per-axis /scenarios/axis_{i}, in file order
/// (status, then message, after the axis columns).
inline constexpr std::array kScenarioDatasets{kScenarioId,
                                              kScenarioAxisIndex,
                                              kScenarioStatus,
                                              kScenarioMessage,
                                              kScenarioSamples,
                                              kScenarioDuration,
                                              kScenarioDistance,
                                              kScenarioEnergy,
                                              kScenarioCostOfTransport,
                                              kScenarioPeakImpactForce,
                                              kScenarioPeakTorque,
                                              kScenarioRmsTorque,
                                              kScenarioRelaxedSamples,
                                              kScenarioFailedSamples,
                                              kScenarioWallTime};

// ---- /runs/{id}: with --keep-runs, each computed scenario in the hexdyn-result/1 layout
// (its own /meta, /model, kinematic and dynamic datasets below the group) ----
inline constexpr const char* kRunsGroup = "/runs";
inline constexpr const char* kRunGroup = "/runs/{id}";

// ===================================================================== hexdyn-envelope/1
// The climbable envelope (envelope/envelope.hpp): W tread depths × B duty factors × S peak
// speeds, C criteria ("kinematic", "torque", "friction"), P probes. Risers are NaN where
// not found: riser_max when even the lowest riser fails, riser_fail when none fails up to
// the top of the searched range.

// ---- /meta: kMetaSchema … kMetaWallTime as a result file's (config_yaml: the envelope
// file's text), then ----
/// The base scene after inherit: and set:, validated and fully resolved.
inline constexpr AttributeSpec kMetaEnvelopeBaseConfigYaml{kMetaGroup, "base_config_yaml",
                                                           Element::kString};
inline constexpr AttributeSpec kMetaEnvelopeName{kMetaGroup, "name", Element::kString};
/// Bisection tolerance and scan step of the riser search [m].
inline constexpr AttributeSpec kMetaEnvelopeTolerance{kMetaGroup, "riser_tolerance",
                                                      Element::kFloat64};
inline constexpr AttributeSpec kMetaEnvelopeStep{kMetaGroup, "riser_step", Element::kFloat64};
/// Every /meta attribute of an envelope file.
inline constexpr std::array kEnvelopeMetaAttributes{
    kMetaSchema,       kMetaSchemaVersion,     kMetaVersion,      kMetaGitCommit,
    kMetaCreatedUtc,   kMetaConfigYaml,        kMetaWallTime,     kMetaEnvelopeBaseConfigYaml,
    kMetaEnvelopeName, kMetaEnvelopeTolerance, kMetaEnvelopeStep, kMetaInputSha256};

// ---- the grid ----
inline constexpr DatasetSpec kEnvelopeTreadDepth{"/axes/tread_depth", "m", Shape::kEnvelopeTreads};
inline constexpr DatasetSpec kEnvelopeDutyFactor{"/axes/duty_factor", "1", Shape::kEnvelopeDuties};
inline constexpr DatasetSpec kEnvelopePeakSpeed{"/axes/peak_speed", "m/s", Shape::kEnvelopeSpeeds};
inline constexpr DatasetSpec kEnvelopeCriteria{"/axes/criteria", "1", Shape::kEnvelopeCriteria,
                                               Element::kString};
/// Searched riser range [m]: from, to.
inline constexpr DatasetSpec kEnvelopeRiserFrom{"/axes/riser_from", "m", Shape::kScalar};
inline constexpr DatasetSpec kEnvelopeRiserTo{"/axes/riser_to", "m", Shape::kScalar};

// ---- /envelope: the boundary per cell and criterion ----
/// Largest riser found climbable (every probe at or below it passed) [m].
inline constexpr DatasetSpec kEnvelopeRiserMax{"/envelope/riser_max", "m", Shape::kEnvelopeGrid};
/// Smallest riser found to fail (riser_fail − riser_max ≤ the tolerance) [m].
inline constexpr DatasetSpec kEnvelopeRiserFail{"/envelope/riser_fail", "m", Shape::kEnvelopeGrid};
/// What fails at riser_fail: "leg L4 reach: full extension", "torque L1_femur", "friction
/// cone L2", "trunk force z", "reach", "planning", ...; "" where nothing fails.
inline constexpr DatasetSpec kEnvelopeLimit{"/envelope/limit", "1", Shape::kEnvelopeGridText,
                                            Element::kString};
/// The failing probe's one-line message (leg, instant, constraint, margin or violation).
inline constexpr DatasetSpec kEnvelopeMessage{"/envelope/message", "1", Shape::kEnvelopeGridText,
                                              Element::kString};
/// The automatic posture at the kinematic riser_max (NaN when the posture is not auto):
/// trunk height above the tread-centre slope line, gait.foot_lateral, smallest margin.
inline constexpr DatasetSpec kEnvelopePostureHeight{"/envelope/posture_height", "m",
                                                    Shape::kEnvelopeCells};
inline constexpr DatasetSpec kEnvelopePostureFootLateral{"/envelope/posture_foot_lateral", "m",
                                                         Shape::kEnvelopeCells};
inline constexpr DatasetSpec kEnvelopePostureMargin{"/envelope/posture_margin", "m",
                                                    Shape::kEnvelopeCells};

// ---- /probes: every evaluation, in the order made ----
/// Cell index into (W,B,S), row-major.
inline constexpr DatasetSpec kProbeCell{"/probes/cell", "1", Shape::kEnvelopeProbes,
                                        Element::kInt32};
/// Criterion index into /axes/criteria.
inline constexpr DatasetSpec kProbeCriterion{"/probes/criterion", "1", Shape::kEnvelopeProbes,
                                             Element::kInt32};
inline constexpr DatasetSpec kProbeRiser{"/probes/riser", "m", Shape::kEnvelopeProbes};
/// 1 passed, 0 failed.
inline constexpr DatasetSpec kProbePassed{"/probes/passed", "1", Shape::kEnvelopeProbes,
                                          Element::kInt8};
inline constexpr DatasetSpec kProbeLimit{"/probes/limit", "1", Shape::kEnvelopeProbes,
                                         Element::kString};
inline constexpr DatasetSpec kProbeMessage{"/probes/message", "1", Shape::kEnvelopeProbes,
                                           Element::kString};

/// Every dataset of an envelope file.
inline constexpr std::array kEnvelopeDatasets{kEnvelopeTreadDepth,    kEnvelopeDutyFactor,
                                              kEnvelopePeakSpeed,     kEnvelopeCriteria,
                                              kEnvelopeRiserFrom,     kEnvelopeRiserTo,
                                              kEnvelopeRiserMax,      kEnvelopeRiserFail,
                                              kEnvelopeLimit,         kEnvelopeMessage,
                                              kEnvelopePostureHeight, kEnvelopePostureFootLateral,
                                              kEnvelopePostureMargin, kProbeCell,
                                              kProbeCriterion,        kProbeRiser,
                                              kProbePassed,           kProbeLimit,
                                              kProbeMessage};

}  // namespace hexdyn::schema
