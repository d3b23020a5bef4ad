// Inverse dynamics of hexdyn against DART 6.12 (Debian libdart-dev) on the same robot,
// states and foot forces: the target "≤ 2 µs per evaluation and ≥ 5× faster
// than DART", both numbers measured in this one process. DART is used here only; the
// library and the pipeline never depend on it.
//  - The DART skeleton is built from hexdyn's RobotModel: the trunk (trunk + payload) on a
//    FreeJoint, the 18 links on RevoluteJoints with the model's joint placements, axes and
//    inertias, gravity (0, 0, −9.81) m/s².
//  - States: every sample of the paper run (bench_paper.hpp), with the six foot forces of
//    bench_dynamics.cpp, (0.5, −0.3, 65.7/3) N in world axes at the foot points. Each state
//    is converted once, before any timing, into DART's generalised coordinates.
//  - Before timing, main() checks that DART's inverse dynamics equals hexdyn's rnea (18
//    joint torques and the trunk wrench) on every sample, and again on every sample with the
//    trunk tilted and spinning (the paper's trunk does not rotate), and exits if any entry
//    differs by more than 1e-6 (N, N m): a mismatched robot would make the ratio meaningless.
//  - BM_HexdynRnea and BM_DartInverseDynamics time one evaluation each, cycling through the
//    samples. BM_DartRatio times whole passes over the samples, hexdyn and DART in turn,
//    and reports the medians per evaluation (`hexdyn_us`, `dart_us`) and their ratio
//    `dart_ratio`. Every benchmark carries `max_abs_diff` from the check.
//
// Conversion between the two sets of coordinates (R = W_R_B, trunk axes → world axes):
//
//   hexdyn ν  = [ v_W ; ω_W ; q̇ ]           v_W velocity of the trunk origin P0, world axes
//   DART  dq  = [ Rᵀω_W ; Rᵀv_W ; q̇ ]       FreeJoint: the trunk's spatial velocity in trunk
//                                            coordinates, (angular, linear) order
//   hexdyn ν̇  = [ a_W ; ω̇_W ; q̈ ]           a_W classical acceleration of P0
//   DART ddq  = [ Rᵀω̇_W ; Rᵀa_W − Rᵀω_W × Rᵀv_W ; q̈ ]
//                                            the spatial acceleration d/dt(dq), whose linear
//                                            part differs from the classical one by ω × v
//   DART  τ   = [ n_B ; f_B ; τ_joints ]     wrench on the trunk about P0, trunk axes
//   hexdyn τ  = [ R f_B ; R n_B ; τ_joints ]
//
// These hold because DART 6.12's FreeJoint has relative Jacobian 1₆ (and time derivative
// 0) when the joint frames coincide with the bodies' frames; the check asserts it. Joint
// k's DART degree of freedom is looked up, not assumed to be 6 + k.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_paper.hpp"

