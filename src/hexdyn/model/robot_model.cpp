#include "hexdyn/model/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "hexdyn/model/leg_chain.hpp"
#include "hexdyn/model/paper_robot.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {
namespace {

/// Bodies of the tree: 1 + the last body with a parent (unused entries hold -1); every body
/// before it has a parent that comes before it.
int count_bodies(const RobotModel& m) {
  int n = 1;
  for (int b = 1; b < kMaxBodies; ++b)
    if (m.parent[b] >= 0) n = b + 1;
  for (int b = 1; b < n; ++b)
    if (m.parent[b] < 0 || m.parent[b] >= b)
      throw std::logic_error("robot model: body " + std::to_string(b) + " has parent " +
                             std::to_string(m.parent[b]) +
                             "; each body's parent is a body before it");
  return n;
}

/// One line of a refused leg table: the leg (by its place) and the body.
[[noreturn]] void refuse_leg(int n, int b, const std::string& what) {
  throw std::logic_error("robot model: leg " + leg_name(n) + " (hip body " + std::to_string(b) +
                         "): " + what);
}

/// The leg whose hip moves body b (a child of the trunk), the n-th in body order: its chain
/// of single children, flat, kMinLegJoints … kMaxLegJoints joints, hip off the centre line.
LegInfo scan_leg(const RobotModel& m, int n_bodies, int n, int b) {
  LegInfo leg;
  leg.name = leg_name(n);
  leg.first_body = b;
  leg.first_joint = b - 1;
  leg.n_joints = 1;
  leg.foot_body = b;
  for (;;) {
    int child = -1, children = 0;
    for (int c = leg.foot_body + 1; c < n_bodies; ++c)
      if (m.parent[c] == leg.foot_body) {
        if (children++ == 0) child = c;
      }
    if (children == 0) break;
    if (children > 1)
      refuse_leg(n, b,
                 "the chain branches at body " + std::to_string(leg.foot_body) + " (" +
                     std::to_string(children) + " children); a leg is a single chain");
    if (child != leg.foot_body + 1)
      refuse_leg(n, b,
                 "body " + std::to_string(child) + " follows body " +
                     std::to_string(leg.foot_body) +
                     "; a leg's bodies are consecutive (flat joint order, leg by leg)");
    leg.foot_body = child;
    ++leg.n_joints;
  }
  if (leg.n_joints < kMinLegJoints || leg.n_joints > kMaxLegJoints)
    refuse_leg(n, b,
               std::to_string(leg.n_joints) + " joints (bodies " + std::to_string(b) + " to " +
                   std::to_string(leg.foot_body) + "); a leg has " + std::to_string(kMinLegJoints) +
                   " to " + std::to_string(kMaxLegJoints));
  const double x = m.p_parent_joint[b].x();
  if (std::abs(x) <= 1e-9)
    refuse_leg(n, b,
               "hip on the trunk's centre line (x = " + std::to_string(x) +
                   " m); a hip is left (x < 0) or right (x > 0) of it");
  leg.side = x < 0.0 ? LegSide::kLeft : LegSide::kRight;
  return leg;
}

}  // namespace

void fill_leg_table(RobotModel& m) {
  const int n_bodies = count_bodies(m);
  std::array<int, 2> per_side{};
  int n = 0, next_body = 1;
  for (int b = 1; b < n_bodies; ++b) {
    if (m.parent[b] != 0) continue;
    if (n == kMaxLegs) refuse_leg(n, b, "more than " + std::to_string(kMaxLegs) + " legs");
    if (b != next_body)
      refuse_leg(n, b,
                 "starts after body " + std::to_string(next_body - 1) +
                     "; each leg's hip is the body after the previous leg's foot");
    LegInfo leg = scan_leg(m, n_bodies, n, b);
    leg.row = per_side[static_cast<int>(leg.side)]++;
    next_body = leg.foot_body + 1;
    m.leg_table[n++] = leg;
  }
  if (n < kMinLegs || next_body != n_bodies)
    throw std::logic_error("robot model: " + std::to_string(n) + " legs over bodies 1 to " +
                           std::to_string(n_bodies - 1) + "; a robot has " +
                           std::to_string(kMinLegs) + " to " + std::to_string(kMaxLegs) +
                           " legs, every body in one of them");
  m.n_legs = n;
  m.n_joints = 0;
  for (int l = 0; l < m.n_legs; ++l) m.n_joints += m.leg_table[l].n_joints;
  m.n_bodies = 1 + m.n_joints;
}

