// The allocation problem with the drive train's rows (allocation/problem.hpp DriveRows,
// docs/theory/drive-train.md#allocation-with-the-drive-train): rows of zero offsets, unit
// weights and the allocation's limit give the problem built without them; offsets d shift the
// torque rows' bounds by d; with weights w the objective is Σ w (τ + d)², τ from
// forces_from_solution; the torque rows and a swing leg's excess name the bound that gave it.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

#include "hexdyn/allocation/problem.hpp"

namespace hexdyn {
namespace {

/// One sample's problem data: random leg Jacobians (leg l's block only, as the dynamics
/// gives them), random contact frames, leg L2 in swing with a torque beyond the limit, L3
/// in its touchdown transient, the others in support.
struct Sample {
  AllocationSplit split;
  LegArray<ContactPhase> phase;
  LegArray<double> impact{};
  LegArray<Mat3> frames;
};

/// The sample's robot: a hexapod's six legs of three joints.
const AllocationLegs kLegTable = uniform_allocation_legs(6, 3);
const int kJointCount = kLegTable.joints;
/// Flat index of joint j of leg l.
int joint_of(int l, int j) { return kLegTable.first_joint[l] + j; }
/// Leg and joint of flat index k.
std::string name_of(int k) {
  int l = 0;
  while (l + 1 < kLegTable.legs && kLegTable.first_joint[l + 1] <= k) ++l;
  return joint_name(l, k - kLegTable.first_joint[l], kLegTable.n_joints[l]);
}

Sample random_sample(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Sample s;
  s.split.trunk_rhs = Vec6::NullaryExpr([&] { return g(rng); });
  s.split.tau0 = JointVector::NullaryExpr(kJointCount, [&] { return 0.3 * g(rng); });
  for (int l = 0; l < kLegTable.legs; ++l) {
    s.split.JjT[l].setZero(kJointCount, 3);
    s.split.JjT[l].middleRows<3>(joint_of(l, 0)) = Mat3::NullaryExpr([&] { return 0.1 * g(rng); });
    s.split.JbT[l] = Eigen::Matrix<double, 6, 3>::NullaryExpr([&] { return g(rng); });
    s.frames[l] = Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    s.impact[l] = 10.0 + std::abs(g(rng));
  }
  s.phase.fill(ContactPhase::kSupport);
  s.phase[1] = ContactPhase::kSwing;
  s.phase[2] = ContactPhase::kImpact;
  s.split.tau0[joint_of(1, 1)] = 1.5;  // beyond the 0.8 N m limit below
  return s;
}

AllocationParams params(FrictionModel friction) {
  AllocationParams alloc;
  alloc.torque_limit_Nm = 0.8;
  alloc.friction = friction;
  return alloc;
}

AllocationLayout build(const AllocationParams& alloc, const Sample& s, QpProblem& qp,
                       const DriveRows* rows = nullptr) {
  return build_allocation_problem(kLegTable, alloc, ContactParams{}, s.split, s.phase, s.impact,
                                  s.frames, qp, rows);
}

/// The flat joint index of a torque row named "torque NAME", "torque NAME (peak)" or
/// "torque NAME (voltage)"; −1 for any other row.
int torque_row_joint(const std::string& name) {
  for (int k = 0; k < kJointCount; ++k) {
    const std::string base = "torque " + name_of(k);
    if (name == base || name == base + " (peak)" || name == base + " (voltage)") return k;
  }
  return -1;
}

/// Rows of the sample's legs with variables: 5 legs × 3 torque rows.
constexpr int kTorqueRows = 15;

}  // namespace

TEST_CASE("allocation with drive rows: neutral rows give the problem built without them",
          "[allocation][drive]") {
  for (FrictionModel friction : {FrictionModel::kPyramid4, FrictionModel::kCone}) {
    const AllocationParams alloc = params(friction);
    const Sample s = random_sample(41);
    DriveRows rows;  // offsets 0, weights 1 by default
    rows.limit_Nm.setConstant(alloc.torque_limit_Nm);
    rows.lower_Nm = -rows.limit_Nm;
    QpProblem plain, driven;
    const AllocationLayout lp = build(alloc, s, plain);
    const AllocationLayout ld = build(alloc, s, driven, &rows);
    REQUIRE(driven.variables() == plain.variables());
    REQUIRE(driven.inequalities() == plain.inequalities());
    CHECK(driven.H == plain.H);
    CHECK(driven.g == plain.g);
    CHECK(driven.constant == Approx(plain.constant).epsilon(1e-15));
    CHECK(driven.A == plain.A);
    CHECK(driven.b == plain.b);
    CHECK(driven.C == plain.C);
    CHECK(driven.lower == plain.lower);
    CHECK(driven.upper == plain.upper);
    CHECK(driven.ineq_names == plain.ineq_names);
    CHECK(driven.ineq_penalty == plain.ineq_penalty);
    CHECK(driven.structure == plain.structure);
    REQUIRE(driven.cones.size() == plain.cones.size());
    CHECK(driven.cones.size() == (friction == FrictionModel::kCone ? 4u : 0u));
    for (std::size_t c = 0; c < plain.cones.size(); ++c) {
      CHECK(driven.cones[c].name == plain.cones[c].name);
      CHECK(driven.cones[c].normal == plain.cones[c].normal);
      CHECK(driven.cones[c].mu == plain.cones[c].mu);
    }
    CHECK(ld.variables == lp.variables);
    CHECK(ld.constant_excess_Nm == lp.constant_excess_Nm);
    CHECK(ld.constant_violation == lp.constant_violation);
    CHECK(lp.constant_violation.find("torque L2_femur (swing leg) by 0.7") == 0);
  }
}

TEST_CASE("allocation with drive rows: offsets shift the torque rows' bounds",
          "[allocation][drive]") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const AllocationParams alloc = params(FrictionModel::kPyramid4);
  const Sample s = random_sample(42);
  DriveRows rows;
  rows.offset_Nm = JointVector::NullaryExpr(kJointCount, [&] { return u(rng); });
  rows.limit_Nm = JointVector::NullaryExpr(kJointCount, [&] { return 1.0 + u(rng); });
  rows.limit_Nm[joint_of(1, 1)] = 0.6;  // below |τ₀| − |d| ≥ 1: the swing leg's excess
  // The lower bounds of a three-phase drive differ from −limit: lower ≤ τ + d ≤ limit.
  rows.lower_Nm = JointVector::NullaryExpr(kJointCount, [&] { return -1.2 + u(rng); });
  rows.lower_Nm[joint_of(1, 1)] = -0.6;
  QpProblem plain, driven;
  build(alloc, s, plain);
  const AllocationLayout ld = build(alloc, s, driven, &rows);
  REQUIRE(driven.inequalities() == plain.inequalities());
  CHECK(driven.C == plain.C);
  int torque_rows = 0;
  for (int i = 0; i < plain.inequalities(); ++i) {
    const int k = torque_row_joint(plain.ineq_names[i]);
    INFO("row " << i << ": " << plain.ineq_names[i]);
    if (k < 0) {
      CHECK(driven.lower[i] == plain.lower[i]);
      CHECK(driven.upper[i] == plain.upper[i]);
      continue;
    }
    ++torque_rows;
    // Without drive rows: τ₀' − τ_max ≤ G x ≤ τ₀' + τ_max (τ₀' the known part of τ); with them
    // lower ≤ τ₀' + d − G x ≤ limit: τ₀' + d − limit ≤ G x ≤ τ₀' + d − lower.
    const double centre = 0.5 * (plain.lower[i] + plain.upper[i]);
    CHECK(plain.upper[i] - plain.lower[i] == Approx(2.0 * alloc.torque_limit_Nm).epsilon(1e-14));
    CHECK(driven.lower[i] == Approx(centre + rows.offset_Nm[k] - rows.limit_Nm[k]).margin(1e-14));
    CHECK(driven.upper[i] == Approx(centre + rows.offset_Nm[k] - rows.lower_Nm[k]).margin(1e-14));
  }
  CHECK(torque_rows == kTorqueRows);
  // The swing leg L2: no row, its drive torques τ₀ + d against the drive's limits.
  double excess = 0.0;
  for (int j = 0; j < kLegTable.n_joints[1]; ++j) {
    const int k = joint_of(1, j);
    const double tau = s.split.tau0[k] + rows.offset_Nm[k];
    excess = std::max({excess, tau - rows.limit_Nm[k], rows.lower_Nm[k] - tau});
  }
  REQUIRE(excess > 0.0);
  CHECK(ld.constant_excess_Nm == Approx(excess).epsilon(1e-14));
}

