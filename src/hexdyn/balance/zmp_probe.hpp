#pragma once
/// \file zmp_probe.hpp
/// The whole robot's zero-moment point and the exact support lines of two feet, for the
/// balanced trunk's passes (balance.hpp, docs/theory/balance.md#the-zero-moment-point and
/// #edges). Internal to the balance stage.
#include <limits>
#include <utility>

#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

/// The wrench the feet must supply for the plan as it stands (its trunk's offset included), from
/// the full inverse dynamics with no foot force (dynamics/rnea.hpp), and what follows from it:
/// the ZMP on the horizontal plane z_r(t) = z_P0(t) − h0 (h0 the trunk origin's height above
/// the feet's mean at t = 0) and the exact line of two feet. The plan is read, never changed; a
/// probe keeps the wrench of its last instant, so forget() must follow every change of the
/// plan's offset.
class ZmpProbe {
 public:
  ZmpProbe(const RobotModel& model, const MotionPlan& plan);

  /// h0 [m].
  double height_m() const { return height_m_; }

  /// Drops the wrench kept for its instant (the path changed).
  void forget() { t_ = std::numeric_limits<double>::quiet_NaN(); }

  /// The ZMP at t, world x and y [m].
  Vec2 at(double t);

  /// The line of the ZMP plane on which two feet p1, p2 (world [m]) alone can supply the
  /// wrench at t, as {p : a · p = b}: the moment about the line through the feet vanishes,
  /// d · (M − p1 × F) = 0 with d = p2 − p1. Written with the ZMP p, M = p × F + M_pz ẑ and
  /// M_pz = M_z − p_x F_y + p_y F_x; F and M_z are taken as the path's (the offset moves M_x
  /// and M_y, the ZMP, far more than F or M_z). a is not normalised.
  std::pair<Vec2, double> edge_line(double t, const Vec3& p1, const Vec3& p2);

 private:
  /// The wrench at t, F and M about the world origin, and z_r there (kept for t).
  void wrench(double t);

  const RobotModel& model_;
  const MotionPlan& plan_;
  RobotData data_;
  RobotKinematicState state_;
  double height_m_ = 0.0;
  Vec3 F_ = Vec3::Zero(), M_ = Vec3::Zero();
  double z_r_ = 0.0;
  double t_ = std::numeric_limits<double>::quiet_NaN();  ///< the instant F_, M_, z_r_ hold for
};

}  // namespace hexdyn
