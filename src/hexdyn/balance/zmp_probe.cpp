#include "hexdyn/balance/zmp_probe.hpp"

namespace hexdyn {

ZmpProbe::ZmpProbe(const RobotModel& model, const MotionPlan& plan)
    : model_(model), plan_(plan), data_(model), state_(model) {
  double feet_z = 0.0;
  for (const LegPlan& leg : plan.gait.legs) feet_z += leg.p_initial_W.z();
  feet_z /= static_cast<double>(plan.gait.legs.size());
  height_m_ = plan.trunk.straight_at(0.0).p_W.z() - feet_z;
}

Vec2 ZmpProbe::at(double t) {
  wrench(t);
  return Vec2((z_r_ * F_.x() - M_.y()) / F_.z(), (M_.x() + z_r_ * F_.y()) / F_.z());
}

std::pair<Vec2, double> ZmpProbe::edge_line(double t, const Vec3& p1, const Vec3& p2) {
  wrench(t);
  const Vec3 d = p2 - p1, c = F_.cross(d);
  const Vec2 a(c.x() - d.z() * F_.y(), c.y() + d.z() * F_.x());
  return {a, p1.dot(c) - c.z() * z_r_ - d.z() * M_.z()};
}

void ZmpProbe::wrench(double t) {
  if (t == t_) return;
  t_ = t;
  robot_state_at(model_, plan_, t, state_);
  const DofVector& tau = rnea(model_, data_, state_.trunk, state_.q, state_.qd, state_.qdd);
  F_ = tau.head<3>();
  M_ = tau.segment<3>(3) + state_.trunk.p_W.cross(F_);
  z_r_ = state_.trunk.p_W.z() - height_m_;  // the offset is horizontal
}

}  // namespace hexdyn
