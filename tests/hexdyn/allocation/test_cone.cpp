// Agreement of the exact-cone back end (src/hexdyn/allocation/cone_backend.hpp) with Ipopt at
// tolerance 1e-12 on every sample of the paper run and of the smoke sweep with
// `allocation.friction: cone`, and with the closed-form projection onto one cone. Every
// answer is also checked by computations that need neither back end (cone_checks.hpp): the
// KKT conditions of the cone problem on optimal samples and of its L1-penalised form on
// every sample, and on relaxed samples the penalised problem re-solved in extended
// precision on the structure of our answer, whose optimum is unique (H positive definite).
// Hard cases are in test_cone_hard.cpp.
//
// The reference is Ipopt at tolerance 1e-12 with an absolute stationarity tolerance
// (kReferenceDualInfTol). The paper run is also compared with Ipopt as a run with
// `allocation.solver: ipopt`, `allocation.tolerance: 1e-12` configures it (Ipopt's own
// dual_inf_tol); there one relaxed sample (t = 3.000234 s, three impact feet, six
// variables) lands 3.4e-6 N from ours. That run ends "Solved To Acceptable Level": its
// compl_inf_tol (1e-3·tolerance, unscaled) is out of reach next to an objective of 6.4e9
// (ρ w = 1e8 on three trunk rows), and Ipopt stops once 15 iterates meet its acceptable
// level, tested on the problem whose objective it scaled by 1e-7; that iterate keeps a
// complementarity of 1e-10, which lets it stand up to ~1e-6 inside friction faces held
// with multipliers of 1e-4. The optimum is unique and our answer is it (within 7e-17 N of the
// extended-precision re-solve): the difference is where Ipopt stopped, and the test
// requires that every such difference be explained so.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/cone_backend.hpp"
#include "hexdyn/allocation/cone_checks.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/sweep.hpp"

using namespace hexdyn;
using namespace hexdyn::test::cone;

namespace {

using test::kInf;

/// Agreement with Ipopt over the samples of a scene (every `stride`-th), solved in order as
/// a run solves them.
struct RunComparison {
  int samples = 0, optimal = 0, relaxed = 0;
  int status_mismatches = 0, name_mismatches = 0, kkt_failures = 0;
  int active_cones = 0;        ///< cones active (λ > 0) on optimal samples
  int objective_failures = 0;  ///< penalised objective above Ipopt's
  double max_dx_optimal = 0.0, max_dx_relaxed = 0.0, max_violation_diff = 0.0;
  double max_cone_violation = -kInf;  ///< relative, on optimal samples
  /// Relaxed samples: the penalised problem re-solved in extended precision on the structure
  /// of our answer (extended_precision_cone_x); samples where that is not certified, and the
  /// largest distances of our answer and of Ipopt's from the certified one.
  int uncertified = 0;
  double max_dx_ours_exact = 0.0, max_dx_ipopt_exact = 0.0;
  /// Uniqueness of the penalised optimum on relaxed samples: the smallest ratio of H's
  /// extreme eigenvalues (H positive definite makes the penalised objective strictly
  /// convex, so the certified KKT point is the only optimum) and the smallest eigenvalue.
  double min_eig_ratio = kInf, min_eig = kInf;
  /// Optional second reference: Ipopt with its own dual_inf_tol (a run's Ipopt at
  /// tolerance 1e-12). Samples more than 1e-6 N from ours; those explained (ours the
  /// certified unique optimum to 1e-7 N, Ipopt's penalised objective not below ours);
  /// the largest difference and where.
  int run_ipopt_over = 0, run_ipopt_explained = 0;
  /// Relaxed samples where the reference Ipopt (1e-12) is beyond 1e-6 N, explained as
  /// for the run's Ipopt below: the unique optimum is ours (certified), Ipopt's point is no
  /// better. Their distance is kept apart from max_dx_relaxed and max_dx_ipopt_exact.
  int reference_explained = 0;
  double max_dx_reference_explained = 0.0;
  double max_dx_run_ipopt = 0.0, run_ipopt_worst_t = 0.0, run_ipopt_worst_ipopt_exact = 0.0;
  std::string first_problem;
};

/// Smallest eigenvalue of H and its ratio to the largest.
std::pair<double, double> extreme_eigenvalues(const QpProblem& qp) {
  const Eigen::MatrixXd H = qp.H.selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H, Eigen::EigenvaluesOnly).eigenvalues();
  return {ev.minCoeff(), ev.minCoeff() / ev.maxCoeff()};
}

