// Tests of the dual active-set back end (src/hexdyn/allocation/active_set_backend.hpp) on sequences
// of problems, as a run solves them: random degenerate sequences certified by the KKT
// conditions and agreeing with a cold back end, warm starts against cold answers, and on
// every sample of the paper run and of the smoke sweep the Ipopt back end: same status,
// same rows named, the same forces.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/active_set_checks.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/sweep.hpp"

using namespace hexdyn;
using namespace hexdyn::test;

TEST_CASE("active-set back end: random degenerate problems are solved to certified optimality",
          "[allocation][active_set]") {
  // Duplicated and scaled rows, zero rows, l = u rows, crossed bounds, infeasible shifts,
  // and slowly changing sequences (warm starts), up to the size limits. Every answer is
  // certified by the KKT conditions of the problem (status 0) or of the penalised problem
  // (status 1), and the warm-started back end agrees with a cold one.
  std::mt19937 rng(12345);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto warm = make_active_set_backend();
  auto cold = make_active_set_backend(active_set(1e6, false));
  QpProblem previous;
  int counts[3] = {0, 0, 0}, certified = 0, agreed = 0, trials = 0;
  std::string first_failure;
  for (int t = 0; t < 1500; ++t) {
    QpProblem p;
    if (t > 0 && U(rng) < 0.4) {
      p = previous;  // the next sample of a slowly changing sequence
      p.g += 0.01 * Eigen::VectorXd::NullaryExpr(p.variables(), [&] { return N(rng); });
    } else {
      const int n = 1 + static_cast<int>(rng() % kActiveSetMaxVariables);
      const int m_eq = n > 3 ? static_cast<int>(rng() % 3) : 0;
      const int m_in = static_cast<int>(rng() % 60);
      p.resize(n, m_eq, m_in);
      const Eigen::MatrixXd M = random_matrix(rng, n, n);
      p.H = M * M.transpose() + 0.01 * Eigen::MatrixXd::Identity(n, n);
      p.g = 3.0 * random_vector(rng, n);
      const Eigen::VectorXd x0 = random_vector(rng, n);
      p.A = random_matrix(rng, m_eq, n);
      p.b = p.A * x0;
      const bool infeasible = U(rng) < 0.3;
      for (int i = 0; i < m_in; ++i) {
        const double kind = U(rng);
        if (kind < 0.2) {
          p.C(i, static_cast<int>(rng() % n)) = 1.0;  // a box
        } else if (kind < 0.25 && i > 0) {
          p.C.row(i) = p.C.row(static_cast<int>(rng() % i)) * (U(rng) < 0.5 ? 1.0 : 2.0);
        } else if (kind >= 0.28) {  // else a zero row
          p.C.row(i) = random_matrix(rng, 1, n);
        }
        const double c = p.C.row(i).dot(x0), bounds = U(rng);
        if (bounds < 0.2) {
          p.lower[i] = p.upper[i] = c;
        } else if (bounds < 0.4) {
          p.lower[i] = c - U(rng);
        } else if (bounds < 0.6) {
          p.upper[i] = c + U(rng);
        } else if (bounds < 0.97) {
          p.lower[i] = c - U(rng), p.upper[i] = c + U(rng);
        }
        if (infeasible && U(rng) < 0.15) {  // may cross the bounds
          if (p.lower[i] > -kQpInfinity)
            p.lower[i] += 3.0 + 5.0 * U(rng);
          else if (p.upper[i] < kQpInfinity)
            p.upper[i] -= 3.0 + 5.0 * U(rng);
        }
        p.ineq_penalty[i] = U(rng) < 0.5 ? 1.0 : 1.0 + 100.0 * U(rng);
        p.ineq_names[i] = "row " + std::to_string(i);
      }
    }
    previous = p;
    const QpOutcome a = warm->solve(p);
    const QpOutcome& b = cold->solve(p);
    ++trials;
    ++counts[static_cast<int>(a.status)];
    const KktVerdict kkt = a.status == SolverStatus::kOptimal ? check_kkt(p, a, 1e-8)
                           : a.status == SolverStatus::kRelaxed
                               ? check_penalised_kkt(p, a, 1e6, 1e-8)
                               : KktVerdict{false, "failed"};
    certified += kkt.ok;
    if (!kkt.ok && first_failure.empty())
      first_failure = std::to_string(t) + ": " + a.message + " " + kkt.why;
    agreed += a.status == b.status && inf_norm(a.x - b.x) <= 1e-6 * (1.0 + inf_norm(b.x));
  }
  INFO("statuses " << counts[0] << "/" << counts[1] << "/" << counts[2] << "; " << first_failure);
  CHECK(certified == trials);
  CHECK(agreed == trials);
  CHECK(counts[1] > 200);  // relaxed answers were exercised
}

