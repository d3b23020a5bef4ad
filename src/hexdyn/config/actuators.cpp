#include "hexdyn/config/actuators.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
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
constexpr double kMaxVoltageUtilization = 1.0;
constexpr double kMaxThermalResistance_KpW = 1e4;
constexpr double kMaxThermalCapacity_JpK = 1e7;
constexpr double kMinTemperature_degC = -100.0;
constexpr double kMaxTemperature_degC = 1000.0;
constexpr double kMaxStageInertia_kgm2 = 1.0;
constexpr std::size_t kMaxGearStages = 8;

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
      {"gear_ratio", positive(kMaxGearRatio), "1", "required, or `gear_stages`",
       "G, motor turns per joint turn", &P::gear_ratio},
      {"torque_constant", positive(kMaxTorqueConstant_NmpA), "N m/A", "required",
       "k_t, motor side, per ampere of the `winding`'s current", &P::torque_constant_NmpA},
      {"resistance", positive(kMaxResistance_ohm), "Ω", "required",
       "R, winding and driver (per phase for a three-phase `winding`)", &P::resistance_ohm},
      {"rotor_inertia", nonnegative(kMaxRotorInertia_kgm2), "kg m^2", "`0`",
       "J_m, motor side; the joint's armature is G² J_m"},
      {"armature", nonnegative(kMaxArmature_kgm2), "kg m^2", "`0`",
       "J_a, joint side; an entry gives `rotor_inertia` or `armature`, not both"},
      {"coulomb_friction", nonnegative(kMaxJointFriction), "N m", "URDF `friction`, else `0`",
       "τ_c, joint side", &P::coulomb_friction_Nm},
      {"viscous_friction", nonnegative(kMaxJointFriction), "N m s/rad", "URDF `damping`, else `0`",
       "b, joint side", &P::viscous_friction_Nmsprad},
      {"gear_efficiency", Range{0.0, 1.0, true, false}, "1", "`1`", "η", &P::gear_efficiency},
      {"voltage", positive(kMaxVoltage_V), "V", "none",
       "supply (a three-phase motor's bus); none: no voltage bound", &P::voltage_V},
      {"peak_torque", positive(kMaxJointEffort_Nm), "N m", "none",
       "bound on \\|τ_drive\\|; none: no peak bound", &P::peak_torque_Nm},
      {"continuous_torque", positive(kMaxJointEffort_Nm), "N m", "none",
       "thermal rating, against the windowed RMS drive torque", &P::continuous_torque_Nm},
      {"regeneration", closed(0.0, 1.0), "1", "`0`",
       "share of negative electrical power returned to the supply", &P::regeneration, false},
      {"thermal_window", positive(kMaxThermalWindow_s), "s", "the whole run",
       "window of the RMS against `continuous_torque`", &P::thermal_window_s, false},
      {"winding",
       {},
       "",
       "`dc`",
       "the convention of k_t, R and the current: a DC motor, or a three-phase motor with "
       "k_t per ampere of q-axis current amplitude (copper loss 3/2 R I², R per phase) or of "
       "power-invariant q-axis current (R I²) "
       "([drive-train.md](docs/theory/drive-train.md#three-phase-motors))",
       nullptr,
       true,
       "`dc`, `three_phase_amplitude`, `three_phase_power`"},
      {"voltage_utilization", Range{0.0, kMaxVoltageUtilization, true, false}, "1", "`0.5`",
       "three-phase: the largest phase-voltage amplitude over `voltage` (0.5 sinusoidal PWM, "
       "0.577 space-vector PWM)",
       &P::voltage_utilization},
      {"gear_stages",
       {},
       "",
       "one stage of `gear_ratio`",
       "the gearbox's stages, motor to joint: `ratio`, and `inertia` turning at the stage's "
       "output (kg m², default 0); the gear ratio is the product of the ratios, and each "
       "inertia adds to the armature through the ratios after it; not with `gear_ratio`",
       nullptr,
       true,
       "a list of 1 to 8 `{ratio, inertia}`"},
      {"thermal_resistance_winding", positive(kMaxThermalResistance_KpW), "K/W", "none",
       "R_th of winding to housing; the thermal model needs this and the next three",
       &P::thermal_resistance_winding_KpW},
      {"thermal_capacity_winding", positive(kMaxThermalCapacity_JpK), "J/K", "none",
       "C_th of the winding", &P::thermal_capacity_winding_JpK},
      {"thermal_resistance_housing", positive(kMaxThermalResistance_KpW), "K/W", "none",
       "R_th of housing to ambient", &P::thermal_resistance_housing_KpW},
      {"thermal_capacity_housing", positive(kMaxThermalCapacity_JpK), "J/K", "none",
       "C_th of the housing", &P::thermal_capacity_housing_JpK},
      {"ambient_temperature", closed(kMinTemperature_degC, kMaxTemperature_degC), "degC", "`25`",
       "T_a, also both nodes' temperature at the start", &P::ambient_temperature_degC, false},
      {"winding_temperature_limit", closed(kMinTemperature_degC, kMaxTemperature_degC), "degC",
       "none", "the winding's rated temperature, against which the time to the limit is found",
       &P::winding_temperature_limit_degC},
  };
  return keys;
}

