// The allocation problem (allocation/problem.hpp): a relaxed allocation against the same
// penalised problem solved as a plain QP with explicit slacks; the structural key against
// the row names it stands for.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// The L1-penalised objective the relaxed allocation minimises (allocation_qp.hpp):
/// f(x) + ρ Σ w_i · (violation of row i at x), violations in row units.
double penalised_objective(const QpProblem& p, const Eigen::VectorXd& x, double rho) {
  double v = 0.0;
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    const double w = p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0;
    if (p.lower[i] > -kQpInfinity) v += w * std::max(0.0, p.lower[i] - c);
    if (p.upper[i] < kQpInfinity) v += w * std::max(0.0, c - p.upper[i]);
  }
  return p.objective(x) + rho * v;
}

/// The same minimisation written as an ordinary QP in (x, s): one slack s_i ≥ 0 per row,
/// lower_i − s_i ≤ C_i x ≤ upper_i + s_i, objective f(x) + ρ Σ w_i s_i (a 1e-12 diagonal
/// keeps H definite). Its optimum is the penalised optimum.
QpProblem explicit_slack_problem(const QpProblem& p, double rho) {
  const int n = p.variables(), m = p.inequalities();
  QpProblem q;
  q.resize(n + m, 0, 3 * m);
  q.H.topLeftCorner(n, n) = p.H;
  q.H.bottomRightCorner(m, m).diagonal().setConstant(1e-12);
  q.g.head(n) = p.g;
  q.constant = p.constant;
  for (int i = 0; i < m; ++i) {
    q.g[n + i] = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
    q.C.row(i).head(n) = p.C.row(i);
    q.C(i, n + i) = 1.0;
    q.lower[i] = p.lower[i];
    q.C.row(m + i).head(n) = p.C.row(i);
    q.C(m + i, n + i) = -1.0;
    q.upper[m + i] = p.upper[i];
    q.C(2 * m + i, n + i) = 1.0;
    q.lower[2 * m + i] = 0.0;
  }
  return q;
}

/// Allocation problem of the paper scene at time t (phases and impact forces as the run
/// sets them); returns the number of legs in their touchdown transient.
int paper_problem_at(const Scene& scene, double t, QpProblem& qp) {
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  RobotData data(model);
  const std::vector<Touchdown> tds = resolve_touchdowns(model, data, plan, scene.contact);
  RobotKinematicState s;
  robot_state_at(model, plan, t, s);
  const ContactSplit& split = contact_split(model, data, s.trunk, s.q, s.qd, s.qdd);
  LegArray<ContactPhase> phase{};
  LegArray<double> f_impact{};
  LegArray<Mat3> W_R_c;
  int impacts = 0;
  for (int l = 0; l < model.legs(); ++l) {
    phase[l] = s.feet[l].in_swing ? ContactPhase::kSwing : ContactPhase::kSupport;
    W_R_c[l] = contact_frame(plan.terrain.normal(s.feet[l].p_W.x(), s.feet[l].p_W.y()));
  }
  for (const Touchdown& td : tds) {
    if (!td.transient.occurred || t < td.t_s || t >= td.t_s + td.transient.duration_s) continue;
    phase[td.leg] = ContactPhase::kImpact;
    f_impact[td.leg] = transient_force_at(td.transient, t - td.t_s);
    ++impacts;
  }
  build_allocation_problem(allocation_legs(model), scene.allocation, scene.contact, split, phase,
                           f_impact, W_R_c, qp);
  return impacts;
}

}  // namespace

