#pragma once
/// \file schema_replay.hpp
/// The `hexdyn-replay/3` contract, part of io/schema.hpp (which includes this header at
/// its end; the generated Python schema holds it too). Same conventions as there.
#include "hexdyn/io/schema.hpp"

namespace hexdyn::schema {

// ======================================================================= hexdyn-replay/3
// A forward replay of a result file (replay/replay.hpp, docs/theory/replay.md): the stored
// torques, with a joint PD on the planned angles, applied to the robot on the terrain through
// the forward dynamics and the compliant contact. T samples at the result's own instants
// /time (up to the end of the replay); every sample is a state the integrator reached, with
// the torques, contact forces and accelerations evaluated at that state (the accelerations
// are the forward dynamics of the stored state, torques and forces). The kinematic and
// dynamic datasets keep the result file's names (kTime, kBasePosition, … kJointTorque,
// kContactForce, kFeetPosition, whose declarations in schema.hpp apply); the ones below
// are the replay's own. Energies are cumulative from the start of the replay.

inline constexpr const char* kReplaySchema = "hexdyn-replay/3";  ///< /meta attr `schema`
inline constexpr std::int64_t kReplaySchemaVersion = 3;          ///< /meta `schema_version`

// ---- /meta: kMetaSchema … kMetaWallTime as a result file's (config_yaml: the scene as
// replayed, its replay: and contact: keys included), then ----
/// Absolute path of the replayed result file.
inline constexpr AttributeSpec kMetaReplaySource{kMetaGroup, "source_result", Element::kString};
/// `created_utc` of the replayed result file.
inline constexpr AttributeSpec kMetaReplaySourceCreated{kMetaGroup, "source_created_utc",
                                                        Element::kString};
/// Every /meta attribute of a replay file.
inline constexpr std::array kReplayMetaAttributes{
    kMetaSchema,       kMetaSchemaVersion,      kMetaVersion,  kMetaGitCommit,
    kMetaCreatedUtc,   kMetaConfigYaml,         kMetaWallTime, kMetaInputSha256,
    kMetaReplaySource, kMetaReplaySourceCreated};

// ---- the replayed motion (besides the result file's names) ----
/// q_replay − q_plan at the same instant [rad].
inline constexpr DatasetSpec kReplayTrackingError{"/joints/tracking_error", "rad", Shape::kTJoint,
                                                  Element::kFloat64,
                                                  "replayed minus planned joint angle"};
/// The plan's stored torque at the sample's instant (the feedforward part of /joints/torque).
inline constexpr DatasetSpec kReplayFeedforward{"/joints/feedforward_torque", "N m", Shape::kTJoint,
                                                Element::kFloat64,
                                                "feedforward joint torque (the plan's)"};
/// Normal force of the compliant law [N] (0 out of contact).
inline constexpr DatasetSpec kReplayNormalForce{"/contacts/normal_force", "N", Shape::kTLeg,
                                                Element::kFloat64, "normal contact force"};
/// Tangential velocity of the contact point while in contact [m/s] (0 out of contact).
inline constexpr DatasetSpec kReplaySlipVelocity{"/contacts/slip_velocity", "m/s", Shape::kTLegXyz,
                                                 Element::kFloat64,
                                                 "tangential velocity of the contact point"};
/// ∫ slip velocity dt since the start [m]: each foot's slip displacement.
inline constexpr DatasetSpec kReplaySlipDisplacement{
    "/contacts/slip_displacement", "m", Shape::kTLegXyz, Element::kFloat64,
    "slip displacement of the contact point since the start"};
/// ∫ |slip velocity| dt since the start [m].
inline constexpr DatasetSpec kReplaySlipDistance{"/contacts/slip_distance", "m", Shape::kTLeg,
                                                 Element::kFloat64,
                                                 "slip distance since the start"};

// ---- /energy: cumulative series ----
/// ∫ Σ_k |τ_k q̇_k| dt of the applied torques (the result's /energy/total, as a series) [J].
inline constexpr DatasetSpec kReplayEnergyActuator{"/energy/actuator", "J", Shape::kT,
                                                   Element::kFloat64,
                                                   "integral of total absolute joint power"};
/// Energy dissipated by each foot's normal damping (touchdowns and support) [J].
inline constexpr DatasetSpec kReplayEnergyDamping{"/energy/contact_damping", "J", Shape::kTLeg,
                                                  Element::kFloat64,
                                                  "energy dissipated by normal contact damping"};
/// Energy dissipated by each foot's tangential (friction) force [J].
inline constexpr DatasetSpec kReplayEnergySlip{"/energy/slip", "J", Shape::kTLeg, Element::kFloat64,
                                               "energy dissipated by friction"};
/// Kinetic energy of the robot [J].
inline constexpr DatasetSpec kReplayEnergyKinetic{"/energy/kinetic", "J", Shape::kT,
                                                  Element::kFloat64, "kinetic energy"};
/// Gravitational potential energy of the robot, zero at z = 0 [J].
inline constexpr DatasetSpec kReplayEnergyPotential{"/energy/potential", "J", Shape::kT,
                                                    Element::kFloat64, "potential energy"};

// ---- /replay: what the replay reports ----
/// Instants of the gait cycles' ends within the replay [s].
inline constexpr DatasetSpec kReplayCycleEnd{"/replay/cycle_end", "s", Shape::kCycles,
                                             Element::kFloat64, "end of each gait cycle"};
/// Trunk position drift at each cycle end, replayed minus planned [m], world axes.
inline constexpr DatasetSpec kReplayPositionDrift{"/replay/position_drift", "m", Shape::kCycles3,
                                                  Element::kFloat64,
                                                  "trunk position drift at the cycle end"};
/// Trunk orientation drift at each cycle end: the rotation vector of R_plan⁻¹ R_replay,
/// trunk axes [rad].
inline constexpr DatasetSpec kReplayOrientationDrift{
    "/replay/orientation_drift", "rad", Shape::kCycles3, Element::kFloat64,
    "trunk orientation drift at the cycle end (rotation vector)"};
/// Largest |q_replay − q_plan| over every joint and sample [rad].
inline constexpr DatasetSpec kReplayMaxTrackingError{"/replay/max_tracking_error", "rad",
                                                     Shape::kScalar, Element::kFloat64,
                                                     "largest joint tracking error"};
/// Flat index of the joint where it occurs.
inline constexpr DatasetSpec kReplayMaxTrackingErrorJoint{
    "/replay/max_tracking_error_joint", "1", Shape::kScalar, Element::kInt32,
    "joint of the largest tracking error, 0-based flat index (0 is L1 coxa, 8 L3 tibia)"};
/// Instant where it occurs [s].
inline constexpr DatasetSpec kReplayMaxTrackingErrorTime{"/replay/max_tracking_error_time", "s",
                                                         Shape::kScalar, Element::kFloat64,
                                                         "instant of the largest tracking error"};
/// Per foot: total slip distance [m], energy lost to slip [J], to normal damping [J].
inline constexpr DatasetSpec kReplaySlipDistanceTotal{
    "/replay/slip_distance", "m", Shape::kLegValues, Element::kFloat64, "total slip distance"};
inline constexpr DatasetSpec kReplaySlipEnergyTotal{"/replay/slip_energy", "J", Shape::kLegValues,
                                                    Element::kFloat64, "energy lost to slip"};
inline constexpr DatasetSpec kReplayTouchdownEnergy{"/replay/touchdown_energy", "J",
                                                    Shape::kLegValues, Element::kFloat64,
                                                    "energy lost to normal contact damping"};
/// The replayed torques' energy and the result's /energy/total over the same span [J].
inline constexpr DatasetSpec kReplayEnergy{"/replay/energy", "J", Shape::kScalar, Element::kFloat64,
                                           "energy of the replayed torques"};
inline constexpr DatasetSpec kReplayEnergyPlan{"/replay/energy_inverse_dynamics", "J",
                                               Shape::kScalar, Element::kFloat64,
                                               "inverse-dynamics energy over the same span"};
/// The balance of energy: the joints' signed work ∫ τ·q̇ dt less the gains in kinetic,
/// potential and contact-spring energy and the energy the contacts dissipated; zero but for
/// the integrator's error [J] (docs/theory/replay.md#balance-of-energy).
inline constexpr DatasetSpec kReplayActuatorWork{"/replay/actuator_work", "J", Shape::kScalar,
                                                 Element::kFloat64, "signed work of the joints"};
inline constexpr DatasetSpec kReplayEnergyResidual{"/replay/energy_residual", "J", Shape::kScalar,
                                                   Element::kFloat64,
                                                   "residual of the balance of energy"};
/// Final trunk position, replayed minus planned [m].
inline constexpr DatasetSpec kReplayFinalError{"/replay/final_position_error", "m", Shape::kVector3,
                                               Element::kFloat64, "final trunk position error"};
/// 1 when the robot reached the plan's end: the replay ran to the last instant, and the
/// trunk ends within half a tread depth (horizontally) and half a riser (vertically) of the
/// planned end, upright (tilt under 0.5 rad) (docs/theory/replay.md#reaching-the-top).
inline constexpr DatasetSpec kReplayReachedTop{"/replay/reached_top", "", Shape::kScalar,
                                               Element::kInt8, "the robot reached the top"};
inline constexpr FlagSpec kReplayReachedTopFlags{"/replay/reached_top", "no yes"};
/// Why the replay ended early (a diverged or fallen state), or "" [text].
inline constexpr DatasetSpec kReplayMessage{"/replay/message", "", Shape::kText, Element::kString,
                                            "why the replay ended, if early"};
/// Integrator: the largest step [s], the steps taken, the wall time of the integration [s].
inline constexpr DatasetSpec kReplayStep{"/replay/step", "s", Shape::kScalar, Element::kFloat64,
                                         "largest integrator step"};
inline constexpr DatasetSpec kReplaySteps{"/replay/steps", "1", Shape::kScalar, Element::kInt32,
                                          "integrator steps taken"};
/// Steps accepted at the smallest step (replay.step / 64) with the normal force still off the
/// contact law by more than replay.tolerance × the weight.
inline constexpr DatasetSpec kReplayForcedSteps{"/replay/forced_steps", "1", Shape::kScalar,
                                                Element::kInt32,
                                                "steps accepted beyond the tolerance"};
inline constexpr DatasetSpec kReplaySeconds{"/replay/seconds", "s", Shape::kScalar,
                                            Element::kFloat64, "wall time of the integration"};

// ---- with actuators only (the driven replay, docs/theory/replay.md#driven-by-the-actuators):
// /joints/drive_torque (kDriveTorque's name: the torque the drive gave, its feedforward the
// plan's /joints/drive_torque, bounded by its envelope with replay.saturate), /joints/torque the
// torque reaching the links (the drive torque less J_a q̈ and the joint's friction), and ----
/// 1 where the joint's drive torque was at its torque–speed bound at the sample.
inline constexpr DatasetSpec kReplaySaturated{"/joints/saturated", "", Shape::kTJoint,
                                              Element::kInt8, "the drive torque at its bound"};
inline constexpr FlagSpec kReplaySaturatedFlags{"/joints/saturated", "no yes"};
/// Cumulative since the start [J]: electrical energy drawn (P⁺ of drive/drive.hpp), the
/// windings' copper loss, the joints' friction loss (Coulomb and viscous).
inline constexpr DatasetSpec kReplayEnergyElectrical{"/energy/electrical", "J", Shape::kT,
                                                     Element::kFloat64,
                                                     "electrical energy drawn by the drives"};
inline constexpr DatasetSpec kReplayEnergyCopper{"/energy/copper_loss", "J", Shape::kT,
                                                 Element::kFloat64,
                                                 "energy lost in the drives' windings"};
inline constexpr DatasetSpec kReplayEnergyJointFriction{
    "/energy/joint_friction", "J", Shape::kT, Element::kFloat64, "energy lost to joint friction"};
/// Per joint, the time its drive torque spent at its bound [s].
inline constexpr DatasetSpec kReplaySaturationTime{"/replay/saturation_time", "s", Shape::kJ,
                                                   Element::kFloat64,
                                                   "time the drive torque spent at its bound"};
/// The replay's electrical energy, and that of the plan's drive torques over the same span
/// (the trapezoid of the electrical power at the plan's samples) [J].
inline constexpr DatasetSpec kReplayElectricalEnergy{"/replay/electrical_energy", "J",
                                                     Shape::kScalar, Element::kFloat64,
                                                     "electrical energy of the replay"};
inline constexpr DatasetSpec kReplayElectricalEnergyPlan{
    "/replay/electrical_energy_inverse_dynamics", "J", Shape::kScalar, Element::kFloat64,
    "inverse-dynamics electrical energy over the same span"};
/// Every dataset a driven replay adds.
inline constexpr std::array kReplayDriveDatasets{kDriveTorque,
                                                 kReplaySaturated,
                                                 kReplayEnergyElectrical,
                                                 kReplayEnergyCopper,
                                                 kReplayEnergyJointFriction,
                                                 kReplaySaturationTime,
                                                 kReplayElectricalEnergy,
                                                 kReplayElectricalEnergyPlan};

/// Every dataset of the replayed motion, in the result file's names and the replay's own.
inline constexpr std::array kReplaySeriesDatasets{kTime,
                                                  kBasePosition,
                                                  kBaseOrientation,
                                                  kBaseLinearVelocity,
                                                  kBaseAngularVelocity,
                                                  kBaseLinearAcceleration,
                                                  kBaseAngularAcceleration,
                                                  kJointPosition,
                                                  kJointVelocity,
                                                  kJointAcceleration,
                                                  kJointTorque,
                                                  kContactForce,
                                                  kFeetPosition,
                                                  kReplayTrackingError,
                                                  kReplayFeedforward,
                                                  kReplayNormalForce,
                                                  kContactPenetration,
                                                  kReplaySlipVelocity,
                                                  kReplaySlipDisplacement,
                                                  kReplaySlipDistance,
                                                  kReplayEnergyActuator,
                                                  kReplayEnergyDamping,
                                                  kReplayEnergySlip,
                                                  kReplayEnergyKinetic,
                                                  kReplayEnergyPotential};
/// Copied from the replayed result: the robot and the terrain (for readers and animate.py).
inline constexpr std::array kReplayModelDatasets{
    kModelUrdf, kModelJointNames, kModelLegNames, kModelLegJointCounts, kTerrainY, kTerrainZ};
/// Every dataset of the replay's report.
inline constexpr std::array kReplayReportDatasets{kReplayCycleEnd,
                                                  kReplayPositionDrift,
                                                  kReplayOrientationDrift,
                                                  kReplayMaxTrackingError,
                                                  kReplayMaxTrackingErrorJoint,
                                                  kReplayMaxTrackingErrorTime,
                                                  kReplaySlipDistanceTotal,
                                                  kReplaySlipEnergyTotal,
                                                  kReplayTouchdownEnergy,
                                                  kReplayEnergy,
                                                  kReplayEnergyPlan,
                                                  kReplayActuatorWork,
                                                  kReplayEnergyResidual,
                                                  kReplayFinalError,
                                                  kReplayReachedTop,
                                                  kReplayMessage,
                                                  kReplayStep,
                                                  kReplaySteps,
                                                  kReplayForcedSteps,
                                                  kReplaySeconds};

}  // namespace hexdyn::schema