namespace {

/// A numeric key of an actuator entry that fills a field: its row of actuator_keys().
struct Field {
  const char* key;
  Range range;
  double ActuatorParams::*member;
  bool of_motor;
};

/// The rows of actuator_keys() with a field, in its order (the order of Entry::values).
const std::vector<Field>& fields() {
  static const std::vector<Field> f = [] {
    std::vector<Field> out;
    for (const ActuatorKey& k : actuator_keys())
      if (k.member) out.push_back({k.key.data(), k.range, k.member, k.of_motor});
    return out;
  }();
  return f;
}

/// The index of `member` in fields().
int field_index(double ActuatorParams::*member) {
  for (std::size_t i = 0; i < fields().size(); ++i)
    if (fields()[i].member == member) return static_cast<int>(i);
  throw std::logic_error("actuator_keys: no such field");
}

/// The range of the key `key` of actuator_keys().
Range key_range(std::string_view key) {
  for (const ActuatorKey& k : actuator_keys())
    if (k.key == key) return k.range;
  throw std::logic_error("actuator_keys: no key " + std::string(key));
}

/// The rotor's inertia as an entry gives it: motor side (rotor_inertia, J_m) or joint side
/// (armature, J_a = G² J_m with the joint's final G).
struct Inertia {
  bool motor_side = false;
  double value_kgm2 = 0.0;
};

using Stages = std::vector<std::array<double, 2>>;

/// One entry (default, a joint type or a joint) as read: its model's values, then its own.
struct Entry {
  std::string model;
  std::vector<std::optional<double>> values = std::vector<std::optional<double>>(fields().size());
  std::optional<Inertia> inertia;
  std::optional<Winding> winding;
  std::optional<Stages> stages;  ///< with values[gear_ratio] their product
};

/// The table's values of `servo` in an entry (NaN: not given).
void apply_servo(const ServoSpec& servo, Entry& e) {
  using P = ActuatorParams;
  const std::pair<double P::*, double> v[] = {
      {&P::gear_ratio, servo.gear_ratio},
      {&P::torque_constant_NmpA, servo.torque_constant_NmpA},
      {&P::resistance_ohm, servo.resistance_ohm},
      {&P::coulomb_friction_Nm, servo.coulomb_friction_Nm},
      {&P::viscous_friction_Nmsprad, servo.viscous_friction_Nmsprad},
      {&P::gear_efficiency, servo.gear_efficiency},
      {&P::voltage_V, servo.voltage_V},
      {&P::peak_torque_Nm, servo.peak_torque_Nm},
      {&P::continuous_torque_Nm, servo.continuous_torque_Nm},
      {&P::voltage_utilization, servo.voltage_utilization},
      {&P::thermal_resistance_winding_KpW, servo.thermal_resistance_winding_KpW},
      {&P::thermal_capacity_winding_JpK, servo.thermal_capacity_winding_JpK},
      {&P::thermal_resistance_housing_KpW, servo.thermal_resistance_housing_KpW},
      {&P::thermal_capacity_housing_JpK, servo.thermal_capacity_housing_JpK},
      {&P::winding_temperature_limit_degC, servo.winding_temperature_limit_degC}};
  for (const auto& [member, value] : v)
    if (!std::isnan(value)) e.values[field_index(member)] = value;
  if (!std::isnan(servo.armature_kgm2)) e.inertia = Inertia{false, servo.armature_kgm2};
  e.winding = servo.winding;
}

std::vector<std::string> servo_names() {
  std::vector<std::string> names;
  for (const ServoSpec& s : servo_table()) names.emplace_back(s.name);
  return names;
}

constexpr const char* kWindingWords[] = {"dc", "three_phase_amplitude", "three_phase_power"};

const char* winding_word(Winding w) { return kWindingWords[static_cast<int>(w)]; }

/// The entry's `gear_stages`: a list of 1 to kMaxGearStages maps {ratio, inertia}.
Stages read_stages(Reader& r, const std::string& path) {
  const YAML::Node node = r.node(path);
  const std::string expected = "a list of 1 to " + std::to_string(kMaxGearStages) +
                               " stages {ratio: (0, 1e5], inertia: [0, 1] kg m^2}";
  if (!node.IsSequence() || node.size() == 0 || node.size() > kMaxGearStages)
    r.fail_value(path, node, expected);
  Stages out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string at = path + "[" + std::to_string(i) + "]";
    const YAML::Node stage = node[i];
    if (!stage.IsMap()) r.fail_value(at, stage, "a map {ratio, inertia}");
    for (const auto& kv : stage) {
      const std::string key = kv.first.as<std::string>();
      if (key != "ratio" && key != "inertia")
        r.fail(at + "." + key, "unknown key, expected ratio or inertia");
    }
    const auto number = [&](const char* key, Range range, double def) {
      if (!stage[key]) return def;
      double v = 0.0;
      const YAML::Node n = stage[key];
      if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v) ||
          !range.contains(v))
        r.fail_value(at + "." + key, n, range.describe());
      return v;
    };
    if (!stage["ratio"]) r.fail(at + ".ratio", "missing, expected the stage's ratio in (0, 1e5]");
    out.push_back({number("ratio", key_range("gear_ratio"), 1.0),
                   number("inertia", nonnegative(kMaxStageInertia_kgm2), 0.0)});
  }
  r.record(path, node);  // as given (each joint's record holds the product and the armature)
  return out;
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
  if (r.has(path + ".winding")) {
    const std::string w =
        r.choice(path + ".winding", {std::begin(kWindingWords), std::end(kWindingWords)});
    for (int i = 0; i < 3; ++i)
      if (w == kWindingWords[i]) e.winding = static_cast<Winding>(i);
  }
  if (r.has(path + ".gear_stages")) {
    if (r.given(path + ".gear_ratio"))
      r.fail(path,
             "got both gear_ratio and gear_stages, expected one of them (the gear ratio is "
             "the product of the stages' ratios)");
    e.stages = read_stages(r, path + ".gear_stages");
    double G = 1.0;
    for (const auto& stage : *e.stages) G *= stage[0];
    e.values[field_index(&ActuatorParams::gear_ratio)] = G;
  }
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
/// armature in place of a rotor_inertia the file gave there, the gear stages' inertia
/// included, and their product as gear_ratio in place of gear_stages). The three-phase and
/// thermal keys only where they apply, so that a DC scene's record is as before.
void record_joint(Reader& r, const std::string& name, const ActuatorParams& a) {
  YAML::Node values(YAML::NodeType::Map);
  if (!a.model.empty()) values["model"] = a.model;
  const bool three_phase = a.winding != Winding::kDc, thermal = thermal_params(a).present;
  for (const Field& f : fields()) {
    const std::string_view key = f.key;
    if (key == "voltage_utilization" && !three_phase) continue;
    if (key == "ambient_temperature" && !thermal) continue;
    if (std::isfinite(a.*f.member)) values[f.key] = a.*f.member;
  }
  if (three_phase) values["winding"] = winding_word(a.winding);
  values["armature"] = a.armature_kgm2;
  values.SetStyle(YAML::EmitterStyle::Flow);
  r.record("actuators.joints." + name, values);
}