TEST_CASE("active-set back end: a feasible problem after a relaxed one is solved to optimality",
          "[allocation][active_set]") {
  std::mt19937 rng(21);
  const QpProblem feasible = random_qp(rng, 9, 0, 6, 9, 15);
  QpProblem infeasible = feasible;
  infeasible.lower[8] = infeasible.upper[8] + 1.0;  // crossed bounds on one row
  auto fresh = make_active_set_backend();
  const QpOutcome reference = fresh->solve(feasible);
  REQUIRE(reference.status == SolverStatus::kOptimal);
  auto backend = make_active_set_backend();
  REQUIRE(backend->solve(infeasible).status == SolverStatus::kRelaxed);
  const QpOutcome after = backend->solve(feasible);  // goes to the penalised form first
  CHECK(after.status == SolverStatus::kOptimal);
  CHECK(after.message.empty());
  CHECK(inf_norm(after.x - reference.x) < 1e-10 * (1.0 + inf_norm(reference.x)));
  CHECK(check_kkt(feasible, after, 1e-9));
  const QpOutcome again = backend->solve(feasible);
  CHECK(again.status == SolverStatus::kOptimal);
  CHECK(inf_norm(again.x - reference.x) < 1e-10 * (1.0 + inf_norm(reference.x)));
  CHECK(again.iterations == 0);  // warm: the previous active set is the answer
}

TEST_CASE("active-set back end: warm starts give the cold answers with fewer changes",
          "[allocation][active_set]") {
  std::mt19937 rng(99);
  auto warm = make_active_set_backend(active_set(1e6, true));
  auto cold = make_active_set_backend(active_set(1e6, false));
  for (const bool relaxed : {false, true}) {
    CAPTURE(relaxed);
    Eigen::VectorXd x0;
    QpProblem p = random_qp(rng, 12, 0, 6, 12, 20, &x0);
    if (relaxed) make_infeasible(p, 6);  // the trunk-like rows cannot hold within the boxes
    const Eigen::VectorXd dg = random_vector(rng, 12);
    const Eigen::MatrixXd dC = random_matrix(rng, p.inequalities(), 12);
    const Eigen::VectorXd db = random_vector(rng, p.inequalities());
    long warm_changes = 0, cold_changes = 0;
    int samples = 0, matched = 0;
    for (int k = 0; k < 60; ++k) {
      QpProblem q = p;
      const double s = 0.002 * k;
      q.g += s * dg;
      q.C += 0.1 * s * dC;
      // Bounds move with the rows (x0 stays feasible) and by a little more.
      const Eigen::VectorXd shift = 0.1 * s * dC * x0 + 0.1 * s * db;
      for (int i = 0; i < q.inequalities(); ++i) {
        if (q.lower[i] > -kQpInfinity) q.lower[i] += shift[i];
        if (q.upper[i] < kQpInfinity) q.upper[i] += shift[i];
      }
      const QpOutcome a = warm->solve(q);
      const QpOutcome& b = cold->solve(q);
      REQUIRE(a.status == b.status);
      CHECK(a.status == (relaxed ? SolverStatus::kRelaxed : SolverStatus::kOptimal));
      matched += inf_norm(a.x - b.x) < 1e-9 * (1.0 + inf_norm(b.x));
      warm_changes += a.iterations;
      cold_changes += b.iterations;
      ++samples;
    }
    CHECK(matched == samples);
    INFO("active-set changes: warm " << warm_changes << ", cold " << cold_changes);
    CHECK(warm_changes * 3 < cold_changes);
  }
  // reset_warm_start: the next solve starts cold.
  QpProblem p = random_qp(rng, 10, 1, 4, 10, 10);
  const int cold_iterations = cold->solve(p).iterations;
  warm->solve(p);
  CHECK(warm->solve(p).iterations == 0);
  warm->reset_warm_start();
  CHECK(warm->solve(p).iterations == cold_iterations);
}