TEST_CASE("allocation with drive rows: the objective is Σ w (τ + d)² of the solution's torques",
          "[allocation][drive]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.2, 3.0);
  for (FrictionModel friction : {FrictionModel::kPyramid4, FrictionModel::kCone}) {
    const AllocationParams alloc = params(friction);
    const Sample s = random_sample(43);
    DriveRows rows;
    rows.offset_Nm = JointVector::NullaryExpr(kJointCount, [&] { return u(rng); });
    rows.limit_Nm.setConstant(2.0);
    rows.lower_Nm = -rows.limit_Nm;
    rows.weight = JointVector::NullaryExpr(kJointCount, [&] { return w(rng); });
    QpProblem qp;
    const AllocationLayout layout = build(alloc, s, qp, &rows);
    REQUIRE(layout.variables == 3 * 4 + 2);  // four support legs, one impact leg
    CHECK((qp.H - qp.H.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * qp.H.cwiseAbs().maxCoeff());
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd x =
          20.0 * Eigen::VectorXd::NullaryExpr(layout.variables, [&] { return u(rng); });
      LegArray<Vec3> F_W;
      JointVector tau;
      forces_from_solution(s.split, layout, x, F_W, tau);
      double expected = 0.0, scale = 0.0;
      for (int k = 0; k < kJointCount; ++k) {
        expected += rows.weight[k] * std::pow(tau[k] + rows.offset_Nm[k], 2);
        scale += rows.weight[k] * std::pow(std::abs(tau[k]) + std::abs(rows.offset_Nm[k]), 2);
      }
      const double quadratic = 0.5 * x.dot(qp.H * x) + qp.g.dot(x) + qp.constant;
      INFO("trial " << trial << ": Σ w (τ + d)² = " << expected);
      CHECK(std::abs(quadratic - expected) <= 1e-12 * (1.0 + scale + x.squaredNorm()));
      CHECK(std::abs(qp.objective(x) - expected) <= 1e-12 * (1.0 + scale + x.squaredNorm()));
    }
  }
}

