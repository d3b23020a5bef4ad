#pragma once
/// \file drive.hpp
/// The drive-train stage (docs/theory/drive-train.md): each joint driven by a geared DC
/// motor (core/scene.hpp ActuatorParams). From the link torques of the inverse dynamics to the
/// torque the drive gives, its bound at the joint's speed, the motor current and the
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

/// The bound on |τ_drive| at joint speed q̇: min(peak_torque, G k_t η (V − G k_t |q̇|) / R),
/// never below 0 (a joint faster than the no-load speed V / (G k_t) can give no torque).
struct DriveLimit {
  double limit_Nm = kInfinity;
  DriveBound bound = DriveBound::kNone;
};
DriveLimit drive_torque_limit(const ActuatorParams& a, double qd_radps);

/// The copper-loss weight R / (G k_t η)² [W/(N m)²]: the loss R I² of a driving joint per
/// τ_drive² (allocation.objective copper_loss).
double copper_loss_weight(const ActuatorParams& a);

/// Motor current I [A] of a joint at drive torque τ and speed q̇: τ / (G k_t η) when
/// driving (τ q̇ ≥ 0), τ η / (G k_t) when back-driven.
double motor_current(const ActuatorParams& a, double tau_Nm, double qd_radps);

/// The electrical power drawn, P⁺ [W]: P = R I² + G k_t q̇ I with I = motor_current, or r P
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
