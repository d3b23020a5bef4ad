#pragma once
/// \file schema_robustness.hpp
/// The `hexdyn-robustness/1` contract, part of io/schema.hpp (which includes this header at
/// its end, after the replay's; the generated Python schema holds it too), and the CF flags of
/// every file kind. Same conventions as there.
#include "hexdyn/io/schema.hpp"

namespace hexdyn::schema {

// =================================================================== hexdyn-robustness/1
// A robustness study (robustness/robustness.hpp, docs/user/robustness.md): one plan replayed
// on RP perturbed worlds. /replays holds each replay's outcome; /perturbations/NAME each
// replay's drawn errors of the perturbations the study names (the others are absent), per
// stair step (ST), leg link (LK), joint (J), component (xyz) or once; /summary the study's
// success probability and failure counts; /tolerance, with a tolerance search, the largest
// tolerated scale of each perturbation (PT). Coordinates: /replay (0 … RP−1), /step (1 … ST),
// /link and /joint (the joint names: link j is the body joint j moves), /xyz,
// /failure_class (the class names), /perturbation (the names searched).

inline constexpr const char* kRobustnessSchema = "hexdyn-robustness/1";  ///< /meta `schema`
inline constexpr std::int64_t kRobustnessSchemaVersion = 1;              ///< /meta `schema_version`

// ---- /meta: kMetaSchema … kMetaWallTime as a result file's (config_yaml: the scene with its
// robustness: section, resolved), then ----
/// The scene's name.
inline constexpr AttributeSpec kMetaRobustnessName{kMetaGroup, "name", Element::kString};
/// The seed of the counter-based draws.
inline constexpr AttributeSpec kMetaRobustnessSeed{kMetaGroup, "seed", Element::kInt64};
/// Every /meta attribute of a robustness file.
inline constexpr std::array kRobustnessMetaAttributes{
    kMetaSchema,         kMetaSchemaVersion, kMetaVersion,  kMetaGitCommit,
    kMetaCreatedUtc,     kMetaConfigYaml,    kMetaWallTime, kMetaInputSha256,
    kMetaRobustnessName, kMetaRobustnessSeed};

// ---- /replays: one entry per replay ----
/// 1 when the replay reached the plan's end with every bound kept (failure none).
inline constexpr DatasetSpec kRobustReachedTop{"/replays/reached_top", "", Shape::kRobustReplays,
                                               Element::kInt8, "replay reached the top"};
/// The failure class (CF flags kRobustFailureFlags).
inline constexpr DatasetSpec kRobustFailure{"/replays/failure", "", Shape::kRobustReplays,
                                            Element::kInt8, "failure class"};
/// When the failure began [s]; NaN without one.
inline constexpr DatasetSpec kRobustFailureTime{"/replays/failure_time", "s", Shape::kRobustReplays,
                                                Element::kFloat64, "time the failure began"};
/// Horizontal distance of the trunk's end from the plan's end [m].
inline constexpr DatasetSpec kRobustDrift{"/replays/drift", "m", Shape::kRobustReplays,
                                          Element::kFloat64, "horizontal drift at the end"};
/// The trunk's height above the world's terrain at the end less the plan's above its own [m].
inline constexpr DatasetSpec kRobustHeightError{"/replays/height_error", "m", Shape::kRobustReplays,
                                                Element::kFloat64,
                                                "trunk height error above the terrain at the end"};
/// The largest slip distance of one foot [m].
inline constexpr DatasetSpec kRobustSlip{"/replays/slip", "m", Shape::kRobustReplays,
                                         Element::kFloat64, "largest slip distance of a foot"};
/// ∫ Σ|τ q̇| dt of the replay [J].
inline constexpr DatasetSpec kRobustEnergy{"/replays/energy", "J", Shape::kRobustReplays,
                                           Element::kFloat64, "joint energy of the replay"};
/// Electrical energy of the replay with actuators; NaN without [J].
inline constexpr DatasetSpec kRobustElectricalEnergy{"/replays/electrical_energy", "J",
                                                     Shape::kRobustReplays, Element::kFloat64,
                                                     "electrical energy of the replay"};
/// The longest time one joint's drive spent at its bound [s] (0 without actuators).
inline constexpr DatasetSpec kRobustSaturationTime{"/replays/saturation_time", "s",
                                                   Shape::kRobustReplays, Element::kFloat64,
                                                   "longest time a drive was saturated"};
/// The least of 1 − value/bound over the margin criteria [1].
inline constexpr DatasetSpec kRobustMargin{"/replays/margin", "1", Shape::kRobustReplays,
                                           Element::kFloat64, "worst margin to a failure bound"};
/// Which criterion gave the margin (CF flags kRobustMarginFlags).
inline constexpr DatasetSpec kRobustMarginCriterion{"/replays/margin_criterion", "",
                                                    Shape::kRobustReplays, Element::kInt8,
                                                    "criterion of the worst margin"};
inline constexpr DatasetSpec kRobustSteps{"/replays/steps", "1", Shape::kRobustReplays,
                                          Element::kInt32, "integrator steps"};
/// Wall time of the replay [s] (a timing field: it differs between identical studies).
inline constexpr DatasetSpec kRobustWallTime{"/replays/wall_time", "s", Shape::kRobustReplays,
                                             Element::kFloat64, "wall time of the replay"};

// ---- /perturbations: each replay's drawn errors (robustness/perturbation.hpp) ----
inline constexpr DatasetSpec kRobustRiserHeight{"/perturbations/riser_height", "m",
                                                Shape::kRobustReplaySteps, Element::kFloat64,
                                                "riser height error"};
inline constexpr DatasetSpec kRobustTreadDepth{"/perturbations/tread_depth", "m",
                                               Shape::kRobustReplaySteps, Element::kFloat64,
                                               "tread depth error"};
inline constexpr DatasetSpec kRobustNosing{"/perturbations/nosing", "m", Shape::kRobustReplaySteps,
                                           Element::kFloat64, "nosing error"};
inline constexpr DatasetSpec kRobustFriction{"/perturbations/friction", "1", Shape::kRobustReplays,
                                             Element::kFloat64, "friction coefficient error"};
inline constexpr DatasetSpec kRobustPayloadMass{"/perturbations/payload_mass", "kg",
                                                Shape::kRobustReplays, Element::kFloat64,
                                                "payload mass added"};
inline constexpr DatasetSpec kRobustPayloadCom{"/perturbations/payload_com", "m",
                                               Shape::kRobustReplayXyz, Element::kFloat64,
                                               "payload position from the trunk centre of mass"};
inline constexpr DatasetSpec kRobustTrunkMass{"/perturbations/trunk_mass", "1",
                                              Shape::kRobustReplays, Element::kFloat64,
                                              "relative trunk mass error"};
inline constexpr DatasetSpec kRobustLinkMass{"/perturbations/link_mass", "1",
                                             Shape::kRobustReplayLinks, Element::kFloat64,
                                             "relative link mass error"};
inline constexpr DatasetSpec kRobustTorqueConstant{"/perturbations/torque_constant", "1",
                                                   Shape::kRobustReplayJoints, Element::kFloat64,
                                                   "relative torque constant error"};
inline constexpr DatasetSpec kRobustResistance{"/perturbations/resistance", "1",
                                               Shape::kRobustReplayJoints, Element::kFloat64,
                                               "relative winding resistance error"};
inline constexpr DatasetSpec kRobustJointFriction{"/perturbations/joint_friction", "1",
                                                  Shape::kRobustReplayJoints, Element::kFloat64,
                                                  "relative joint friction error"};
inline constexpr DatasetSpec kRobustFootPlacement{"/perturbations/foot_placement", "m",
                                                  Shape::kRobustReplays, Element::kFloat64,
                                                  "terrain displacement along y"};
inline constexpr DatasetSpec kRobustContactStiffness{"/perturbations/contact_stiffness", "1",
                                                     Shape::kRobustReplays, Element::kFloat64,
                                                     "relative contact stiffness error"};
/// The perturbation datasets in the order of robustness/perturbation.hpp's Perturbation.
inline constexpr std::array kRobustPerturbationDatasets{
    kRobustRiserHeight,     kRobustTreadDepth, kRobustNosing,        kRobustFriction,
    kRobustPayloadMass,     kRobustPayloadCom, kRobustTrunkMass,     kRobustLinkMass,
    kRobustTorqueConstant,  kRobustResistance, kRobustJointFriction, kRobustFootPlacement,
    kRobustContactStiffness};

// ---- /summary ----
inline constexpr DatasetSpec kRobustReplayCount{"/summary/replays", "1", Shape::kScalar,
                                                Element::kInt32, "replays"};
inline constexpr DatasetSpec kRobustSuccesses{"/summary/successes", "1", Shape::kScalar,
                                              Element::kInt32, "replays that reached the top"};
inline constexpr DatasetSpec kRobustPSuccess{"/summary/p_success", "1", Shape::kScalar,
                                             Element::kFloat64, "success fraction"};
/// The Wilson score interval of p_success at 95 % [1].
inline constexpr DatasetSpec kRobustWilsonLow{"/summary/wilson_low", "1", Shape::kScalar,
                                              Element::kFloat64,
                                              "lower end of the 95 % Wilson interval"};
inline constexpr DatasetSpec kRobustWilsonHigh{"/summary/wilson_high", "1", Shape::kScalar,
                                               Element::kFloat64,
                                               "upper end of the 95 % Wilson interval"};
inline constexpr DatasetSpec kRobustFailureCount{"/summary/failure_count", "1",
                                                 Shape::kRobustClasses, Element::kInt32,
                                                 "replays per failure class"};
/// The bounds applied (the drift's resolved from the terrain when not given).
inline constexpr DatasetSpec kRobustDriftBound{"/summary/drift_bound", "m", Shape::kScalar,
                                               Element::kFloat64, "largest drift of a success"};
inline constexpr DatasetSpec kRobustSlipBound{"/summary/slip_bound", "m", Shape::kScalar,
                                              Element::kFloat64, "largest slip of a success"};
inline constexpr DatasetSpec kRobustSaturationBound{"/summary/saturation_bound", "s",
                                                    Shape::kScalar, Element::kFloat64,
                                                    "longest saturation of a success"};
inline constexpr DatasetSpec kRobustPlanWallTime{"/summary/plan_wall_time", "s", Shape::kScalar,
                                                 Element::kFloat64, "wall time of the planning"};

// ---- /tolerance: with tolerance_search ----
inline constexpr DatasetSpec kRobustToleranceScale{"/tolerance/scale", "1",
                                                   Shape::kRobustPerturbations, Element::kFloat64,
                                                   "largest scale passing the target"};
/// scale × the distribution's largest error, in the unit /tolerance/unit names.
inline constexpr DatasetSpec kRobustToleranceMagnitude{
    "/tolerance/magnitude", "", Shape::kRobustPerturbations, Element::kFloat64,
    "largest error tolerated"};
inline constexpr DatasetSpec kRobustToleranceUnit{
    "/tolerance/unit", "", Shape::kRobustPerturbations, Element::kString, "unit of the magnitude"};
inline constexpr DatasetSpec kRobustTolerancePSuccess{
    "/tolerance/p_success", "1", Shape::kRobustPerturbations, Element::kFloat64,
    "success fraction at the scale"};
/// The largest scale searched: robustness.tolerance.max_scale, or less where a larger one could
/// draw an unphysical world (a riser reversed, a zero stiffness).
inline constexpr DatasetSpec kRobustToleranceMaxScale{"/tolerance/max_scale", "1",
                                                      Shape::kRobustPerturbations,
                                                      Element::kFloat64, "largest scale searched"};
/// 1 when the largest scale searched passed: the tolerance is at least that.
inline constexpr DatasetSpec kRobustToleranceCensored{"/tolerance/censored", "",
                                                      Shape::kRobustPerturbations, Element::kInt8,
                                                      "passed at the largest scale searched"};
inline constexpr DatasetSpec kRobustToleranceProbes{
    "/tolerance/probes", "1", Shape::kRobustPerturbations, Element::kInt32, "scales evaluated"};
inline constexpr DatasetSpec kRobustToleranceReplays{"/tolerance/replays", "1", Shape::kScalar,
                                                     Element::kInt32, "replays per scale"};
inline constexpr DatasetSpec kRobustToleranceTarget{"/tolerance/target", "1", Shape::kScalar,
                                                    Element::kFloat64, "success fraction asked"};

// ---- coordinates ----
inline constexpr DatasetSpec kReplayIndexCoordinate{"/replay", "1", Shape::kRobustReplays,
                                                    Element::kInt32, "replay index"};
inline constexpr DatasetSpec kStepCoordinate{"/step", "1", Shape::kRobustSteps, Element::kInt32,
                                             "stair step, from 1"};
inline constexpr DatasetSpec kLinkCoordinate{"/link", "", Shape::kRobustLinks, Element::kString,
                                             "leg link, by the joint that moves it"};
inline constexpr DatasetSpec kFailureClassCoordinate{"/failure_class", "", Shape::kRobustClasses,
                                                     Element::kString, "failure class"};
inline constexpr DatasetSpec kPerturbationCoordinate{
    "/perturbation", "", Shape::kRobustPerturbations, Element::kString, "perturbation"};

inline constexpr FlagSpec kRobustReachedTopFlags{"/replays/reached_top", "no yes"};
inline constexpr FlagSpec kRobustFailureFlags{"/replays/failure",
                                              "none slipped stubbed saturated fell drifted"};
inline constexpr FlagSpec kRobustMarginFlags{"/replays/margin_criterion", "slip drift saturation"};
inline constexpr FlagSpec kRobustCensoredFlags{"/tolerance/censored", "no yes"};

/// Every dataset of a robustness file but the perturbations and the tolerance search's.
// clang-format off
inline constexpr std::array kRobustnessDatasets{
    kRobustReachedTop, kRobustFailure, kRobustFailureTime, kRobustDrift, kRobustHeightError,
    kRobustSlip, kRobustEnergy, kRobustElectricalEnergy, kRobustSaturationTime, kRobustMargin,
    kRobustMarginCriterion, kRobustSteps, kRobustWallTime, kRobustReplayCount, kRobustSuccesses,
    kRobustPSuccess, kRobustWilsonLow, kRobustWilsonHigh, kRobustFailureCount, kRobustDriftBound,
    kRobustSlipBound, kRobustSaturationBound, kRobustPlanWallTime, kReplayIndexCoordinate,
    kFailureClassCoordinate};
/// With a tolerance search.
inline constexpr std::array kRobustToleranceDatasets{
    kRobustToleranceScale, kRobustToleranceMaxScale, kRobustToleranceMagnitude, kRobustToleranceUnit,
    kRobustTolerancePSuccess, kRobustToleranceCensored, kRobustToleranceProbes,
    kRobustToleranceReplays, kRobustToleranceTarget, kPerturbationCoordinate};
/// The coordinates of the perturbations' other dimensions, each present when a perturbation
/// uses it (and /joint, /xyz: schema.hpp's kJointCoordinate, kXyzCoordinate).
inline constexpr std::array kRobustPerturbationCoordinates{kStepCoordinate, kLinkCoordinate};
// clang-format on

/// Every CF flag declaration of the five file kinds.
inline constexpr std::array kFlags{
    kContactPhaseFlags,    kSolverStatusFlags,     kSampleKindFlags,       kContactSlipFlags,
    kScenarioStatusFlags,  kProbePassedFlags,      kReplayReachedTopFlags, kWindingLimitFlags,
    kReplaySaturatedFlags, kRobustReachedTopFlags, kRobustFailureFlags,    kRobustMarginFlags,
    kRobustCensoredFlags};

}  // namespace hexdyn::schema
