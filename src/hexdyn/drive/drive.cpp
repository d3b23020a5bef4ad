#include "hexdyn/drive/drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "hexdyn/drive/thermal.hpp"
#include "hexdyn/power/power.hpp"

namespace hexdyn {
namespace {

double sgn(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

/// The samples (t, s) with s linear between them: s(x) and ∫_{t_0}^{x} s, from the
/// cumulative integral at the samples.
class PiecewiseLinear {
 public:
  PiecewiseLinear(const std::vector<double>& t, std::vector<double> s)
      : t_(t), s_(std::move(s)), c_(t.size(), 0.0) {
    for (std::size_t i = 1; i < t_.size(); ++i)
      c_[i] = c_[i - 1] + 0.5 * (s_[i - 1] + s_[i]) * (t_[i] - t_[i - 1]);
  }
  double value(double x) const {
    const std::size_t i = interval(x);
    const double h = t_[i + 1] - t_[i];
    return h > 0.0 ? s_[i] + (s_[i + 1] - s_[i]) * (x - t_[i]) / h : s_[i];
  }
  double integral(double x) const {
    const std::size_t i = interval(x);
    return c_[i] + 0.5 * (x - t_[i]) * (s_[i] + value(x));
  }

 private:
  /// The interval [t_i, t_{i+1}] holding x (clamped to the first and last).
  std::size_t interval(double x) const {
    const auto it = std::upper_bound(t_.begin(), t_.end(), x);
    const std::size_t i = it == t_.begin() ? 0 : static_cast<std::size_t>(it - t_.begin()) - 1;
    return std::min(i, t_.size() - 2);
  }
  const std::vector<double>& t_;
  std::vector<double> s_, c_;
};

/// The thermal series of e (ElectricalResult) from each joint's copper loss (T×joints), when
/// some joint has a thermal model.
void add_thermal(const DriveTrainParams& drive, const std::vector<double>& t,
                 const RowMatrix& copper, ElectricalResult& e) {
  const int J = drive.joints.size();
  bool any = false;
  for (int k = 0; k < J; ++k) any = any || thermal_params(drive.joints[k]).present;
  if (!any || t.empty()) return;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto T = static_cast<Eigen::Index>(t.size());
  e.winding_temperature_degC.setConstant(T, J, nan);
  e.housing_temperature_degC.setConstant(T, J, nan);
  e.peak_winding_temperature_degC.assign(J, nan);
  e.time_to_limit_s.assign(J, nan);
  e.limit_reached.assign(J, 0);
  for (int k = 0; k < J; ++k) {
    const ThermalParams p = thermal_params(drive.joints[k]);
    if (!p.present) continue;
    const ThermalTrace trace = simulate_thermal(p, t, copper.data() + k, J);
    for (Eigen::Index i = 0; i < T; ++i) {
      e.winding_temperature_degC(i, k) = trace.winding_degC[static_cast<std::size_t>(i)];
      e.housing_temperature_degC(i, k) = trace.housing_degC[static_cast<std::size_t>(i)];
    }
    e.peak_winding_temperature_degC[k] = trace.peak_winding_degC;
    e.time_to_limit_s[k] = trace.time_to_limit_s;
    e.limit_reached[k] = trace.reached ? 1 : 0;
  }
}

}  // namespace

JointVector drive_torque_offset(const DriveTrainParams& drive, const JointVector& qd,
                                const JointVector& qdd) {
  JointVector d(drive.joints.size());
  for (int k = 0; k < drive.joints.size(); ++k) {
    const ActuatorParams& a = drive.joints[k];
    d[k] = a.armature_kgm2 * qdd[k] + a.coulomb_friction_Nm * sgn(qd[k]) +
           a.viscous_friction_Nmsprad * qd[k];
  }
  return d;
}

const char* bound_name(DriveBound bound) {
  switch (bound) {
    case DriveBound::kPeak:
      return "peak";
    case DriveBound::kVoltage:
      return "voltage";
    case DriveBound::kNone:
      break;
  }
  return "";
}

namespace {

/// A DC motor's bound on |τ_drive| (docs/theory/drive-train.md#torque-bound).
DriveLimit dc_torque_limit(const ActuatorParams& a, double qd) {
  DriveLimit out;
  if (std::isfinite(a.peak_torque_Nm)) out = {a.peak_torque_Nm, DriveBound::kPeak};
  if (std::isfinite(a.voltage_V)) {
    const double Gk = a.gear_ratio * a.torque_constant_NmpA;
    const double v = std::max(
        0.0, Gk * a.gear_efficiency * (a.voltage_V - Gk * std::abs(qd)) / a.resistance_ohm);
    if (v < out.limit_Nm) out = {v, DriveBound::kVoltage};
  }
  out.lower_Nm = -out.limit_Nm;
  return out;
}

/// A three-phase motor's bounds: the voltage range through the gearbox, then the peak rating.
DriveLimit three_phase_torque_limit(const ActuatorParams& a, double qd) {
  DriveLimit out;
  DriveBound upper = DriveBound::kNone, lower = DriveBound::kNone;
  if (std::isfinite(a.voltage_V)) {
    const MotorTorqueRange m = drive_voltage_range(a, a.gear_ratio * qd);
    out.limit_Nm = joint_torque_of_motor(a, m.upper_Nm, qd);
    out.lower_Nm = joint_torque_of_motor(a, m.lower_Nm, qd);
    upper = lower = DriveBound::kVoltage;
  }
  // Each side clamped to ±peak, as MIT's ActuatorModel clamps the motor's torque: past the
  // speed where even the full voltage drives more than the peak (both sides beyond it), the
  // drive holds its current limit and the side stays at the peak.
  if (std::isfinite(a.peak_torque_Nm)) {
    const double peak = a.peak_torque_Nm;
    if (out.limit_Nm > peak || out.limit_Nm < -peak) {
      out.limit_Nm = std::clamp(out.limit_Nm, -peak, peak);
      upper = DriveBound::kPeak;
    }
    if (out.lower_Nm > peak || out.lower_Nm < -peak) {
      out.lower_Nm = std::clamp(out.lower_Nm, -peak, peak);
      lower = DriveBound::kPeak;
    }
  }
  out.bound = upper == DriveBound::kVoltage || lower == DriveBound::kVoltage ? DriveBound::kVoltage
              : upper == DriveBound::kPeak || lower == DriveBound::kPeak     ? DriveBound::kPeak
                                                                             : DriveBound::kNone;
  return out;
}

}  // namespace

DriveLimit drive_torque_limit(const ActuatorParams& a, double qd) {
  return a.winding == Winding::kDc ? dc_torque_limit(a, qd) : three_phase_torque_limit(a, qd);
}

MotorTorqueRange drive_voltage_range(const ActuatorParams& a, double motor_speed) {
  const double c = copper_factor(a.winding);
  const double kt = a.torque_constant_NmpA;
  const double ke = kt / c;
  const double scale = a.winding == Winding::kThreePhasePower ? std::sqrt(1.5) : 1.0;
  const double vq = scale * a.voltage_utilization * a.voltage_V;
  return {kt * (-vq - ke * motor_speed) / a.resistance_ohm,
          kt * (vq - ke * motor_speed) / a.resistance_ohm};
}

double joint_torque_of_motor(const ActuatorParams& a, double motor_torque, double qd) {
  return motor_torque * qd >= 0.0 ? a.gear_efficiency * a.gear_ratio * motor_torque
                                  : a.gear_ratio * motor_torque / a.gear_efficiency;
}

double copper_loss_weight(const ActuatorParams& a) {
  const double c = a.gear_ratio * a.torque_constant_NmpA * a.gear_efficiency;
  return copper_factor(a.winding) * a.resistance_ohm / (c * c);
}

double motor_current(const ActuatorParams& a, double tau, double qd) {
  const double Gk = a.gear_ratio * a.torque_constant_NmpA;
  return tau * qd >= 0.0 ? tau / (Gk * a.gear_efficiency) : tau * a.gear_efficiency / Gk;
}

double copper_loss(const ActuatorParams& a, double I) {
  return copper_factor(a.winding) * a.resistance_ohm * I * I;
}

double electrical_power(const ActuatorParams& a, double tau, double qd) {
  const double I = motor_current(a, tau, qd);
  const double P = copper_loss(a, I) + a.gear_ratio * a.torque_constant_NmpA * qd * I;
  return P >= 0.0 ? P : a.regeneration * P;
}

double largest_window_rms(const std::vector<double>& t, const double* y, int stride,
                          double window_s) {
  const std::size_t n = t.size();
  if (n == 0) return 0.0;
  if (n == 1) return std::abs(y[0]);
  std::vector<double> s(n);
  for (std::size_t i = 0; i < n; ++i) s[i] = y[i * stride] * y[i * stride];
  const PiecewiseLinear f(t, std::move(s));
  const double t0 = t.front(), t1 = t.back();
  if (!(window_s < t1 - t0))
    return t1 > t0 ? std::sqrt(f.integral(t1) / (t1 - t0)) : std::abs(y[0]);
  // F(a) = ∫_a^{a+W} s is piecewise quadratic in a, with breakpoints where a or a + W is a
  // sample time; F'(a) = s(a + W) − s(a) is linear between them, so F's largest value is at
  // a breakpoint or where F' falls through zero.
  std::vector<double> a;
  a.reserve(2 * n);
  for (double ti : t) {
    if (ti <= t1 - window_s) a.push_back(ti);
    if (ti - window_s >= t0) a.push_back(ti - window_s);
  }
  std::sort(a.begin(), a.end());
  const auto F = [&](double x) { return f.integral(x + window_s) - f.integral(x); };
  const auto dF = [&](double x) { return f.value(x + window_s) - f.value(x); };
  double best = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    best = std::max(best, F(a[i]));
    if (i + 1 == a.size() || a[i + 1] <= a[i]) continue;
    const double d0 = dF(a[i]), d1 = dF(a[i + 1]);
    if (d0 > 0.0 && d1 < 0.0) best = std::max(best, F(a[i] + (a[i + 1] - a[i]) * d0 / (d0 - d1)));
  }
  return std::sqrt(std::max(0.0, best) / window_s);
}

ElectricalResult compute_electrical(const DriveTrainParams& drive, const std::vector<double>& t,
                                    const RowMatrix& qd, const RowMatrix& tau, double total_mass_kg,
                                    double distance_m) {
  const int T = static_cast<int>(t.size());
  const int J = drive.joints.size();
  ElectricalResult e;
  e.current_A.resize(T, J);
  e.power_W.resize(T, J);
  e.total_power_W.assign(T, 0.0);
  std::vector<double> copper(T, 0.0), friction(T, 0.0), regenerated(T, 0.0);
  RowMatrix joint_copper(T, J);
  for (int i = 0; i < T; ++i) {
    for (int k = 0; k < J; ++k) {
      const ActuatorParams& a = drive.joints[k];
      const double w = qd(i, k);
      const double I = motor_current(a, tau(i, k), w);
      const double drawn = electrical_power(a, tau(i, k), w);
      e.current_A(i, k) = I;
      e.power_W(i, k) = drawn;
      e.total_power_W[i] += drawn;
      joint_copper(i, k) = copper_loss(a, I);
      copper[i] += joint_copper(i, k);
      friction[i] += a.coulomb_friction_Nm * std::abs(w) + a.viscous_friction_Nmsprad * w * w;
      regenerated[i] += std::max(0.0, -drawn);  // r P of a negative P: what returns
    }
  }
  e.energy_J = trapezoid(t, e.total_power_W.data());
  e.copper_loss_J = trapezoid(t, copper.data());
  e.friction_loss_J = trapezoid(t, friction.data());
  e.regenerated_J = trapezoid(t, regenerated.data());
  e.cost_of_transport = e.energy_J / (total_mass_kg * kGravity * distance_m);
  e.energy_joint_J.resize(J);
  e.rms_torque_Nm.resize(J);
  e.window_rms_torque_Nm.resize(J);
  e.continuous_torque_Nm.resize(J);
  for (int k = 0; k < J; ++k) {
    e.continuous_torque_Nm[k] = drive.joints[k].continuous_torque_Nm;
    e.energy_joint_J[k] = trapezoid(t, e.power_W.data() + k, J);
    e.rms_torque_Nm[k] = largest_window_rms(t, tau.data() + k, J, kInfinity);
    e.window_rms_torque_Nm[k] =
        largest_window_rms(t, tau.data() + k, J, drive.joints[k].thermal_window_s);
  }
  add_thermal(drive, t, joint_copper, e);
  return e;
}

}  // namespace hexdyn
