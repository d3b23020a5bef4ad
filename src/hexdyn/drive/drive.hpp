#pragma once
/// \file drive.hpp
/// The drive-train stage (docs/theory/drive-train.md): each joint driven by a geared DC or
/// three-phase motor (core/scene.hpp ActuatorParams). From the link torques of the inverse dynamics
/// to the torque the drive gives, its bound at the joint's speed, the motor current and the
/// electrical power, and their integrals over the run.
///
/// Joint side throughout: τ [N m], q̇ [rad/s], q̈ [rad/s²]; the motor turns at G q̇.
#include <cstdint>
#include <vector>

#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// τ_drive − τ_link = J_a q̈ + τ_c sgn(q̇) + b q̇ of every joint [N m], sgn(0) = 0; qd_radps,
/// qdd_radps2 and the result: drive.joints.size() joints.
JointVector drive_torque_offset(const DriveTrainParams& drive, const JointVector& qd_radps,
                                const JointVector& qdd_radps2);

/// Which bound limits |τ_drive| (/solver messages name it): none, the peak rating, or the
/// voltage (the back-EMF at the joint's speed).
enum class DriveBound : std::int8_t { kNone = 0, kPeak = 1, kVoltage = 2 };

/// "peak" or "voltage" ("" for kNone).
const char* bound_name(DriveBound bound);

/// The bounds on τ_drive at joint speed q̇: lower_Nm ≤ τ_drive ≤ limit_Nm
/// (docs/theory/drive-train.md#torque-bound). A DC motor: |τ_drive| ≤ min(peak_torque, G k_t η (V −
/// G k_t |q̇|) / R), never below 0 (a joint faster than the no-load speed V / (G k_t) can give no
/// torque), lower_Nm = −limit_Nm. A three-phase motor: the field-oriented drive's voltage
/// bound |R I + k_e G q̇| ≤ V_q on each side (drive_voltage_range), through the gearbox, and
/// ±peak_torque; the two sides differ at speed, and one may exclude 0. `bound` names the
/// tighter kind of either side.
struct DriveLimit {
  double limit_Nm = kInfinity;
  DriveBound bound = DriveBound::kNone;
  double lower_Nm = -kInfinity;
};
DriveLimit drive_torque_limit(const ActuatorParams& a, double qd_radps);

/// A three-phase motor's range of motor torque at motor speed ω_m = G q̇ from its voltage
/// bound: k_t (±V_q − k_e ω_m) / R, with the back-EMF constant k_e = k_t / c (c =
/// copper_factor) and the largest q-axis voltage V_q = u V (amplitude-invariant) or √(3/2) u V
/// (power-invariant), u the voltage utilization (docs/theory/drive-train.md#voltage-limit).
struct MotorTorqueRange {
  double lower_Nm = -kInfinity, upper_Nm = kInfinity;
};
MotorTorqueRange drive_voltage_range(const ActuatorParams& a, double motor_speed_radps);

/// The joint torque of motor torque τ_m at joint speed q̇ through the gearbox: η G τ_m when
/// driving (τ_m q̇ ≥ 0), G τ_m / η when back-driven.
double joint_torque_of_motor(const ActuatorParams& a, double motor_torque_Nm, double qd_radps);

/// The copper-loss weight c R / (G k_t η)² [W/(N m)²]: the loss c R I² of a driving joint per
/// τ_drive² (allocation.objective copper_loss; c = copper_factor of the winding).
double copper_loss_weight(const ActuatorParams& a);

/// Motor current I [A] of a joint at drive torque τ and speed q̇, in the winding's convention:
/// τ / (G k_t η) when driving (τ q̇ ≥ 0), τ η / (G k_t) when back-driven.
double motor_current(const ActuatorParams& a, double tau_Nm, double qd_radps);

/// The copper loss c R I² [W] of current I (c = copper_factor of the winding).
double copper_loss(const ActuatorParams& a, double current_A);

/// The electrical power drawn, P⁺ [W]: P = c R I² + G k_t q̇ I with I = motor_current, or r P
/// when P < 0.
double electrical_power(const ActuatorParams& a, double tau_Nm, double qd_radps);

/// The electrical side of a run (core/result.hpp ElectricalResult) from its drive torques and
/// joint speeds. time_s: T increasing sample times [s]; joint_velocity, drive_torque:
/// T×drive.joints.size();
/// total_mass_kg > 0, distance_m > 0 (the cost of transport's m and d).
ElectricalResult compute_electrical(const DriveTrainParams& drive,
                                    const std::vector<double>& time_s,
                                    const RowMatrix& joint_velocity, const RowMatrix& drive_torque,
                                    double total_mass_kg, double distance_m);

/// The largest RMS of the samples (t, y) over any window [a, a + window_s] ⊆ [t_0, t_end],
/// y linear between samples (as the trapezoid rule); over [t_0, t_end] when the window is
/// longer (|y_0| for one sample). y[k·stride], k < t.size().
double largest_window_rms(const std::vector<double>& t, const double* y, int stride,
                          double window_s);

}  // namespace hexdyn
