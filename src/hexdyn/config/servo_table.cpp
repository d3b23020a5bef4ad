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
