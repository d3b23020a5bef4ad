#pragma once
/// \file schema.hpp
/// The HDF5 contracts of hexdyn in one place (described in docs/user/output.md, whose
/// tables are generated from this header): `hexdyn-result/5` (one run) here, and, in the
/// headers this one includes at its end, `hexdyn-sweep/5` (a parameter sweep,
/// schema_sweep.hpp), `hexdyn-envelope/2` (the climbable envelope, envelope/envelope.hpp,
/// schema_envelope.hpp) and `hexdyn-replay/3` (schema_replay.hpp), each with its schema
/// name and version, every /meta attribute, and for every dataset its path, `units`, shape,
/// element type and `long_name`. The
/// writers (io/result_layout.cpp, sweep/sweep_file.cpp, envelope/envelope_file.cpp) take
/// every path, units string and long name from here, and label every dataset with the
/// dimensions of its shape (dimension_names(), io/labels.hpp), so that netCDF-4 readers
/// (xarray, ncdump) open the files. The Python reader hexdyn.results takes the same
/// declarations from the module `_schema` the build generates by compiling this header
/// (bindings/python/schema/schema_py.cpp, cmake/python.cmake), so the layout is typed
/// once. Keep declarations on the regular pattern
///     inline constexpr DatasetSpec kName{"path", "units", Shape::kX, Element::kY, "long name"};
/// (a name of a `const char*` constant may stand for a string). A change of layout is a
/// new schema version. The vocabulary of the declarations (Shape and its netCDF dimensions,
/// Element, DatasetSpec, AttributeSpec, FlagSpec, at()) is io/dataset_spec.hpp.
///
/// Shapes: T output samples, L legs and J joints of the robot (the lengths of
/// /model/leg_names and /model/joint_names; 6 and 18 for a hexapod of three-joint legs),
/// n touchdowns, m solver messages, Y gait cycles, K vertices of the terrain profile; in a
/// sweep file N scenarios, A axes, V values of one axis, J the length of its /joint_names.
/// (T,L,3) datasets are leg-major
/// (index [t][leg][axis]); all vectors are in the world frame G0 unless the name says
/// otherwise. Units strings are UDUNITS-2 units: "1" marks dimensionless numbers
/// (quaternions, counts, ratios); "" writes no `units` attribute: text and CF flag
/// datasets (codes, see FlagSpec); "key" marks a sweep axis value, written in the SI unit
/// of its scene key (config/key_units.hpp). Paths with "{i}" (axis number 0..A−1), "{id}"
/// (scenario id) or "{key}" (an axis key) are templates: at().
#include <array>
#include <cstdint>

#include "hexdyn/io/dataset_spec.hpp"  // IWYU pragma: export

