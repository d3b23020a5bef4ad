/// \file model/leg_motion.cpp
/// The leg entry points for legs of any length (robot_model.hpp): each leg as a serial chain,
/// its motion by the three-joint solvers or by the redundant resolution
/// (model/redundant_leg.hpp, docs/theory/model.md#redundant-legs), and its reach.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "hexdyn/model/leg_chain.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

static_assert(kMaxChainJoints == kMaxLegJoints, "a leg chain holds every leg's joints");

namespace {

/// Joint j of leg `leg` as a chain joint in H: the hip joint at H's origin with H's axes (H is
/// the hip joint's frame), the others at their tree placements.
ChainJoint chain_joint(const RobotModel& m, int leg, int j) {
  const int b = m.body(leg, j);
  ChainJoint c;
  if (j > 0) {
    c.p_parent_m = m.p_parent_joint[b];
    c.R_parent = m.R_parent_joint[b];
  }
  c.axis = m.axis[b].normalized();
  c.type = m.prismatic(m.joint(leg, j)) ? ChainJointType::kPrismatic : ChainJointType::kRevolute;
  return c;
}

/// Nominal pose and weights (RobotModel::leg_resolution).
RedundantResolution resolution_of(const RobotModel& m, int leg) {
  const int n = m.leg(leg).n_joints;
  RedundantResolution r;
  r.q_nominal = ChainVector::Zero(n);
  r.weight = ChainVector::Ones(n);
  for (int j = 0; j < n; ++j) {
    const int k = m.joint(leg, j);
    const double lo = m.joint_lower_rad[k], hi = m.joint_upper_rad[k];
    const bool limited = std::isfinite(lo) && std::isfinite(hi) && hi > lo;
    const double range = limited ? hi - lo : (m.prismatic(k) ? 0.1 : 2.0 * M_PI);
    if (limited) r.q_nominal[j] = 0.5 * (lo + hi);
    r.weight[j] = 1.0 / (range * range);
  }
  return r;
}

/// Smallest singular value of a 3 × m Jacobian [m/rad]: the leg's distance to a singularity.
double smallest_singular_value(const LegJacobian& J) {
  const Mat3 JJt = J * J.transpose();
  const Vec3 ev = Eigen::SelfAdjointEigenSolver<Mat3>(JJt, Eigen::EigenvaluesOnly).eigenvalues();
  return std::sqrt(std::max(ev[0], 0.0));
}

/// The resolution of a leg on its chain, and its verdict in `ik`: reached (converged, inside
/// the joint limits, away from a singularity by robot.ik_min_margin) or why not.
RedundantLegMotion chain_leg_solve(const RobotModel& m, int leg, const Vec3& p_H, const Vec3& pd_H,
                                   const Vec3& pdd_H, LegIkResult& ik) {
  const RedundantResolution& res = m.leg_resolution[leg];
  const RedundantLegMotion r =
      redundant_leg_motion(m.leg_chain_table[leg], res, p_H, pd_H, pdd_H, res.q_nominal);
  ik.q = r.q;
  ik.ok = false;
  if (!r.converged) {
    std::ostringstream why;
    why << "no joint positions reach the foot target (the redundant resolution did not "
           "converge; foot error "
        << r.foot_error_m << " m)";
    ik.reason = why.str();
    ik.margin_m = -r.foot_error_m;
    return r;
  }
  for (int j = 0; j < m.leg(leg).n_joints; ++j) {
    const int k = m.joint(leg, j);
    const double lo = m.joint_lower_rad[k], hi = m.joint_upper_rad[k];
    if (r.q[j] < lo || r.q[j] > hi) {
      ik.reason = "joint " + m.joint_source_names[k] + " outside its limits";
      ik.margin_m = std::min(r.q[j] - lo, hi - r.q[j]);
      ik.margin_unit = "rad";
      return r;
    }
  }
  ik.margin_m = smallest_singular_value(chain_jacobian(m.leg_chain_table[leg], r.q));
  if (ik.margin_m < m.ik_min_margin_m) {
    ik.reason = "within robot.ik_min_margin of a singular configuration";
    return r;
  }
  ik.ok = true;
  return r;
}

/// leg_motion_H of a leg of three revolute joints: the kinematics stage's own path, the paper
/// geometry's sines and cosines computed once for J, J̇ and the tree's poses.
void three_joint_motion(const RobotModel& m, int leg, const Vec3& p_H, const Mat3& F_R_H,
                        const Vec3& v_F, const Vec3& a_F, LegMotion& out) {
  out.ik = leg_inverse_kinematics(m, leg, p_H);
  if (!out.ik.ok) return;
  const Vec3 q = out.ik.q;
  const bool paper = m.leg_geometry == LegGeometry::kPaperPlanar;
  const LegTrig trig = paper ? leg_trig(q) : LegTrig{};
  // A chain leg's pose once for J and J̇ (chain_pose: three rotations about its axes).
  const LegChainPose pose = paper ? LegChainPose{} : chain_pose(m, leg, q);
  const Mat3 J = paper ? paper_leg_jacobian_H(m, leg, trig) : chain_jacobian_H(pose);
  const Eigen::PartialPivLU<Mat3> lu(J);
  // ṗ and p̈ in H formed inside the solves' right-hand sides, one expression each, and solved
  // into 3-vectors (a solve into a vector of dynamic size takes another path through Eigen's
  // triangular solves): the kinematics stage's operations as they were, the same bits.
  const Vec3 qd = lu.solve(F_R_H.transpose() * v_F);
  const Mat3 Jd =
      paper ? paper_leg_jacobian_dot_H(m, leg, trig, qd) : chain_jacobian_dot_H(pose, qd);
  const Vec3 qdd = lu.solve(F_R_H.transpose() * a_F - Jd * qd);  // a fixed-size solve
  out.qd = qd;
  out.qdd = qdd;
  out.cos_q.resize(3);
  out.sin_q.resize(3);
  if (paper) {
    out.cos_q[0] = trig.c1;
    out.sin_q[0] = trig.s1;
    out.cos_q[1] = trig.c2;
    out.sin_q[1] = trig.s2;
    out.cos_q[2] = std::cos(q[2]);
    out.sin_q[2] = std::sin(q[2]);
  } else {
    for (int j = 0; j < 3; ++j) {  // the pose's std::cos and std::sin of q
      out.cos_q[j] = pose.cos_q[j];
      out.sin_q[j] = pose.sin_q[j];
    }
  }
}

}  // namespace

