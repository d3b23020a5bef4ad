// The shipped servo table (config/servo_table.hpp, docs/user/servos.md): every entry has its
// required values, the names are unique lowercase words that find_servo finds, and each servo
// is a consistent geared DC motor, checked against the ROBOTIS e-Manual figures typed below
// from the e-Manual itself, not from the table: its stall torque η G k_t V / R and its no-load
// speed. For a servo the table derives from the datasheet the two hold exactly (that is the
// derivation); for a servo Rhoban/bam identified they hold within the tolerance stated below.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <string_view>

#include "hexdyn/config/servo_table.hpp"

namespace hexdyn {
namespace {

/// A servo's e-Manual Specifications table at the supply the table uses.
struct Emanual {
  std::string_view name;
  bool identified_by_bam;    ///< constants from bam's m1 model, not from these figures
  double gear_ratio;         ///< G [–]
  double voltage_V;          ///< [V]
  double stall_torque_Nm;    ///< τ_s [N m]
  double stall_current_A;    ///< I_s [A]
  double no_load_speed_rpm;  ///< n_0 [rev/min]
};

// https://emanual.robotis.com/docs/en/dxl/ax/ax-12a/, mx/mx-28/, mx/mx-64/, mx/mx-106/,
// x/xl330-m288/, x/xm430-w350/ (Specifications: Gear Ratio, Stall Torque, No Load Speed).
constexpr Emanual kEmanual[] = {
    {"dynamixel_ax12a", false, 254.0, 12.0, 1.5, 1.5, 59.0},
    {"dynamixel_mx28", false, 193.0, 12.0, 2.5, 1.4, 55.0},
    {"dynamixel_mx64", true, 200.0, 12.0, 6.0, 4.1, 63.0},
    {"dynamixel_mx106", true, 225.0, 12.0, 8.4, 5.2, 45.0},
    {"dynamixel_xl330_m288", true, 288.4, 5.0, 0.52, 1.47, 103.0},
    {"dynamixel_xm430_w350", false, 353.5, 12.0, 4.1, 2.3, 46.0},
};

// bam fitted its constants to pendulum trajectories, not to a stall test, with no gear
// efficiency in its model; ROBOTIS measures the stall torque as the momentary torque the
// servo reaches, above what its own performance graph shows (e-Manual, note under the
// performance graph). The two sources differ by up to 18 % on the stall torque (MX-64) and
// 12 % on the no-load speed (MX-106): docs/user/servos.md#consistency. 25 % admits that and
// still catches what a wrong entry would be off by: a joint-side constant left undivided by G
// (200 to 354) or divided twice, rev/min read as rad/s (9.5).
constexpr double kCrossSourceTolerance = 0.25;

double no_load_speed_radps(const Emanual& e) {
  return e.no_load_speed_rpm * 2.0 * std::numbers::pi / 60.0;
}

/// The joint torque at stall of the motor the entry describes: η G k_t I_s with I_s = V / R.
double stall_torque_from_constants(const ServoSpec& s) {
  return s.gear_efficiency * s.gear_ratio * s.torque_constant_NmpA * s.voltage_V / s.resistance_ohm;
}

/// The joint speed at which the motor's torque, η G k_t (V − G k_t ω) / R, balances the
/// friction τ_c + b ω of the entry (none where the table gives none).
double no_load_speed_from_constants(const ServoSpec& s) {
  const double tau_c = std::isnan(s.coulomb_friction_Nm) ? 0.0 : s.coulomb_friction_Nm;
  const double b = std::isnan(s.viscous_friction_Nmsprad) ? 0.0 : s.viscous_friction_Nmsprad;
  const double k = s.gear_efficiency * s.gear_ratio * s.torque_constant_NmpA / s.resistance_ohm;
  const double ke = s.gear_ratio * s.torque_constant_NmpA;  // back EMF per joint rad/s
  return (k * s.voltage_V - tau_c) / (k * ke + b);
}

bool present_and_positive(double value) { return std::isfinite(value) && value > 0.0; }

/// An optional value: NaN (not given) or a positive number.
bool absent_or_positive(double value) { return std::isnan(value) || present_and_positive(value); }

TEST_CASE("servo table: every entry has its required values", "[servo_table]") {
  REQUIRE(servo_table().size() >= 6);
  for (const ServoSpec& s : servo_table()) {
    INFO(s.name);
    CHECK(std::string(s.description).size() > 0);
    CHECK(std::string(s.sources).find('\n') == std::string::npos);
    CHECK(std::string(s.sources).size() > 0);
    CHECK(present_and_positive(s.gear_ratio));
    CHECK(present_and_positive(s.torque_constant_NmpA));
    CHECK(present_and_positive(s.resistance_ohm));
    CHECK(present_and_positive(s.voltage_V));
    CHECK(present_and_positive(s.peak_torque_Nm));
    CHECK(std::isfinite(s.gear_efficiency));
    CHECK(s.gear_efficiency > 0.0);
    CHECK(s.gear_efficiency <= 1.0);
    CHECK(absent_or_positive(s.armature_kgm2));
    CHECK(absent_or_positive(s.coulomb_friction_Nm));
    CHECK(absent_or_positive(s.viscous_friction_Nmsprad));
    CHECK(absent_or_positive(s.continuous_torque_Nm));
    if (!std::isnan(s.continuous_torque_Nm)) CHECK(s.continuous_torque_Nm < s.peak_torque_Nm);
  }
}

TEST_CASE("servo table: names are unique lowercase words that find_servo finds", "[servo_table]") {
  std::set<std::string> names;
  for (const ServoSpec& s : servo_table()) {
    const std::string name = s.name;
    INFO(name);
    CHECK(names.insert(name).second);
    CHECK(!name.empty());
    for (char c : name) CHECK(((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'));
    CHECK(find_servo(name) == &s);
  }
  for (const Emanual& e : kEmanual) CHECK(find_servo(e.name) != nullptr);
  CHECK(find_servo("") == nullptr);
  CHECK(find_servo("dynamixel_mx65") == nullptr);
  CHECK(find_servo("DYNAMIXEL_MX64") == nullptr);
  CHECK(find_servo("dynamixel_mx64 ") == nullptr);
  CHECK(find_servo("dynamixel_mx6") == nullptr);
}

TEST_CASE("servo table: each servo is the geared DC motor of its datasheet", "[servo_table]") {
  for (const Emanual& e : kEmanual) {
    INFO(e.name);
    const ServoSpec* s = find_servo(e.name);
    REQUIRE(s != nullptr);
    CHECK(s->gear_ratio == e.gear_ratio);
    CHECK(s->voltage_V == e.voltage_V);
    CHECK(s->peak_torque_Nm == e.stall_torque_Nm);
    const double stall = stall_torque_from_constants(*s);
    const double no_load = no_load_speed_from_constants(*s);
    if (e.identified_by_bam) {
      CHECK(stall == Approx(e.stall_torque_Nm).epsilon(kCrossSourceTolerance));
      CHECK(no_load == Approx(no_load_speed_radps(e)).epsilon(kCrossSourceTolerance));
    } else {
      // Derived from the datasheet: R = V / I_s, and the torque-speed line passes through
      // the stall point and the no-load point, to rounding.
      CHECK(s->resistance_ohm == Approx(e.voltage_V / e.stall_current_A).epsilon(1e-12));
      CHECK(stall == Approx(e.stall_torque_Nm).epsilon(1e-12));
      CHECK(no_load == Approx(no_load_speed_radps(e)).epsilon(1e-12));
    }
  }
}

}  // namespace
}  // namespace hexdyn
