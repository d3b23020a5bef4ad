#include "hexdyn/contact/touchdowns.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "hexdyn/core/cancel.hpp"

namespace hexdyn {

double foot_effective_mass(const RobotModel& model, RobotData& data, const BaseState& base,
                           const JointVector& q, int leg, const Vec3& n_W) {
  crba(model, data, base, q);
  FootNormals normals;
  normals.fill(n_W);  // a sphere foot's Jacobian is its contact point's on this surface
  foot_jacobians(model, data, base, q, &normals);
  const int c = 6 + model.joint(leg, 0);  // the leg's first column among the coordinates
  const int m = model.leg(leg).n_joints;
  Mat3 Lambda_inv;
  if (m == 3) {
    // A leg of three joints: the fixed-size blocks (the shipped robots' arithmetic).
    const Mat3 M_ll = data.M.block<3, 3>(c, c);
    const Mat3 J = data.J_foot_W[leg].block<3, 3>(0, c);
    Lambda_inv = J * M_ll.llt().solve(J.transpose());
  } else {
    using LegMatrix =
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLegJoints, kMaxLegJoints>;
    const LegMatrix M_ll = data.M.block(c, c, m, m);
    const LegJacobian J = data.J_foot_W[leg].block(0, c, 3, m);
    Lambda_inv = J * M_ll.llt().solve(J.transpose());
  }
  return 1.0 / (n_W.transpose() * Lambda_inv * n_W);
}

namespace {

/// The feet standing at t (positions, world frame) and their quasi-static vertical loads:
/// the minimum-norm loads f with Σ f = m g and no moment about the centre of mass's vertical
/// line (least squares when they cannot balance it).
struct StandingFeet {
  std::vector<int> legs;
  std::vector<Vec3> p_W;
  Eigen::VectorXd load_N;
};

StandingFeet standing_feet(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                           double t_s) {
  RobotKinematicState s;
  robot_state_at(model, plan, t_s, s);
  const Momentum& m = robot_momentum(model, data, s.trunk, s.q, s.qd);
  StandingFeet out;
  for (int l = 0; l < model.legs(); ++l)
    if (!s.feet[l].in_swing) {
      out.legs.push_back(l);
      out.p_W.push_back(s.feet[l].p_W);
    }
  Eigen::MatrixXd A(3, static_cast<Eigen::Index>(out.legs.size()));
  for (std::size_t i = 0; i < out.legs.size(); ++i)
    A.col(static_cast<Eigen::Index>(i)) << 1.0, out.p_W[i].x() - m.com_W.x(),
        out.p_W[i].y() - m.com_W.y();
  const Eigen::Vector3d b(m.mass_kg * model.gravity_W.norm(), 0.0, 0.0);
  out.load_N = out.legs.empty() ? Eigen::VectorXd() : A.completeOrthogonalDecomposition().solve(b);
  return out;
}

/// Just before or after t_s [s].
double nudged(double t_s, double sign) { return t_s + sign * 1e-9 * std::max(1.0, std::abs(t_s)); }

}  // namespace

double touchdown_load_share(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                            double t_s, int leg, const Vec3& n_W) {
  // Just after the touchdown: the landing leg stands, a leg lifting off at that instant swings.
  const StandingFeet feet = standing_feet(model, data, plan, nudged(t_s, 1.0));
  for (std::size_t i = 0; i < feet.legs.size(); ++i)
    if (feet.legs[i] == leg)
      return std::max(0.0, feet.load_N[static_cast<Eigen::Index>(i)] * n_W.normalized().z());
  return 0.0;
}

double touchdown_sink(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                      const ContactParams& contact, double t_s, const Vec3& p_W) {
  // Just before the touchdown: the feet that carry the robot while the landing foot descends.
  const StandingFeet feet = standing_feet(model, data, plan, nudged(t_s, -1.0));
  if (feet.legs.empty()) return 0.0;
  // The plane δ = a + b x + c y through the feet's static penetrations (minimum norm, least
  // squares: exact for three feet), at the landing foot.
  Eigen::MatrixXd A(static_cast<Eigen::Index>(feet.legs.size()), 3);
  Eigen::VectorXd delta(static_cast<Eigen::Index>(feet.legs.size()));
  for (std::size_t i = 0; i < feet.legs.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    A.row(r) << 1.0, feet.p_W[i].x(), feet.p_W[i].y();
    delta[r] = static_penetration(contact, std::max(0.0, feet.load_N[r]));
  }
  const Eigen::Vector3d plane = A.completeOrthogonalDecomposition().solve(delta);
  return std::max(0.0, plane[0] + plane[1] * p_W.x() + plane[2] * p_W.y());
}

std::vector<Touchdown> resolve_touchdowns(const RobotModel& model, RobotData& data,
                                          const MotionPlan& plan, const ContactParams& contact) {
  std::vector<Touchdown> out;
  RobotKinematicState s;
  for (int leg = 0; leg < model.legs(); ++leg) {
    for (const Swing& sw : plan.gait.legs[leg].swings) {
      check_cancelled();
      Touchdown td;
      td.leg = leg;
      td.t_s = sw.t_touchdown_s;
      td.normal_W = plan.terrain.normal(sw.p_touchdown_W.x(), sw.p_touchdown_W.y());
      const FootMotion arrival = swing_foot_motion(sw, sw.t_touchdown_s);
      td.approach_speed_mps = -arrival.v_W.dot(td.normal_W);
      robot_state_at(model, plan, td.t_s, s);
      td.effective_mass_kg = foot_effective_mass(model, data, s.trunk, s.q, leg, td.normal_W);
      // Rigid contact: no transient (occurred = false), the foot supports from touchdown on.
      if (contact.model == ContactModel::kCompliant) {
        double load = 0.0, delay = 0.0;
        if (contact.touchdown == TouchdownModel::kLoaded && td.approach_speed_mps > 0.0) {
          load = touchdown_load_share(model, data, plan, td.t_s, leg, td.normal_W);
          const double sink = touchdown_sink(model, data, plan, contact, td.t_s, sw.p_touchdown_W);
          delay = sink / td.approach_speed_mps;
        }
        td.transient = simulate_touchdown(contact, td.effective_mass_kg, td.approach_speed_mps,
                                          ImpactOptions{}, load, delay);
      }
      out.push_back(std::move(td));
    }
  }
  std::sort(out.begin(), out.end(), [](const Touchdown& a, const Touchdown& b) {
    return a.t_s < b.t_s || (a.t_s == b.t_s && a.leg < b.leg);
  });
  return out;
}

std::vector<ImpactRecord> impact_records(const std::vector<Touchdown>& touchdowns) {
  std::vector<ImpactRecord> out;
  for (const Touchdown& td : touchdowns) {
    if (!td.transient.occurred) continue;
    ImpactRecord r;
    r.leg = td.leg;
    r.t_start_s = td.t_s;
    r.duration_s = td.after_touchdown_s();
    r.peak_force_N = td.transient.peak_force_N;
    r.impulse_Ns = td.transient.impulse_Ns;
    r.effective_mass_kg = td.effective_mass_kg;
    r.approach_speed_mps = td.approach_speed_mps;
    out.push_back(r);
  }
  return out;
}

Mat3 contact_frame(const Vec3& n_W) {
  const Vec3 n = n_W.normalized();
  Vec3 t1 = Vec3::UnitX() - n.x() * n;
  if (t1.norm() < 1e-9) t1 = Vec3::UnitY() - n.y() * n;
  t1.normalize();
  Mat3 R;
  R.col(0) = t1;
  R.col(1) = n.cross(t1);
  R.col(2) = n;
  return R;
}

void sample_contacts(const KinematicsResult& kin, int i, const Terrain& terrain,
                     const std::vector<Touchdown>& touchdowns, SampleContacts& out) {
  const double t = kin.time_s[i];
  const int legs = static_cast<int>(kin.contact_phase.cols());
  out.impacting_legs = 0;
  for (int l = 0; l < legs; ++l) {
    out.phase[l] = kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kSwing)
                       ? ContactPhase::kSwing
                       : ContactPhase::kSupport;
    out.impact_force_N[l] = 0.0;
    out.impact_penetration_m[l] = 0.0;
    const Vec3 p = kin.foot_position.row(i).segment<3>(3 * l).transpose();
    out.W_R_contact[l] = contact_frame(terrain.normal(p.x(), p.y()));
  }
  for (const Touchdown& td : touchdowns) {
    // The transient's own time runs from the first contact, contact_lead_s() before td.t_s;
    // its end as the output grid places it (pipeline.cpp), to the last bit.
    if (!td.transient.occurred || t < td.t_s || t >= td.t_s + td.after_touchdown_s()) continue;
    const double since_contact = t - td.t_s + td.contact_lead_s();
    if (out.phase[td.leg] == ContactPhase::kSwing) continue;
    out.phase[td.leg] = ContactPhase::kImpact;
    out.impact_force_N[td.leg] = transient_force_at(td.transient, since_contact);
    out.impact_penetration_m[td.leg] = transient_penetration_at(td.transient, since_contact);
    ++out.impacting_legs;
  }
}

ContactSchedule schedule_contacts(const KinematicsResult& kin, const Terrain& terrain,
                                  const std::vector<Touchdown>& touchdowns) {
  const int T = kin.samples();
  ContactSchedule s;
  s.samples.resize(T);
  const int legs = static_cast<int>(kin.contact_phase.cols());
  s.phase.setZero(T, legs);
  for (int i = 0; i < T; ++i) {
    sample_contacts(kin, i, terrain, touchdowns, s.samples[i]);
    for (int l = 0; l < legs; ++l) s.phase(i, l) = static_cast<std::int8_t>(s.samples[i].phase[l]);
  }
  return s;
}

}  // namespace hexdyn