void prepare_serial_chains(RobotModel& m) {
  for (int leg = 0; leg < m.legs(); ++leg) {
    const int n = m.leg(leg).n_joints;
    SerialChain& c = m.leg_chain_table[leg];
    c = SerialChain{};
    c.count = n;
    bool prismatic = false;
    for (int j = 0; j < n; ++j) {
      c.joints[static_cast<std::size_t>(j)] = chain_joint(m, leg, j);
      prismatic = prismatic || m.prismatic(m.joint(leg, j));
    }
    c.p_foot_m = m.p_foot_last[leg];
    m.leg_on_chain[leg] = n != 3 || prismatic;
    m.leg_resolution[leg] = resolution_of(m, leg);
    if (!m.leg_on_chain[leg]) continue;
    // Outward direction: the zero-pose foot seen from the hip joint, without its component
    // along the trunk normal (as prepare_leg_chains does for three joints).
    LegIkData& d = m.leg_ik[leg];
    const Vec3 foot0 = chain_foot_position(c, ChainVector::Zero(n));
    const Vec3 out = foot0 - foot0.dot(d.up_H) * d.up_H;
    if (out.norm() >= 1e-9) d.outward_H = out.normalized();
    d.method = LegIkMethod::kNumeric;
    d.q_start = m.leg_resolution[leg].q_nominal.head<3>();
  }
}

