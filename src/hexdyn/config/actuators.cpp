#include "hexdyn/config/actuators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/config/servo_table.hpp"
#include "hexdyn/core/value_bounds.hpp"

namespace hexdyn::scene_keys {
namespace {

constexpr double kMaxGearRatio = 1e5;
constexpr double kMaxTorqueConstant_NmpA = 100.0;
constexpr double kMaxResistance_ohm = 1e4;
constexpr double kMaxVoltage_V = 1e4;
constexpr double kMaxRotorInertia_kgm2 = 1.0;
constexpr double kMaxArmature_kgm2 = 1e4;
constexpr double kMaxThermalWindow_s = 1e6;

constexpr double kNotGiven = std::numeric_limits<double>::quiet_NaN();

}  // namespace

const std::vector<ActuatorKey>& actuator_keys() {
  using P = ActuatorParams;
  static const std::vector<ActuatorKey> keys = {
      {"model",
       {},
       "",
       "none",
       "the servo whose values the entry starts from; an unknown name gets the list of the "
       "known ones"},
      {"gear_ratio", positive(kMaxGearRatio), "1", "required", "G, motor turns per joint turn",
       &P::gear_ratio},
      {"torque_constant", positive(kMaxTorqueConstant_NmpA), "N m/A", "required", "k_t, motor side",
       &P::torque_constant_NmpA},
      {"resistance", positive(kMaxResistance_ohm), "Ω", "required", "R, winding and driver",
       &P::resistance_ohm},
      {"rotor_inertia", nonnegative(kMaxRotorInertia_kgm2), "kg m^2", "`0`",
       "J_m, motor side; the joint's armature is G² J_m"},
      {"armature", nonnegative(kMaxArmature_kgm2), "kg m^2", "`0`",
       "J_a, joint side; an entry gives `rotor_inertia` or `armature`, not both"},
      {"coulomb_friction", nonnegative(kMaxJointFriction), "N m", "URDF `friction`, else `0`",
       "τ_c, joint side", &P::coulomb_friction_Nm},
      {"viscous_friction", nonnegative(kMaxJointFriction), "N m s/rad", "URDF `damping`, else `0`",
       "b, joint side", &P::viscous_friction_Nmsprad},
      {"gear_efficiency", Range{0.0, 1.0, true, false}, "1", "`1`", "η", &P::gear_efficiency},
      {"voltage", positive(kMaxVoltage_V), "V", "none", "supply; none: no voltage bound",
       &P::voltage_V},
      {"peak_torque", positive(kMaxJointEffort_Nm), "N m", "none",
       "bound on \\|τ_drive\\|; none: no peak bound", &P::peak_torque_Nm},
      {"continuous_torque", positive(kMaxJointEffort_Nm), "N m", "none",
       "thermal rating, against the windowed RMS drive torque", &P::continuous_torque_Nm},
      {"regeneration", closed(0.0, 1.0), "1", "`0`",
       "share of negative electrical power returned to the supply", &P::regeneration},
      {"thermal_window", positive(kMaxThermalWindow_s), "s", "the whole run",
       "window of the RMS against `continuous_torque`", &P::thermal_window_s},
  };
  return keys;
}

namespace {

/// A numeric key of an actuator entry that fills a field: its row of actuator_keys().
struct Field {
  const char* key;
  Range range;
  double ActuatorParams::*member;
};

/// The rows of actuator_keys() with a field, in its order (the order of Entry::values).
const std::array<Field, 11>& fields() {
  static const std::array<Field, 11> f = [] {
    std::array<Field, 11> out{};
    std::size_t i = 0;
    for (const ActuatorKey& k : actuator_keys())
      if (k.member) out.at(i++) = {k.key.data(), k.range, k.member};
    if (i != out.size()) throw std::logic_error("actuator_keys: expected 11 fields");
    return out;
  }();
  return f;
}

/// The range of the key `key` of actuator_keys().
Range key_range(std::string_view key) {
  for (const ActuatorKey& k : actuator_keys())
    if (k.key == key) return k.range;
  throw std::logic_error("actuator_keys: no key " + std::string(key));
}

constexpr int kGearRatio = 0, kTorqueConstant = 1, kResistance = 2;  // the required fields
/// fields()[0, kServoFields) are the servo's own (ServoSpec); regeneration and thermal_window,
/// of its driver and its use, are not.
constexpr int kServoFields = 9;

/// The rotor's inertia as an entry gives it: motor side (rotor_inertia, J_m) or joint side
/// (armature, J_a = G² J_m with the joint's final G).
struct Inertia {
  bool motor_side = false;
  double value_kgm2 = 0.0;
};

/// One entry (default, a joint type or a joint) as read: its model's values, then its own.
struct Entry {
  std::string model;
  std::array<std::optional<double>, 11> values;
  std::optional<Inertia> inertia;
};

/// The table's values of `servo` in an entry (NaN: not given).
void apply_servo(const ServoSpec& servo, Entry& e) {
  const double v[11] = {servo.gear_ratio,
                        servo.torque_constant_NmpA,
                        servo.resistance_ohm,
                        servo.coulomb_friction_Nm,
                        servo.viscous_friction_Nmsprad,
                        servo.gear_efficiency,
                        servo.voltage_V,
                        servo.peak_torque_Nm,
                        servo.continuous_torque_Nm,
                        kNotGiven,
                        kNotGiven};
  for (int i = 0; i < 11; ++i)
    if (!std::isnan(v[i])) e.values[i] = v[i];
  if (!std::isnan(servo.armature_kgm2)) e.inertia = Inertia{false, servo.armature_kgm2};
}

std::vector<std::string> servo_names() {
  std::vector<std::string> names;
  for (const ServoSpec& s : servo_table()) names.emplace_back(s.name);
  return names;
}

/// The entry at `path` (absent: an empty entry).
Entry read_entry(Reader& r, const std::string& path) {
  Entry e;
  // Absent: asked for all the same, so that an unknown key beside it lists it as allowed
  // (a present entry is not asked for as a whole: its own keys are, one by one).
  if (!r.given(path)) return (void)r.has(path), e;
  const YAML::Node node = r.peek(path);
  if (!node.IsMap())
    r.fail_value(path, node,
                 "a mapping of actuator keys (model, gear_ratio, torque_constant, resistance, …)");
  if (r.has(path + ".model")) {
    e.model = r.choice(path + ".model", servo_names());
    apply_servo(*find_servo(e.model), e);
  }
  for (std::size_t i = 0; i < fields().size(); ++i)
    if (r.has(path + "." + fields()[i].key))
      e.values[i] = r.number(path + "." + fields()[i].key, fields()[i].range);
  const bool rotor = r.has(path + ".rotor_inertia"), armature = r.has(path + ".armature");
  if (rotor && armature)
    r.fail(path,
           "got both rotor_inertia and armature, expected one of them (armature = "
           "gear_ratio² × rotor_inertia)");
  if (rotor)
    e.inertia = Inertia{true, r.number(path + ".rotor_inertia", key_range("rotor_inertia"))};
  if (armature) e.inertia = Inertia{false, r.number(path + ".armature", key_range("armature"))};
  return e;
}

/// The joint names the `joints` entry may use, for messages.
std::string joint_list(const JointFacts& joints) {
  std::string list;
  for (int k = 0; k < joints.count; ++k) list += (list.empty() ? "" : ", ") + joints.names[k];
  return list;
}

/// By place in a leg of three joints (docs/user/configuration.md#actuators).
constexpr int kTypedLegJoints = 3;
constexpr const char* kTypes[kTypedLegJoints] = {"coxa", "femur", "tibia"};

/// "j1" … "j6": by place from the hip, in a leg of any length.
std::string position_key(int place) { return "j" + std::to_string(place + 1); }

/// The entries `actuators` may hold for this robot: default, joints, the types, and j1 … jm
/// for its longest leg's m joints. A key not among them is refused before any value is read,
/// so that a misspelt entry is named as such.
void check_entry_names(Reader& r, const YAML::Node& section, const JointFacts& joints) {
  int places = 0;
  for (int k = 0; k < joints.count; ++k) places = std::max(places, joints.place[k] + 1);
  std::vector<std::string> allowed = {"coxa", "default", "femur", "joints", "tibia"};
  for (int p = 0; p < places; ++p) allowed.push_back(position_key(p));
  for (const auto& kv : section) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      r.fail_unknown("actuators." + key, allowed);
  }
  for (int j = 0; j < kTypedLegJoints; ++j)
    if (r.given(std::string("actuators.") + kTypes[j]) && r.given("actuators." + position_key(j)))
      r.fail("actuators." + position_key(j), std::string("got both actuators.") + kTypes[j] +
                                                 " and actuators." + position_key(j) +
                                                 ", expected one of them (a leg of three joints' " +
                                                 position_key(j) + " is its " + kTypes[j] + ")");
}

/// actuators.joints: one entry per joint named, by flat joint index.
JointArray<Entry> read_joint_entries(Reader& r, const JointFacts& joints) {
  JointArray<Entry> out;
  if (!r.given("actuators.joints")) return (void)r.has("actuators.joints"), out;
  const YAML::Node node = r.peek("actuators.joints");
  if (!node.IsMap())
    r.fail_value("actuators.joints", node, "a mapping of joint names to actuator entries");
  for (const auto& kv : node) {
    const std::string name = kv.first.as<std::string>();
    int k = 0;
    while (k < joints.count && joints.names[k] != name) ++k;
    if (k == joints.count)
      r.fail("actuators.joints." + name,
             "unknown joint, expected one of the robot's joints: " + joint_list(joints));
    out[k] = read_entry(r, "actuators.joints." + name);
  }
  return out;
}

/// Writes joint k's resolved values as the whole of actuators.joints.NAME (the joint side
/// armature in place of a rotor_inertia the file gave there).
void record_joint(Reader& r, const std::string& name, const ActuatorParams& a) {
  YAML::Node values(YAML::NodeType::Map);
  if (!a.model.empty()) values["model"] = a.model;
  for (const Field& f : fields())
    if (std::isfinite(a.*f.member)) values[f.key] = a.*f.member;
  values["armature"] = a.armature_kgm2;
  values.SetStyle(YAML::EmitterStyle::Flow);
  r.record("actuators.joints." + name, values);
}

}  // namespace

