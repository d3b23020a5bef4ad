#include "hexdyn/dynamics/rnea.hpp"

#include <cmath>

namespace hexdyn {
namespace {

/// Where the terrain acts on leg l's foot body, in its frame: the foot point, or a sphere
/// foot's contact point centre − r n (n: normals_W[l], +z when null; rnea.hpp), from the
/// foot body's pose in data.X_world_body.
Vec3 contact_point_foot(const RobotModel& model, const RobotData& data, int l,
                        LegVectors normals_W) {
  const double r = model.foot_radius_m[l];
  if (r == 0.0) return model.p_foot_last[l];
  const Vec3 n_W = !normals_W.empty() ? normals_W[l] : Vec3::UnitZ();
  return model.p_foot_last[l] - r * (data.X_world_body[model.foot_body(l)].R.transpose() * n_W);
}

Inertia to_spatial(const RigidInertia& r) { return Inertia{r.mass_kg, r.com_m, r.inertia_com}; }

/// Motion subspace of the joint that moves body b, body coordinates: [a; 0] (revolute) or
/// [0; a] (prismatic).
Motion joint_subspace(const RobotModel& model, int b) {
  return model.prismatic(b - 1) ? Motion{Vec3::Zero(), model.axis[b]}
                                : Motion{model.axis[b], Vec3::Zero()};
}

/// S_bᵀ f: the generalised force of joint b for a force f across it (body coordinates).
double joint_force(const RobotModel& model, int b, const Force& f) {
  return model.prismatic(b - 1) ? model.axis[b].dot(f.linear) : model.axis[b].dot(f.angular);
}

/// Spatial velocity and acceleration of the trunk in trunk coordinates from the base
/// state. The spatial linear acceleration is that of the body-fixed point at P0 seen
/// from a fixed point of space: a_P0 − ω × v_P0. `gravity_W` is subtracted from the
/// acceleration (Featherstone's fictitious upward acceleration).
void base_motion(const BaseState& s, const Vec3& a_P0_W, const Vec3& omegadot_W,
                 const Vec3& gravity_W, Motion& v0_B, Motion& a0_B) {
  const Mat3 B_R_W = s.W_R_B.transpose();
  v0_B = Motion{B_R_W * s.omega_W, B_R_W * s.v_W};
  a0_B = Motion{B_R_W * omegadot_W, B_R_W * (a_P0_W - gravity_W) - v0_B.angular.cross(v0_B.linear)};
}

/// Forward pass of the recursive Newton–Euler algorithm: body velocities and
/// accelerations in body coordinates, from the trunk's and the joint rates.
void forward_motion_pass(const RobotModel& model, RobotData& data, const Motion& v0_B,
                         const Motion& a0_B, const JointVector& qd, const JointVector* qdd) {
  data.v_body[0] = v0_B;
  data.a_body[0] = a0_B;
  for (int b = 1; b < model.bodies(); ++b) {
    const int p = model.parent[b];
    const Transform& X = data.X_parent_body[b];
    const Motion S = joint_subspace(model, b);  // motion subspace, body coordinates
    const Motion v_joint = qd[b - 1] * S;
    data.v_body[b] = X.apply_inverse(data.v_body[p]) + v_joint;
    data.a_body[b] = X.apply_inverse(data.a_body[p]) + cross(data.v_body[b], v_joint);
    if (qdd != nullptr) data.a_body[b] += (*qdd)[b - 1] * S;
  }
}

}  // namespace

void foot_jacobians_at_poses(const RobotModel& model, RobotData& data, const BaseState& state,
                             LegVectors normals_W) {
  for (int l = 0; l < model.legs(); ++l) {
    const Vec3 r_foot = contact_point_foot(model, data, l, normals_W);
    const Vec3 p_foot_W = data.X_world_body[model.foot_body(l)].apply_point(r_foot);
    data.p_foot_W[l] = p_foot_W;
    DofJacobian& J = data.J_foot_W[l];
    J.setZero();
    J.block<3, 3>(0, 0).setIdentity();
    J.block<3, 3>(0, 3) = -skew(p_foot_W - state.p_W);
    for (int j = 0; j < model.leg(l).n_joints; ++j) {
      const int k = model.joint(l, j), b = model.body(l, j);
      const Transform& X = data.X_world_body[b];
      J.col(6 + k) = model.prismatic(k) ? Vec3(X.R * model.axis[b])
                                        : Vec3((X.R * model.axis[b]).cross(p_foot_W - X.p));
    }
  }
}

RobotData::RobotData(const RobotModel& model)
    : tau(DofVector::Zero(model.dofs())),
      M(DofMatrix::Zero(model.dofs(), model.dofs())),
      bias(DofVector::Zero(model.dofs())),
      M_llt(model.dofs()),
      nu_dot(DofVector::Zero(model.dofs())) {
  split.tau0.setZero(model.joints());
  for (int b = 0; b < model.bodies(); ++b) I_body[b] = to_spatial(model.inertia[b]);
  R_fixed[0] = R_cos[0] = R_sin[0] = Mat3::Zero();
  for (int b = 1; b < model.bodies(); ++b) {
    const Vec3& a = model.axis[b];
    const Mat3 A = a * a.transpose();
    R_fixed[b] = model.R_parent_joint[b] * A;
    R_cos[b] = model.R_parent_joint[b] * (Mat3::Identity() - A);
    R_sin[b] = model.R_parent_joint[b] * skew(a);
    slide[b] = model.R_parent_joint[b] * a;
    if (model.prismatic(b - 1)) {
      R_fixed[b] = model.R_parent_joint[b];
      R_cos[b] = R_sin[b] = Mat3::Zero();
    }
  }
  for (int l = 0; l < model.legs(); ++l) {
    J_foot_W[l].setZero(3, model.dofs());
    p_foot_W[l].setZero();
    a_foot_bias_W[l].setZero();
    split.JjT[l].setZero(model.joints(), 3);
    split.JbT[l].setZero();
  }
  for (int b = 0; b < model.bodies(); ++b) {
    omega_body_W[b].setZero();
    v_com_body_W[b].setZero();
  }
}

void update_kinematics(const RobotModel& model, RobotData& data, const BaseState& state,
                       const JointVector& q) {
  if (data.kinematics_q.size() == q.size() && data.kinematics_q == q &&
      data.kinematics_p_W == state.p_W && data.kinematics_W_R_B == state.W_R_B)
    return;
  data.X_parent_body[0] = Transform::Identity();
  data.X_world_body[0] = Transform{state.W_R_B, state.p_W};
  for (int b = 1; b < model.bodies(); ++b) {
    Transform& X = data.X_parent_body[b];
    if (model.prismatic(b - 1)) {
      X.R = data.R_fixed[b];
      X.p = model.p_parent_joint[b] + q[b - 1] * data.slide[b];
    } else {
      const double c = std::cos(q[b - 1]), s = std::sin(q[b - 1]);
      X.R = data.R_fixed[b] + c * data.R_cos[b] + s * data.R_sin[b];
      X.p = model.p_parent_joint[b];
    }
    data.X_world_body[b] = data.X_world_body[model.parent[b]] * X;
  }
  data.kinematics_q = q;
  data.kinematics_p_W = state.p_W;
  data.kinematics_W_R_B = state.W_R_B;
}

const DofVector& rnea(const RobotModel& model, RobotData& data, const BaseState& state,
                      const JointVector& q, const JointVector& qd, const JointVector& qdd,
                      LegVectors foot_forces_W, LegVectors normals_W) {
  update_kinematics(model, data, state, q);
  Motion v0_B, a0_B;
  base_motion(state, state.a_W, state.omegadot_W, model.gravity_W, v0_B, a0_B);
  forward_motion_pass(model, data, v0_B, a0_B, qd, &qdd);

  // Net force on each body: f = I a + v ×* I v (Newton–Euler in body coordinates).
  for (int b = 0; b < model.bodies(); ++b) {
    const Inertia& I = data.I_body[b];
    data.f_body[b] = I * data.a_body[b] + cross(data.v_body[b], I * data.v_body[b]);
  }
  // Terrain forces act on the foot bodies at the contact points; they relieve the joints.
  if (!foot_forces_W.empty()) {
    for (int l = 0; l < model.legs(); ++l) {
      const Vec3 r_foot = contact_point_foot(model, data, l, normals_W);
      const int b = model.foot_body(l);
      const Vec3 F_b = data.X_world_body[b].R.transpose() * foot_forces_W[l];
      data.f_body[b] -= Force{r_foot.cross(F_b), F_b};
    }
  }
  // Backward pass: joint torques, and the subtree forces accumulate onto the trunk.
  for (int b = model.bodies() - 1; b >= 1; --b) {
    data.tau[6 + b - 1] = joint_force(model, b, data.f_body[b]);
    data.f_body[model.parent[b]] += data.X_parent_body[b].apply(data.f_body[b]);
  }
  // Trunk wrench about P0, from trunk axes to world axes.
  data.tau.head<3>() = state.W_R_B * data.f_body[0].linear;
  data.tau.segment<3>(3) = state.W_R_B * data.f_body[0].angular;
  return data.tau;
}

const DofMatrix& crba(const RobotModel& model, RobotData& data, const BaseState& state,
                      const JointVector& q) {
  update_kinematics(model, data, state, q);
  for (int b = 0; b < model.bodies(); ++b) data.Ic_body[b] = data.I_body[b];
  for (int b = model.bodies() - 1; b >= 1; --b)
    data.Ic_body[model.parent[b]] =
        data.Ic_body[model.parent[b]] + data.X_parent_body[b].apply(data.Ic_body[b]);

  DofMatrix& M = data.M;
  // Joint rows: the momentum F = Ic S of the subtree at b moving with joint b alone,
  // carried towards the root, projected on each ancestor's axis.
  for (int b = 1; b < model.bodies(); ++b) {
    const int k = 6 + b - 1;
    Force F = data.Ic_body[b] * joint_subspace(model, b);
    M(k, k) = joint_force(model, b, F);
    int j = b;
    while (model.parent[j] != 0) {
      F = data.X_parent_body[j].apply(F);
      j = model.parent[j];
      M(6 + j - 1, k) = M(k, 6 + j - 1) = joint_force(model, j, F);
    }
    F = data.X_parent_body[j].apply(F);  // into trunk coordinates, moment about P0
    // Coupling with the trunk: the generalised base momentum is (linear, angular about
    // P0) in world axes.
    M.block<3, 1>(0, k) = state.W_R_B * F.linear;
    M.block<3, 1>(3, k) = state.W_R_B * F.angular;
    M.block<1, 3>(k, 0) = M.block<3, 1>(0, k).transpose();
    M.block<1, 3>(k, 3) = M.block<3, 1>(3, k).transpose();
  }
  // Zero the joint-joint entries of legs that do not share a chain.
  for (int la = 0; la < model.legs(); ++la)
    for (int lb = 0; lb < model.legs(); ++lb)
      if (la != lb)
        M.block(6 + model.joint(la, 0), 6 + model.joint(lb, 0), model.leg(la).n_joints,
                model.leg(lb).n_joints)
            .setZero();

  // Trunk block from the whole-robot composite inertia, in world axes about P0:
  //   [[m 1, −m [c]], [m [c], I_c − m [c]²]]   for ν = (v_W, ω_W), c = COM − P0.
  const Inertia& Ic0 = data.Ic_body[0];
  const Vec3 c_W = state.W_R_B * Ic0.com;
  const Mat3 C = skew(c_W);
  const Mat3 I_com_W = state.W_R_B * Ic0.I_com * state.W_R_B.transpose();
  M.block<3, 3>(0, 0) = Ic0.mass * Mat3::Identity();
  M.block<3, 3>(0, 3) = -Ic0.mass * C;
  M.block<3, 3>(3, 0) = Ic0.mass * C;
  M.block<3, 3>(3, 3) = I_com_W - Ic0.mass * C * C;
  return M;
}

void foot_jacobians(const RobotModel& model, RobotData& data, const BaseState& state,
                    const JointVector& q, LegVectors normals_W) {
  update_kinematics(model, data, state, q);
  foot_jacobians_at_poses(model, data, state, normals_W);
}

const LegArray<Vec3>& foot_bias_accelerations(const RobotModel& model, RobotData& data,
                                              const BaseState& state, const JointVector& q,
                                              const JointVector& qd, LegVectors normals_W) {
  update_kinematics(model, data, state, q);
  Motion v0_B, a0_B;
  base_motion(state, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), v0_B, a0_B);
  forward_motion_pass(model, data, v0_B, a0_B, qd, nullptr);
  for (int l = 0; l < model.legs(); ++l) {
    const Vec3 r = contact_point_foot(model, data, l, normals_W);
    const int b = model.foot_body(l);
    const Motion& v = data.v_body[b];
    const Motion& a = data.a_body[b];
    // Classical acceleration of the body-fixed point r: a_O + ω̇ × r + ω × (v_O + ω × r),
    // with the classical a_O = spatial a.linear + ω × v_O.
    const Vec3 a_point_b =
        a.linear + a.angular.cross(r) + v.angular.cross(v.linear + v.angular.cross(r));
    data.a_foot_bias_W[l] = data.X_world_body[b].R * a_point_b;
  }
  return data.a_foot_bias_W;
}

