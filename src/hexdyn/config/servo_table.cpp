/// \file servo_table.cpp
/// The shipped servos (docs/user/servos.md lists every value with its source). Two kinds of
/// entry: a servo that Rhoban/bam identified takes its electrical and friction constants from
/// bam's model m1 and its ratings from the ROBOTIS e-Manual; a servo with no identification
/// takes everything from the e-Manual, the constants derived from the datasheet's stall and
/// no-load points (docs/user/servos.md#derived-values). Either way the servo is the geared DC
/// motor τ = η G k_t (V − G k_t ω) / R at the joint.
#include "hexdyn/config/servo_table.hpp"

#include <array>
#include <limits>
#include <numbers>

namespace hexdyn {
namespace {

constexpr double kNotGiven = std::numeric_limits<double>::quiet_NaN();

/// One ROBOTIS e-Manual specification table, read at one supply.
struct Datasheet {
  double gear_ratio;         ///< G [–]
  double voltage_V;          ///< the supply the three ratings below are given at [V]
  double stall_torque_Nm;    ///< τ_s [N m]
  double stall_current_A;    ///< I_s [A]
  double no_load_speed_rpm;  ///< n_0 [rev/min]
};

constexpr double no_load_speed_radps(const Datasheet& d) {
  return d.no_load_speed_rpm * 2.0 * std::numbers::pi / 60.0;
}

/// k_t, motor side, from the back EMF at no load: V = G k_t ω_0 (no-load current neglected).
constexpr double torque_constant_from_no_load(const Datasheet& d) {
  return d.voltage_V / (d.gear_ratio * no_load_speed_radps(d));
}

/// R from the stall current: at ω = 0 the motor draws I_s = V / R.
constexpr double resistance_from_stall(const Datasheet& d) {
  return d.voltage_V / d.stall_current_A;
}

/// η from the stall torque: τ_s = η G k_t I_s, the share of the motor's torque the joint gets.
constexpr double efficiency_from_stall(const Datasheet& d) {
  return d.stall_torque_Nm / (d.gear_ratio * torque_constant_from_no_load(d) * d.stall_current_A);
}

/// A servo known from its datasheet alone: the torque-speed line through (0, τ_s) and (ω_0, 0).
constexpr ServoSpec from_datasheet(const char* name, const char* description, const Datasheet& d,
                                   double continuous_torque_Nm, const char* sources) {
  return ServoSpec{name,
                   description,
                   d.gear_ratio,
                   torque_constant_from_no_load(d),
                   resistance_from_stall(d),
                   kNotGiven,
                   kNotGiven,
                   kNotGiven,
                   efficiency_from_stall(d),
                   d.voltage_V,
                   d.stall_torque_Nm,
                   continuous_torque_Nm,
                   sources};
}

/// The values of one bam parameter file for model m1 (Coulomb and viscous friction): every
/// one joint side, `kt` the joint-side constant G k_t of τ = kt (V − kt ω) / R.
struct BamM1 {
  double kt_joint_NmpA;             ///< kt [N m/A]
  double resistance_ohm;            ///< R [Ω]
  double armature_kgm2;             ///< armature [kg m²]
  double coulomb_friction_Nm;       ///< friction_base [N m]
  double viscous_friction_Nmsprad;  ///< friction_viscous [N m s/rad]
};

/// A servo bam identified: its constants from bam, G and the ratings from the datasheet. bam's
/// model has no gear efficiency (its kt is the joint's torque per ampere, and its losses are
/// the friction terms), so η = 1 reproduces it.
constexpr ServoSpec from_bam_m1(const char* name, const char* description, const Datasheet& d,
                                const BamM1& m, double continuous_torque_Nm, const char* sources) {
  return ServoSpec{name,
                   description,
                   d.gear_ratio,
                   m.kt_joint_NmpA / d.gear_ratio,
                   m.resistance_ohm,
                   m.armature_kgm2,
                   m.coulomb_friction_Nm,
                   m.viscous_friction_Nmsprad,
                   1.0,
                   d.voltage_V,
                   d.stall_torque_Nm,
                   continuous_torque_Nm,
                   sources};
}

// The e-Manual's Specifications tables (https://emanual.robotis.com/docs/en/dxl/...), at the
// recommended supply where the table gives several (12 V; 5.0 V for the XL330). A servo bam
// identified takes G, V and τ_s from it; its I_s and n_0 are for docs/user/servos.md#consistency.
constexpr Datasheet kAx12a{254.0, 12.0, 1.5, 1.5, 59.0};        // ax/ax-12a/
constexpr Datasheet kMx28{193.0, 12.0, 2.5, 1.4, 55.0};         // mx/mx-28/
constexpr Datasheet kMx64{200.0, 12.0, 6.0, 4.1, 63.0};         // mx/mx-64/
constexpr Datasheet kMx106{225.0, 12.0, 8.4, 5.2, 45.0};        // mx/mx-106/
constexpr Datasheet kXl330M288{288.4, 5.0, 0.52, 1.47, 103.0};  // x/xl330-m288/
constexpr Datasheet kXm430W350{353.5, 12.0, 4.1, 2.3, 46.0};    // x/xm430-w350/

// Rhoban/bam, bam/params/<servo>/m1.json at commit 1b5a1ce (github.com/Rhoban/bam), as printed.
constexpr BamM1 kBamMx64{1.6224667906987444, 3.949433673232461, 0.011951238325312509,
                         0.09038677246291783, 0.011691602145974832};
constexpr BamM1 kBamMx106{2.1913757006745245, 2.9649903987776804, 0.026609234235148084,
                          0.10352026623606064, 0.03520238029013507};
constexpr BamM1 kBamXl330{0.3866957639281311, 4.017129222290597, 0.0018141672784458866,
                          0.01283272036582759, 0.003661672282824312};

/// A brushless joint module: a three-phase motor of the stated winding convention (k_t per
/// ampere of that current, R per phase), its joint-side values and its two-node thermal model
/// (docs/user/servos.md#brushless-modules).
struct Module {
  const char* name;
  const char* description;
  double gear_ratio;            ///< G [–]
  double torque_constant_NmpA;  ///< k_t, motor side [N m/A]
  double resistance_ohm;        ///< R per phase [Ω]
  double rotor_inertia_kgm2;    ///< J_m, motor side [kg m²] (NaN: not given)
  double coulomb_friction_Nm;   ///< joint side [N m] (NaN: not given)
  double viscous_friction_Nmsprad;
  double voltage_V;               ///< the bus [V]
  double voltage_utilization;     ///< u [–]
  double peak_torque_Nm;          ///< joint side [N m]
  std::array<double, 4> thermal;  ///< R_th,wh [K/W], C_th,w [J/K], R_th,ha [K/W], C_th,h [J/K]
  double winding_limit_degC;      ///< [°C]
  const char* sources;
};

constexpr ServoSpec from_module(const Module& m) {
  ServoSpec s{m.name,
              m.description,
              m.gear_ratio,
              m.torque_constant_NmpA,
              m.resistance_ohm,
              m.gear_ratio * m.gear_ratio * m.rotor_inertia_kgm2,
              m.coulomb_friction_Nm,
              m.viscous_friction_Nmsprad,
              1.0,
              m.voltage_V,
              m.peak_torque_Nm,
              kNotGiven,
              m.sources};
  s.winding = Winding::kThreePhaseAmplitude;
  s.voltage_utilization = m.voltage_utilization;
  s.thermal_resistance_winding_KpW = m.thermal[0];
  s.thermal_capacity_winding_JpK = m.thermal[1];
  s.thermal_resistance_housing_KpW = m.thermal[2];
  s.thermal_capacity_housing_JpK = m.thermal[3];
  s.winding_temperature_limit_degC = m.winding_limit_degC;
  return s;
}

// mit-biomimetics/Cheetah-Software, common/include/Dynamics/MiniCheetah.h and ActuatorModel.h
// (commit aa89b8a): _motorKT = 0.05 ("flux linkage * pole pairs"), _motorR = 0.173, _batteryV
// = 24, _motorTauMax = 3 (motor side), ratios 6 / 6 / 9.33, rotor inertia 63e-6 kg m² about its
// spin axis, joint damping 0.01, dry friction 0.2. ActuatorModel's τ = 1.5 kt (v − 2 kt ω) / R,
// |v| ≤ V is the amplitude-invariant q axis with k_t = 1.5 kt, R per phase = 0.173 / 2 and a
// phase amplitude of V / 2 (docs/theory/drive-train.md#voltage-limit).
constexpr double kCheetahKt = 0.05, kCheetahR = 0.173, kCheetahTauMax = 3.0;
// Assumed two-node thermal values of the brushless modules (no maker publishes them): the
// winding's capacity from its copper mass (c = 385 J/(kg K)), the housing's from the module's
// aluminium mass (c = 900 J/(kg K)), resistances giving time constants of tens of seconds
// (winding) and several minutes (housing); limits: class-F-like 120 °C, the
// demagnetisation-safe bound small outrunners are sold with. docs/user/servos.md#brushless-modules.
constexpr std::array<double, 4> kSmallOutrunnerThermal{2.0, 8.0, 6.0, 30.0};
constexpr std::array<double, 4> kCheetahThermal{1.0, 40.0, 2.5, 150.0};
constexpr std::array<double, 4> kGoThermal{1.0, 50.0, 2.0, 200.0};
constexpr std::array<double, 4> kAnydriveThermal{0.5, 150.0, 1.0, 800.0};

constexpr Module kModules[] = {
    {"odri_actuator",
     "ODRI actuator module (Solo-12, Bolt): T-Motor Antigravity 4004 300 kV, two 3:1 belt stages",
     9.0, 0.025, 0.23255, 4.5e-6, kNotGiven, kNotGiven, 24.0, 0.5, 2.5, kSmallOutrunnerThermal,
     120.0,
     "G = 9 (two 3:1 belt stages), 2.5 N m at 12 A: open_robot_actuator_hardware "
     "mechanics/actuator_module_v1 README; k_t = 0.025 N m/A, J_m = 4.5e-6 kg m^2: "
     "robot_properties_solo src/robot_properties_solo/config.py (motor_torque_constant, "
     "motor_inertia); R = 0.23255 Ohm per phase: the motor identification of the actuator "
     "module's documentation; "
     "winding three_phase_amplitude, V = 24, u = 0.5, friction, thermal values, limit: ASSUMED"},
    {"mini_cheetah_hip", "MIT Mini Cheetah module, abduction and hip: 6:1 planetary, at 24 V", 6.0,
     1.5 * kCheetahKt, 0.5 * kCheetahR, 63e-6, 0.2, 0.01, 24.0, 0.5, 6.0 * kCheetahTauMax,
     kCheetahThermal, 120.0,
     "G = 6, kt = 0.05, R = 0.173, V = 24, tau_max = 3 N m motor side, rotor 63e-6 kg m^2, "
     "damping 0.01, dry friction 0.2: Cheetah-Software common/include/Dynamics/MiniCheetah.h; "
     "k_t = 1.5 kt, R = 0.173/2 per phase, u = 0.5: ActuatorModel.h read as the "
     "amplitude-invariant q axis (docs/theory/drive-train.md#voltage-limit); thermal values, "
     "limit: ASSUMED"},
    {"mini_cheetah_knee", "MIT Mini Cheetah module, knee: 9.33:1 (planetary and belt), at 24 V",
     9.33, 1.5 * kCheetahKt, 0.5 * kCheetahR, 63e-6, 0.2, 0.01, 24.0, 0.5, 9.33 * kCheetahTauMax,
     kCheetahThermal, 120.0,
     "G = 9.33 and the rest as mini_cheetah_hip: Cheetah-Software "
     "common/include/Dynamics/MiniCheetah.h, ActuatorModel.h; thermal values, limit: ASSUMED"},
    {"unitree_go_m8010_6", "Unitree GO-M8010-6, 6.33:1 planetary, at 24 V", 6.33,
     1.5 * 0.5 * 24.0 / (6.33 * 30.0), 0.5 * 24.0 * 1.5 * 0.5 * 24.0 / (30.0 * 23.7), kNotGiven,
     kNotGiven, kNotGiven, 24.0, 0.5, 23.7, kGoThermal, 120.0,
     "G = 6.33, 23.7 N m peak, 30 rad/s at the output, 24 V: Unitree GO-M8010-6 product page; "
     "30 V at most: GO-M8010-6 user manual V1.2; k_t from the no-load speed (u V = k_e G w_0, "
     "k_t = 1.5 k_e) and R from the peak as the voltage-limited stall torque: DERIVED under "
     "those ASSUMPTIONS; rotor inertia, friction: not published; thermal values, limit: ASSUMED"},
    {"anydrive", "ANYbotics ANYdrive (ANYmal C), harmonic drive, at 48 V", 50.0,
     1.5 * 0.5 * 48.0 / (50.0 * 7.5), 0.5 * 48.0 * 1.5 * 0.5 * 48.0 / (7.5 * 80.0), kNotGiven,
     kNotGiven, kNotGiven, 48.0, 0.5, 80.0, kAnydriveThermal, 120.0,
     "80 N m, 7.5 rad/s: robots/anymal_c.urdf <limit effort velocity> (ANYbotics' anymal_c "
     "description); G = 50, V = 48: ASSUMED; k_t from the no-load speed, R from the peak as the "
     "voltage-limited stall torque: DERIVED under those ASSUMPTIONS; thermal values, limit: "
     "ASSUMED"},
};

constexpr std::array kServos{
    from_datasheet(
        "dynamixel_ax12a", "ROBOTIS Dynamixel AX-12A, cored DC motor, 254:1, at 12 V", kAx12a,
        kAx12a.stall_torque_Nm / 5.0,
        "G, stall 1.5 N m at 1.5 A, 59 rev/min at 12 V, continuous = stall/5 (its note: stable "
        "motion with loads of 1/5 of stall or less): "
        "e-Manual emanual.robotis.com/docs/en/dxl/ax/ax-12a/ Specifications; k_t = V/(G w_0), "
        "R = V/I_s, eta = tau_s/(G k_t I_s) (docs/user/servos.md#derived-values); "
        "armature, friction: not published"),
    from_datasheet(
        "dynamixel_mx28", "ROBOTIS Dynamixel MX-28 (T/R/AT/AR), coreless DC motor, 193:1, at 12 V",
        kMx28, kNotGiven,
        "G, stall 2.5 N m at 1.4 A, 55 rev/min at 12 V: e-Manual "
        "emanual.robotis.com/docs/en/dxl/mx/mx-28/ Specifications; k_t = V/(G w_0), R = V/I_s, "
        "eta = tau_s/(G k_t I_s) (docs/user/servos.md#derived-values); armature, friction, "
        "continuous rating: not published"),
    from_bam_m1(
        "dynamixel_mx64", "ROBOTIS Dynamixel MX-64 (T/R/AT/AR), coreless DC motor, 200:1, at 12 V",
        kMx64, kBamMx64, kNotGiven,
        "G k_t = 1.6225 N m/A, R, armature, Coulomb and viscous friction: Rhoban/bam "
        "bam/params/mx64/m1.json (commit 1b5a1ce), eta = 1 (model m1 has none); G, stall "
        "6.0 N m at 12 V: e-Manual emanual.robotis.com/docs/en/dxl/mx/mx-64/ Specifications; "
        "continuous rating: not published"),
    from_bam_m1(
        "dynamixel_mx106", "ROBOTIS Dynamixel MX-106 (T/R), coreless DC motor, 225:1, at 12 V",
        kMx106, kBamMx106, kNotGiven,
        "G k_t = 2.1914 N m/A, R, armature, Coulomb and viscous friction: Rhoban/bam "
        "bam/params/mx106/m1.json (commit 1b5a1ce), eta = 1 (model m1 has none); G, stall "
        "8.4 N m at 12 V: e-Manual emanual.robotis.com/docs/en/dxl/mx/mx-106/ Specifications; "
        "continuous rating: not published"),
    from_bam_m1(
        "dynamixel_xl330_m288", "ROBOTIS Dynamixel XL330-M288-T, cored DC motor, 288.4:1, at 5 V",
        kXl330M288, kBamXl330, kNotGiven,
        "G k_t = 0.3867 N m/A, R, armature, Coulomb and viscous friction: Rhoban/bam "
        "bam/params/xl330/m1.json (commit 1b5a1ce; bam's XL330-288-T), eta = 1 (model m1 has "
        "none); G, stall 0.52 N m at 5.0 V: e-Manual "
        "emanual.robotis.com/docs/en/dxl/x/xl330-m288/ Specifications; continuous rating: "
        "not published"),
    from_datasheet(
        "dynamixel_xm430_w350",
        "ROBOTIS Dynamixel XM430-W350 (T/R), coreless DC motor, 353.5:1, at 12 V", kXm430W350,
        kNotGiven,
        "G, stall 4.1 N m at 2.3 A, 46 rev/min at 12 V: e-Manual "
        "emanual.robotis.com/docs/en/dxl/x/xm430-w350/ Specifications; k_t = V/(G w_0), "
        "R = V/I_s, eta = tau_s/(G k_t I_s) (docs/user/servos.md#derived-values); armature, "
        "friction, continuous rating: not published (bam has no XM430 parameters)"),
    from_module(kModules[0]),
    from_module(kModules[1]),
    from_module(kModules[2]),
    from_module(kModules[3]),
    from_module(kModules[4]),
};

}  // namespace

std::span<const ServoSpec> servo_table() { return kServos; }

const ServoSpec* find_servo(std::string_view name) {
  for (const ServoSpec& servo : kServos) {
    if (name == servo.name) return &servo;
  }
  return nullptr;
}

}  // namespace hexdyn
