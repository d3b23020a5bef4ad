#include "hexdyn/model/stance.hpp"

#include <cmath>

namespace hexdyn {

NominalStance stance_at_pose(const RobotModel& model, int leg, const Vec3& q) {
  NominalStance s;
  s.q = q;
  const Vec3 up_H = model.R_B_H[leg].transpose() * Vec3::UnitZ();
  const Vec3 p_H = leg_foot_position_H(model, leg, q);
  s.depth_m = -p_H.dot(up_H);
  s.radius_m = (p_H + s.depth_m * up_H).norm();
  return s;
}

NominalStance default_nominal_stance(const RobotModel& model, int leg) {
  const LegIkData& d = model.leg_ik[leg];
  // The leg's plane at zero coxa angle: normal w1 (the femur axis); in it, up and outward.
  const Vec3 w1 = d.w1_H.normalized();
  Vec3 up = d.up_H - d.up_H.dot(w1) * w1;
  Vec3 out = up.cross(w1);
  if (up.norm() > 1e-9 && out.norm() > 1e-9) {
    up.normalize();
    out.normalize();
    if (out.dot(d.outward_H) < 0.0) out = -out;
    // Femur joint in the plane, then the femur level (l2 outward) and the tibia plumb (l3 down);
    // kappa keeps the foot's fixed offset along the femur axis.
    const Vec3 o1 = d.o1_H - d.o1_H.dot(w1) * w1;
    const Vec3 target = o1 + d.kappa_m * w1 + d.l2_m * out - d.l3_m * up;
    const LegIkResult ik = leg_inverse_kinematics(model, leg, target);
    if (ik.ok) return stance_at_pose(model, leg, ik.q);
  }
  NominalStance s = stance_at_pose(model, leg, d.q_start);
  s.from_pose = false;
  return s;
}

}  // namespace hexdyn
