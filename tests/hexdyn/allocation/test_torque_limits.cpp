// Per-joint torque limits (AllocationParams::joint_torque_limit_Nm, a URDF robot's effort
// limits): each joint's torque row of the allocation problem is bounded by its own limit,
// |τ_k| ≤ limit_k with τ = τ₀ − G x, and the scalar limit applies to every joint when no
// per-joint limits are set; a swing leg's torque beyond its own limit is reported.
#include <catch2/catch.hpp>
#include <random>

#include "hexdyn/allocation/problem.hpp"

namespace hexdyn {

TEST_CASE("allocation: torque rows use each joint's own limit", "[allocation][limits]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const AllocationLegs legs = uniform_allocation_legs(6, 3);  // a hexapod
  const int joints = legs.joints;
  AllocationSplit split;
  split.tau0.resize(joints);
  for (int k = 0; k < joints; ++k) split.tau0[k] = u(rng);
  for (int l = 0; l < legs.legs; ++l) {
    split.JjT[l].resize(joints, 3);
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < joints; ++r) split.JjT[l](r, c) = u(rng);
      for (int r = 0; r < 6; ++r) split.JbT[l](r, c) = u(rng);
    }
  }
  LegArray<ContactPhase> phase;
  phase.fill(ContactPhase::kSupport);
  phase[1] = ContactPhase::kSwing;  // leg L2 swings: its torques are constants
  LegArray<double> impact{};
  LegArray<Mat3> R;
  R.fill(Mat3::Identity());
  AllocationParams alloc;
  ContactParams contact;
  decltype(alloc.joint_torque_limit_Nm)::value_type limits{};
  for (int k = 0; k < joints; ++k) limits[k] = 0.5 + 0.1 * k;
  for (const bool per_joint : {true, false}) {
    alloc.joint_torque_limit_Nm.reset();
    if (per_joint) alloc.joint_torque_limit_Nm = limits;
    QpProblem qp;
    const AllocationLayout layout =
        build_allocation_problem(legs, alloc, contact, split, phase, impact, R, qp);
    const double worst = layout.constant_excess_Nm;
    const std::string& violation = layout.constant_violation;
    int rows = 0;
    for (int i = 0; i < qp.inequalities(); ++i) {
      for (int k = 0; k < joints; ++k) {
        const int l = k / 3, j = k - legs.first_joint[l];
        if (qp.ineq_names[i] != "torque " + joint_name(l, j, legs.n_joints[l])) continue;
        const double lim = per_joint ? limits[k] : alloc.torque_limit_Nm;
        // Row value C x = G x; τ = τ₀ − G x within ±lim  ⇔  τ₀ − lim ≤ G x ≤ τ₀ + lim.
        CHECK(qp.lower[i] == Approx(split.tau0[k] - lim).margin(1e-15));
        CHECK(qp.upper[i] == Approx(split.tau0[k] + lim).margin(1e-15));
        ++rows;
      }
    }
    CHECK(rows == 15);  // five support legs
    double expect = 0.0;
    for (int j = 0; j < 3; ++j) {
      const int k = legs.first_joint[1] + j;
      expect = std::max(expect,
                        std::abs(split.tau0[k]) - (per_joint ? limits[k] : alloc.torque_limit_Nm));
    }
    CHECK(worst == Approx(expect).margin(1e-15));
    // The excess is named, with its swing-leg joint, exactly when there is one.
    CHECK(violation.empty() == !(expect > 0.0));
    if (expect > 0.0) CHECK(violation.find("(swing leg)") != std::string::npos);
  }
}

}  // namespace hexdyn