TEST_CASE("allocation problem: a relaxed allocation minimises the penalised violation",
          "[problem]") {
  // Samples whose rows cannot all hold: inside the paper's touchdown transients (the
  // known impact forces), and during stance with a 0.5 N m torque limit. The scene's back
  // end's answer must be the minimiser of its penalised problem, which Ipopt finds as a
  // plain QP once the slacks are explicit variables (too many for the active-set back end).
  struct Case {
    std::vector<Override> overrides;
    double t_s;
  };
  const std::vector<Case> cases = {{{}, 3.0001},
                                   {{}, 1.7002},
                                   {{{"allocation.torque_limit", "0.5"}}, 0.1},
                                   {{{"allocation.torque_limit", "0.5"}}, 2.0}};
  for (const Case& c : cases) {
    const Scene scene = load_scene(kPaper, c.overrides);
    const double rho = ipopt_options_from(scene.allocation).slack_penalty;
    QpProblem qp;
    paper_problem_at(scene, c.t_s, qp);
    auto backend = make_allocation_backend(scene.allocation);
    const QpOutcome relaxed = backend->solve(qp);
    const QpProblem explicit_qp = explicit_slack_problem(qp, rho);
    auto ipopt = make_ipopt_backend(ipopt_options_from(scene.allocation));
    const QpOutcome reference = ipopt->solve(explicit_qp);
    const Eigen::VectorXd x_ref = reference.x.head(qp.variables());
    const double j_relaxed = penalised_objective(qp, relaxed.x, rho);
    const double j_ref = penalised_objective(qp, x_ref, rho);
    INFO("t = " << c.t_s << " s" << (c.overrides.empty() ? "" : ", torque limit 0.5 N m")
                << ": relaxed " << relaxed.message);
    INFO("penalised objective: back end "
         << j_relaxed << ", minimum " << j_ref
         << "; violations at the minimum: " << describe_violations(qp, x_ref, 1e-9));
    REQUIRE(reference.status == SolverStatus::kOptimal);
    CHECK(relaxed.status == SolverStatus::kRelaxed);
    CHECK(j_relaxed <= j_ref + 1e-6 * std::abs(j_ref));
  }
}

TEST_CASE("allocation problem: the structural key tells row layouts apart as the row names do",
          "[problem]") {
  // Every contact-phase combination of the six legs under each friction model, built twice
  // with different numbers. Within one friction model (fixed for a run), two problems share
  // the key exactly when they share every row name (and so every row kind); across models
  // an equal key still implies equal names.
  const Scene scene = load_scene(kPaper);
  const AllocationLegs legs = allocation_legs(build_robot_model(scene.robot));
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  struct Built {
    int model = 0;
    std::uint64_t key = 0;
    std::vector<std::string> names;
  };
  std::vector<Built> built;
  const FrictionModel models[3] = {FrictionModel::kPyramid4, FrictionModel::kPyramid8,
                                   FrictionModel::kCone};
  for (int fm = 0; fm < 3; ++fm) {
    AllocationParams alloc = scene.allocation;
    alloc.friction = models[fm];
    for (int code = 0; code < 729; ++code) {  // 3⁶: every phase of each of six legs
      LegArray<ContactPhase> phase{};
      for (int l = 0, c = code; l < legs.legs; ++l, c /= 3)
        phase[l] = static_cast<ContactPhase>(c % 3);
      std::uint64_t keys[2];
      std::vector<std::string> names[2];
      for (int rep = 0; rep < 2; ++rep) {
        AllocationSplit split;
        split.trunk_rhs = Vec6::NullaryExpr([&] { return g(rng); });
        split.tau0 = JointVector::NullaryExpr(legs.joints, [&] { return g(rng); });
        for (int l = 0; l < legs.legs; ++l)
          split.JjT[l] =
              AllocationSplit::JointRows::NullaryExpr(legs.joints, 3, [&] { return g(rng); });
        for (int l = 0; l < legs.legs; ++l)
          split.JbT[l] = Eigen::Matrix<double, 6, 3>::NullaryExpr([&] { return g(rng); });
        LegArray<double> f_impact{};
        LegArray<Mat3> frames;
        for (int l = 0; l < legs.legs; ++l) {
          f_impact[l] = 10.0 + std::abs(g(rng));
          frames[l] = Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
        }
        QpProblem qp;
        build_allocation_problem(legs, alloc, scene.contact, split, phase, f_impact, frames, qp);
        keys[rep] = qp.structure;
        names[rep] = qp.ineq_names;
        for (const SecondOrderCone& c : qp.cones) names[rep].push_back(c.name);
      }
      CHECK(keys[0] == keys[1]);
      CHECK(names[0] == names[1]);
      built.push_back({fm, keys[0], names[0]});
    }
  }
  long same_model_pairs = 0, mismatches = 0, equal_names_across = 0;
  for (std::size_t i = 0; i < built.size(); ++i)
    for (std::size_t j = i + 1; j < built.size(); ++j) {
      const bool same_key = built[i].key == built[j].key;
      const bool same_names = built[i].names == built[j].names;
      if (built[i].model == built[j].model) {
        ++same_model_pairs;
        mismatches += same_key != same_names;
      } else {
        mismatches += same_key && !same_names;
        equal_names_across += same_names;
      }
    }
  CHECK(same_model_pairs == 3L * 729 * 728 / 2);
  CHECK(mismatches == 0);
  CHECK(equal_names_across > 0);  // e.g. all legs in swing: the six trunk rows alone
}

}  // namespace hexdyn