namespace {

/// The robot of the YAML keys has legs of a coxa, a femur and a tibia (core/scene.hpp).
void check_yaml_robot_counts(const RobotParams& params) {
  if (params.leg_joints != kYamlRobotLegJoints || params.legs < kMinLegs || params.legs > kMaxLegs)
    throw std::logic_error("robot model: the YAML robot has legs of " +
                           std::to_string(kYamlRobotLegJoints) + " joints, got " +
                           std::to_string(params.legs) + " legs of " +
                           std::to_string(params.leg_joints));
}

}  // namespace

RobotModel build_robot_model(const RobotParams& params) {
  RobotModel m;
  if (params.urdf) {
    m = build_robot_model(*params.urdf, params.ik_min_margin_m);
    // A leg on its chain resolves toward its stance: the default one is the resolution's own
    // nominal pose, robot.nominal_pose replaces it (model/stance.hpp).
    if (static_cast<int>(params.stance.size()) == m.legs())
      for (int l = 0; l < m.legs(); ++l)
        if (m.leg_on_chain[l]) set_leg_nominal_pose(m, l, params.stance[l].q);
  } else {
    check_yaml_robot_counts(params);
    // The one builder on the YAML robot's description, then its closed forms as a shortcut
    // (model/paper_robot.hpp).
    m = build_robot_model(paper_description(params), params.ik_min_margin_m);
    use_paper_closed_forms(m, params);
  }
  if (params.drive.present && params.drive.joints.size() != m.joints())
    throw std::logic_error("robot model: drive trains for " +
                           std::to_string(params.drive.joints.size()) + " joints, the robot has " +
                           std::to_string(m.joints()));
  m.drive = params.drive;
  return m;
}

// Foot in the coxa frame: f(β2, β3) = (l1 + l2 c2 + l3 c23, w, −d1 + l2 s2 + l3 s23);
// p_H = Rz(θ1) f.
Vec3 leg_foot_position_H(const RobotModel& m, int leg, const Vec3& q) {
  if (m.leg_geometry == LegGeometry::kChain) return chain_foot_position_H(m, leg, q);
  const auto& L = m.link_length_m;
  const double c1 = std::cos(q[0]), s1 = std::sin(q[0]);
  const double rho = L[0] + L[1] * std::cos(q[1]) + L[2] * std::cos(q[1] + q[2]);
  const double z = -m.d1_m + L[1] * std::sin(q[1]) + L[2] * std::sin(q[1] + q[2]);
  const double w = m.lateral_m[leg];
  return Vec3(c1 * rho - s1 * w, s1 * rho + c1 * w, z);
}

LegTrig leg_trig(const Vec3& q) {
  LegTrig t;
  t.c1 = std::cos(q[0]);
  t.s1 = std::sin(q[0]);
  t.s2 = std::sin(q[1]);
  t.c2 = std::cos(q[1]);
  t.s23 = std::sin(q[1] + q[2]);
  t.c23 = std::cos(q[1] + q[2]);
  return t;
}

Mat3 leg_jacobian_H(const RobotModel& m, int leg, const Vec3& q) {
  if (m.leg_geometry == LegGeometry::kChain) return chain_jacobian_H(m, leg, q);
  return paper_leg_jacobian_H(m, leg, leg_trig(q));
}

Mat3 leg_jacobian_dot_H(const RobotModel& m, int leg, const Vec3& q, const Vec3& qd) {
  if (m.leg_geometry == LegGeometry::kChain) return chain_jacobian_dot_H(m, leg, q, qd);
  return paper_leg_jacobian_dot_H(m, leg, leg_trig(q), qd);
}

Mat3 paper_leg_jacobian_H(const RobotModel& m, int leg, const LegTrig& t) {
  const auto& L = m.link_length_m;
  const double c1 = t.c1, s1 = t.s1, s2 = t.s2, c2 = t.c2, s23 = t.s23, c23 = t.c23;
  const double rho = L[0] + L[1] * c2 + L[2] * c23;
  const double w = m.lateral_m[leg];
  const double drho2 = -L[1] * s2 - L[2] * s23, drho3 = -L[2] * s23;
  const double dz2 = L[1] * c2 + L[2] * c23, dz3 = L[2] * c23;
  Mat3 J;
  J << -s1 * rho - c1 * w, c1 * drho2, c1 * drho3,  //
      c1 * rho - s1 * w, s1 * drho2, s1 * drho3,    //
      0.0, dz2, dz3;
  return J;
}

