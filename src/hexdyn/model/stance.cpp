#include "hexdyn/model/stance.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "hexdyn/model/leg_chain.hpp"

namespace hexdyn {

namespace {

/// Radius and depth of a stance whose foot is at p_H (hip frame).
void set_radius_and_depth(const RobotModel& model, int leg, const Vec3& p_H, NominalStance& s) {
  const Vec3 up_H = model.R_B_H[leg].transpose() * Vec3::UnitZ();
  s.depth_m = -p_H.dot(up_H);
  s.radius_m = (p_H + s.depth_m * up_H).norm();
}

}  // namespace

NominalStance stance_at_pose(const RobotModel& model, int leg, const LegVector& q,
                             std::string source) {
  NominalStance s;
  s.q = q;
  s.source = std::move(source);
  set_radius_and_depth(model, leg, leg_foot_position(model, leg, q), s);
  return s;
}

namespace {

/// The hanging pose of a leg with a rolling hip: the foot straight below its zero-pose point,
/// at the depth hypot(l2, l3) where femur and tibia would stand square to each other.
NominalStance hanging_stance(const RobotModel& model, int leg) {
  const LegIkData& d = model.leg_ik[leg];
  const Vec3 foot0 = leg_foot_position_H(model, leg, Vec3::Zero());
  const Vec3 target = foot0 - (foot0.dot(d.up_H) + std::hypot(d.l2_m, d.l3_m)) * d.up_H;
  const LegIkResult ik = leg_inverse_kinematics(model, leg, target);
  if (ik.ok) return stance_at_pose(model, leg, ik.q, "nominal pose");
  NominalStance s =
      stance_at_pose(model, leg, d.q_start, "fallback: mid-range joint angles (" + ik.reason + ")");
  s.from_pose = false;
  return s;
}

}  // namespace

NominalStance default_nominal_stance(const RobotModel& model, int leg) {
  if (model.leg_on_chain[leg]) {
    // A leg solved on its chain stands at the redundant resolution's nominal pose.
    return stance_at_pose(model, leg, model.leg_resolution[leg].q_nominal,
                          "nominal pose (middle of the joint limits)");
  }
  const LegIkData& d = model.leg_ik[leg];
  if (rolling_hip(d)) return hanging_stance(model, leg);
  // The leg's plane at zero coxa angle: normal w1 (the femur axis); in it, up and outward.
  const Vec3 w1 = d.w1_H.normalized();
  Vec3 up = d.up_H - d.up_H.dot(w1) * w1;
  Vec3 out = up.cross(w1);
  std::string why = "the femur axis is along the trunk normal: no leg plane";
  if (up.norm() > 1e-9 && out.norm() > 1e-9) {
    up.normalize();
    out.normalize();
    if (out.dot(d.outward_H) < 0.0) out = -out;
    // Femur joint in the plane, then the femur level (l2 outward) and the tibia plumb (l3 down);
    // kappa keeps the foot's fixed offset along the femur axis.
    const Vec3 o1 = d.o1_H - d.o1_H.dot(w1) * w1;
    const Vec3 target = o1 + d.kappa_m * w1 + d.l2_m * out - d.l3_m * up;
    const LegIkResult ik = leg_inverse_kinematics(model, leg, target);
    if (ik.ok) return stance_at_pose(model, leg, ik.q, "nominal pose");
    why = ik.reason;
  }
  NominalStance s =
      stance_at_pose(model, leg, d.q_start, "fallback: mid-range joint angles (" + why + ")");
  s.from_pose = false;
  return s;
}

StanceMean stance_mean(std::span<const NominalStance> stance) {
  StanceMean m;
  const int n = static_cast<int>(stance.size());
  for (int leg = 0; leg < n; ++leg)
    if (stance[leg].from_pose) m.legs.push_back(leg);
  if (m.legs.empty())
    for (int leg = 0; leg < n; ++leg) m.legs.push_back(leg);
  for (int leg : m.legs) {
    m.radius_m += stance[leg].radius_m;
    m.depth_m += stance[leg].depth_m;
  }
  m.radius_m /= static_cast<double>(m.legs.size());
  m.depth_m /= static_cast<double>(m.legs.size());
  return m;
}

namespace {

/// "the mean over L1, L2, L4" or "the mean over all " + std::to_string(stance.size()) + " legs,
/// none at its pose".
std::string mean_words(const StanceMean& m, std::span<const NominalStance> stance) {
  if (!stance[m.legs.front()].from_pose)
    return "the mean over all " + std::to_string(stance.size()) + " legs, none at its pose";
  std::string names;
  for (int leg : m.legs) names += (names.empty() ? "" : ", ") + leg_name(leg);
  return "the mean over " + names +
         (m.legs.size() < stance.size() ? ", the legs at their pose" : "");
}

}  // namespace

std::string stance_text(std::span<const NominalStance> stance) {
  std::ostringstream s;
  for (int leg = 0; leg < static_cast<int>(stance.size()); ++leg) {
    const NominalStance& l = stance[leg];
    s << leg_name(leg) << ": " << l.source << ", q [";
    for (int j = 0; j < l.q.size(); ++j) s << (j ? ", " : "") << l.q[j];
    s << "] rad, radius " << l.radius_m << " m, depth " << l.depth_m << " m\n";
  }
  const StanceMean m = stance_mean(stance);
  s << "stance radius " << m.radius_m << " m: " << mean_words(m, stance)
    << " (gait.foot_lateral's default)\n";
  return s.str();
}

std::vector<std::string> stance_fallback_warnings(std::span<const NominalStance> stance) {
  std::vector<std::string> out;
  const StanceMean m = stance_mean(stance);
  const bool all = !stance[m.legs.front()].from_pose;
  for (int leg = 0; leg < static_cast<int>(stance.size()); ++leg) {
    const NominalStance& l = stance[leg];
    if (l.from_pose) continue;
    std::ostringstream s;
    s << leg_name(leg) << ": the nominal pose is out of reach, stance " << l.source << ", radius "
      << l.radius_m << " m, " << (all ? "averaged into" : "left out of")
      << " gait.foot_lateral's default " << m.radius_m << " m (" << mean_words(m, stance)
      << "); give the leg a pose, robot.nominal_pose: {" << leg_name(leg)
      << ": [coxa, femur, tibia]}, or set gait.foot_lateral";
    out.push_back(s.str());
  }
  return out;
}

}  // namespace hexdyn