namespace hexdyn::schema {

inline constexpr const char* kResultSchema = "hexdyn-result/5";  ///< /meta attr `schema`
inline constexpr std::int64_t kResultSchemaVersion = 5;          ///< /meta attr `schema_version`
inline constexpr const char* kSweepSchema = "hexdyn-sweep/5";    ///< sweep files' `schema`
inline constexpr std::int64_t kSweepSchemaVersion = 5;           ///< sweep files' `schema_version`
inline constexpr const char* kEnvelopeSchema = "hexdyn-envelope/2";  ///< envelope files' `schema`
inline constexpr std::int64_t kEnvelopeSchemaVersion = 2;  ///< envelope files' `schema_version`

// ======================================================================= hexdyn-result/5

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
inline constexpr const char* kUnitsAttribute = "units";  ///< on every dataset with units
/// CF `long_name`, on every dataset.
inline constexpr const char* kLongNameAttribute = "long_name";

/// double, output.tolerance the adaptive grid was refined to (0: not refined)
/// (docs/theory/output-grid.md#error-control)
inline constexpr const char* kAttrGridTolerance = "grid_tolerance";
/// double, the estimated relative error of the energies on the stored samples, the largest of
/// the total and the per-joint ones
inline constexpr const char* kAttrGridEnergyError = "grid_energy_error";
/// double, the estimated relative error of the peaks of the stored series (joint torques,
/// total power, contact force), the largest
inline constexpr const char* kAttrGridPeakError = "grid_peak_error";

/// string, the quadrature rule over /time by which /energy/total, /energy/per_joint and
/// /energy/cycle are integrated from /power/per_joint
/// (docs/theory/output-grid.md#energy-from-the-samples): kEnergyRuleCubic on the adaptive grid,
/// kEnergyRuleTrapezoid on the uniform grid. Files of layout version 2 have none: their rule is the
/// trapezoid over /power/total.
inline constexpr const char* kAttrEnergyRule = "energy_rule";
/// Per joint, ∫|p| of the interpolant p of /power/per_joint through the 4 samples nearest each
/// interval within its piece (the runs of samples between a /sample_kind 1 sample and the
/// next), split at p's roots; a piece of 2 intervals takes the quadratic, of 1 the line; an
/// interval from a left-limit sample to its event the trapezoid. /energy/total = the sum over
/// the joints; /energy/cycle the same over each cycle's span.
inline constexpr const char* kEnergyRuleCubic = "piecewise-cubic";
/// The trapezoid of /power/total (and of |/power/per_joint| per joint) over /time.
inline constexpr const char* kEnergyRuleTrapezoid = "trapezoid";

inline constexpr AttributeSpec kMetaSchema{kMetaGroup, kAttrSchema, Element::kString};
inline constexpr AttributeSpec kMetaSchemaVersion{kMetaGroup, kAttrSchemaVersion, Element::kInt64};
inline constexpr AttributeSpec kMetaVersion{kMetaGroup, kAttrVersion, Element::kString};
inline constexpr AttributeSpec kMetaGitCommit{kMetaGroup, kAttrGitCommit, Element::kString};
inline constexpr AttributeSpec kMetaCreatedUtc{kMetaGroup, kAttrCreatedUtc, Element::kString};
inline constexpr AttributeSpec kMetaConfigYaml{kMetaGroup, kAttrConfigYaml, Element::kString};
inline constexpr AttributeSpec kMetaWallTime{kMetaGroup, kAttrWallTime, Element::kFloat64};
inline constexpr AttributeSpec kMetaInputSha256{kMetaGroup, kAttrInputSha256, Element::kString};
inline constexpr AttributeSpec kMetaGridTolerance{kMetaGroup, kAttrGridTolerance,
                                                  Element::kFloat64};
inline constexpr AttributeSpec kMetaGridEnergyError{kMetaGroup, kAttrGridEnergyError,
                                                    Element::kFloat64};
inline constexpr AttributeSpec kMetaGridPeakError{kMetaGroup, kAttrGridPeakError,
                                                  Element::kFloat64};
inline constexpr AttributeSpec kMetaEnergyRule{kMetaGroup, kAttrEnergyRule, Element::kString};
/// Every /meta attribute of a result file.
inline constexpr std::array kResultMetaAttributes{
    kMetaSchema,        kMetaSchemaVersion,   kMetaVersion,       kMetaGitCommit,
    kMetaCreatedUtc,    kMetaConfigYaml,      kMetaWallTime,      kMetaInputSha256,
    kMetaGridTolerance, kMetaGridEnergyError, kMetaGridPeakError, kMetaEnergyRule};

// ---- /model ----
inline constexpr DatasetSpec kModelUrdf{"/model/urdf", "", Shape::kText, Element::kString,
                                        "robot description (URDF) as simulated"};
inline constexpr DatasetSpec kModelJointNames{"/model/joint_names", "", Shape::kJointNames,
                                              Element::kString, "joint names, leg-major"};
inline constexpr DatasetSpec kModelLegNames{"/model/leg_names", "", Shape::kLegNames,
                                            Element::kString, "leg names"};
/// Joints of each leg, hip to foot (/model/joint_names: each leg's in turn, in leg order).
/// From layout version 4 (versions 2 and 3: three joints a leg).
inline constexpr DatasetSpec kModelLegJointCounts{"/model/leg_joint_counts", "1", Shape::kLegValues,
                                                  Element::kInt32, "number of joints of each leg"};
inline constexpr DatasetSpec kModelTotalMass{"/model/total_mass", "kg", Shape::kScalar,
                                             Element::kFloat64, "total mass of the robot"};
/// A URDF robot's legs L1 … L6: "L1: JOINT1 JOINT2 JOINT3 foot FOOT", the description's
/// joint names hip to foot and the foot's link (or "offset X Y Z LINK", m in that link's
/// frame), then "radius R" (m) for a sphere foot. Written only for a robot read from a URDF
/// (kUrdfRobotDatasets).
inline constexpr DatasetSpec kModelLegMapping{"/model/leg_mapping", "", Shape::kLegNames,
                                              Element::kString, "URDF joints and foot of each leg"};

// ---- kinematics: always written ----
inline constexpr DatasetSpec kTime{"/time", "s", Shape::kT, Element::kFloat64, "time"};
inline constexpr DatasetSpec kBasePosition{"/base/position", "m", Shape::kT3, Element::kFloat64,
                                           "trunk frame origin position"};
/// Quaternion w, x, y, z of the rotation body → world.
inline constexpr DatasetSpec kBaseOrientation{
    "/base/orientation", "1", Shape::kT4, Element::kFloat64,
    "trunk orientation quaternion (w, x, y, z), body to world"};
inline constexpr DatasetSpec kBaseLinearVelocity{"/base/linear_velocity", "m/s", Shape::kT3,
                                                 Element::kFloat64, "trunk linear velocity"};
inline constexpr DatasetSpec kBaseAngularVelocity{"/base/angular_velocity", "rad/s", Shape::kT3,
                                                  Element::kFloat64, "trunk angular velocity"};
inline constexpr DatasetSpec kBaseLinearAcceleration{"/base/linear_acceleration", "m/s^2",
                                                     Shape::kT3, Element::kFloat64,
                                                     "trunk linear acceleration"};
inline constexpr DatasetSpec kBaseAngularAcceleration{"/base/angular_acceleration", "rad/s^2",
                                                      Shape::kT3, Element::kFloat64,
                                                      "trunk angular acceleration"};
inline constexpr DatasetSpec kJointPosition{"/joints/position", "rad", Shape::kTJoint,
                                            Element::kFloat64, "joint angle"};
inline constexpr DatasetSpec kJointVelocity{"/joints/velocity", "rad/s", Shape::kTJoint,
                                            Element::kFloat64, "joint angular velocity"};
inline constexpr DatasetSpec kJointAcceleration{"/joints/acceleration", "rad/s^2", Shape::kTJoint,
                                                Element::kFloat64, "joint angular acceleration"};
/// Where each foot touches, or would touch in swing: the planned foot path; a sphere foot's
/// contact point, centre − r n (docs/theory/model.md#sphere-feet).
inline constexpr DatasetSpec kFeetPosition{"/feet/position", "m", Shape::kTLegXyz,
                                           Element::kFloat64, "foot position"};
/// A sphere foot's centre, the point the IK places: /feet/position + r n, n the unit normal of
/// the surface under the foot (in a swing, lift-off and touchdown normals blended); a point
/// foot's is its /feet/position. Written only for a robot with a sphere foot
/// (kSphereFootDatasets).
inline constexpr DatasetSpec kFeetCenter{"/feet/center", "m", Shape::kTLegXyz, Element::kFloat64,
                                         "sphere foot centre position"};
inline constexpr DatasetSpec kFeetVelocity{"/feet/velocity", "m/s", Shape::kTLegXyz,
                                           Element::kFloat64, "foot velocity"};
inline constexpr DatasetSpec kComPosition{"/com/position", "m", Shape::kT3, Element::kFloat64,
                                          "centre of mass position"};
/// 0 swing, 1 impact, 2 support (ContactPhase; CF flags kContactPhaseFlags).
inline constexpr DatasetSpec kContactPhase{"/contacts/phase", "", Shape::kTLeg, Element::kInt8,
                                           "contact phase of each leg"};
/// 0 an ordinary sample, 1 the left limit of a contact event: a sample 1e-10 s before a
/// touchdown, the end of a touchdown transient or a lift-off, holding every value just before
/// it (docs/theory/output-grid.md#event-samples); adaptive grid only (CF flags kSampleKindFlags).
inline constexpr DatasetSpec kSampleKind{"/sample_kind", "", Shape::kT, Element::kInt8,
                                         "kind of output sample"};
/// Start of each gait cycle (phase τ = 0, 1, …), the first 0; the last cycle runs to the end.
inline constexpr DatasetSpec kGaitCycleStart{"/gait/cycle_start", "s", Shape::kCycles,
                                             Element::kFloat64, "start time of each gait cycle"};
/// The terrain's height profile z(y), world frame, as a polyline (a vertical riser is two
/// vertices of equal y); constant along x. Covers the run's feet and trunk with 0.25 m margin
/// (stairs: every riser).
inline constexpr DatasetSpec kTerrainY{"/terrain/y", "m", Shape::kTerrainPoints, Element::kFloat64,
                                       "y of each terrain profile vertex"};
/// Terrain height at each vertex of /terrain/y.
inline constexpr DatasetSpec kTerrainZ{"/terrain/z", "m", Shape::kTerrainPoints, Element::kFloat64,
                                       "terrain height at each profile vertex"};
/// A height map's grid as used (terrain.type height_map; docs/theory/stages.md#height-maps):
/// the x of each column, the y of each row, and the height of each node, row-major.
inline constexpr DatasetSpec kTerrainMapX{"/terrain/map_x", "m", Shape::kMapColumns,
                                          Element::kFloat64, "x of each height map column"};
inline constexpr DatasetSpec kTerrainMapY{"/terrain/map_y", "m", Shape::kMapRows, Element::kFloat64,
                                          "y of each height map row"};
inline constexpr DatasetSpec kTerrainMapZ{"/terrain/map_z", "m", Shape::kMapGrid, Element::kFloat64,
                                          "height of each height map node"};
inline constexpr const char* kTerrainGroup = "/terrain";
/// "flat", "slope", "stairs" or "height_map" (terrain.type), on the group /terrain.
inline constexpr AttributeSpec kTerrainType{kTerrainGroup, "type", Element::kString};

// ---- dynamics: written only when the dynamic stages ran ----
inline constexpr DatasetSpec kJointTorque{"/joints/torque", "N m", Shape::kTJoint,
                                          Element::kFloat64, "joint torque"};
/// Force of the terrain on the foot, world frame.
inline constexpr DatasetSpec kContactForce{"/contacts/force", "N", Shape::kTLegXyz,
                                           Element::kFloat64, "force of the terrain on the foot"};
inline constexpr DatasetSpec kContactPenetration{"/contacts/penetration", "m", Shape::kTLeg,
                                                 Element::kFloat64,
                                                 "foot penetration into the terrain"};
/// |F_t| / F_n of the chosen force in each foot's contact frame (docs/theory/grip.md); NaN on
/// a swing leg and where a relaxed sample's force does not press the foot; never infinite.
inline constexpr DatasetSpec kContactUtilizedFriction{"/contacts/utilized_friction", "1",
                                                      Shape::kTLeg, Element::kFloat64,
                                                      "utilised friction coefficient"};
/// 1 where the leg cannot hold at the scene's μ: its friction held only with slack, or the
/// sample needs more friction than μ and the leg is at its friction limit or binds the
/// required friction (docs/theory/grip.md#slip-onset); 0 elsewhere (CF flags kContactSlipFlags).
inline constexpr DatasetSpec kContactSlip{"/contacts/slip", "", Shape::kTLeg, Element::kInt8,
                                          "slip onset flag"};
/// The least friction coefficient for which the sample's rows admit a force distribution
/// under the scene's friction model; NaN where none does (the reason in /solver/messages).
/// Written unless output.required_friction is false.
inline constexpr DatasetSpec kRequiredFriction{"/contacts/required_friction", "1", Shape::kT,
                                               Element::kFloat64, "required friction coefficient"};
/// The leg whose friction binds at the required friction, 0-based (an index into the `leg`
/// dimension), −1 where none does. Written with /contacts/required_friction.
inline constexpr DatasetSpec kRequiredFrictionLeg{
    "/contacts/required_friction_leg", "", Shape::kT, Element::kInt8,
    "leg binding the required friction, 0-based (0 is L1), -1 none"};
/// Leg of each touchdown, 0-based (0..5): an index into the `leg` dimension (L1 is 0).
inline constexpr DatasetSpec kImpactLeg{
    "/impacts/leg", "", Shape::kN, Element::kInt32,
    "leg of the touchdown, 0-based index into the leg dimension (0 is L1)"};
inline constexpr DatasetSpec kImpactStart{"/impacts/t_start", "s", Shape::kN, Element::kFloat64,
                                          "touchdown start time"};
inline constexpr DatasetSpec kImpactDuration{"/impacts/duration", "s", Shape::kN, Element::kFloat64,
                                             "touchdown transient duration"};
inline constexpr DatasetSpec kImpactPeakForce{
    "/impacts/peak_force", "N", Shape::kN, Element::kFloat64, "peak normal force of the touchdown"};
inline constexpr DatasetSpec kImpactImpulse{"/impacts/impulse", "N s", Shape::kN, Element::kFloat64,
                                            "normal impulse of the touchdown"};
inline constexpr DatasetSpec kImpactEffectiveMass{"/impacts/effective_mass", "kg", Shape::kN,
                                                  Element::kFloat64,
                                                  "effective mass of the touchdown"};
inline constexpr DatasetSpec kImpactApproachSpeed{"/impacts/approach_speed", "m/s", Shape::kN,
                                                  Element::kFloat64,
                                                  "foot approach speed at touchdown"};
inline constexpr DatasetSpec kJointPower{"/power/per_joint", "W", Shape::kTJoint, Element::kFloat64,
                                         "signed joint power tau*omega"};
inline constexpr DatasetSpec kTotalPower{"/power/total", "W", Shape::kT, Element::kFloat64,
                                         "total absolute joint power sum |tau*omega|"};
/// The rule /meta energy_rule names over /time
/// (docs/theory/output-grid.md#energy-from-the-samples).
inline constexpr DatasetSpec kEnergyTotal{"/energy/total", "J", Shape::kScalar, Element::kFloat64,
                                          "energy: integral of total absolute joint power"};
/// ∫|τ_k ω_k| (/power/per_joint) over /time by the rule /meta energy_rule names.
inline constexpr DatasetSpec kEnergyJoint{"/energy/per_joint", "J", Shape::kJ, Element::kFloat64,
                                          "energy per joint: integral of |tau*omega|"};
/// Energy of each gait cycle (from /gait/cycle_start to the next, the last to the end):
/// by the rule /meta energy_rule names, a bound between samples cutting its interval's
/// interpolant (the trapezoid's: /power/total interpolated linearly); sums to /energy/total.
inline constexpr DatasetSpec kEnergyCycle{"/energy/cycle", "J", Shape::kCycles, Element::kFloat64,
                                          "energy per gait cycle"};
/// ∫max(0, τ_k ω_k) summed over the joints, by the rule of /energy/total: the work the joints
/// do on the robot. With /energy/negative_work: positive − negative = /energy/total,
/// positive + negative = the net joint work.
inline constexpr DatasetSpec kEnergyPositiveWork{
    "/energy/positive_work", "J", Shape::kScalar, Element::kFloat64,
    "positive joint work: integral of max(0, tau*omega)"};
/// ∫min(0, τ_k ω_k) summed over the joints (≤ 0): the work the joints absorb (braking a
/// descent, a touchdown).
inline constexpr DatasetSpec kEnergyNegativeWork{
    "/energy/negative_work", "J", Shape::kScalar, Element::kFloat64,
    "negative joint work: integral of min(0, tau*omega)"};
inline constexpr DatasetSpec kEnergyPositiveWorkJoint{"/energy/positive_work_per_joint", "J",
                                                      Shape::kJ, Element::kFloat64,
                                                      "positive work per joint"};
inline constexpr DatasetSpec kEnergyNegativeWorkJoint{"/energy/negative_work_per_joint", "J",
                                                      Shape::kJ, Element::kFloat64,
                                                      "negative work per joint"};
inline constexpr DatasetSpec kCostOfTransport{"/energy/cost_of_transport", "1", Shape::kScalar,
                                              Element::kFloat64, "cost of transport E/(m g d)"};
inline constexpr DatasetSpec kEnergyDistance{"/energy/distance", "m", Shape::kScalar,
                                             Element::kFloat64, "distance travelled by the trunk"};
/// 0 optimal, 1 relaxed (slack used), 2 failed (CF flags kSolverStatusFlags).
inline constexpr DatasetSpec kSolverStatus{"/solver/status", "", Shape::kT, Element::kInt8,
                                           "allocation solver status of the sample"};
inline constexpr DatasetSpec kSolverIterations{"/solver/iterations", "1", Shape::kT,
                                               Element::kFloat64, "allocation solver iterations"};
/// Σ τ² of the sample's joint torques (with actuators: of the drive torques, whatever
/// allocation.objective minimised).
inline constexpr DatasetSpec kSolverObjective{"/solver/objective", "N^2 m^2", Shape::kT,
                                              Element::kFloat64, "allocation objective sum tau^2"};
inline constexpr DatasetSpec kSolverSeconds{"/solver/seconds", "s", Shape::kT, Element::kFloat64,
                                            "allocation solve time"};
/// One message per relaxed or failed sample.
inline constexpr DatasetSpec kSolverMessages{"/solver/messages", "", Shape::kTextList,
                                             Element::kString,
                                             "solver message of each relaxed or failed sample"};

// ---- the drive train: written only for a scene with actuators ----
// (docs/theory/drive-train.md; the resolved actuators of every joint are in /meta
// config_yaml under actuators.joints, keyed by /model/joint_names.)
/// τ_drive = τ + J_a q̈ + τ_c sgn(q̇) + b q̇: the torque the joint's drive gives.
inline constexpr DatasetSpec kDriveTorque{"/joints/drive_torque", "N m", Shape::kTJoint,
                                          Element::kFloat64, "drive torque"};
/// The bound τ_drive ≤ it at the sample: a DC motor's bound on |τ_drive|, min(peak_torque,
/// G k_t η (V − G k_t |q̇|) / R); a three-phase motor's upper bound from its voltage range and
/// peak rating; or the allocation's torque limit for a joint with neither.
inline constexpr DatasetSpec kDriveTorqueLimit{"/joints/drive_torque_limit", "N m", Shape::kTJoint,
                                               Element::kFloat64, "bound on the drive torque"};
/// The bound τ_drive ≥ it at the sample: −/joints/drive_torque_limit but for a three-phase
/// motor at speed, whose voltage range is not symmetric (docs/theory/drive-train.md#voltage-limit).
inline constexpr DatasetSpec kDriveTorqueLowerLimit{"/joints/drive_torque_lower_limit", "N m",
                                                    Shape::kTJoint, Element::kFloat64,
                                                    "lower bound on the drive torque"};
/// I = τ_drive / (G k_t η) when driving (τ_drive q̇ ≥ 0), τ_drive η / (G k_t) when back-driven,
/// in the convention of the actuator's `winding` (a three-phase motor's q-axis current).
inline constexpr DatasetSpec kMotorCurrent{"/joints/current", "A", Shape::kTJoint,
                                           Element::kFloat64, "motor current"};
/// RMS of τ_drive over the run (trapezoid rule of τ_drive² over /time).
inline constexpr DatasetSpec kDriveTorqueRms{"/joints/drive_torque_rms", "N m", Shape::kJ,
                                             Element::kFloat64, "RMS drive torque over the run"};
/// The largest RMS of τ_drive over any window of the joint's thermal_window in the run (the
/// run's RMS when the window is longer): against the continuous rating.
inline constexpr DatasetSpec kDriveTorqueWindowRms{
    "/joints/drive_torque_window_rms", "N m", Shape::kJ, Element::kFloat64,
    "largest RMS drive torque over a thermal window"};
/// P⁺: P = c R I² + G k_t q̇ I where P ≥ 0, r P where P < 0 (r: regeneration; c 3/2 for an
/// amplitude-invariant three-phase winding, else 1).
inline constexpr DatasetSpec kElectricalPower{"/power/electrical", "W", Shape::kTJoint,
                                              Element::kFloat64, "electrical power drawn"};
inline constexpr DatasetSpec kElectricalTotalPower{
    "/power/electrical_total", "W", Shape::kT, Element::kFloat64, "total electrical power drawn"};
/// Trapezoid rule over /time of /power/electrical_total, as /energy/total.
inline constexpr DatasetSpec kEnergyElectrical{"/energy/electrical", "J", Shape::kScalar,
                                               Element::kFloat64, "electrical energy drawn"};
inline constexpr DatasetSpec kEnergyElectricalJoint{"/energy/electrical_per_joint", "J", Shape::kJ,
                                                    Element::kFloat64,
                                                    "electrical energy drawn per joint"};
/// Trapezoid rule of Σ c R I².
inline constexpr DatasetSpec kEnergyCopperLoss{"/energy/copper_loss", "J", Shape::kScalar,
                                               Element::kFloat64, "copper loss R I^2"};
/// Trapezoid rule of Σ (τ_c |q̇| + b q̇²).
inline constexpr DatasetSpec kEnergyFrictionLoss{"/energy/friction_loss", "J", Shape::kScalar,
                                                 Element::kFloat64, "joint friction loss"};
/// Trapezoid rule of Σ r max(0, −P): what regeneration returns to the supply.
inline constexpr DatasetSpec kEnergyRegenerated{"/energy/regenerated", "J", Shape::kScalar,
                                                Element::kFloat64, "energy regenerated"};
inline constexpr DatasetSpec kCostOfTransportElectrical{
    "/energy/cost_of_transport_electrical", "1", Shape::kScalar, Element::kFloat64,
    "electrical cost of transport E_el/(m g d)"};

// ---- the thermal model: written only when some joint's actuator has one ----
// (docs/theory/drive-train.md#thermal-model; NaN for a joint without one.)
/// T_w, the winding node of the two-node model under the copper loss c R I² (linear between
/// samples), both nodes at the ambient at the first sample.
inline constexpr DatasetSpec kWindingTemperature{"/thermal/winding_temperature", "degC",
                                                 Shape::kTJoint, Element::kFloat64,
                                                 "winding temperature"};
inline constexpr DatasetSpec kHousingTemperature{"/thermal/housing_temperature", "degC",
                                                 Shape::kTJoint, Element::kFloat64,
                                                 "housing temperature"};
/// The largest T_w over the run, between samples too.
inline constexpr DatasetSpec kPeakWindingTemperature{"/thermal/peak_winding_temperature", "degC",
                                                     Shape::kJ, Element::kFloat64,
                                                     "peak winding temperature"};
/// The first /time at which T_w reaches the joint's winding_temperature_limit; +inf when it
/// never does (then /thermal/limit_reached is 0).
inline constexpr DatasetSpec kTimeToWindingLimit{"/thermal/time_to_limit", "s", Shape::kJ,
                                                 Element::kFloat64,
                                                 "time the winding reaches its limit"};
/// 1 where T_w reaches the limit in the run, 0 elsewhere (CF flags kWindingLimitFlags).
inline constexpr DatasetSpec kWindingLimitReached{"/thermal/limit_reached", "", Shape::kJ,
                                                  Element::kInt8,
                                                  "winding reaches its temperature limit"};
/// The largest of /thermal/peak_winding_temperature.
inline constexpr DatasetSpec kThermalPeak{"/thermal/peak", "degC", Shape::kScalar,
                                          Element::kFloat64,
                                          "peak winding temperature over the joints"};
/// The least of /thermal/time_to_limit (+inf: no joint reaches its limit).
inline constexpr DatasetSpec kThermalFirstLimit{"/thermal/first_time_to_limit", "s", Shape::kScalar,
                                                Element::kFloat64,
                                                "first time a winding reaches its limit"};

// ---- coordinate variables: one per dimension (dimension_names), at the root ----
// Group coordinates, in every file kind: each group G below the root (of the file, or of a
// kept run /runs/{id}) whose datasets use dimension D holds the coordinate variable G/D, a
// copy of the root's /D (element type, shape, values, `units`, `long_name`), an HDF5
// dimension scale named D to which G's datasets are attached; so a group opened alone
// (xarray.open_dataset(file, group=G), netCDF-4) has named, valued coordinates. They are
// derived, not listed in the tables of this header: a reader takes an undeclared dataset
// G/D that is a dimension scale (attribute CLASS "DIMENSION_SCALE") for one and may skip it.
// A dataset declared at G/D on the dimension D alone (an envelope's /axes/tread_depth) is
// that coordinate itself.
inline constexpr DatasetSpec kLegCoordinate{"/leg", "", Shape::kLegNames, Element::kString,
                                            "leg name"};
inline constexpr DatasetSpec kJointCoordinate{"/joint", "", Shape::kJointNames, Element::kString,
                                              "joint name, leg-major"};
inline constexpr DatasetSpec kXyzCoordinate{"/xyz", "", Shape::kXyz, Element::kString,
                                            "Cartesian component, world frame G0"};
inline constexpr DatasetSpec kWxyzCoordinate{"/wxyz", "", Shape::kWxyz, Element::kString,
                                             "quaternion component, scalar first"};
/// Index coordinates 0..n−1 of the dimensions without labels: /impact and /message in the
/// result layout, the others created by io/labels.hpp when a dataset uses the dimension.
inline constexpr DatasetSpec kImpactCoordinate{"/impact", "1", Shape::kN, Element::kInt32,
                                               "touchdown index"};
inline constexpr DatasetSpec kMessageCoordinate{"/message", "1", Shape::kTextList, Element::kInt32,
                                                "solver message index"};
inline constexpr DatasetSpec kCycleCoordinate{"/gait_cycle", "1", Shape::kCycles, Element::kInt32,
                                              "gait cycle index"};
inline constexpr DatasetSpec kTerrainPointCoordinate{
    "/terrain_point", "1", Shape::kTerrainPoints, Element::kInt32, "terrain profile vertex index"};
inline constexpr DatasetSpec kMapXCoordinate{"/map_x", "1", Shape::kMapColumns, Element::kInt32,
                                             "height map column index"};
inline constexpr DatasetSpec kMapYCoordinate{"/map_y", "1", Shape::kMapRows, Element::kInt32,
                                             "height map row index"};

// ---- CF flags on the datasets of codes ----
inline constexpr FlagSpec kContactPhaseFlags{"/contacts/phase", "swing impact support"};
inline constexpr FlagSpec kSolverStatusFlags{"/solver/status", "optimal relaxed failed"};
inline constexpr FlagSpec kSampleKindFlags{"/sample_kind", "ordinary left_limit"};
inline constexpr FlagSpec kContactSlipFlags{"/contacts/slip", "holds slips"};
inline constexpr FlagSpec kWindingLimitFlags{"/thermal/limit_reached", "below reached"};

/// Every dataset present in every result file.
inline constexpr std::array kModelDatasets{kModelUrdf, kModelJointNames, kModelLegNames,
                                           kModelLegJointCounts, kModelTotalMass};
// clang-format off
inline constexpr std::array kKinematicDatasets{
    kTime, kBasePosition, kBaseOrientation, kBaseLinearVelocity, kBaseAngularVelocity,
    kBaseLinearAcceleration, kBaseAngularAcceleration, kJointPosition, kJointVelocity,
    kJointAcceleration, kFeetPosition, kFeetVelocity, kComPosition, kContactPhase, kSampleKind,
    kGaitCycleStart, kTerrainY, kTerrainZ};
// clang-format on
/// The coordinate variables of every result file (the index ones when their dimension is
/// used: /impact with the dynamics, /message with /solver/messages).
inline constexpr std::array kResultCoordinates{kLegCoordinate, kJointCoordinate, kXyzCoordinate,
                                               kWxyzCoordinate};
inline constexpr std::array kResultIndexCoordinates{kImpactCoordinate, kMessageCoordinate,
                                                    kCycleCoordinate, kTerrainPointCoordinate};
/// Datasets present when the robot was read from a URDF.
inline constexpr std::array kUrdfRobotDatasets{kModelLegMapping};
/// Datasets present on a height map (terrain.type height_map), with their index coordinates.
inline constexpr std::array kHeightMapDatasets{kTerrainMapX, kTerrainMapY, kTerrainMapZ,
                                               kMapXCoordinate, kMapYCoordinate};
/// Datasets present when some foot is a sphere (robot.foot_radius, or a URDF's sphere foot).
inline constexpr std::array kSphereFootDatasets{kFeetCenter};
/// Datasets present when the dynamic stages ran.
// clang-format off
inline constexpr std::array kDynamicsDatasets{
    kJointTorque, kContactForce, kContactPenetration, kContactUtilizedFriction, kContactSlip, kImpactLeg, kImpactStart, kImpactDuration,
    kImpactPeakForce, kImpactImpulse, kImpactEffectiveMass, kImpactApproachSpeed, kJointPower,
    kTotalPower, kEnergyTotal, kEnergyJoint, kEnergyCycle, kEnergyPositiveWork, kEnergyNegativeWork,
    kEnergyPositiveWorkJoint, kEnergyNegativeWorkJoint, kCostOfTransport, kEnergyDistance,
    kSolverStatus, kSolverIterations, kSolverObjective, kSolverSeconds, kSolverMessages};
/// Datasets present with the dynamics unless output.required_friction is false.
inline constexpr std::array kRequiredFrictionDatasets{kRequiredFriction, kRequiredFrictionLeg};
/// Datasets present when the scene had actuators (besides the dynamics).
inline constexpr std::array kDriveTrainDatasets{
    kDriveTorque, kDriveTorqueLimit, kDriveTorqueLowerLimit, kMotorCurrent, kDriveTorqueRms,
    kDriveTorqueWindowRms, kElectricalPower, kElectricalTotalPower, kEnergyElectrical,
    kEnergyElectricalJoint, kEnergyCopperLoss, kEnergyFrictionLoss, kEnergyRegenerated,
    kCostOfTransportElectrical};
/// Datasets present when some joint's actuator has a thermal model (besides the drive train's).
inline constexpr std::array kThermalDatasets{
    kWindingTemperature, kHousingTemperature, kPeakWindingTemperature, kTimeToWindingLimit,
    kWindingLimitReached, kThermalPeak, kThermalFirstLimit};
// clang-format on

}  // namespace hexdyn::schema

// The sweep contract, in its own header (parsed as part of this one).
#include "hexdyn/io/schema_sweep.hpp"  // IWYU pragma: export
// The envelope contract, in its own header (parsed as part of this one).
#include "hexdyn/io/schema_envelope.hpp"  // IWYU pragma: export
// The replay contract, in its own header (parsed as part of this one).
#include "hexdyn/io/schema_replay.hpp"  // IWYU pragma: export
// The robustness contract and every file kind's CF flags, in its own header (parsed as part
// of this one).
#include "hexdyn/io/schema_robustness.hpp"  // IWYU pragma: export