namespace {

using namespace hexdyn;
namespace dd = dart::dynamics;

/// Foot forces of bench_dynamics.cpp: force of the terrain on each foot [N], world axes.
LegArray<Vec3> foot_forces_W(const RobotModel& model) {
  LegArray<Vec3> f;
  for (int l = 0; l < model.legs(); ++l) f[l] = Vec3(0.5, -0.3, 65.7 / 3.0);
  return f;
}

Eigen::Isometry3d isometry(const Mat3& R, const Vec3& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = p;
  return T;
}

/// Mass, COM and inertia about the COM, all in the body frame (as RigidInertia).
dd::Inertia dart_inertia(const RigidInertia& r) {
  return dd::Inertia(r.mass_kg, r.com_m, r.inertia_com);
}

/// The robot of a RobotModel as a DART skeleton, with the index maps between the two.
struct DartRobot {
  dd::SkeletonPtr skeleton;
  BodyArray<dd::BodyNode*> body{};  ///< hexdyn body b → DART body node
  JointArray<int> dof{};            ///< hexdyn joint k → DART dof index
  dd::FreeJoint* trunk_joint = nullptr;
  Vec3 foot_tibia = Vec3::Zero();      ///< foot point in the tibia frame [m]
  LegArray<dd::BodyNode*> foot{};      ///< each leg's foot body (RobotModel::foot_body)
  int legs = 0, joints = 0, dofs = 0;  ///< the model's counts
};

DartRobot make_dart_robot(const RobotModel& model) {
  DartRobot r;
  r.skeleton = dd::Skeleton::create("hexdyn");
  r.skeleton->setGravity(Eigen::Vector3d(0.0, 0.0, -kGravity));

  dd::FreeJoint::Properties trunk;
  trunk.mName = "trunk_free";  // joint frames = parent (world) and trunk frames
  auto [trunk_joint, trunk_body] = r.skeleton->createJointAndBodyNodePair<dd::FreeJoint>(
      nullptr, trunk, dd::BodyNode::AspectProperties("trunk", dart_inertia(model.inertia[0])));
  r.trunk_joint = trunk_joint;
  r.body[0] = trunk_body;

  // Body b's frame in its parent's: T_ParentBodyToJoint · Rot(axis, q), child frame = joint
  // frame, as hexdyn's X_parent_body = (R_parent_joint · Rot(axis, q), p_parent_joint).
  r.legs = model.legs();
  r.joints = model.joints();
  r.dofs = model.dofs();
  for (int b = 1; b < model.bodies(); ++b) {
    if (model.parent[b] < 0 || model.parent[b] >= b)
      throw std::logic_error("bench_dynamics_dart: bodies are not in topological order");
    dd::RevoluteJoint::Properties joint;
    joint.mName = "joint_" + std::to_string(b - 1);
    joint.mAxis = model.axis[b];
    joint.mT_ParentBodyToJoint = isometry(model.R_parent_joint[b], model.p_parent_joint[b]);
    joint.mT_ChildBodyToJoint = Eigen::Isometry3d::Identity();
    auto [j, body] = r.skeleton->createJointAndBodyNodePair<dd::RevoluteJoint>(
        r.body[model.parent[b]], joint,
        dd::BodyNode::AspectProperties("body_" + std::to_string(b),
                                       dart_inertia(model.inertia[b])));
    r.body[b] = body;
    r.dof[b - 1] = static_cast<int>(j->getIndexInSkeleton(0));
  }
  r.foot_tibia = Vec3(model.link_length_m[2], 0.0, 0.0);
  for (int l = 0; l < model.legs(); ++l) r.foot[l] = r.body[model.foot_body(l)];
  return r;
}

/// One sample in DART's generalised coordinates (DART dof order, see the file comment).
/// Dynamic-size vectors: the type Skeleton::setPositions etc. take, so no copy is made.
struct DartState {
  Eigen::VectorXd q, dq, ddq;
};

DartState to_dart(const DartRobot& r, const bench::SampleState& s) {
  const BaseState& b = s.base;
  const Mat3 B_R_W = b.W_R_B.transpose();
  const Vec3 omega_B = B_R_W * b.omega_W, v_B = B_R_W * b.v_W;
  DartState d{Eigen::VectorXd::Zero(r.dofs), Eigen::VectorXd::Zero(r.dofs),
              Eigen::VectorXd::Zero(r.dofs)};
  const int t = static_cast<int>(r.trunk_joint->getIndexInSkeleton(0));
  d.q.segment<6>(t) = dd::FreeJoint::convertToPositions(isometry(b.W_R_B, b.p_W));
  d.dq.segment<3>(t) = omega_B;
  d.dq.segment<3>(t + 3) = v_B;
  d.ddq.segment<3>(t) = B_R_W * b.omegadot_W;
  d.ddq.segment<3>(t + 3) = B_R_W * b.a_W - omega_B.cross(v_B);
  for (int k = 0; k < r.joints; ++k) {
    d.q[r.dof[k]] = s.q[k];
    d.dq[r.dof[k]] = s.qd[k];
    d.ddq[r.dof[k]] = s.qdd[k];
  }
  return d;
}

/// One DART inverse-dynamics evaluation: state, foot forces (world-axes force at the foot
/// point, an offset in the tibia frame), then Skeleton::computeInverseDynamics with the
/// external forces. Result: the generalised forces in DART dof order.
void dart_inverse_dynamics(DartRobot& r, const DartState& s, const LegArray<Vec3>& F_W,
                           DofVector& out) {
  dd::Skeleton& sk = *r.skeleton;
  out.resize(r.dofs);
  sk.setPositions(s.q);
  sk.setVelocities(s.dq);
  sk.setAccelerations(s.ddq);
  for (int l = 0; l < r.legs; ++l)
    r.foot[l]->setExtForce(F_W[l], r.foot_tibia, /*isForceLocal=*/false, /*isOffsetLocal=*/true);
  sk.computeInverseDynamics(/*withExternalForces=*/true, /*withDampingForces=*/false,
                            /*withSpringForces=*/false);
  for (int i = 0; i < r.dofs; ++i) out[i] = sk.getForce(static_cast<std::size_t>(i));
}

/// DART's generalised forces (DART order) in hexdyn's coordinates (dynamics.hpp).
DofVector to_hexdyn(const DartRobot& r, const BaseState& b, const DofVector& dart) {
  const int t = static_cast<int>(r.trunk_joint->getIndexInSkeleton(0));
  DofVector tau(r.dofs);
  tau.head<3>() = b.W_R_B * dart.segment<3>(t + 3);  // force on the trunk [N]
  tau.segment<3>(3) = b.W_R_B * dart.segment<3>(t);  // moment about P0 [N m]
  for (int k = 0; k < r.joints; ++k) tau[6 + k] = dart[r.dof[k]];
  return tau;
}

/// Everything the benchmarks share: the paper states in both coordinate sets, both robots.
struct Setup {
  const RobotModel& model;
  std::vector<bench::SampleState> samples;
  DartRobot dart;
  std::vector<DartState> dart_samples;
  LegArray<Vec3> forces = foot_forces_W(model);
};

Setup& setup() {
  static Setup s = [] {
    const bench::PaperSetup& p = bench::paper_setup();
    Setup out{p.model, {}, make_dart_robot(p.model), {}};
    for (int i = 0; i < p.kin.samples(); ++i) {
      out.samples.push_back(bench::sample_state(p.kin, i));
      out.dart_samples.push_back(to_dart(out.dart, out.samples.back()));
    }
    return out;
  }();
  return s;
}

/// Worst disagreement of DART with hexdyn over every checked state (check_agreement).
struct Agreement {
  double max_abs_diff = 0.0;  ///< max |τ_DART − τ_hexdyn| over entries and states [N, N m]
  double max_rel_diff = 0.0;  ///< the same over max(1, ‖τ_hexdyn‖∞) of each state
  int states = 0;             ///< states compared
  int worst_state = -1, worst_row = -1;
};
Agreement g_agreement;

constexpr double kMaxAbsDiff = 1e-6;  ///< [N, N m]; the torques are O(10) N m

/// Compares DART with hexdyn on one state (with the foot forces); updates g_agreement.
/// False if DART's FreeJoint Jacobian is not the identity the conversion relies on.
bool compare(Setup& s, RobotData& data, const bench::SampleState& x) {
  const DartState d = to_dart(s.dart, x);
  DofVector dart_tau;
  dart_inverse_dynamics(s.dart, d, s.forces, dart_tau);
  const dd::Joint& trunk_joint = *s.dart.trunk_joint;
  if (!trunk_joint.getRelativeJacobian().isIdentity(1e-12) ||
      !trunk_joint.getRelativeJacobianTimeDeriv().isZero(1e-12)) {
    std::fprintf(stderr,
                 "bench_dynamics_dart: DART's FreeJoint Jacobian is not the identity; the "
                 "state conversion of this benchmark does not apply to DART %s\n",
                 DART_VERSION);
    return false;
  }
  const DofVector& tau = rnea(s.model, data, x.base, x.q, x.qd, x.qdd, &s.forces);
  const DofVector diff = (to_hexdyn(s.dart, x.base, dart_tau) - tau).cwiseAbs();
  int row = 0;
  const double e = diff.maxCoeff(&row);
  if (e > g_agreement.max_abs_diff) {
    g_agreement.max_abs_diff = e;
    g_agreement.worst_state = g_agreement.states;
    g_agreement.worst_row = row;
  }
  g_agreement.max_rel_diff =
      std::max(g_agreement.max_rel_diff, e / std::max(1.0, tau.cwiseAbs().maxCoeff()));
  ++g_agreement.states;
  return true;
}

/// Compares DART with hexdyn on every sample of the paper run, then on the same samples
/// with the trunk tilted and spinning (pseudo-random, fixed seed): the paper's trunk never
/// rotates (ω = ω̇ = 0), which would leave the ω × v terms of the conversion untested.
/// False (with a message) if they disagree by more than kMaxAbsDiff.
bool check_agreement() {
  Setup& s = setup();
  RobotData data(s.model);
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random_vec = [&](double scale) -> Vec3 {
    return scale * Vec3(u(rng), u(rng), u(rng));
  };
  for (const bench::SampleState& x : s.samples)
    if (!compare(s, data, x)) return false;
  for (bench::SampleState x : s.samples) {
    const Vec3 tilt = random_vec(0.5);  // rotation vector [rad]
    x.base.W_R_B = x.base.W_R_B * Eigen::AngleAxisd(tilt.norm(), tilt.normalized()).matrix();
    x.base.omega_W = random_vec(3.0);      // [rad/s]
    x.base.omegadot_W = random_vec(30.0);  // [rad/s²]
    if (!compare(s, data, x)) return false;
  }
  std::fprintf(stderr,
               "bench_dynamics_dart: DART %s vs hexdyn rnea on %d states (%zu paper samples, "
               "then spun): max |diff| %.3g (state %d, row %d), max relative %.3g\n",
               DART_VERSION, g_agreement.states, s.samples.size(), g_agreement.max_abs_diff,
               g_agreement.worst_state, g_agreement.worst_row, g_agreement.max_rel_diff);
  if (!(g_agreement.max_abs_diff <= kMaxAbsDiff)) {
    std::fprintf(stderr,
                 "bench_dynamics_dart: DART and hexdyn disagree by more than %g: the two robots "
                 "or the coordinate conversion differ, the timing ratio would be meaningless\n",
                 kMaxAbsDiff);
    return false;
  }
  return true;
}

void BM_HexdynRnea(benchmark::State& state) {
  Setup& s = setup();
  RobotData data(s.model);
  std::size_t i = 0;
  for (auto _ : state) {
    const bench::SampleState& x = s.samples[i];
    i = i + 1 == s.samples.size() ? 0 : i + 1;
    benchmark::DoNotOptimize(rnea(s.model, data, x.base, x.q, x.qd, x.qdd, &s.forces).data());
    benchmark::ClobberMemory();
  }
  state.counters["max_abs_diff"] = g_agreement.max_abs_diff;
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexdynRnea)->Unit(benchmark::kMicrosecond);

void BM_DartInverseDynamics(benchmark::State& state) {
  Setup& s = setup();
  DofVector tau;
  std::size_t i = 0;
  for (auto _ : state) {
    dart_inverse_dynamics(s.dart, s.dart_samples[i], s.forces, tau);
    i = i + 1 == s.samples.size() ? 0 : i + 1;
    benchmark::DoNotOptimize(tau.data());
    benchmark::ClobberMemory();
  }
  state.counters["max_abs_diff"] = g_agreement.max_abs_diff;
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DartInverseDynamics)->Unit(benchmark::kMicrosecond);

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// One iteration = one pass over every sample with hexdyn and one with DART, in
/// alternating order so that a drift of the clock rate affects both alike. Counters:
/// median time per evaluation of each [µs] and dart_ratio = DART's over hexdyn's.
void BM_DartRatio(benchmark::State& state) {
  Setup& s = setup();
  RobotData data(s.model);
  DofVector tau;
  const double n = static_cast<double>(s.samples.size());
  const auto hexdyn_pass = [&] {
    for (const bench::SampleState& x : s.samples) {
      benchmark::DoNotOptimize(rnea(s.model, data, x.base, x.q, x.qd, x.qdd, &s.forces).data());
      benchmark::ClobberMemory();
    }
  };
  const auto dart_pass = [&] {
    for (const DartState& x : s.dart_samples) {
      dart_inverse_dynamics(s.dart, x, s.forces, tau);
      benchmark::DoNotOptimize(tau.data());
      benchmark::ClobberMemory();
    }
  };
  const auto seconds = [](const auto& pass) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<double> hexdyn_us, dart_us;
  bool hexdyn_first = true;
  for (auto _ : state) {
    if (hexdyn_first) {
      hexdyn_us.push_back(1e6 * seconds(hexdyn_pass) / n);
      dart_us.push_back(1e6 * seconds(dart_pass) / n);
    } else {
      dart_us.push_back(1e6 * seconds(dart_pass) / n);
      hexdyn_us.push_back(1e6 * seconds(hexdyn_pass) / n);
    }
    hexdyn_first = !hexdyn_first;
  }
  const double hexdyn = median(hexdyn_us), dart = median(dart_us);
  state.counters["hexdyn_us"] = hexdyn;
  state.counters["dart_us"] = dart;
  state.counters["dart_ratio"] = dart / hexdyn;
  state.counters["samples"] = n;
  state.counters["max_abs_diff"] = g_agreement.max_abs_diff;
}
BENCHMARK(BM_DartRatio)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  if (!check_agreement()) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