TEST_CASE("allocation with drive rows: torque rows name the drive's bound", "[allocation][drive]") {
  const AllocationParams alloc = params(FrictionModel::kPyramid4);
  const Sample s = random_sample(44);
  const char* suffix[3] = {"", " (peak)", " (voltage)"};
  // For each kind of the swing leg's excess: the kinds cycle over the joints otherwise.
  for (std::int8_t swing_kind : {std::int8_t{0}, std::int8_t{1}, std::int8_t{2}}) {
    DriveRows rows;
    rows.limit_Nm.setConstant(alloc.torque_limit_Nm);
    rows.lower_Nm = -rows.limit_Nm;
    for (int k = 0; k < kJointCount; ++k) rows.bound[k] = static_cast<std::int8_t>(k % 3);
    rows.bound[joint_of(1, 1)] = swing_kind;
    QpProblem qp;
    const AllocationLayout layout = build(alloc, s, qp, &rows);
    int named = 0;
    for (int i = 0; i < qp.inequalities(); ++i) {
      const int k = torque_row_joint(qp.ineq_names[i]);
      if (k < 0) continue;
      ++named;
      CHECK(qp.ineq_names[i] == "torque " + name_of(k) + suffix[k % 3]);
    }
    CHECK(named == kTorqueRows);
    const std::string expect[3] = {"torque L2_femur (swing leg) by ",
                                   "torque L2_femur (swing leg, peak) by ",
                                   "torque L2_femur (swing leg, voltage) by "};
    INFO(layout.constant_violation);
    CHECK(layout.constant_violation.rfind(expect[swing_kind], 0) == 0);
  }
}

}  // namespace hexdyn