const Momentum& robot_momentum(const RobotModel& model, RobotData& data, const BaseState& state,
                               const JointVector& q, const JointVector& qd) {
  update_kinematics(model, data, state, q);
  // Body velocities in world axes: a revolute joint adds axis_W q̇ to the angular
  // velocity and leaves the velocity of the joint origin (the child's origin) unchanged.
  BodyArray<Vec3>& omega = data.omega_body_W;
  BodyArray<Vec3> v_origin_W;  // velocity of each body frame's origin
  omega[0] = state.omega_W;
  v_origin_W[0] = state.v_W;
  Momentum& h = data.momentum;
  h = Momentum{};
  for (int b = 0; b < model.bodies(); ++b) {
    const Transform& X = data.X_world_body[b];
    if (b > 0) {
      const int p = model.parent[b];
      // A prismatic joint adds axis_W q̇ to the velocity of the child's origin instead.
      const Vec3 axis_W = X.R * model.axis[b];
      const bool slides = model.prismatic(b - 1);
      omega[b] = slides ? omega[p] : Vec3(omega[p] + axis_W * qd[b - 1]);
      v_origin_W[b] = v_origin_W[p] + omega[p].cross(X.p - data.X_world_body[p].p);
      if (slides) v_origin_W[b] += axis_W * qd[b - 1];
    }
    const RigidInertia& in = model.inertia[b];
    const Vec3 c_W = X.apply_point(in.com_m);
    const Vec3 v_c_W = v_origin_W[b] + omega[b].cross(c_W - X.p);
    data.v_com_body_W[b] = v_c_W;
    const Vec3 p_lin = in.mass_kg * v_c_W;
    h.linear_W += p_lin;
    h.angular_O_W += X.R * (in.inertia_com * (X.R.transpose() * omega[b])) + c_W.cross(p_lin);
    h.com_W += in.mass_kg * c_W;
    h.mass_kg += in.mass_kg;
  }
  h.com_W /= h.mass_kg;
  h.angular_com_W = h.angular_O_W - h.com_W.cross(h.linear_W);
  return h;
}

const ContactSplit& contact_split(const RobotModel& model, RobotData& data, const BaseState& state,
                                  const JointVector& q, const JointVector& qd,
                                  const JointVector& qdd, LegVectors normals_W) {
  rnea(model, data, state, q, qd, qdd, nullptr);
  foot_jacobians_at_poses(model, data, state, normals_W);  // kinematics already updated by rnea
  ContactSplit& s = data.split;
  s.trunk_rhs = data.tau.head<6>();
  const int n = model.joints();
  s.tau0 = data.tau.tail(n);
  for (int l = 0; l < model.legs(); ++l) {
    s.JbT[l] = data.J_foot_W[l].leftCols<6>().transpose();
    s.JjT[l] = data.J_foot_W[l].rightCols(n).transpose();
  }
  return s;
}

}  // namespace hexdyn