Mat3 paper_leg_jacobian_dot_H(const RobotModel& m, int leg, const LegTrig& t, const Vec3& qd) {
  const auto& L = m.link_length_m;
  const double c1 = t.c1, s1 = t.s1, s2 = t.s2, c2 = t.c2, s23 = t.s23, c23 = t.c23;
  const double w = m.lateral_m[leg];
  const double t1 = qd[0], t2 = qd[1], t23 = qd[1] + qd[2];
  const double rho = L[0] + L[1] * c2 + L[2] * c23;
  const double drho2 = -L[1] * s2 - L[2] * s23, drho3 = -L[2] * s23;
  // time derivatives of rho, drho2, drho3, dz2, dz3
  const double rho_t = drho2 * t2 + drho3 * qd[2];
  const double drho2_t = -L[1] * c2 * t2 - L[2] * c23 * t23;
  const double drho3_t = -L[2] * c23 * t23;
  const double dz2_t = -L[1] * s2 * t2 - L[2] * s23 * t23;
  const double dz3_t = -L[2] * s23 * t23;
  Mat3 Jd;
  Jd(0, 0) = -c1 * t1 * rho - s1 * rho_t + s1 * t1 * w;
  Jd(1, 0) = -s1 * t1 * rho + c1 * rho_t - c1 * t1 * w;
  Jd(2, 0) = 0.0;
  Jd(0, 1) = -s1 * t1 * drho2 + c1 * drho2_t;
  Jd(1, 1) = c1 * t1 * drho2 + s1 * drho2_t;
  Jd(2, 1) = dz2_t;
  Jd(0, 2) = -s1 * t1 * drho3 + c1 * drho3_t;
  Jd(1, 2) = c1 * t1 * drho3 + s1 * drho3_t;
  Jd(2, 2) = dz3_t;
  return Jd;
}

LegIkResult leg_inverse_kinematics(const RobotModel& m, int leg, const Vec3& p) {
  if (m.leg_on_chain[leg]) return chain_leg_inverse_kinematics(m, leg, p);
  if (m.leg_geometry == LegGeometry::kChain) return chain_inverse_kinematics(m, leg, p);
  LegIkResult r;
  const auto& L = m.link_length_m;
  const double w = m.lateral_m[leg];
  const double r2 = p.x() * p.x() + p.y() * p.y();
  if (r2 <= w * w + 1e-12) {
    r.reason = "foot inside the lateral offset of the coxa axis";
    r.margin_m = std::sqrt(r2) - std::abs(w);
    return r;
  }
  const double rho = std::sqrt(r2 - w * w);
  const double theta1 = std::atan2(p.y(), p.x()) - std::atan2(w, rho);
  const double u = rho - L[0];
  const double v = p.z() + m.d1_m;
  const double dist = std::hypot(u, v);
  if (!planar_reach_ok(dist, L[1], L[2], m.ik_min_margin_m, r)) return r;
  const double cos3 = (u * u + v * v - L[1] * L[1] - L[2] * L[2]) / (2.0 * L[1] * L[2]);
  const double beta3 = -std::acos(std::clamp(cos3, -1.0, 1.0));  // knee up
  const double beta2 =
      std::atan2(v, u) - std::atan2(L[2] * std::sin(beta3), L[1] + L[2] * std::cos(beta3));
  r.q = Vec3(wrap_angle(theta1), wrap_angle(beta2), beta3);
  for (int j = 0; j < m.leg(leg).n_joints; ++j) {
    const double lo = m.joint_lower_rad[m.joint(leg, j)], hi = m.joint_upper_rad[m.joint(leg, j)];
    if (r.q[j] < lo || r.q[j] > hi) {
      r.reason = "joint " + joint_name(leg, j) + " outside its limits";
      r.margin_m = std::min(r.q[j] - lo, hi - r.q[j]);
      r.margin_unit = "rad";
      return r;
    }
  }
  r.ok = true;
  return r;
}

void forward_kinematics_tree(const RobotModel& m, const JointVector& q, BodyPoses& out) {
  JointVector cos_q(m.joints()), sin_q(m.joints());
  for (int k = 0; k < m.joints(); ++k) {
    cos_q[k] = std::cos(q[k]);
    sin_q[k] = std::sin(q[k]);
  }
  forward_kinematics_tree(m, cos_q, sin_q, out);
  if (std::none_of(m.joint_type.begin(), m.joint_type.begin() + m.joints(),
                   [](JointType t) { return t == JointType::kPrismatic; }))
    return;
  // A prismatic joint slides its body along the axis without turning it: every body placed
  // again, in body order (its parent first); a revolute joint as above.
  for (int b = 1; b < m.bodies(); ++b) {
    const int p = m.parent[b];
    if (m.prismatic(b - 1)) {
      out.p_B[b] = out.p_B[p] +
                   out.R_B[p] * (m.p_parent_joint[b] + m.R_parent_joint[b] * m.axis[b] * q[b - 1]);
      out.R_B[b] = out.R_B[p] * m.R_parent_joint[b];
    } else {
      out.p_B[b] = out.p_B[p] + out.R_B[p] * m.p_parent_joint[b];
      out.R_B[b] =
          out.R_B[p] * m.R_parent_joint[b] * rot_axis_cs(m.axis[b], cos_q[b - 1], sin_q[b - 1]);
    }
  }
}