/// The joint-side inertia of gear stages (motor to joint): each stage's inertia times the
/// square of the ratios after it.
double stage_armature(const Stages& stages) {
  double sum = 0.0, after = 1.0;
  for (auto it = stages.rbegin(); it != stages.rend(); ++it) {
    sum += after * after * (*it)[1];
    after *= (*it)[0];
  }
  return sum;
}

/// The thermal model's four values: all or none (`at`: "actuators.joints.NAME.").
void check_thermal(Reader& r, const std::string& at, const ActuatorParams& a) {
  const std::pair<const char*, double> v[] = {
      {"thermal_resistance_winding", a.thermal_resistance_winding_KpW},
      {"thermal_capacity_winding", a.thermal_capacity_winding_JpK},
      {"thermal_resistance_housing", a.thermal_resistance_housing_KpW},
      {"thermal_capacity_housing", a.thermal_capacity_housing_JpK}};
  int given = 0;
  for (const auto& [key, value] : v) given += std::isnan(value) ? 0 : 1;
  if (given == 0 || given == 4) return;
  for (const auto& [key, value] : v)
    if (std::isnan(value))
      r.fail(at + key,
             "missing, expected the thermal model's four values "
             "(thermal_resistance_winding, thermal_capacity_winding, "
             "thermal_resistance_housing, thermal_capacity_housing) or none of them");
}