void set_leg_nominal_pose(RobotModel& m, int leg, const LegVector& q) {
  m.leg_resolution[leg].q_nominal = q;
  m.leg_ik[leg].q_start = q.head<3>();
}

Vec3 leg_foot_position(const RobotModel& m, int leg, const LegVector& q) {
  if (m.leg_on_chain[leg]) return chain_foot_position(m.leg_chain_table[leg], q);
  return leg_foot_position_H(m, leg, Vec3(q.head<3>()));
}

LegJacobian leg_jacobian(const RobotModel& m, int leg, const LegVector& q) {
  if (m.leg_on_chain[leg]) return chain_jacobian(m.leg_chain_table[leg], q);
  return leg_jacobian_H(m, leg, Vec3(q.head<3>()));
}

LegIkResult chain_leg_inverse_kinematics(const RobotModel& m, int leg, const Vec3& p_H) {
  LegIkResult ik;
  chain_leg_solve(m, leg, p_H, Vec3::Zero(), Vec3::Zero(), ik);
  return ik;
}

void leg_motion_H(const RobotModel& m, int leg, const Vec3& p_H, const Vec3& pd_H,
                  const Vec3& pdd_H, LegMotion& out) {
  leg_motion(m, leg, p_H, Mat3::Identity(), pd_H, pdd_H, out);
}

void leg_motion(const RobotModel& m, int leg, const Vec3& p_H, const Mat3& F_R_H, const Vec3& v_F,
                const Vec3& a_F, LegMotion& out) {
  if (!m.leg_on_chain[leg]) {
    three_joint_motion(m, leg, p_H, F_R_H, v_F, a_F, out);
    return;
  }
  const Vec3 pd_H = F_R_H.transpose() * v_F, pdd_H = F_R_H.transpose() * a_F;
  const RedundantLegMotion r = chain_leg_solve(m, leg, p_H, pd_H, pdd_H, out.ik);
  if (!out.ik.ok) return;
  out.qd = r.qd;
  out.qdd = r.qdd;
  const int n = m.leg(leg).n_joints;
  out.cos_q.resize(n);
  out.sin_q.resize(n);
  for (int j = 0; j < n; ++j) {
    const bool slides = m.prismatic(m.joint(leg, j));
    out.cos_q[j] = slides ? 1.0 : std::cos(r.q[j]);
    out.sin_q[j] = slides ? 0.0 : std::sin(r.q[j]);
  }
}

double leg_reach_m(const RobotModel& m, int leg) {
  if (m.leg_geometry == LegGeometry::kPaperPlanar)
    return leg_foot_position_H(m, leg, Vec3::Zero()).norm();
  const int n = m.leg(leg).n_joints;
  const double at_zero = leg_foot_position(m, leg, LegVector::Zero(n)).norm();
  double segments = 0.0;  // summed hip to foot: for three joints (femur + tibia) + foot
  for (int j = 1; j < n; ++j) segments += m.p_parent_joint[m.body(leg, j)].norm();
  for (int j = 0; j < n; ++j) {
    const int k = m.joint(leg, j);
    const double travel = std::max(std::abs(m.joint_lower_rad[k]), std::abs(m.joint_upper_rad[k]));
    if (m.prismatic(k) && std::isfinite(travel)) segments += travel;
  }
  return std::max(at_zero, segments + m.p_foot_last[leg].norm());
}

double longest_leg_reach_m(const RobotModel& m) {
  double reach_m = 0.0;
  for (int l = 0; l < m.legs(); ++l) reach_m = std::max(reach_m, leg_reach_m(m, l));
  return reach_m;
}

bool has_prismatic_joints(const RobotModel& m) {
  return std::any_of(m.joint_type.begin(), m.joint_type.begin() + m.joints(),
                     [](JointType t) { return t == JointType::kPrismatic; });
}

}  // namespace hexdyn