/// `with_run_ipopt`: also compare with Ipopt as a run configures it at tolerance 1e-12
/// (RunComparison::run_ipopt_*).
RunComparison compare_with_ipopt(const Scene& scene, int stride = 1, bool with_run_ipopt = false) {
  const PreparedScene prep = prepare_scene(scene);
  const KinematicsResult kin = sample_kinematics(prep.model, prep.plan, prep.grid);
  RobotData data(prep.model);
  const double rho = scene.allocation.slack_penalty;
  IpoptOptions io = ipopt_options_from(scene.allocation);
  io.tolerance = 1e-12;
  io.dual_inf_tol = kReferenceDualInfTol;
  auto ipopt = make_ipopt_backend(io);
  IpoptOptions run_io = ipopt_options_from(scene.allocation);
  run_io.tolerance = 1e-12;
  auto run_ipopt = with_run_ipopt ? make_ipopt_backend(run_io) : nullptr;
  auto cone = make_allocation_backend(scene.allocation);
  QpProblem qp;
  SampleContacts contacts;
  RunComparison r;
  auto note = [&](int i, const std::string& what) {
    if (r.first_problem.empty())
      r.first_problem =
          "sample " + std::to_string(i) + " t = " + std::to_string(kin.time_s[i]) + ": " + what;
  };
  for (int i = 0; i < kin.samples(); i += stride) {
    const ContactSplit& split = contact_split(
        prep.model, data, base_state_at(kin, i), kin.joint_position.row(i).transpose(),
        kin.joint_velocity.row(i).transpose(), kin.joint_acceleration.row(i).transpose());
    sample_contacts(kin, i, prep.plan.terrain, prep.touchdowns, contacts);
    build_allocation_problem(scene.allocation, scene.contact, split, contacts.phase,
                             contacts.impact_force_N, contacts.W_R_contact, qp);
    const QpOutcome ref = ipopt->solve(qp);
    const QpOutcome run_ref = run_ipopt ? run_ipopt->solve(qp) : QpOutcome{};
    const QpOutcome& out = cone->solve(qp);
    ++r.samples;
    bool ours_certified_unique = false;  // ours within 1e-7 N of the unique optimum
    Eigen::VectorXd unique_optimum;
    const double dx = inf_norm(out.x - ref.x);
    if (out.status != ref.status) {
      ++r.status_mismatches;
      note(i, "status " + std::to_string(static_cast<int>(out.status)) + " (" + out.message +
                  ") vs Ipopt " + std::to_string(static_cast<int>(ref.status)) + " (" +
                  ref.message + ")");
    }
    if (out.status == SolverStatus::kOptimal) {
      ++r.optimal;
      r.max_dx_optimal = std::max(r.max_dx_optimal, dx);
      if (!qp.cones.empty())
        r.max_cone_violation = std::max(r.max_cone_violation, worst_cone_violation(qp, out.x));
      if (const KktVerdict kkt = check_kkt(qp, out, 1e-9); !kkt) {
        ++r.kkt_failures, note(i, kkt.why);
      } else {
        ours_certified_unique = extreme_eigenvalues(qp).second > 1e-6;
        unique_optimum = out.x;
      }
      for (int k = 0; k < out.lambda_cone.size(); ++k) r.active_cones += out.lambda_cone[k] > 1e-9;
    } else {
      ++r.relaxed;
      if (named_rows(out.message) != named_rows(ref.message)) {
        ++r.name_mismatches;
        note(i, out.message + " vs Ipopt " + ref.message);
      }
      r.max_violation_diff =
          std::max(r.max_violation_diff, inf_norm(violations(qp, out.x) - violations(qp, ref.x)));
      const ExtendedSolution exact = extended_precision_cone_x(qp, out, rho);
      if (!exact.certified) {
        ++r.uncertified, note(i, "extended-precision re-solve not certified: " + exact.why);
      } else {
        r.max_dx_ours_exact = std::max(r.max_dx_ours_exact, inf_norm(out.x - exact.x));
      }
      const auto [lmin, ratio] = extreme_eigenvalues(qp);
      r.min_eig = std::min(r.min_eig, lmin);
      r.min_eig_ratio = std::min(r.min_eig_ratio, ratio);
      ours_certified_unique = exact.certified && ratio > 1e-6 && inf_norm(out.x - exact.x) < 1e-7;
      unique_optimum = exact.x;
      const double ours = penalised_objective(qp, out.x, rho);
      if (dx > 1e-6 && ours_certified_unique &&
          penalised_objective(qp, ref.x, rho) >= ours - 1e-10 * (1.0 + std::abs(ours))) {
        ++r.reference_explained;
        r.max_dx_reference_explained = std::max(r.max_dx_reference_explained, dx);
      } else {
        r.max_dx_relaxed = std::max(r.max_dx_relaxed, dx);
        if (exact.certified)
          r.max_dx_ipopt_exact = std::max(r.max_dx_ipopt_exact, inf_norm(ref.x - exact.x));
      }
    }
    if (const KktVerdict kkt = check_penalised_kkt(qp, out, rho, 1e-9); !kkt)
      ++r.kkt_failures, note(i, kkt.why);
    const double gap = penalised_objective(qp, ref.x, rho) - penalised_objective(qp, out.x, rho);
    if (gap < -1e-10 * (1.0 + std::abs(penalised_objective(qp, ref.x, rho))))
      ++r.objective_failures, note(i, "penalised objective above Ipopt's");
    if (run_ipopt) {
      // Ipopt as a run configures it: a difference beyond 1e-6 N is explained when the
      // optimum is unique (H positive definite, the penalised objective strictly convex),
      // ours is it to 1e-7 N (certified), and Ipopt's point is no better: Ipopt is then
      // more than 9e-7 N from the only optimum.
      const double dr = inf_norm(out.x - run_ref.x);
      if (dr > r.max_dx_run_ipopt) {
        r.max_dx_run_ipopt = dr, r.run_ipopt_worst_t = kin.time_s[i];
        r.run_ipopt_worst_ipopt_exact =
            unique_optimum.size() ? inf_norm(run_ref.x - unique_optimum) : -1.0;
      }
      if (dr > 1e-6) {
        ++r.run_ipopt_over;
        const double ours = penalised_objective(qp, out.x, rho);
        if (ours_certified_unique &&
            penalised_objective(qp, run_ref.x, rho) >= ours - 1e-10 * (1.0 + std::abs(ours))) {
          ++r.run_ipopt_explained;
        } else {
          std::ostringstream os;
          os << "Ipopt at its own dual_inf_tol " << dr << " N away, not explained";
          note(i, os.str());
        }
      }
    }
  }
  return r;
}