void forward_kinematics_tree(const RobotModel& m, const JointVector& cos_q,
                             const JointVector& sin_q, BodyPoses& out) {
  out.R_B[0].setIdentity();
  out.p_B[0].setZero();
  for (int b = 1; b < m.bodies(); ++b) {
    const int p = m.parent[b];
    out.p_B[b] = out.p_B[p] + out.R_B[p] * m.p_parent_joint[b];
    out.R_B[b] =
        out.R_B[p] * m.R_parent_joint[b] * rot_axis_cs(m.axis[b], cos_q[b - 1], sin_q[b - 1]);
  }
}

Mat3 rot_axis_cs(const Vec3& axis, double c, double s) {
  // Eigen/src/Geometry/AngleAxis.h, AngleAxis::toRotationMatrix, term for term.
  const Vec3 sin_axis = s * axis;
  const Vec3 cos1_axis = (1.0 - c) * axis;
  Mat3 R;
  double tmp = cos1_axis.x() * axis.y();
  R(0, 1) = tmp - sin_axis.z();
  R(1, 0) = tmp + sin_axis.z();
  tmp = cos1_axis.x() * axis.z();
  R(0, 2) = tmp + sin_axis.y();
  R(2, 0) = tmp - sin_axis.y();
  tmp = cos1_axis.y() * axis.z();
  R(1, 2) = tmp - sin_axis.x();
  R(2, 1) = tmp + sin_axis.x();
  R.diagonal() = cos1_axis.cwiseProduct(axis).array() + c;
  return R;
}

Vec3 tree_foot_position_B(const RobotModel& m, const BodyPoses& poses, int leg) {
  const int b_foot = m.foot_body(leg);
  return poses.p_B[b_foot] + poses.R_B[b_foot] * m.p_foot_last[leg];
}

bool has_sphere_feet(const RobotModel& m) {
  return std::any_of(m.foot_radius_m.begin(), m.foot_radius_m.begin() + m.legs(),
                     [](double r) { return r > 0.0; });
}

Vec3 center_of_mass_B(const RobotModel& m, const BodyPoses& poses) {
  Vec3 c = Vec3::Zero();
  for (int b = 0; b < m.bodies(); ++b)
    c += m.inertia[b].mass_kg * (poses.p_B[b] + poses.R_B[b] * m.inertia[b].com_m);
  return c / m.total_mass_kg;
}

RigidInertia combine_inertias(const RigidInertia& a, const RigidInertia& b) {
  if (b.mass_kg == 0.0) return a;
  if (a.mass_kg == 0.0) return b;
  RigidInertia r;
  r.mass_kg = a.mass_kg + b.mass_kg;
  r.com_m = (a.mass_kg * a.com_m + b.mass_kg * b.com_m) / r.mass_kg;
  auto shift = [&](const RigidInertia& x) {
    const Vec3 d = x.com_m - r.com_m;
    return Mat3(x.inertia_com +
                x.mass_kg * (d.squaredNorm() * Mat3::Identity() - d * d.transpose()));
  };
  r.inertia_com = shift(a) + shift(b);
  return r;
}

bool planar_reach_ok(double dist_m, double l2_m, double l3_m, double min_margin_m, LegIkResult& r) {
  const double margin_ext = (l2_m + l3_m) - dist_m;
  const double margin_fold = dist_m - std::abs(l2_m - l3_m);
  r.margin_m = std::min(margin_ext, margin_fold);
  if (margin_ext < min_margin_m) {
    r.reason =
        margin_ext < 0.0 ? "beyond full extension" : "within robot.ik_min_margin of full extension";
    return false;
  }
  if (margin_fold < min_margin_m) {
    r.reason = margin_fold < 0.0 ? "inside full fold" : "within robot.ik_min_margin of full fold";
    return false;
  }
  return true;
}

}  // namespace hexdyn
