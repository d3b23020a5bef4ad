// Allocation problems of robots that are not hexapods: a quadruped (4 legs, 12 joints), an
// octopod (8 legs, 24 joints, as many force unknowns as the active-set solver takes) and the
// largest robot the capacities allow (8 legs of 6 joints). Each problem is built by
// build_allocation_problem from hand-made contact split data (AllocationSplit: leg Jacobian
// blocks, trunk wrench, joint torques) and checked against computations that do not use the
// builder or the solver:
//  - its rows, counted and written from the layout's definition (six trunk rows, then per leg
//    one torque row per joint, a support leg's minimum normal force, its friction faces);
//  - the active-set back end's answer, by the KKT conditions of the QP (stationarity, primal
//    and dual feasibility, complementarity; kkt_check.hpp) to 1e-9, and by Ipopt's optimum of
//    the same QP;
//  - the largest problem's rows against the solver's row budget (kActiveSetMaxRows): under the
//    exact cone, the required friction's probes replace each cone by a 16-gon, the largest
//    face count of any problem.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/goldfarb_idnani.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/kkt_check.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/core/spatial.hpp"
#include "hexdyn/grip/required_friction.hpp"

namespace hexdyn {
namespace {

/// One sample's data for a robot of `legs.legs` legs.
struct Robot {
  AllocationLegs legs;
  AllocationSplit split;
  LegArray<ContactPhase> phase{};
  LegArray<double> impact{};
  LegArray<Mat3> frames;
  double torque_limit_Nm = 0.0;
};

/// Feet on a ring of radius 0.3 m, 0.25 m below the trunk; contact frames tilted up to 0.2 rad
/// from +z; each leg's joint block of its transposed Jacobian random (0.1 m scale, only the
/// leg's own joints move its foot); joint torques τ₀ of 0.3 N m. The trunk wrench is that of
/// forces F_l drawn inside a friction cone of μ = 0.3 (f_n 10–20 N), so that the problem is
/// feasible; the torque limit is 1.2 times the largest torque those forces need, so that some
/// torque rows may bind at the optimum.
Robot random_robot(std::mt19937& rng, int n_legs, int leg_joints, ContactPhase phase) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Robot r;
  r.legs = uniform_allocation_legs(n_legs, leg_joints);
  const int joints = r.legs.joints;
  r.split.tau0 = JointVector::NullaryExpr(joints, [&] { return 0.3 * g(rng); });
  JointVector tau = r.split.tau0;
  for (int l = 0; l < n_legs; ++l) {
    const double a = 2.0 * M_PI * (l + 0.5) / n_legs;
    const Vec3 p(0.3 * std::cos(a), 0.3 * std::sin(a), -0.25);
    r.split.JbT[l].topRows<3>() = Mat3::Identity();
    r.split.JbT[l].bottomRows<3>() = skew(p);
    r.split.JjT[l].setZero(joints, 3);
    r.split.JjT[l].middleRows(r.legs.first_joint[l], leg_joints) =
        Eigen::MatrixXd::NullaryExpr(leg_joints, 3, [&] { return 0.1 * g(rng); });
    const Vec3 axis(u(rng), u(rng), 0.0);
    r.frames[l] = Eigen::AngleAxisd(0.2 * u(rng), axis.normalized()).toRotationMatrix();
    const double fn = 15.0 + 5.0 * u(rng), t = 0.3 * fn * std::abs(u(rng)), b = M_PI * u(rng);
    const Vec3 F = r.frames[l] * Vec3(t * std::cos(b), t * std::sin(b), fn);
    r.phase[l] = phase;
    r.impact[l] = fn;
    r.split.trunk_rhs += r.split.JbT[l] * F;
    tau -= r.split.JjT[l] * F;
  }
  r.torque_limit_Nm = 1.2 * tau.cwiseAbs().maxCoeff();
  return r;
}

AllocationParams params(FrictionModel friction, double torque_limit_Nm) {
  AllocationParams alloc;
  alloc.friction = friction;
  alloc.torque_limit_Nm = torque_limit_Nm;
  return alloc;
}

AllocationLayout build(const Robot& r, FrictionModel friction, QpProblem& qp, double mu = 0.5) {
  ContactParams contact;
  contact.friction_coefficient = mu;
  return build_allocation_problem(r.legs, params(friction, r.torque_limit_Nm), contact, r.split,
                                  r.phase, r.impact, r.frames, qp);
}

int faces_of(FrictionModel m) { return m == FrictionModel::kPyramid8 ? 8 : 4; }

/// The problem's rows from their definition (problem.hpp), for support legs: the trunk rows
/// B x = trunk wrench with B_l = JbT_l R_l, then per leg its torque rows τ₀ − G x within
/// ±limit (G_l = JjT_l R_l, the leg's own joints), f_n ≥ min_normal_force, and the faces.
void check_rows(const Robot& r, FrictionModel friction, const QpProblem& qp,
                const AllocationLayout& layout) {
  const int faces = faces_of(friction);
  int expected_rows = 6;
  for (int l = 0; l < r.legs.legs; ++l) expected_rows += r.legs.n_joints[l] + 1 + faces;
  REQUIRE(qp.inequalities() == expected_rows);
  REQUIRE(qp.variables() == 3 * r.legs.legs);
  REQUIRE(layout.n_legs == r.legs.legs);
  int row = 6;
  for (int l = 0; l < r.legs.legs; ++l) {
    const int o = layout.legs[l].offset;
    CHECK(o == 3 * l);
    const Eigen::Matrix<double, 6, 3> B = r.split.JbT[l] * r.frames[l];
    CHECK((qp.C.block(0, o, 6, 3) - B).cwiseAbs().maxCoeff() <= 1e-15);
    for (int j = 0; j < r.legs.n_joints[l]; ++j, ++row) {
      const int k = r.legs.first_joint[l] + j;
      const Eigen::RowVector3d G = r.split.JjT[l].row(k) * r.frames[l];
      CHECK((qp.C.block(row, o, 1, 3) - G).cwiseAbs().maxCoeff() <= 1e-15);
      CHECK(qp.C.row(row).squaredNorm() == Approx(G.squaredNorm()).epsilon(1e-14));
      CHECK(qp.lower[row] == Approx(r.split.tau0[k] - r.torque_limit_Nm).epsilon(1e-14));
      CHECK(qp.upper[row] == Approx(r.split.tau0[k] + r.torque_limit_Nm).epsilon(1e-14));
    }
    CHECK(qp.C(row, o + 2) == 1.0);  // the minimum normal force
    row += 1 + faces;
  }
  for (int i = 0; i < 6; ++i) CHECK(qp.lower[i] == r.split.trunk_rhs[i]);
}

/// The active-set answer of the problem of `r` against the KKT conditions and Ipopt.
void check_solution(const Robot& r, FrictionModel friction) {
  QpProblem qp;
  const AllocationLayout layout = build(r, friction, qp);
  if (r.phase[0] == ContactPhase::kSupport) check_rows(r, friction, qp, layout);
  auto active_set = make_active_set_backend();
  const QpOutcome out = active_set->solve(qp);
  INFO(out.message);
  REQUIRE(out.status == SolverStatus::kOptimal);
  CHECK(test::check_kkt(qp, out, 1e-9));
  auto ipopt = make_ipopt_backend(ipopt_options_from(params(friction, r.torque_limit_Nm)));
  const QpOutcome reference = ipopt->solve(qp);
  REQUIRE(reference.status == SolverStatus::kOptimal);
  const auto objective = [&](const Eigen::VectorXd& x) {
    return 0.5 * x.dot(qp.H.selfadjointView<Eigen::Lower>() * x) + qp.g.dot(x) + qp.constant;
  };
  INFO("objective: active set " << objective(out.x) << ", Ipopt " << objective(reference.x));
  CHECK(objective(out.x) <= objective(reference.x) + 1e-7 * (1.0 + std::abs(qp.constant)));
  CHECK((out.x - reference.x).cwiseAbs().maxCoeff() <= 1e-4 * (1.0 + reference.x.norm()));
  // The forces and torques of the answer: τ = τ₀ − Σ J_jᵀ F, each within the limit.
  LegArray<Vec3> F_W;
  JointVector tau;
  forces_from_solution(r.split, layout, out.x, F_W, tau);
  REQUIRE(tau.size() == r.legs.joints);
  CHECK(tau.cwiseAbs().maxCoeff() <= r.torque_limit_Nm * (1.0 + 1e-9));
  Vec6 wrench = Vec6::Zero();
  for (int l = 0; l < r.legs.legs; ++l) wrench += r.split.JbT[l] * F_W[l];
  CHECK((wrench - r.split.trunk_rhs).cwiseAbs().maxCoeff() <=
        1e-9 * (1.0 + r.split.trunk_rhs.norm()));
}

}  // namespace

