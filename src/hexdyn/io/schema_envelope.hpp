#pragma once
/// \file schema_envelope.hpp
/// The `hexdyn-envelope/2` contract, part of io/schema.hpp (which includes this header at
/// its end; the generated Python schema holds both, in that order). Same conventions as there.
#include "hexdyn/io/schema.hpp"

namespace hexdyn::schema {

// ===================================================================== hexdyn-envelope/2
// The climbable envelope (envelope/envelope.hpp): W tread depths × B duty factors × S peak
// speeds, C criteria ("kinematic", "torque", "friction"), P probes. An envelope file with
// `cases:` (D cases, each setting K keys: one robot design each) adds the dimension `case`
// before the others: the kEnvelopeCase* declarations below replace those of the same path. Risers
// are NaN where not found: riser_max when even the lowest riser fails, riser_fail when none fails
// up to the top of the searched range.

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
/// "up" or "down": the way the stairs were walked; the risers of the file are magnitudes.
inline constexpr AttributeSpec kMetaEnvelopeDirection{kMetaGroup, "direction", Element::kString};
/// Every /meta attribute of an envelope file.
inline constexpr std::array kEnvelopeMetaAttributes{
    kMetaSchema,       kMetaSchemaVersion,     kMetaVersion,      kMetaGitCommit,
    kMetaCreatedUtc,   kMetaConfigYaml,        kMetaWallTime,     kMetaEnvelopeBaseConfigYaml,
    kMetaEnvelopeName, kMetaEnvelopeTolerance, kMetaEnvelopeStep, kMetaEnvelopeDirection,
    kMetaInputSha256};

// ---- the grid ----
inline constexpr DatasetSpec kEnvelopeTreadDepth{"/axes/tread_depth", "m", Shape::kEnvelopeTreads,
                                                 Element::kFloat64, "tread depth"};
inline constexpr DatasetSpec kEnvelopeDutyFactor{"/axes/duty_factor", "1", Shape::kEnvelopeDuties,
                                                 Element::kFloat64, "duty factor"};
inline constexpr DatasetSpec kEnvelopePeakSpeed{"/axes/peak_speed", "m/s", Shape::kEnvelopeSpeeds,
                                                Element::kFloat64, "peak speed"};
inline constexpr DatasetSpec kEnvelopeCriteria{"/axes/criteria", "", Shape::kEnvelopeCriteria,
                                               Element::kString, "criterion"};
/// Searched riser range [m]: from, to.
inline constexpr DatasetSpec kEnvelopeRiserFrom{"/axes/riser_from", "m", Shape::kScalar,
                                                Element::kFloat64, "lowest riser searched"};
inline constexpr DatasetSpec kEnvelopeRiserTo{"/axes/riser_to", "m", Shape::kScalar,
                                              Element::kFloat64, "highest riser searched"};

// ---- /envelope: the boundary per cell and criterion ----
/// Largest riser found climbable (every probe at or below it passed) [m].
inline constexpr DatasetSpec kEnvelopeRiserMax{"/envelope/riser_max", "m", Shape::kEnvelopeGrid,
                                               Element::kFloat64, "largest riser found climbable"};
/// Smallest riser found to fail (riser_fail − riser_max ≤ the tolerance) [m].
inline constexpr DatasetSpec kEnvelopeRiserFail{"/envelope/riser_fail", "m", Shape::kEnvelopeGrid,
                                                Element::kFloat64, "smallest riser found to fail"};
/// The required friction of the run at riser_max: the largest /contacts/required_friction over
/// its support samples (docs/theory/grip.md), the criterion's own limits in force (μ lifted to
/// 10 for torque: μ* does not depend on the scene's μ); NaN for the kinematic criterion, where
/// riser_max is NaN, or where a support sample admits no μ.
inline constexpr DatasetSpec kEnvelopeRiserMaxRequiredFriction{
    "/envelope/riser_max_required_friction", "1", Shape::kEnvelopeGrid, Element::kFloat64,
    "required friction coefficient at riser_max"};
/// What fails at riser_fail: "leg L4 reach: full extension", "torque L1_femur", "friction
/// cone L2", "trunk force z", "reach", "planning", ...; "" where nothing fails.
inline constexpr DatasetSpec kEnvelopeLimit{"/envelope/limit", "", Shape::kEnvelopeGrid,
                                            Element::kString, "what fails at riser_fail"};
/// The failing probe's one-line message (leg, instant, constraint, margin or violation).
inline constexpr DatasetSpec kEnvelopeMessage{"/envelope/message", "", Shape::kEnvelopeGrid,
                                              Element::kString, "message of the failing probe"};
/// The automatic posture at the kinematic riser_max (NaN when the posture is not auto):
/// trunk height above the tread-centre slope line, gait.foot_lateral, smallest margin.
inline constexpr DatasetSpec kEnvelopePostureHeight{
    "/envelope/posture_height", "m", Shape::kEnvelopeCells, Element::kFloat64,
    "automatic trunk height at the kinematic riser_max"};
inline constexpr DatasetSpec kEnvelopePostureFootLateral{
    "/envelope/posture_foot_lateral", "m", Shape::kEnvelopeCells, Element::kFloat64,
    "automatic foot lateral distance at the kinematic riser_max"};
inline constexpr DatasetSpec kEnvelopePostureMargin{
    "/envelope/posture_margin", "m", Shape::kEnvelopeCells, Element::kFloat64,
    "smallest kinematic margin of the automatic posture"};

// ---- /probes: every evaluation, in the order made ----
/// Cell index into (W,B,S), or (D,W,B,S) with cases, row-major.
inline constexpr DatasetSpec kProbeCell{"/probes/cell", "1", Shape::kEnvelopeProbes,
                                        Element::kInt32,
                                        "cell index into the grid of posture_height, row-major"};
/// Criterion index into /axes/criteria.
inline constexpr DatasetSpec kProbeCriterion{"/probes/criterion", "1", Shape::kEnvelopeProbes,
                                             Element::kInt32,
                                             "criterion index into the criterion dimension"};
inline constexpr DatasetSpec kProbeRiser{"/probes/riser", "m", Shape::kEnvelopeProbes,
                                         Element::kFloat64, "riser height probed"};
/// 1 passed, 0 failed (CF flags kProbePassedFlags).
inline constexpr DatasetSpec kProbePassed{"/probes/passed", "", Shape::kEnvelopeProbes,
                                          Element::kInt8, "probe outcome"};
inline constexpr DatasetSpec kProbeLimit{"/probes/limit", "", Shape::kEnvelopeProbes,
                                         Element::kString, "what failed"};
inline constexpr DatasetSpec kProbeMessage{"/probes/message", "", Shape::kEnvelopeProbes,
                                           Element::kString, "message of the probe"};

// ---- coordinate variables (dimension_names) ----
inline constexpr DatasetSpec kTreadDepthCoordinate{"/tread_depth", "m", Shape::kEnvelopeTreads,
                                                   Element::kFloat64, "tread depth"};
inline constexpr DatasetSpec kDutyFactorCoordinate{"/duty_factor", "1", Shape::kEnvelopeDuties,
                                                   Element::kFloat64, "duty factor"};
inline constexpr DatasetSpec kPeakSpeedCoordinate{"/peak_speed", "m/s", Shape::kEnvelopeSpeeds,
                                                  Element::kFloat64, "peak speed"};
inline constexpr DatasetSpec kCriterionCoordinate{"/criterion", "", Shape::kEnvelopeCriteria,
                                                  Element::kString, "criterion"};
inline constexpr DatasetSpec kProbeCoordinate{"/probe", "1", Shape::kEnvelopeProbes,
                                              Element::kInt32, "probe index"};
inline constexpr std::array kEnvelopeCoordinates{kTreadDepthCoordinate, kDutyFactorCoordinate,
                                                 kPeakSpeedCoordinate, kCriterionCoordinate,
                                                 kProbeCoordinate};

// ---- with `cases:`: the cases, and the grid with its leading dimension `case` ----
inline constexpr DatasetSpec kEnvelopeCaseLabels{"/axes/case", "", Shape::kEnvelopeCases,
                                                 Element::kString, "case label"};
/// The keys every case sets, in the order of the first case.
inline constexpr DatasetSpec kEnvelopeCaseKeys{"/axes/case_keys", "", Shape::kEnvelopeCaseKeys,
                                               Element::kString, "keys each case sets"};
/// Each case's value of each key as YAML text (p/q evaluated, a robot.urdf path absolute).
inline constexpr DatasetSpec kEnvelopeCaseValues{"/axes/case_values", "",
                                                 Shape::kEnvelopeCaseValues, Element::kString,
                                                 "value of each key in each case"};
inline constexpr DatasetSpec kCaseCoordinate{"/case", "", Shape::kEnvelopeCases, Element::kString,
                                             "case label"};
inline constexpr DatasetSpec kCaseKeyCoordinateEnvelope{"/case_key", "", Shape::kEnvelopeCaseKeys,
                                                        Element::kString, "keys each case sets"};
inline constexpr DatasetSpec kEnvelopeCaseRiserMax{"/envelope/riser_max", "m",
                                                   Shape::kEnvelopeCaseGrid, Element::kFloat64,
                                                   "largest riser found climbable"};
inline constexpr DatasetSpec kEnvelopeCaseRiserFail{"/envelope/riser_fail", "m",
                                                    Shape::kEnvelopeCaseGrid, Element::kFloat64,
                                                    "smallest riser found to fail"};
inline constexpr DatasetSpec kEnvelopeCaseRiserMaxRequiredFriction{
    "/envelope/riser_max_required_friction", "1", Shape::kEnvelopeCaseGrid, Element::kFloat64,
    "required friction coefficient at riser_max"};
inline constexpr DatasetSpec kEnvelopeCaseLimit{"/envelope/limit", "", Shape::kEnvelopeCaseGrid,
                                                Element::kString, "what fails at riser_fail"};
inline constexpr DatasetSpec kEnvelopeCaseMessage{"/envelope/message", "", Shape::kEnvelopeCaseGrid,
                                                  Element::kString, "message of the failing probe"};
inline constexpr DatasetSpec kEnvelopeCasePostureHeight{
    "/envelope/posture_height", "m", Shape::kEnvelopeCaseCells, Element::kFloat64,
    "automatic trunk height at the kinematic riser_max"};
inline constexpr DatasetSpec kEnvelopeCasePostureFootLateral{
    "/envelope/posture_foot_lateral", "m", Shape::kEnvelopeCaseCells, Element::kFloat64,
    "automatic foot lateral distance at the kinematic riser_max"};
inline constexpr DatasetSpec kEnvelopeCasePostureMargin{
    "/envelope/posture_margin", "m", Shape::kEnvelopeCaseCells, Element::kFloat64,
    "smallest kinematic margin of the automatic posture"};
/// What an envelope file with cases holds besides (or, by path, instead of) kEnvelopeDatasets
/// and kEnvelopeCoordinates.
// clang-format off
inline constexpr std::array kEnvelopeCaseDatasets{
    kEnvelopeCaseLabels, kEnvelopeCaseKeys, kEnvelopeCaseValues, kCaseCoordinate,
    kCaseKeyCoordinateEnvelope, kEnvelopeCaseRiserMax, kEnvelopeCaseRiserFail, kEnvelopeCaseLimit,
    kEnvelopeCaseMessage, kEnvelopeCasePostureHeight, kEnvelopeCasePostureFootLateral,
    kEnvelopeCasePostureMargin, kEnvelopeCaseRiserMaxRequiredFriction};
// clang-format on

// ---- with `search: friction` (envelope/envelope.hpp): the least μ per cell and riser, R risers
// of the scan; the grids above hold the friction criterion's boundary on the same scan ----
/// The scan's risers [m]: riser.from, from + step, …, riser.to.
inline constexpr DatasetSpec kEnvelopeRisers{"/axes/riser", "m", Shape::kEnvelopeRisers,
                                             Element::kFloat64, "riser height"};
inline constexpr DatasetSpec kRiserCoordinate{"/riser", "m", Shape::kEnvelopeRisers,
                                              Element::kFloat64, "riser height"};
/// The least friction coefficient the run needs: the largest /contacts/required_friction over
/// its support samples, with the torque limit lifted (NaN where a support sample admits no μ
/// or the run fails; the probe's message says why). Independent of the scene's μ.
inline constexpr DatasetSpec kEnvelopeRequiredFriction{
    "/envelope/required_friction", "1", Shape::kEnvelopeMuGrid, Element::kFloat64,
    "least friction coefficient of the support samples"};
/// Its binding leg, 0-based; −1 where none.
inline constexpr DatasetSpec kEnvelopeRequiredFrictionLeg{
    "/envelope/required_friction_leg", "", Shape::kEnvelopeMuGrid, Element::kInt32,
    "leg binding the least friction coefficient, 0-based (0 is L1), -1 none"};
/// The time of the sample that needs it [s]; NaN where none.
inline constexpr DatasetSpec kEnvelopeRequiredFrictionTime{
    "/envelope/required_friction_time", "s", Shape::kEnvelopeMuGrid, Element::kFloat64,
    "time of the sample needing the least friction coefficient"};
inline constexpr DatasetSpec kEnvelopeCaseRequiredFriction{
    "/envelope/required_friction", "1", Shape::kEnvelopeCaseMuGrid, Element::kFloat64,
    "least friction coefficient of the support samples"};
inline constexpr DatasetSpec kEnvelopeCaseRequiredFrictionLeg{
    "/envelope/required_friction_leg", "", Shape::kEnvelopeCaseMuGrid, Element::kInt32,
    "leg binding the least friction coefficient, 0-based (0 is L1), -1 none"};
inline constexpr DatasetSpec kEnvelopeCaseRequiredFrictionTime{
    "/envelope/required_friction_time", "s", Shape::kEnvelopeCaseMuGrid, Element::kFloat64,
    "time of the sample needing the least friction coefficient"};
/// What a friction search's file holds besides kEnvelopeDatasets (with cases, the
/// kEnvelopeCase* grids replace those of the same path).
inline constexpr std::array kEnvelopeFrictionDatasets{
    kEnvelopeRisers, kRiserCoordinate, kEnvelopeRequiredFriction, kEnvelopeRequiredFrictionLeg,
    kEnvelopeRequiredFrictionTime};
inline constexpr std::array kEnvelopeCaseFrictionDatasets{kEnvelopeCaseRequiredFriction,
                                                          kEnvelopeCaseRequiredFrictionLeg,
                                                          kEnvelopeCaseRequiredFrictionTime};

/// Written by every envelope since the required friction per cell (not in kEnvelopeDatasets:
/// earlier version-2 files lack it).
inline constexpr std::array kEnvelopeGripDatasets{kEnvelopeRiserMaxRequiredFriction};

inline constexpr FlagSpec kProbePassedFlags{"/probes/passed", "failed passed"};

/// Every dataset of an envelope file.
// clang-format off
inline constexpr std::array kEnvelopeDatasets{
    kEnvelopeTreadDepth, kEnvelopeDutyFactor, kEnvelopePeakSpeed, kEnvelopeCriteria,
    kEnvelopeRiserFrom, kEnvelopeRiserTo, kEnvelopeRiserMax, kEnvelopeRiserFail, kEnvelopeLimit,
    kEnvelopeMessage, kEnvelopePostureHeight, kEnvelopePostureFootLateral, kEnvelopePostureMargin,
    kProbeCell, kProbeCriterion, kProbeRiser, kProbePassed, kProbeLimit, kProbeMessage};
// clang-format on

}  // namespace hexdyn::schema
