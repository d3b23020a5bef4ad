#pragma once
/// \file actuators.hpp
/// Internal to config/: the scene's `actuators` section (docs/user/configuration.md#actuators,
/// docs/theory/drive-train.md) read into one resolved ActuatorParams per joint.
///
///     actuators:
///       default: {model: dynamixel_mx64}                  # every joint
///       femur: {gear_ratio: 200, torque_constant: 0.0081}  # by joint type: coxa, femur, tibia
///       joints: {L2_femur: {model: dynamixel_xm430_w350}}  # by name (/model/joint_names)
///
/// An entry's `model:` (config/servo_table.hpp) gives its values first, its own keys then
/// override them. A joint's values come, field by field, from the most specific entry that
/// gives them: joints.NAME over its type over default over the URDF's <dynamics damping
/// friction> (viscous and Coulomb friction) over the built-in defaults (ActuatorParams). An
/// entry that names a model replaces the servo: the servo's values a less specific entry gave
/// (all but regeneration and thermal_window) go back to the defaults before the model's and
/// the entry's own apply, so that one servo's armature never reaches another's joint.
/// gear_ratio (or gear_stages), torque_constant and resistance must be given for every joint;
/// the thermal model's four resistances and capacities all or none.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "hexdyn/config/scene_key_table.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn::scene_keys {

/// One key of an actuator entry, declared once: the reader checks it against this row, and
/// the table of docs/user/configuration.md#actuators is generated from the rows
/// (config/scene_key_docs.hpp).
struct ActuatorKey {
  std::string_view key;
  Range range{};          ///< a number's; `model`, `winding`, `gear_stages`: see allowed_text
  std::string_view unit;  ///< UDUNITS-2 ("" none, "1" dimensionless)
  std::string_view default_text;
  std::string_view meaning;
  /// The field (null: read by code: model, winding, gear stages, inertia).
  double ActuatorParams::*member = nullptr;
  /// A value of the motor itself: an entry naming another `model` resets it (false: of the
  /// driver, the environment or the use: regeneration, thermal_window, ambient_temperature).
  bool of_motor = true;
  std::string_view allowed_text = {};  ///< the docs' "allowed" cell of a key read by code
};

/// Every key of an actuator entry, in the docs' order.
const std::vector<ActuatorKey>& actuator_keys();

class Reader;

/// What the robot says about its joints, in flat joint order, the first `count` entries:
/// names (/model/joint_names), each joint's place in its leg (0 at the hip) and its leg's
/// joint count (the entries actuators.coxa, femur, tibia apply by place to legs of three
/// joints), and the URDF's <dynamics> values (0 for the robot of the YAML keys).
struct JointFacts {
  int count = 0;
  JointArray<std::string> names;
  JointArray<int> place{}, leg_joints{};
  JointArray<double> damping_Nmsprad{}, friction_Nm{};
};

/// Reads `actuators` (absent: present = false and nothing recorded) and records every
/// joint's resolved values under actuators.joints.NAME in the resolved tree. Throws
/// ConfigError "SOURCE: actuators.KEY: got VALUE, expected WHAT" for a bad value and
/// "SOURCE: actuators.joints.NAME.FIELD: missing, …" for a required value no entry gives.
DriveTrainParams read_actuators(Reader& r, const JointFacts& joints);

/// The words of allocation.objective.
std::string objective_word(AllocationObjective objective);

}  // namespace hexdyn::scene_keys
