#include "hexdyn/planning/motion.hpp"

#include <cmath>

namespace hexdyn {
namespace {

// Smootherstep S(u) = 10u³ − 15u⁴ + 6u⁵ and its integral; the ramp speed is v·S(t/T_r),
// so speed, acceleration and jerk are continuous (position C³).
double ramp_speed(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }
double ramp_speed_d(double u) { return 30.0 * u * u * (1.0 - u) * (1.0 - u); }
double ramp_travel(double u) { return u * u * u * u * (2.5 + u * (-3.0 + u)); }

}  // namespace

TrunkMotion::TrunkMotion(const MotionParams& motion, const GaitParams& gait, const Terrain& terrain,
                         double hold_s) {
  pitch_rad_ = terrain.mean_slope_rad();
  direction_W_ = Vec3(0.0, std::cos(pitch_rad_), std::sin(pitch_rad_));
  W_R_B_ = bryant_to_rotation(Vec3(pitch_rad_, 0.0, 0.0));
  p0_W_ = motion.initial_position_m;
  stride_m_ = (gait.stroke_m / gait.duty_factor) / std::cos(pitch_rad_);
  cycles_ = motion.cycles;
  v_cruise_ = motion.peak_speed_mps;
  t_ramp_ = motion.ramp_duration_s;
  hold_s_ = hold_s;
  duration_s_ = total_travel_m() / v_cruise_ + t_ramp_ + 2.0 * hold_s_;
}

double TrunkMotion::travel(double t) const {
  const double T = moving_s();
  t = std::clamp(t - hold_s_, 0.0, T);
  const double ramp_travel_m = 0.5 * v_cruise_ * t_ramp_;
  if (t < t_ramp_) return v_cruise_ * t_ramp_ * ramp_travel(t / t_ramp_);
  if (t > T - t_ramp_)
    return total_travel_m() - v_cruise_ * t_ramp_ * ramp_travel((T - t) / t_ramp_);
  return ramp_travel_m + v_cruise_ * (t - t_ramp_);
}

double TrunkMotion::speed(double t) const {
  const double T = moving_s();
  t -= hold_s_;
  if (t <= 0.0 || t >= T) return 0.0;
  if (t < t_ramp_) return v_cruise_ * ramp_speed(t / t_ramp_);
  if (t > T - t_ramp_) return v_cruise_ * ramp_speed((T - t) / t_ramp_);
  return v_cruise_;
}

double TrunkMotion::acceleration(double t) const {
  const double T = moving_s();
  t -= hold_s_;
  if (t <= 0.0 || t >= T) return 0.0;
  if (t < t_ramp_) return v_cruise_ / t_ramp_ * ramp_speed_d(t / t_ramp_);
  if (t > T - t_ramp_) return -v_cruise_ / t_ramp_ * ramp_speed_d((T - t) / t_ramp_);
  return 0.0;
}

double TrunkMotion::time_at_travel(double s) const {
  if (s <= 0.0) return hold_s_;
  if (s >= total_travel_m()) return duration_s_ - hold_s_;
  // travel() is continuous and strictly increasing between the holds: bisection to round-off.
  double lo = hold_s_, hi = duration_s_ - hold_s_;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * duration_s_; ++i) {
    const double mid = 0.5 * (lo + hi);
    (travel(mid) < s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> TrunkMotion::cycle_start_times() const {
  std::vector<double> t;
  for (int k = 0; k < cycles_; ++k) t.push_back(k == 0 ? 0.0 : time_at_phase(k));
  return t;
}

BaseState TrunkMotion::at(double t) const {
  BaseState x = straight_at(t);
  if (!offset_) return x;
  const OffsetState e = offset_->at(t);
  x.p_W.head<2>() += e.e;
  x.v_W.head<2>() += e.ed;
  x.a_W.head<2>() += e.edd;
  return x;
}

BaseState TrunkMotion::straight_at(double t) const {
  BaseState x;
  x.p_W = p0_W_ + travel(t) * direction_W_;
  x.v_W = speed(t) * direction_W_;
  x.a_W = acceleration(t) * direction_W_;
  x.W_R_B = W_R_B_;
  return x;
}

}  // namespace hexdyn