void check_comparison(const RunComparison& r) {
  INFO(r.samples << " samples, " << r.relaxed << " relaxed; max |Δx| optimal " << r.max_dx_optimal
                 << " N, relaxed " << r.max_dx_relaxed << " N; violations " << r.max_violation_diff
                 << "; cone " << r.max_cone_violation << "; relaxed vs extended precision: ours "
                 << r.max_dx_ours_exact << " N, Ipopt " << r.max_dx_ipopt_exact << " N, "
                 << r.uncertified
                 << " not certified; H's eigenvalue ratio on relaxed samples >= " << r.min_eig_ratio
                 << "; Ipopt at its own dual_inf_tol: " << r.run_ipopt_over << " beyond 1e-6 N, "
                 << r.run_ipopt_explained << " explained; reference Ipopt beyond 1e-6 N on "
                 << r.reference_explained << " relaxed sample(s), explained (at most "
                 << r.max_dx_reference_explained << " N). " << r.first_problem);
  CHECK(r.status_mismatches == 0);
  CHECK(r.name_mismatches == 0);
  CHECK(r.kkt_failures == 0);
  CHECK(r.objective_failures == 0);
  CHECK(r.max_dx_optimal < 1e-6);
  CHECK(r.max_dx_relaxed < 1e-6);
  CHECK(r.max_violation_diff < 1e-6);
  // Relaxed samples against the third computation: both answers within 1e-6 N of the
  // penalised optimum solved in extended precision on our answer's structure (certified
  // on every relaxed sample).
  CHECK(r.uncertified == 0);
  CHECK(r.max_dx_ours_exact < 1e-6);
  CHECK(r.max_dx_ipopt_exact < 1e-6);
  CHECK(r.max_cone_violation <= 1e-11);
  // The penalised optimum of every relaxed sample is unique: H positive definite with a
  // margin far above rounding.
  CHECK((r.relaxed == 0 || r.min_eig_ratio > 1e-6));
  CHECK(r.run_ipopt_explained == r.run_ipopt_over);
}

Scene paper_with(std::vector<std::pair<std::string, std::string>> overrides) {
  overrides.emplace_back("allocation.friction", "cone");
  std::vector<Override> ov;
  for (auto& [k, v] : overrides) ov.push_back({k, v});
  return load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml", ov);
}

}  // namespace