namespace {

/// Agreement of the two back ends over every sample of a scene, solved in order as a run
/// solves them (warm starts, relaxed runs): worst figures and counts.
struct RunComparison {
  int samples = 0, relaxed = 0;
  int status_mismatches = 0;
  int name_mismatches = 0;
  int kkt_failures = 0;
  int objective_failures = 0;  ///< active-set penalised objective above Ipopt's
  double max_dx_optimal = 0.0;
  double max_dx_relaxed = 0.0;
  double max_violation_diff = 0.0;
  double max_dx_extended = 0.0;  ///< against the extended-precision solve
  std::string first_problem;
};

RunComparison compare_backends(const Scene& scene) {
  const PreparedScene prep = prepare_scene(scene);
  const KinematicsResult kin = sample_kinematics(prep.model, prep.plan, prep.grid);
  RobotData data(prep.model);
  const double rho = scene.allocation.slack_penalty;
  IpoptOptions io = ipopt_options_from(scene.allocation);
  io.tolerance = 1e-12;  // the reference: strict solves to the last digits
  auto ipopt = make_ipopt_backend(io);
  auto active = make_active_set_backend(active_set_options_from(scene.allocation));
  QpProblem qp;
  SampleContacts contacts;
  RunComparison r;
  auto note = [&](int i, const std::string& what) {
    if (r.first_problem.empty())
      r.first_problem =
          "sample " + std::to_string(i) + " t = " + std::to_string(kin.time_s[i]) + ": " + what;
  };
  for (int i = 0; i < kin.samples(); ++i) {
    const ContactSplit& split = contact_split(
        prep.model, data, base_state_at(kin, i), kin.joint_position.row(i).transpose(),
        kin.joint_velocity.row(i).transpose(), kin.joint_acceleration.row(i).transpose());
    sample_contacts(kin, i, prep.plan.terrain, prep.touchdowns, contacts);
    build_allocation_problem(scene.allocation, scene.contact, split, contacts.phase,
                             contacts.impact_force_N, contacts.W_R_contact, qp);
    const QpOutcome ref = ipopt->solve(qp);
    const QpOutcome& out = active->solve(qp);
    ++r.samples;
    const double dx = inf_norm(out.x - ref.x);
    if (out.status != ref.status) {
      ++r.status_mismatches;
      note(i, "status " + std::to_string(static_cast<int>(out.status)) + " vs Ipopt " +
                  std::to_string(static_cast<int>(ref.status)));
    }
    if (out.status == SolverStatus::kOptimal) {
      r.max_dx_optimal = std::max(r.max_dx_optimal, dx);
      if (const KktVerdict kkt = check_kkt(qp, out, 1e-9); !kkt) ++r.kkt_failures, note(i, kkt.why);
    } else {
      ++r.relaxed;
      r.max_dx_relaxed = std::max(r.max_dx_relaxed, dx);
      if (named_rows(out.message) != named_rows(ref.message)) {
        ++r.name_mismatches;
        note(i, out.message + " vs Ipopt " + ref.message);
      }
      r.max_violation_diff = std::max(
          r.max_violation_diff, inf_norm(row_violations(qp, out.x) - row_violations(qp, ref.x)));
    }
    if (const KktVerdict kkt = check_penalised_kkt(qp, out, rho, 1e-9); !kkt)
      ++r.kkt_failures, note(i, kkt.why);
    // The active-set answer is the exact penalised optimum: Ipopt's penalised objective is
    // not below it (to rounding of F, which holds ρ w times the violations).
    const double gap = penalised_objective(qp, ref.x, rho) - penalised_objective(qp, out.x, rho);
    const double scale = 1.0 + std::abs(penalised_objective(qp, ref.x, rho));
    if (gap < -1e-10 * scale) ++r.objective_failures, note(i, "penalised objective above Ipopt's");
    r.max_dx_extended =
        std::max(r.max_dx_extended, inf_norm(extended_precision_x(qp, out, rho) - out.x));
  }
  return r;
}

void check_comparison(const RunComparison& r) {
  INFO(r.samples << " samples, " << r.relaxed << " relaxed; max |Δx| optimal " << r.max_dx_optimal
                 << " N, relaxed " << r.max_dx_relaxed << " N; violations " << r.max_violation_diff
                 << "; extended precision " << r.max_dx_extended << " N. " << r.first_problem);
  CHECK(r.status_mismatches == 0);
  CHECK(r.name_mismatches == 0);
  CHECK(r.kkt_failures == 0);
  CHECK(r.objective_failures == 0);
  CHECK(r.max_dx_optimal < 1e-6);
  CHECK(r.max_dx_relaxed < 1e-6);
  CHECK(r.max_violation_diff < 1e-6);
  CHECK(r.max_dx_extended < 1e-6);
}

}  // namespace

