#pragma once
/// \file motion.hpp
/// Trunk motion along the mean terrain slope (docs/theory/stages.md#motion-planning): the
/// trunk frame keeps Bryant angles (α0, 0, 0) with α0 the mean slope, and P0 travels along
/// e = (0, cos α0, sin α0) with a C² speed profile: a smootherstep ramp from rest to
/// the cruise speed, cruise, and the mirrored ramp to rest. One gait cycle is one
/// stride of travel, s0/β horizontally, so the gait phase τ = travel / stride.
///
/// A balanced trunk (motion.trunk: balanced, balance/balance.hpp) adds a horizontal offset
/// e(t) (planning/trunk_offset.hpp) to P0's path: at() then returns the straight path plus
/// e, ė, ë; travel, phase and the footholds stay those of the straight path. Such a trunk
/// also stands still for hold_s at the start and at the end (settle_time_s in
/// planning/posture.hpp): the travel then runs over [hold_s, duration_s − hold_s].
#include <memory>
#include <vector>

#include "hexdyn/core/base_state.hpp"
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/planning/terrain.hpp"
#include "hexdyn/planning/trunk_offset.hpp"

namespace hexdyn {

class TrunkMotion {
 public:
  /// hold_s ≥ 0: the time the trunk stands still before its travel starts and after it ends
  /// [s]; 0 (every straight trunk) leaves the motion that of the speed profile alone.
  TrunkMotion(const MotionParams& motion, const GaitParams& gait, const Terrain& terrain,
              double hold_s = 0.0);

  /// Trunk state at t (ω and ω̇ zero: the attitude is constant), the offset included.
  BaseState at(double t_s) const;
  /// The straight path's state at t, without the offset.
  BaseState straight_at(double t_s) const;
  /// Adds a horizontal offset to the path (null: none, the straight path).
  void set_offset(std::shared_ptr<const TrunkOffset> offset) { offset_ = std::move(offset); }
  const TrunkOffset* offset() const { return offset_.get(); }
  const std::shared_ptr<const TrunkOffset>& shared_offset() const { return offset_; }
  /// Travel along the slope s(t) [m], speed ṡ and acceleration s̈.
  double travel(double t_s) const;
  double speed(double t_s) const;
  double acceleration(double t_s) const;
  /// Inverse of travel(): the time at which the trunk has travelled s (0 ≤ s ≤ total); the
  /// end of the first hold for s ≤ 0, the start of the last for s ≥ total.
  double time_at_travel(double s_m) const;
  /// Gait phase in cycles, τ(t) = s(t) / stride, and its inverse.
  double phase(double t_s) const { return travel(t_s) / stride_m_; }
  double time_at_phase(double tau) const { return time_at_travel(tau * stride_m_); }
  /// Start of each gait cycle k = 0 … cycles−1, where the phase τ reaches k [s]: 0, then
  /// the given cycle durations' partial sums (motion.cycle_durations) or, for a scene given
  /// by its speed, the instants the trunk has travelled k strides.
  std::vector<double> cycle_start_times() const;
  /// P0 when the trunk has travelled τ strides; extrapolated linearly outside [0, cycles].
  Vec3 position_at_phase(double tau) const { return p0_W_ + tau * stride_m_ * direction_W_; }

  double duration_s() const { return duration_s_; }
  double stride_m() const { return stride_m_; }  ///< along the slope, per cycle
  double total_travel_m() const { return cycles_ * stride_m_; }
  int cycles() const { return cycles_; }
  double cruise_speed_mps() const { return v_cruise_; }
  double ramp_duration_s() const { return t_ramp_; }
  double hold_s() const { return hold_s_; }  ///< standing still at each end [s]
  const Mat3& W_R_B() const { return W_R_B_; }
  double pitch_rad() const { return pitch_rad_; }

 private:
  Vec3 p0_W_, direction_W_;
  Mat3 W_R_B_;
  double pitch_rad_ = 0.0, stride_m_ = 0.0, v_cruise_ = 0.0, t_ramp_ = 0.0, duration_s_ = 0.0;
  double hold_s_ = 0.0;
  /// The travel's own duration, without the holds [s].
  double moving_s() const { return duration_s_ - 2.0 * hold_s_; }
  int cycles_ = 0;
  std::shared_ptr<const TrunkOffset> offset_;
};

}  // namespace hexdyn
