#pragma once
/// \file servo_table.hpp
/// The shipped table of servos that a scene's `actuators` entries name with `model:`
/// (docs/user/servos.md lists every value with its source). Values are SI, joint side
/// unless said; NaN where the sources give no value (the entry's own keys or the defaults
/// of config/actuators.hpp then apply). Every servo gives G, k_t, R, η, V and the peak
/// torque; the armature, the friction and the continuous rating may be NaN. A servo is the
/// geared DC motor τ = η G k_t (V − G k_t ω) / R at the joint
/// (docs/user/servos.md#the-motor-model); a brushless module is a three-phase motor of the
/// stated winding convention (docs/theory/drive-train.md#three-phase-motors).
#include <limits>
#include <span>
#include <string_view>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// A value the table does not give.
inline constexpr double kNotGivenValue = std::numeric_limits<double>::quiet_NaN();

/// One servo of the table.
struct ServoSpec {
  const char* name;                 ///< the `model:` word, e.g. "dynamixel_mx64"
  const char* description;          ///< maker, type and the operating point, e.g. "… at 12 V"
  double gear_ratio;                ///< G [–]
  double torque_constant_NmpA;      ///< k_t, motor side [N m/A] (joint side / G)
  double resistance_ohm;            ///< R, winding and driver [Ω]
  double armature_kgm2;             ///< J_a = G² J_m, joint side [kg m²]
  double coulomb_friction_Nm;       ///< τ_c, joint side [N m]
  double viscous_friction_Nmsprad;  ///< b, joint side [N m s/rad]
  double gear_efficiency;           ///< η ∈ (0, 1]
  double voltage_V;                 ///< the supply the ratings are given at [V]
  double peak_torque_Nm;            ///< stall torque at voltage_V [N m]
  double continuous_torque_Nm;      ///< continuous (thermal) rating [N m]
  const char* sources;              ///< where each value comes from, one line
  // Three-phase motors and the thermal model (NaN: not given; the defaults apply).
  Winding winding = Winding::kDc;                          ///< the convention of k_t and R
  double voltage_utilization = kNotGivenValue;             ///< u, three-phase [–]
  double thermal_resistance_winding_KpW = kNotGivenValue;  ///< R_th,wh [K/W]
  double thermal_capacity_winding_JpK = kNotGivenValue;    ///< C_th,w [J/K]
  double thermal_resistance_housing_KpW = kNotGivenValue;  ///< R_th,ha [K/W]
  double thermal_capacity_housing_JpK = kNotGivenValue;    ///< C_th,h [J/K]
  double winding_temperature_limit_degC = kNotGivenValue;  ///< the winding's rating [°C]
};

/// Every servo of the table, in the order docs/user/servos.md lists them.
std::span<const ServoSpec> servo_table();

/// The servo named exactly `name` (case and all), or null.
const ServoSpec* find_servo(std::string_view name);

}  // namespace hexdyn