TEST_CASE("allocation of any robot: a quadruped and an octopod against KKT and Ipopt",
          "[allocation]") {
  std::mt19937 rng(43);
  for (int n_legs : {4, 8}) {
    for (FrictionModel friction : {FrictionModel::kPyramid4, FrictionModel::kPyramid8}) {
      for (int k = 0; k < 5; ++k) {
        INFO(n_legs << " legs, " << faces_of(friction) << " faces, sample " << k);
        check_solution(random_robot(rng, n_legs, 3, ContactPhase::kSupport), friction);
      }
    }
  }
}

TEST_CASE("allocation of any robot: legs of four to six joints and impact legs", "[allocation]") {
  std::mt19937 rng(4343);
  for (int leg_joints : {4, 6}) {
    for (ContactPhase phase : {ContactPhase::kSupport, ContactPhase::kImpact}) {
      INFO(leg_joints << " joints a leg, "
                      << (phase == ContactPhase::kImpact ? "impact" : "support"));
      check_solution(random_robot(rng, 4, leg_joints, phase), FrictionModel::kPyramid8);
    }
  }
}

TEST_CASE("allocation of any robot: the largest problem fits the active-set solver",
          "[allocation]") {
  // Eight legs of six joints (48 joints, 24 force unknowns). The most rows a leg brings are
  // the required friction's under the exact cone: its six torque rows, the minimum normal
  // force and the 16-gon that stands in for its cone.
  std::mt19937 rng(8);
  const Robot r = random_robot(rng, kMaxLegs, kMaxLegJoints, ContactPhase::kSupport);
  QpProblem qp;
  const AllocationLayout layout = build(r, FrictionModel::kCone, qp, 0.3);
  REQUIRE(qp.variables() == kActiveSetMaxVariables);
  REQUIRE(qp.cones.size() == static_cast<std::size_t>(kMaxLegs));
  CHECK(qp.inequalities() + 16 * static_cast<int>(qp.cones.size()) == kActiveSetMaxRows);
  // μ* of it: the forces were drawn inside a cone of μ = 0.3, so μ* ≤ 0.3; the solve fails
  // with a message if a probe exceeds the solver's rows or variables.
  RequiredFrictionSolver solver(make_active_set_backend());
  const RequiredFriction& mu = solver.solve(qp, layout, nullptr);
  INFO(mu.message);
  CHECK(mu.message.empty());
  CHECK(mu.mu <= 0.3 + 1e-6);
  CHECK(mu.mu > 0.0);
  // Every leg in its touchdown transient keeps the inscribed 16-gon under the exact cone.
  Robot impact = r;
  impact.phase.fill(ContactPhase::kImpact);
  QpProblem qp_impact;
  build(impact, FrictionModel::kCone, qp_impact, 0.3);
  CHECK(qp_impact.inequalities() == 6 + kMaxLegs * (kMaxLegJoints + 16));
  CHECK(qp_impact.inequalities() <= kActiveSetMaxRows);
  const QpOutcome out = make_active_set_backend()->solve(qp_impact);
  INFO(out.message);
  CHECK(out.status != SolverStatus::kFailed);
  if (out.status == SolverStatus::kOptimal) CHECK(test::check_kkt(qp_impact, out, 1e-9));
  // And the allocation under the largest pyramid.
  check_solution(r, FrictionModel::kPyramid8);
}

}  // namespace hexdyn