DriveTrainParams read_actuators(Reader& r, const JointFacts& joints) {
  DriveTrainParams out;
  if (!r.given("actuators")) return out;
  out.present = true;
  const YAML::Node section = r.peek("actuators");
  if (!section.IsMap())
    r.fail_value("actuators", section,
                 "a mapping with default, coxa, femur, tibia, j1 … j6 and joints entries");
  check_entry_names(r, section, joints);
  const Entry all = read_entry(r, "actuators.default");
  std::array<Entry, kTypedLegJoints> by_type;
  for (int j = 0; j < kTypedLegJoints; ++j)
    by_type[j] = read_entry(r, std::string("actuators.") + kTypes[j]);
  LegJointArray<Entry> by_place;
  for (int p = 0; p < kMaxLegJoints; ++p)
    if (r.given("actuators." + position_key(p)))
      by_place[p] = read_entry(r, "actuators." + position_key(p));
  const Entry untyped;  // a joint of a leg of other than three joints: no type entry
  const JointArray<Entry> by_joint = read_joint_entries(r, joints);
  out.joints.count = joints.count;
  for (int k = 0; k < joints.count; ++k) {
    const bool typed = joints.leg_joints[k] == kTypedLegJoints;
    const Entry& type_entry = typed ? by_type[joints.place[k]] : untyped;
    ActuatorParams& a = out.joints[k];
    // The joint without any entry: the built-in defaults and the URDF's friction.
    ActuatorParams base;
    base.viscous_friction_Nmsprad = joints.damping_Nmsprad[k];
    base.coulomb_friction_Nm = joints.friction_Nm[k];
    a = base;
    std::array<bool, 11> given{};
    Inertia inertia;
    // A type and its place are never both given (check_entry_names).
    const std::array<const Entry*, 4> chain{&all, &type_entry, &by_place[joints.place[k]],
                                            &by_joint[k]};
    for (const Entry* e : chain) {
      if (!e->model.empty()) {  // another servo: none of a less specific entry's servo values
        for (int i = 0; i < kServoFields; ++i) {
          a.*fields()[i].member = base.*fields()[i].member;
          given[i] = false;
        }
        inertia = Inertia{};
        a.model = e->model;
      }
      for (std::size_t i = 0; i < fields().size(); ++i)
        if (e->values[i]) {
          a.*fields()[i].member = *e->values[i];
          given[i] = true;
        }
      if (e->inertia) inertia = *e->inertia;
    }
    for (int i : {kGearRatio, kTorqueConstant, kResistance})
      if (!given[i])
        r.fail("actuators.joints." + joints.names[k] + "." + fields()[i].key,
               std::string("missing, expected it from actuators.default, ") +
                   (typed ? std::string("actuators.") + kTypes[joints.place[k]] + ", " : "") +
                   "actuators." + position_key(joints.place[k]) + ", actuators.joints." +
                   joints.names[k] + " or their model");
    a.armature_kgm2 =
        inertia.motor_side ? a.gear_ratio * a.gear_ratio * inertia.value_kgm2 : inertia.value_kgm2;
    record_joint(r, joints.names[k], a);
  }
  return out;
}

std::string objective_word(AllocationObjective objective) {
  return objective == AllocationObjective::kCopperLoss ? "copper_loss" : "torque_squared";
}

}  // namespace hexdyn::scene_keys
