// replay.early_contact: hold (docs/theory/replay.md#early-contact): the joint rates that hold a
// foot still under the trunk's twist (step_system.hpp holding_rates), checked against finite
// differences of the tree's forward kinematics, a computation that shares no code with the
// foot Jacobians they are built from.
#include <Eigen/SVD>
#include <catch2/catch.hpp>
#include <random>

#include "hexdyn/dynamics/dynamics_samples.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/replay/step_system.hpp"

namespace hexdyn {
using namespace test;
namespace {

/// The world position of leg l's foot point with the trunk moved along the twist (v, ω) of s
/// for t seconds (p + v t, exp(ω t) R) and the joints at q + q̇ t.
Vec3 foot_after(const RobotModel& model, const Sample& s, const PaperJointVector& qd, int l,
                double t) {
  BaseState st = s.state;
  st.p_W += s.state.v_W * t;
  st.W_R_B = so3_exp(s.state.omega_W * t) * s.state.W_R_B;
  BodyPoses poses;
  forward_kinematics_tree(model, s.q + qd * t, poses);
  return st.p_W + st.W_R_B * tree_foot_position_B(model, poses, l);
}

}  // namespace

TEST_CASE("holding rates keep a foot still under the trunk's twist", "[replay]") {
  std::mt19937 rng(41);
  const double h = 1e-6;
  int checked = 0;
  for (const RobotModel& model : sample_models()) {
    RobotData data(model);
    for (int n = 0; n < 20; ++n) {
      const Sample s = random_sample(rng);
      foot_jacobians(model, data, s.state, s.q);
      PaperJointVector held = s.qd;
      for (int l = 0; l < kPaperLegs; ++l) {
        const LegInfo& leg = model.leg(l);
        held.segment(leg.first_joint, leg.n_joints) = holding_rates(leg, data.J_foot_W[l], s.state);
      }
      for (int l = 0; l < kPaperLegs; ++l) {
        // Near a singular leg the rates grow without bound and the differences' truncation
        // with them: such legs are left out (σ_min of the leg's columns below 2 cm/rad).
        const LegInfo& leg = model.leg(l);
        const Eigen::MatrixXd J_leg =
            data.J_foot_W[l].middleCols(6 + leg.first_joint, leg.n_joints);
        if (Eigen::JacobiSVD<Eigen::MatrixXd>(J_leg).singularValues().minCoeff() < 0.02) continue;
        ++checked;
        const Vec3 moving = (foot_after(model, s, s.qd, l, h) - foot_after(model, s, s.qd, l, -h));
        const Vec3 still = (foot_after(model, s, held, l, h) - foot_after(model, s, held, l, -h));
        // The random rates move the foot at about 1 m/s; the holding ones do not move it.
        CHECK(moving.norm() / (2.0 * h) > 1e-2);
        CHECK(still.norm() / (2.0 * h) < 1e-6);
      }
    }
  }
  CHECK(checked > 100);
}

}  // namespace hexdyn