/// The entries that apply to one joint, least specific first.
using EntryChain = std::array<const Entry*, 4>;

/// Joint k's values from its entries (the chain), over `base`.
ActuatorParams resolve_joint(Reader& r, const JointFacts& joints, int k, const EntryChain& chain,
                             const ActuatorParams& base) {
  ActuatorParams a = base;
  std::vector<bool> given(fields().size(), false);
  Inertia inertia;
  Stages stages;
  for (const Entry* e : chain) {
    if (!e->model.empty()) {  // another servo: none of a less specific entry's servo values
      for (std::size_t i = 0; i < fields().size(); ++i)
        if (fields()[i].of_motor) {
          a.*fields()[i].member = base.*fields()[i].member;
          given[i] = false;
        }
      inertia = Inertia{};
      stages.clear();
      a.winding = base.winding;
      a.model = e->model;
    }
    for (std::size_t i = 0; i < fields().size(); ++i)
      if (e->values[i]) {
        a.*fields()[i].member = *e->values[i];
        given[i] = true;
      }
    if (e->values[field_index(&ActuatorParams::gear_ratio)]) stages = e->stages.value_or(Stages{});
    if (e->inertia) inertia = *e->inertia;
    if (e->winding) a.winding = *e->winding;
  }
  const bool typed = joints.leg_joints[k] == kTypedLegJoints;
  const std::string at = "actuators.joints." + joints.names[k] + ".";
  for (double ActuatorParams::*m :
       {&ActuatorParams::gear_ratio, &ActuatorParams::torque_constant_NmpA,
        &ActuatorParams::resistance_ohm})
    if (!given[field_index(m)])
      r.fail(at + fields()[field_index(m)].key,
             std::string("missing, expected it from actuators.default, ") +
                 (typed ? std::string("actuators.") + kTypes[joints.place[k]] + ", " : "") +
                 "actuators." + position_key(joints.place[k]) + ", actuators.joints." +
                 joints.names[k] + " or their model");
  check_thermal(r, at, a);
  a.gear_stages = stages;
  a.armature_kgm2 =
      (inertia.motor_side ? a.gear_ratio * a.gear_ratio * inertia.value_kgm2 : inertia.value_kgm2);
  if (!stages.empty()) a.armature_kgm2 += stage_armature(stages);
  return a;
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
    // The joint without any entry: the built-in defaults and the URDF's friction.
    ActuatorParams base;
    base.viscous_friction_Nmsprad = joints.damping_Nmsprad[k];
    base.coulomb_friction_Nm = joints.friction_Nm[k];
    // A type and its place are never both given (check_entry_names).
    const EntryChain chain{&all, typed ? &by_type[joints.place[k]] : &untyped,
                           &by_place[joints.place[k]], &by_joint[k]};
    out.joints[k] = resolve_joint(r, joints, k, chain, base);
    record_joint(r, joints.names[k], out.joints[k]);
  }
  return out;
}

std::string objective_word(AllocationObjective objective) {
  return objective == AllocationObjective::kCopperLoss ? "copper_loss" : "torque_squared";
}

}  // namespace hexdyn::scene_keys
