#pragma once
/// \file result_schema.hpp
/// The `hexdyn-result/1` HDF5 contract (DESIGN.md §4) in one place: schema name and
/// version, and for every dataset its path, its shape and its `units` attribute.
/// Writers (output.cpp) and readers (tests, analysis/hexdyn_results.py, which mirrors
/// this table) use these names; a change of layout is a new schema version.
///
/// Shapes: T output samples, 6 legs, 18 joints, n touchdowns, m solver messages.
/// (T,6,3) datasets are leg-major (index [t][leg][axis]); all vectors are in the world
/// frame G0 unless the name says otherwise. Units strings: "1" marks dimensionless
/// numbers (quaternions, status codes, counts, ratios) and text.
#include <array>
#include <cstdint>

namespace hexdyn::schema {

inline constexpr const char* kResultSchema = "hexdyn-result/1";  ///< /meta attr `schema`
inline constexpr std::int64_t kResultSchemaVersion = 1;          ///< /meta attr `schema_version`
inline constexpr const char* kSweepSchema = "hexdyn-sweep/1";    ///< sweep files

/// Shape of a dataset in terms of the run's sizes.
enum class Shape {
  kScalar,      ///< ()
  kText,        ///< () variable-length UTF-8 string
  kTextList,    ///< (m) variable-length UTF-8 strings, m may be 0
  kJointNames,  ///< (18) strings
  kLegNames,    ///< (6) strings
  kJ,           ///< (18)
  kT,           ///< (T)
  kT3,          ///< (T,3)
  kT4,          ///< (T,4)
  kT6,          ///< (T,6)
  kT18,         ///< (T,18)
  kT6x3,        ///< (T,6,3)
  kN,           ///< (n), one entry per touchdown, n may be 0
};

/// Element type stored in the file.
enum class Element { kFloat64, kInt8, kInt32, kString };

/// One dataset of the contract.
struct DatasetSpec {
  const char* path;   ///< absolute HDF5 path
  const char* units;  ///< value of the mandatory `units` attribute
  Shape shape = Shape::kScalar;
  Element element = Element::kFloat64;
};

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
inline constexpr const char* kUnitsAttribute = "units";        ///< on every dataset

// ---- /model ----
inline constexpr DatasetSpec kModelUrdf{"/model/urdf", "1", Shape::kText, Element::kString};
inline constexpr DatasetSpec kModelJointNames{"/model/joint_names", "1", Shape::kJointNames,
                                              Element::kString};
inline constexpr DatasetSpec kModelLegNames{"/model/leg_names", "1", Shape::kLegNames,
                                            Element::kString};
inline constexpr DatasetSpec kModelTotalMass{"/model/total_mass", "kg", Shape::kScalar};

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
/// Datasets present when the dynamic stages ran.
inline constexpr std::array kDynamicsDatasets{
    kJointTorque,         kContactForce,        kContactPenetration, kImpactLeg,
    kImpactStart,         kImpactDuration,      kImpactPeakForce,    kImpactImpulse,
    kImpactEffectiveMass, kImpactApproachSpeed, kJointPower,         kTotalPower,
    kEnergyTotal,         kEnergyJoint,         kCostOfTransport,    kEnergyDistance,
    kSolverStatus,        kSolverIterations,    kSolverObjective,    kSolverSeconds,
    kSolverMessages};

}  // namespace hexdyn::schema
