#pragma once
/// \file zmp_probe.hpp
/// The whole robot's zero-moment point and the exact support lines of two feet, for the
/// balanced trunk's passes (balance.hpp, docs/theory/balance.md#the-zero-moment-point and
/// #edges). Internal to the balance stage.
#include <utility>

#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

/// The wrench the feet must supply at one instant (ZmpProbe::wrench_at): F and M about the
/// world origin [N, N m], world axes, and z_r, the height of the ZMP plane there [m].
struct ZmpWrench {
  Vec3 F = Vec3::Zero(), M = Vec3::Zero();
  double z_r = 0.0;
};

/// The wrench the feet must supply for the plan as it stands (its trunk's offset included), from
/// the full inverse dynamics with no foot force (dynamics/rnea.hpp), and what follows from it:
/// the ZMP on the horizontal plane z_r(t) = z_P0(t) − h0 (h0 the trunk origin's height above
/// the feet's mean at t = 0) and the exact line of two feet. The plan is read, never changed:
/// a wrench is the plan's at the moment it is taken.
class ZmpProbe {
 public:
  ZmpProbe(const RobotModel& model, const MotionPlan& plan);

  /// h0 [m].
  double height_m() const { return height_m_; }

  /// The wrench at t.
  ZmpWrench wrench_at(double t);

  /// The ZMP of wrench w, world x and y [m].
  static Vec2 zmp(const ZmpWrench& w);

  /// The line of the ZMP plane on which two feet p1, p2 (world [m]) alone can supply the
  /// wrench w, as {p : a · p = b}: the moment about the line through the feet vanishes,
  /// d · (M − p1 × F) = 0 with d = p2 − p1. Written with the ZMP p, M = p × F + M_pz ẑ and
  /// M_pz = M_z − p_x F_y + p_y F_x; F and M_z are taken as the path's (the offset moves M_x
  /// and M_y, the ZMP, far more than F or M_z). a is not normalised.
  static std::pair<Vec2, double> edge_line(const ZmpWrench& w, const Vec3& p1, const Vec3& p2);

 private:
  const RobotModel& model_;
  const MotionPlan& plan_;
  RobotData data_;
  RobotKinematicState state_;
  double height_m_ = 0.0;
};

}  // namespace hexdyn