TEST_CASE("cone back end: one foot is the closed-form projection onto its cone",
          "[allocation][cone]") {
  // Inside, on the far side (apex), and the boundary cases in between, for μ from 0.001 to 5.
  auto backend = cone_backend();
  std::mt19937 rng(4);
  std::normal_distribution<double> N(0.0, 1.0);
  int apex = 0, boundary = 0, inside = 0;
  for (const double mu : {0.001, 0.05, 0.3, 1.0, 5.0}) {
    for (int trial = 0; trial < 40; ++trial) {
      const Eigen::Vector3d a(3.0 * N(rng), 3.0 * N(rng), 2.0 * N(rng));
      CAPTURE(mu, trial, a.transpose());
      const QpProblem p = single_foot(a, mu);
      // n ≥ 0 never binds apart from the apex: the projection has n ≥ 0.
      const Eigen::Vector3d expected = project_onto_cone(a, mu);
      const QpOutcome& out = backend->solve(p);
      REQUIRE(out.status == SolverStatus::kOptimal);
      CHECK(inf_norm(out.x - expected) < 1e-10 * (1.0 + a.norm()));
      CHECK(check_kkt(p, out, 1e-9));
      CHECK(worst_cone_violation(p, out.x) <= 1e-12);
      apex += expected.norm() == 0.0;
      inside += expected == a;
      boundary += expected.norm() > 0.0 && !(expected == a);
    }
  }
  CHECK(apex > 10);
  CHECK(inside > 10);
  CHECK(boundary > 50);
}

TEST_CASE("cone back end: every sample of the paper run with the exact cone agrees with Ipopt",
          "[allocation][cone][paper]") {
  // Same status, same rows and cones giving way by the same amounts, forces within 1e-6 N of
  // Ipopt at tolerance 1e-12; optimal samples also satisfy the cone problem's KKT conditions
  // and hold their cones to 1e-11 relative.
  const RunComparison r = compare_with_ipopt(paper_with({}), 1, true);
  CHECK(r.samples > 500);
  CHECK(r.relaxed > 100);       // touchdown transients
  CHECK(r.active_cones > 250);  // the torque-optimal forces ride the friction limit
  check_comparison(r);
  WARN("paper run, cone: "
       << r.samples << " samples (" << r.relaxed << " relaxed, " << r.active_cones
       << " active cones on optimal samples): max |Δx| vs Ipopt " << r.max_dx_optimal
       << " N optimal, " << r.max_dx_relaxed << " N relaxed; worst cone " << r.max_cone_violation
       << " relative; relaxed samples vs extended precision: ours " << r.max_dx_ours_exact
       << " N, Ipopt " << r.max_dx_ipopt_exact << " N (" << r.uncertified
       << " not certified); H's smallest eigenvalue on relaxed samples " << r.min_eig
       << ", ratio to its largest >= " << r.min_eig_ratio
       << "; Ipopt at its own dual_inf_tol (a run with tolerance 1e-12): max |Δx| "
       << r.max_dx_run_ipopt << " N at t = " << r.run_ipopt_worst_t << " s ("
       << r.run_ipopt_worst_ipopt_exact << " N from the unique optimum), " << r.run_ipopt_over
       << " sample(s) beyond 1e-6 N, " << r.run_ipopt_explained << " explained");
}

TEST_CASE("cone back end: every sample of the smoke sweep with the exact cone agrees with Ipopt",
          "[allocation][cone][sweep]") {
  const SweepSpec spec = load_sweep(HEXDYN_SOURCE_DIR "/configs/sweeps/smoke.yaml");
  REQUIRE(spec.scenario_count() == 8);
  double worst_optimal = 0.0, worst_relaxed = 0.0;
  for (std::size_t k = 0; k < spec.scenario_count(); ++k) {
    const ScenarioInput in = scenario_input(spec, k);
    CAPTURE(in.id);
    Scene scene = load_scene_from_string(in.yaml, in.id);
    scene.allocation.friction = FrictionModel::kCone;
    scene.allocation.solver = AllocationSolver::kActiveSet;
    const RunComparison r = compare_with_ipopt(scene);
    CHECK(r.samples > 30);
    check_comparison(r);
    worst_optimal = std::max(worst_optimal, r.max_dx_optimal);
    worst_relaxed = std::max(worst_relaxed, r.max_dx_relaxed);
  }
  WARN("smoke sweep, cone: max |Δx| vs Ipopt " << worst_optimal << " N optimal, " << worst_relaxed
                                               << " N relaxed");
}