TEST_CASE("active-set back end: every sample of the paper run agrees with Ipopt",
          "[allocation][active_set][paper]") {
  // Every sample: the same status, the same rows giving way by the same amounts, forces
  // within 1e-6 N. Relaxed samples also: the active-set forces are the exact penalised
  // optimum (KKT certificate, extended-precision re-solve).
  SECTION("the paper's grid: 1e-6 N on every sample") {
    const RunComparison r = compare_backends(load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml"));
    CHECK(r.samples > 500);
    CHECK(r.relaxed > 100);  // touchdown transients
    check_comparison(r);
    WARN("paper run: " << r.samples << " samples (" << r.relaxed << " relaxed): max |Δx| vs Ipopt "
                       << r.max_dx_optimal << " N optimal, " << r.max_dx_relaxed
                       << " N relaxed; vs extended precision " << r.max_dx_extended << " N");
  }
  SECTION("the denser grid of 40 samples per transient and 1 ms event steps: 1e-6 N too") {
    // 648 relaxed samples. Degenerate penalised optima (rows that hold with zero
    // multipliers next to ρ w up to 1e9) are where Ipopt's own inexactness would show;
    // the KKT certificate and the extended-precision re-solve check our side of them.
    const RunComparison r = compare_backends(
        load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml",
                   {{"output.impact_samples", "40"}, {"output.event_step", "1e-3"}}));
    CHECK(r.samples > 1000);
    CHECK(r.relaxed > 500);
    check_comparison(r);
    WARN("paper run, 40 samples per transient: "
         << r.samples << " samples (" << r.relaxed << " relaxed): max |Δx| vs Ipopt "
         << r.max_dx_optimal << " N optimal, " << r.max_dx_relaxed << " N relaxed");
  }
}

TEST_CASE("active-set back end: every sample of the smoke sweep agrees with Ipopt",
          "[allocation][active_set][sweep]") {
  const SweepSpec spec = load_sweep(HEXDYN_SOURCE_DIR "/configs/sweeps/smoke.yaml");
  REQUIRE(spec.scenario_count() == 8);
  for (std::size_t k = 0; k < spec.scenario_count(); ++k) {
    const ScenarioInput in = scenario_input(spec, k);
    CAPTURE(in.id);
    const RunComparison r = compare_backends(load_scene_from_string(in.yaml, in.id));
    CHECK(r.samples > 30);
    check_comparison(r);
  }
}
