#include "hexdyn/balance/zmp_probe.hpp"

namespace hexdyn {

ZmpProbe::ZmpProbe(const RobotModel& model, const MotionPlan& plan)
    : model_(model), plan_(plan), data_(model), state_(model) {
  height_m_ = plan.trunk.straight_at(0.0).p_W.z() - mean_initial_foot_z(plan.gait);
}

Vec2 ZmpProbe::zmp(const ZmpWrench& w) {
  return Vec2((w.z_r * w.F.x() - w.M.y()) / w.F.z(), (w.M.x() + w.z_r * w.F.y()) / w.F.z());
}

std::pair<Vec2, double> ZmpProbe::edge_line(const ZmpWrench& w, const Vec3& p1, const Vec3& p2) {
  const Vec3 d = p2 - p1, c = w.F.cross(d);
  const Vec2 a(c.x() - d.z() * w.F.y(), c.y() + d.z() * w.F.x());
  return {a, p1.dot(c) - c.z() * w.z_r - d.z() * w.M.z()};
}

ZmpWrench ZmpProbe::wrench_at(double t) {
  robot_state_at(model_, plan_, t, state_);
  const DofVector& tau = rnea(model_, data_, state_.trunk, state_.q, state_.qd, state_.qdd);
  ZmpWrench w;
  w.F = tau.head<3>();
  w.M = tau.segment<3>(3) + state_.trunk.p_W.cross(w.F);
  w.z_r = state_.trunk.p_W.z() - height_m_;  // the offset is horizontal
  return w;
}

}  // namespace hexdyn
