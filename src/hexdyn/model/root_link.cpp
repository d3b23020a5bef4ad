#include "hexdyn/model/root_link.hpp"

namespace hexdyn {
namespace {

/// The state of the frame at offset r_B (trunk axes) with axes R_rel relative to `from`'s,
/// both fixed in the same rigid body: its pose, and the velocity and acceleration of its
/// origin (world axes).
BaseState moved_frame(const BaseState& from, const Vec3& r_B, const Mat3& R_rel) {
  BaseState to = from;
  const Vec3 r = from.W_R_B * r_B;
  to.W_R_B = from.W_R_B * R_rel;
  to.p_W = from.p_W + r;
  to.v_W = from.v_W + from.omega_W.cross(r);
  to.a_W = from.a_W + from.omegadot_W.cross(r) + from.omega_W.cross(from.omega_W.cross(r));
  return to;
}

}  // namespace

BaseState root_link_state(const RobotModel& model, const BaseState& trunk) {
  return moved_frame(trunk, model.p_B_root, model.B_R_root);
}

BaseState trunk_state_from_root_link(const RobotModel& model, const BaseState& root) {
  // In the root frame's axes the trunk origin is at −B_R_rootᵀ p_B_root, its axes B_R_rootᵀ.
  const Mat3 root_R_B = model.B_R_root.transpose();
  return moved_frame(root, -(root_R_B * model.p_B_root), root_R_B);
}

}  // namespace hexdyn
