// Tests of the exact-cone back end (src/hexdyn/allocation/cone.hpp). Every answer is
// checked against a second computation: the closed-form projection onto a second-order
// cone, Ipopt at tolerance 1e-12, and the KKT conditions of the cone problem, which need no
// cone multiplier from the back end (the residual of stationarity on a cone's variables
// must lie in the dual cone and be complementary to the forces). On every sample of the
// paper run and of the smoke sweep with the exact cone: the status and rows named as by
// Ipopt, forces within 1e-6 N, and the cone holding on every optimal sample.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/allocation/active_set.hpp"
#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/cone.hpp"
#include "hexdyn/allocation/ipopt.hpp"
#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/allocation/qp_test_problems.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/config.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/sweep/sweep.hpp"

using namespace hexdyn;

namespace {

using test::kInf;

double inf_norm(const Eigen::VectorXd& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

/// Ipopt as the reference: tolerance 1e-12, cold starts.
std::unique_ptr<AllocationBackend> reference_ipopt(double slack_penalty = 1e6) {
  IpoptOptions o;
  o.tolerance = 1e-12;
  o.slack_penalty = slack_penalty;
  o.warm_start = false;
  return make_ipopt_backend(o);
}

std::unique_ptr<AllocationBackend> cone_backend(double slack_penalty = 1e6) {
  ConeOptions o;
  o.qp.slack_penalty = slack_penalty;
  return make_cone_backend(o);
}

/// Largest cone violation ‖t‖ − μ n relative to max(1, ‖t‖) (≤ 0 when every cone holds).
double worst_cone_violation(const QpProblem& p, const Eigen::VectorXd& x) {
  double worst = -kInf;
  for (const SecondOrderCone& c : p.cones) {
    const double r = std::hypot(x[c.tangent1], x[c.tangent2]);
    worst = std::max(worst, (r - c.mu * x[c.normal]) / std::max(1.0, r));
  }
  return worst;
}

/// KKT conditions of a cone problem at an answer of status 0, with its row multipliers
/// only: y = H x + g − Aᵀλ_eq − Cᵀλ_in must vanish off the cones and, on each cone's
/// (t1, t2, n), lie in the dual cone {μ‖y_t‖ ≤ y_n} and be complementary, yᵀ(t, n) = 0;
/// the rows' own conditions (feasibility, multiplier signs, complementarity) by check_kkt
/// on the problem without cones whose gradient absorbs y. The cones must hold. Also
/// compares the back end's λ_cone with y_n / μ where the cone is active away from its apex.
bool check_cone_kkt(const QpProblem& p, const QpOutcome& out, double tol, std::string* why) {
  std::ostringstream os;
  const Eigen::VectorXd& x = out.x;
  const Eigen::MatrixXd H = p.H.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd y = H * x + p.g;
  double scale = 1.0 + inf_norm(H * x) + inf_norm(p.g);
  if (p.equalities() > 0) y -= p.A.transpose() * out.lambda_eq;
  if (p.inequalities() > 0) {
    y -= p.C.transpose() * out.lambda_ineq;
    scale += inf_norm(p.C.transpose() * out.lambda_ineq);
  }
  QpProblem q = p;
  q.cones.clear();
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    const Eigen::Vector2d yt(y[c.tangent1], y[c.tangent2]);
    const double yn = y[c.normal];
    const Eigen::Vector2d t(x[c.tangent1], x[c.tangent2]);
    const double n = x[c.normal];
    if (t.norm() - c.mu * n > tol * std::max(1.0, t.norm())) {
      os << "cone " << k << " violated by " << t.norm() - c.mu * n;
      *why = os.str();
      return false;
    }
    if (c.mu * yt.norm() > yn + tol * scale) {
      os << "cone " << k << ": residual (" << yt.transpose() << ", " << yn << ") not in the dual cone";
      *why = os.str();
      return false;
    }
    if (std::abs(yt.dot(t) + yn * n) > tol * scale * (1.0 + t.norm() + std::abs(n))) {
      os << "cone " << k << ": complementarity " << yt.dot(t) + yn * n;
      *why = os.str();
      return false;
    }
    if (out.lambda_cone.size() == static_cast<int>(p.cones.size()) && t.norm() > 1e-6 && c.mu > 0.0 &&
        std::abs(out.lambda_cone[k] - yn / c.mu) > 1e-6 * scale / c.mu) {
      os << "cone " << k << ": λ_cone " << out.lambda_cone[k] << " vs y_n/μ " << yn / c.mu;
      *why = os.str();
      return false;
    }
    for (int idx : {c.tangent1, c.tangent2, c.normal}) q.g[idx] -= y[idx];
  }
  return check_kkt(q, out, tol, why);
}

/// ½xᵀHx + gᵀx + c + ρ Σ w · (violation of each row and cone), in row units; violations
/// within rounding (1e-12·(1 + |bound|)) count as 0.
double penalised_objective(const QpProblem& p, const Eigen::VectorXd& x, double rho) {
  auto beyond = [](double v, double bound) { return v > 1e-12 * (1.0 + std::abs(bound)) ? v : 0.0; };
  double v = 0.0;
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    const double w = p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0;
    if (p.lower[i] > -kQpInfinity) v += w * beyond(p.lower[i] - c, p.lower[i]);
    if (p.upper[i] < kQpInfinity) v += w * beyond(c - p.upper[i], p.upper[i]);
  }
  for (const SecondOrderCone& c : p.cones) {
    const double bound = c.mu * x[c.normal];
    v += c.penalty * beyond(std::hypot(x[c.tangent1], x[c.tangent2]) - bound, bound);
  }
  return p.objective(x) + rho * v;
}

/// KKT conditions of the L1-penalised cone problem at an answer (status 0 or 1), with its
/// row multipliers only. y = H x + g − Aᵀλ_eq − Cᵀλ_in; off the cones y = 0; per
/// inequality row λ_i in the subdifferential of its penalty (ρw below the lower bound, −ρw
/// above the upper one, 0 inside, in between at a bound); per cone, y on (t, n) in minus
/// the subdifferential of ρw max(0, ‖t‖ − μn): ρw(−t/‖t‖, μ) where the cone is violated, 0
/// strictly inside, s(−u, μ) with s ∈ [0, ρw], ‖u‖ ≤ 1 and s(‖t‖ − μ n) = 0 on its
/// boundary. With H positive definite these certify the unique penalised optimum.
bool check_penalised_cone_kkt(const QpProblem& p, const QpOutcome& out, double rho, double tol,
                              std::string* why) {
  std::ostringstream os;
  const Eigen::VectorXd& x = out.x;
  const Eigen::MatrixXd H = p.H.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd y = H * x + p.g;
  Eigen::VectorXd scale = (H * x).cwiseAbs() + p.g.cwiseAbs();
  if (p.equalities() > 0) {
    y -= p.A.transpose() * out.lambda_eq;
    scale += p.A.cwiseAbs().transpose() * out.lambda_eq.cwiseAbs();
  }
  if (p.inequalities() > 0) {
    y -= p.C.transpose() * out.lambda_ineq;
    scale += p.C.cwiseAbs().transpose() * out.lambda_ineq.cwiseAbs();
  }
  std::vector<bool> on_cone(static_cast<std::size_t>(p.variables()), false);
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    const double kappa = rho * c.penalty;
    const Eigen::Vector2d t(x[c.tangent1], x[c.tangent2]), yt(y[c.tangent1], y[c.tangent2]);
    const double yn = y[c.normal], r = t.norm(), excess = r - c.mu * x[c.normal];
    const double ytol = tol * (1.0 + kappa + scale[c.tangent1] + scale[c.tangent2] + scale[c.normal]);
    const double d = tol * (1.0 + r);
    bool ok = true;
    if (excess > d) {
      ok = (yt + kappa * t / r).norm() <= ytol && std::abs(yn - kappa * c.mu) <= ytol;
    } else if (excess < -d) {
      ok = yt.norm() <= ytol && std::abs(yn) <= ytol;
    } else {
      ok = yn >= -ytol && yn <= kappa * c.mu + ytol && c.mu * yt.norm() <= yn + ytol &&
           std::abs(yt.dot(t) + yn * x[c.normal]) <= ytol * (1.0 + r + std::abs(x[c.normal]));
    }
    if (!ok) {
      os << "cone " << k << ": excess " << excess << ", residual (" << yt.transpose() << ", " << yn
         << ") not in the penalty's subdifferential (ρw = " << kappa << ")";
      *why = os.str();
      return false;
    }
    for (int idx : {c.tangent1, c.tangent2, c.normal}) on_cone[static_cast<std::size_t>(idx)] = true;
  }
  for (int j = 0; j < p.variables(); ++j) {
    if (!on_cone[static_cast<std::size_t>(j)] && std::abs(y[j]) > tol * (1.0 + scale[j])) {
      os << "stationarity residual " << y[j] << " in variable " << j;
      *why = os.str();
      return false;
    }
  }
  for (int i = 0; i < p.equalities(); ++i) {
    if (std::abs(p.A.row(i).dot(x) - p.b[i]) > tol * (1.0 + std::abs(p.b[i]))) {
      *why = "equality " + p.eq_name(i) + " violated";
      return false;
    }
  }
  for (int i = 0; i < p.inequalities(); ++i) {
    const double kappa = rho * (p.ineq_penalty.size() ? p.ineq_penalty[i] : 1.0);
    const double c = p.C.row(i).dot(x), lam = out.lambda_ineq[i];
    const double lo = p.lower[i], hi = p.upper[i];
    const bool has_lo = lo > -kQpInfinity, has_hi = hi < kQpInfinity;
    auto minus_slope = [&](double at) {
      return (has_lo && at < lo ? kappa : 0.0) - (has_hi && at > hi ? kappa : 0.0);
    };
    const double d = std::max(has_lo ? tol * (1.0 + std::abs(lo)) : 0.0, has_hi ? tol * (1.0 + std::abs(hi)) : 0.0);
    const double lmin = std::min(minus_slope(c - d), minus_slope(c + d));
    const double lmax = std::max(minus_slope(c - d), minus_slope(c + d));
    if (lam < lmin - tol * (1.0 + kappa) || lam > lmax + tol * (1.0 + kappa)) {
      os << p.ineq_name(i) << ": C x = " << c << " in [" << lo << ", " << hi << "], λ = " << lam << " not in ["
         << lmin << ", " << lmax << "]";
      *why = os.str();
      return false;
    }
  }
  return true;
}

/// Projection of (t, n) onto {‖t‖ ≤ μ n} in the metric ½|·|²: closed form.
Eigen::Vector3d project_onto_cone(const Eigen::Vector3d& a, double mu) {
  const Eigen::Vector2d t = a.head<2>();
  const double n = a[2], r = t.norm();
  if (r <= mu * n) return a;
  if (mu * r <= -n) return Eigen::Vector3d::Zero();
  // The nearest point on the ray n = r'/μ in the plane of t: minimise (r' − r)² + (r'/μ − n)².
  const double rp = (r + n / mu) / (1.0 + 1.0 / (mu * mu));
  Eigen::Vector3d out;
  out << rp * t / r, rp / mu;
  return out;
}

/// One foot, min ½|x − a|² subject to its cone (and n ≥ 0, as the allocation has).
QpProblem single_foot(const Eigen::Vector3d& a, double mu) {
  QpProblem p;
  p.resize(3, 0, 1);
  p.H.setIdentity();
  p.g = -a;
  p.constant = 0.5 * a.squaredNorm();
  p.C(0, 2) = 1.0;
  p.lower[0] = 0.0;
  p.ineq_names = {"normal L1"};
  p.ineq_penalty[0] = 1e3;
  p.cones.push_back({0, 1, 2, mu, "friction cone L1", 1e3});
  return p;
}

/// Rows named in a "relaxed: a by 1, b by 2" message, sorted.
std::vector<std::string> named_rows(const std::string& message) {
  std::vector<std::string> names;
  const std::string prefix = "relaxed: ";
  if (message.rfind(prefix, 0) != 0) return names;
  std::size_t pos = prefix.size();
  while (pos < message.size()) {
    const std::size_t by = message.find(" by ", pos);
    if (by == std::string::npos) break;
    names.push_back(message.substr(pos, by - pos));
    const std::size_t comma = message.find(", ", by);
    if (comma == std::string::npos) break;
    pos = comma + 2;
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// Violation of every row and cone at x (row units; 0 where it holds).
Eigen::VectorXd violations(const QpProblem& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(p.inequalities() + static_cast<int>(p.cones.size()));
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    if (p.lower[i] > -kQpInfinity) v[i] += std::max(0.0, p.lower[i] - c);
    if (p.upper[i] < kQpInfinity) v[i] += std::max(0.0, c - p.upper[i]);
  }
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    v[p.inequalities() + static_cast<int>(k)] =
        std::max(0.0, std::hypot(x[c.tangent1], x[c.tangent2]) - c.mu * x[c.normal]);
  }
  return v;
}

/// Agreement with Ipopt over the samples of a scene (every `stride`-th), solved in order as
/// a run solves them.
struct RunComparison {
  int samples = 0, optimal = 0, relaxed = 0;
  int status_mismatches = 0, name_mismatches = 0, kkt_failures = 0;
  int active_cones = 0;  ///< cones active (λ > 0) on optimal samples
  int objective_failures = 0;  ///< penalised objective above Ipopt's
  double max_dx_optimal = 0.0, max_dx_relaxed = 0.0, max_violation_diff = 0.0;
  double max_cone_violation = -kInf;  ///< relative, on optimal samples
  std::string first_problem;
};

RunComparison compare_with_ipopt(const Scene& scene, int stride = 1) {
  const PreparedScene prep = prepare_scene(scene);
  const KinematicsResult kin = sample_kinematics(prep.model, prep.plan, prep.grid);
  RobotData data(prep.model);
  const double rho = scene.allocation.slack_penalty;
  IpoptOptions io = ipopt_options_from(scene.allocation);
  io.tolerance = 1e-12;
  auto ipopt = make_ipopt_backend(io);
  auto cone = make_allocation_backend(scene.allocation);
  QpProblem qp;
  std::array<int, kLegs> offset{};
  SampleContacts contacts;
  RunComparison r;
  auto note = [&](int i, const std::string& what) {
    if (r.first_problem.empty())
      r.first_problem = "sample " + std::to_string(i) + " t = " + std::to_string(kin.time_s[i]) + ": " + what;
  };
  for (int i = 0; i < kin.samples(); i += stride) {
    const ContactSplit& split = contact_split(
        prep.model, data, base_state_at(kin, i), kin.joint_position.row(i).transpose(),
        kin.joint_velocity.row(i).transpose(), kin.joint_acceleration.row(i).transpose());
    sample_contacts(kin, i, prep.plan.terrain, prep.touchdowns, contacts);
    build_allocation_problem(scene.allocation, scene.contact, split, contacts.phase, contacts.impact_force_N,
                             contacts.W_R_contact, qp, offset, nullptr);
    const QpOutcome ref = ipopt->solve(qp);
    const QpOutcome& out = cone->solve(qp);
    ++r.samples;
    const double dx = inf_norm(out.x - ref.x);
    if (out.status != ref.status) {
      ++r.status_mismatches;
      note(i, "status " + std::to_string(static_cast<int>(out.status)) + " (" + out.message + ") vs Ipopt " +
                  std::to_string(static_cast<int>(ref.status)) + " (" + ref.message + ")");
    }
    if (out.status == SolverStatus::kOptimal) {
      ++r.optimal;
      r.max_dx_optimal = std::max(r.max_dx_optimal, dx);
      if (!qp.cones.empty()) r.max_cone_violation = std::max(r.max_cone_violation, worst_cone_violation(qp, out.x));
      std::string why;
      if (!check_cone_kkt(qp, out, 1e-9, &why)) ++r.kkt_failures, note(i, why);
      for (int k = 0; k < out.lambda_cone.size(); ++k) r.active_cones += out.lambda_cone[k] > 1e-9;
    } else {
      ++r.relaxed;
      r.max_dx_relaxed = std::max(r.max_dx_relaxed, dx);
      if (named_rows(out.message) != named_rows(ref.message)) {
        ++r.name_mismatches;
        note(i, out.message + " vs Ipopt " + ref.message);
      }
      r.max_violation_diff = std::max(r.max_violation_diff, inf_norm(violations(qp, out.x) - violations(qp, ref.x)));
    }
    std::string why;
    if (!check_penalised_cone_kkt(qp, out, rho, 1e-9, &why)) ++r.kkt_failures, note(i, why);
    const double gap = penalised_objective(qp, ref.x, rho) - penalised_objective(qp, out.x, rho);
    if (gap < -1e-10 * (1.0 + std::abs(penalised_objective(qp, ref.x, rho))))
      ++r.objective_failures, note(i, "penalised objective above Ipopt's");
  }
  return r;
}

void check_comparison(const RunComparison& r) {
  INFO(r.samples << " samples, " << r.relaxed << " relaxed; max |Δx| optimal " << r.max_dx_optimal
                 << " N, relaxed " << r.max_dx_relaxed << " N; violations " << r.max_violation_diff
                 << "; cone " << r.max_cone_violation << ". " << r.first_problem);
  CHECK(r.status_mismatches == 0);
  CHECK(r.name_mismatches == 0);
  CHECK(r.kkt_failures == 0);
  CHECK(r.objective_failures == 0);
  CHECK(r.max_dx_optimal < 1e-6);
  // Relaxed samples: Ipopt's penalised solves stop at a tolerance relative to multipliers
  // ρ w up to 1e9, a few µN from the exact penalised optimum; ours is certified by the
  // penalised KKT conditions above and its penalised objective is never above Ipopt's.
  CHECK(r.max_dx_relaxed < 1e-5);
  CHECK(r.max_violation_diff < 1e-6);
  CHECK(r.max_cone_violation <= 1e-11);
}

Scene paper_with(std::vector<std::pair<std::string, std::string>> overrides) {
  overrides.emplace_back("allocation.friction", "cone");
  std::vector<Override> ov;
  for (auto& [k, v] : overrides) ov.push_back({k, v});
  return load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml", ov);
}

}  // namespace

TEST_CASE("cone back end: one foot is the closed-form projection onto its cone", "[allocation][cone]") {
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
      std::string why;
      CHECK(check_cone_kkt(p, out, 1e-9, &why));
      INFO(why);
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
  const RunComparison r = compare_with_ipopt(paper_with({}));
  CHECK(r.samples > 500);
  CHECK(r.relaxed > 100);  // touchdown transients
  CHECK(r.active_cones > 250);  // the torque-optimal forces ride the friction limit
  check_comparison(r);
  WARN("paper run, cone: " << r.samples << " samples (" << r.relaxed << " relaxed, " << r.active_cones
                           << " active cones on optimal samples): max |Δx| vs Ipopt " << r.max_dx_optimal
                           << " N optimal, " << r.max_dx_relaxed << " N relaxed; worst cone "
                           << r.max_cone_violation << " relative");
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
  WARN("smoke sweep, cone: max |Δx| vs Ipopt " << worst_optimal << " N optimal, " << worst_relaxed << " N relaxed");
}

namespace {

/// Feet of a trunk held by `feet.size()` legs: x = (t1, t2, n) per foot (contact frame =
/// world), objective |τ₀ − G x|² with a random well-conditioned block-diagonal G (3×3 per
/// leg, as the allocation's), trunk rows Σ F = f_W and Σ p × F = m_W as l = u rows
/// (weight 1e2), normal ≥ 0 (1e3), |τ| ≤ limit (1), cones (1e3): the allocation's structure.
QpProblem trunk_problem(std::mt19937& rng, const std::vector<Eigen::Vector3d>& feet, double mu,
                        const Eigen::Vector3d& f_W, const Eigen::Vector3d& m_W, double torque_limit) {
  const int legs = static_cast<int>(feet.size()), n = 3 * legs;
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, n);
  for (int l = 0; l < legs; ++l)
    G.block<3, 3>(3 * l, 3 * l) = 0.1 * Eigen::Matrix3d::Identity() + 0.03 * Eigen::Matrix3d::NullaryExpr([&] { return N(rng); });
  Eigen::VectorXd tau0(n);
  for (int j = 0; j < n; ++j) tau0[j] = 0.5 * N(rng);
  QpProblem p;
  p.resize(n, 0, 6 + 4 * legs);
  p.H = 2.0 * G.transpose() * G;
  p.g = -2.0 * G.transpose() * tau0;
  p.constant = tau0.squaredNorm();
  const char* trunk[6] = {"trunk force x", "trunk force y", "trunk force z", "trunk moment x", "trunk moment y", "trunk moment z"};
  for (int l = 0; l < legs; ++l) {
    p.C.block<3, 3>(0, 3 * l).setIdentity();
    Eigen::Matrix3d cross;
    cross << 0, -feet[l].z(), feet[l].y(), feet[l].z(), 0, -feet[l].x(), -feet[l].y(), feet[l].x(), 0;
    p.C.block<3, 3>(3, 3 * l) = cross;
  }
  for (int r = 0; r < 6; ++r) {
    p.lower[r] = p.upper[r] = r < 3 ? f_W[r] : m_W[r - 3];
    p.ineq_names[r] = trunk[r];
    p.ineq_penalty[r] = 1e2;
  }
  int row = 6;
  for (int l = 0; l < legs; ++l) {
    const std::string leg = "L" + std::to_string(l + 1);
    for (int j = 0; j < 3; ++j, ++row) {
      p.C.row(row).segment<3>(3 * l) = G.row(3 * l + j).segment<3>(3 * l);
      p.lower[row] = tau0[3 * l + j] - torque_limit;
      p.upper[row] = tau0[3 * l + j] + torque_limit;
      p.ineq_names[row] = "torque " + leg + "_j" + std::to_string(j + 1);
    }
    p.C(row, 3 * l + 2) = 1.0;
    p.lower[row] = 0.0;
    p.ineq_penalty[row] = 1e3;
    p.ineq_names[row++] = "normal " + leg;
    p.cones.push_back({3 * l, 3 * l + 1, 3 * l + 2, mu, "friction cone " + leg, 1e3});
  }
  return p;
}

/// Solves p with the cone back end and Ipopt (1e-12) and checks: same status and rows
/// named, forces within `dx` N, KKT conditions (strict for status 0, penalised for 1),
/// penalised objective not above Ipopt's, finite outcome. Returns the cone answer.
QpOutcome check_against_ipopt(const QpProblem& p, double dx = 1e-6) {
  auto cone = cone_backend();
  auto ipopt = reference_ipopt();
  const QpOutcome ref = ipopt->solve(p);
  const QpOutcome out = cone->solve(p);
  INFO("cone: " << out.message << " | Ipopt: " << ref.message);
  CHECK(out.x.allFinite());
  CHECK(std::isfinite(out.objective));
  CHECK(out.status == ref.status);
  CHECK(named_rows(out.message) == named_rows(ref.message));
  CHECK(inf_norm(out.x - ref.x) < dx);
  std::string why;
  if (out.status == SolverStatus::kOptimal) {
    CHECK(check_cone_kkt(p, out, 1e-9, &why));
    INFO(why);
    CHECK(worst_cone_violation(p, out.x) <= 1e-11);
  }
  CHECK(check_penalised_cone_kkt(p, out, 1e6, 1e-9, &why));
  INFO(why);
  // To rounding of F, which holds ρ w times the violations.
  CHECK(penalised_objective(p, out.x, 1e6) <=
        penalised_objective(p, ref.x, 1e6) + 1e-10 * (1.0 + std::abs(penalised_objective(p, ref.x, 1e6))));
  return out;
}

const std::vector<Eigen::Vector3d> kTripod = {{-0.2, 0.3, 0.0}, {0.25, 0.0, 0.0}, {-0.2, -0.3, 0.0}};
const Eigen::Vector3d kWeight(0.0, 0.0, 65.7);

}  // namespace

TEST_CASE("cone back end: hard cases agree with Ipopt at 1e-12 and the KKT conditions",
          "[allocation][cone][hard]") {
  std::mt19937 rng(2718);
  SECTION("mu = 5: wide cones, the friction limit far away") {
    const QpProblem p = trunk_problem(rng, kTripod, 5.0, kWeight + Eigen::Vector3d(3, 8, 0), {1, -2, 0.5}, 6.0);
    CHECK(check_against_ipopt(p).status == SolverStatus::kOptimal);
  }
  SECTION("mu = 0.001: the trunk's horizontal force cannot be carried, the cones give way") {
    // A horizontal demand of 8 N through cones of μ = 0.001 (≤ 0.07 N in all): the trunk
    // rows (weight 1e2) give way rather than the cones (1e3).
    const QpProblem p = trunk_problem(rng, kTripod, 0.001, kWeight + Eigen::Vector3d(0, 8, 0), {0, 0, 0}, 6.0);
    const QpOutcome out = check_against_ipopt(p, 1e-5);
    CHECK(out.status == SolverStatus::kRelaxed);
    CHECK(out.message.find("trunk force y") != std::string::npos);
  }
  SECTION("mu = 0.001 with a purely vertical load: optimal, cones nearly closed") {
    // Ipopt does not converge on this one (its penalised cone solve stops at the iteration
    // limit and it returns the inscribed 16-gon answer, flagged "approximate"); the cone
    // back end's answer is certified by the KKT conditions of the cone problem instead.
    const QpProblem p = trunk_problem(rng, kTripod, 0.001, kWeight, {0, 0, 0}, 6.0);
    auto backend = cone_backend();
    const QpOutcome& out = backend->solve(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    std::string why;
    CHECK(check_cone_kkt(p, out, 1e-9, &why));
    INFO(why);
    CHECK(worst_cone_violation(p, out.x) <= 1e-11);
    auto ipopt = reference_ipopt();
    const QpOutcome& ref = ipopt->solve(p);
    CHECK((ref.status == SolverStatus::kOptimal || ref.message.rfind("approximate", 0) == 0));
    CHECK(penalised_objective(p, out.x, 1e6) <= penalised_objective(p, ref.x, 1e6) + 1e-10);
  }
  SECTION("a foot at the apex of its cone: unloaded at the optimum") {
    // Two feet carry a load between them; a third, far to the side, is pulled away from
    // the ground by its torques (τ₀ wants a negative normal force): f = 0 at the optimum.
    QpProblem p = trunk_problem(rng, {{-0.1, 0.0, 0.0}, {0.1, 0.0, 0.0}, {0.0, 0.5, 0.0}}, 0.3, kWeight,
                                {0, 0, 0}, 60.0);
    // τ of leg 3 = τ₀ − G₃ x₃: pull x₃ towards (2, −1, −5) N.
    const Eigen::Matrix3d G3 = Eigen::Matrix3d::Identity() * 0.1;
    p.H.block<3, 3>(6, 6) = 2.0 * G3.transpose() * G3;
    p.g.segment<3>(6) = -2.0 * G3.transpose() * (G3 * Eigen::Vector3d(2, -1, -5));
    for (int j = 0; j < 3; ++j) p.C.row(6 + 8 + j).setZero(), p.C(6 + 8 + j, 6 + j) = 0.1;
    const QpOutcome out = check_against_ipopt(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    CHECK(out.x.segment<3>(6).norm() < 1e-9);
  }
  SECTION("a foot near the apex: f_n small but positive on the boundary") {
    // Against the closed-form projection: Ipopt's smoothed cone (ε = 1e-9 N) is not
    // accurate at these force scales. Rows, and so the half-spaces, hold to the back end's
    // row tolerance, 1e-9 N absolute near 0.
    for (const double pull : {1e-2, 1e-4, 1e-6}) {
      CAPTURE(pull);
      const Eigen::Vector3d a(pull, 0.3 * pull, 0.5 * pull);
      const QpProblem p = single_foot(a, 0.3);
      auto backend = cone_backend();
      const QpOutcome& out = backend->solve(p);
      REQUIRE(out.status == SolverStatus::kOptimal);
      CHECK(inf_norm(out.x - project_onto_cone(a, 0.3)) < 2e-9);
      CHECK(out.x[2] > 0.0);
      CHECK(worst_cone_violation(p, out.x) <= 1e-9);
    }
  }
  SECTION("all feet friction-limited at once") {
    // A large horizontal demand that every foot must help carry, μ = 0.3.
    const std::vector<Eigen::Vector3d> six = {{-0.2, 0.3, 0}, {0.2, 0.3, 0}, {-0.25, 0, 0},
                                              {0.25, 0, 0},   {-0.2, -0.3, 0}, {0.2, -0.3, 0}};
    const QpProblem p = trunk_problem(rng, six, 0.3, kWeight + Eigen::Vector3d(12.0, 15.0, 0.0), {0, 0, 0}, 60.0);
    const QpOutcome out = check_against_ipopt(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    int active = 0;
    for (std::size_t k = 0; k < p.cones.size(); ++k) {
      const SecondOrderCone& c = p.cones[k];
      active += std::hypot(out.x[c.tangent1], out.x[c.tangent2]) >= c.mu * out.x[c.normal] - 1e-9;
    }
    CHECK(active == 6);
  }
  SECTION("an infeasible sample must relax: a cone of lower weight gives way and is named") {
    QpProblem p = trunk_problem(rng, kTripod, 0.1, kWeight + Eigen::Vector3d(0, 15.0, 0), {0, 0, 0}, 60.0);
    for (SecondOrderCone& c : p.cones) c.penalty = 1.0;  // cones give way before the trunk rows
    const QpOutcome out = check_against_ipopt(p, 1e-5);
    REQUIRE(out.status == SolverStatus::kRelaxed);
    CHECK(out.message.find("friction cone") != std::string::npos);
    CHECK(out.message.find("trunk") == std::string::npos);
    CHECK(out.max_violation > 0.1);
  }
  SECTION("three nearly collinear feet: trunk moment rows nearly dependent") {
    // Feet on a line along y, the middle one 1 mm off it: the moment about y is carried by
    // that millimetre and the tangential forces alone.
    const std::vector<Eigen::Vector3d> line = {{0.0, 0.3, 0.0}, {1e-3, 0.0, 0.0}, {0.0, -0.3, 0.0}};
    const QpProblem p = trunk_problem(rng, line, 0.3, kWeight, {0.0, 0.0, 0.0}, 60.0);
    const QpOutcome out = check_against_ipopt(p, 1e-5);
    CHECK(out.x.allFinite());
  }
  SECTION("torque limits active together with the cone") {
    const QpProblem loose = trunk_problem(rng, kTripod, 0.3, kWeight + Eigen::Vector3d(4, 9, 0), {0.5, 0, 0}, 60.0);
    const QpOutcome free = check_against_ipopt(loose);
    REQUIRE(free.status == SolverStatus::kOptimal);
    // Tighten the limit until it binds but stays feasible: 97 % of the largest |τ| at the
    // answer with loose limits.
    QpProblem p = loose;
    Eigen::VectorXd tau = Eigen::VectorXd::Zero(9);
    for (int i = 6; i < p.inequalities(); ++i)
      if (p.ineq_names[i].rfind("torque", 0) == 0) tau[(i - 6) / 4 * 3 + (i - 6) % 4] = p.C.row(i).dot(free.x) - 0.5 * (p.lower[i] + p.upper[i]);
    const double limit = 0.97 * tau.cwiseAbs().maxCoeff();
    for (int i = 6; i < p.inequalities(); ++i) {
      if (p.ineq_names[i].rfind("torque", 0) != 0) continue;
      const double mid = 0.5 * (p.lower[i] + p.upper[i]);
      p.lower[i] = mid - limit, p.upper[i] = mid + limit;
    }
    const QpOutcome out = check_against_ipopt(p);
    REQUIRE(out.status == SolverStatus::kOptimal);
    int torque_active = 0, cone_active = 0;
    for (int i = 6; i < p.inequalities(); ++i)
      torque_active += p.ineq_names[i].rfind("torque", 0) == 0 && std::abs(out.lambda_ineq[i]) > 1e-9;
    for (int k = 0; k < out.lambda_cone.size(); ++k) cone_active += out.lambda_cone[k] > 1e-9;
    CHECK(torque_active > 0);
    CHECK(cone_active > 0);
  }
}

TEST_CASE("cone back end: warm starts, problems without cones, options", "[allocation][cone]") {
  std::mt19937 rng(31);
  SECTION("a slowly changing sequence: warm answers equal cold ones") {
    auto warm = cone_backend();
    ConeOptions o;
    o.warm_start = false;
    o.qp.warm_start = false;
    auto cold = make_cone_backend(o);
    QpProblem p = trunk_problem(rng, kTripod, 0.3, kWeight + Eigen::Vector3d(3, 8, 0), {0.5, 0, 0}, 6.0);
    for (int k = 0; k < 40; ++k) {
      p.lower[1] = p.upper[1] = 8.0 + 0.2 * k;  // a growing forward push
      const QpOutcome a = warm->solve(p);
      const QpOutcome& b = cold->solve(p);
      CAPTURE(k);
      REQUIRE(a.status == b.status);
      CHECK(inf_norm(a.x - b.x) < 1e-9);
    }
  }
  SECTION("without cones it is the active-set back end") {
    QpProblem p = trunk_problem(rng, kTripod, 0.3, kWeight, {0, 0, 0}, 6.0);
    p.cones.clear();
    auto cone = cone_backend();
    auto qp = make_active_set_backend();
    const QpOutcome a = cone->solve(p);
    const QpOutcome& b = qp->solve(p);
    CHECK(a.status == b.status);
    CHECK(a.x == b.x);
    CHECK(a.lambda_cone.size() == 0);
  }
  SECTION("non-finite data fail with a finite fallback") {
    QpProblem p = single_foot(Eigen::Vector3d(1, 0, 0), 0.3);
    p.g[1] = std::nan("");
    auto backend = cone_backend();
    const QpOutcome& out = backend->solve(p);
    CHECK(out.status == SolverStatus::kFailed);
    CHECK(out.x.allFinite());
    CHECK(out.message.rfind("failed: non-finite", 0) == 0);
  }
  SECTION("bad options") {
    ConeOptions o;
    o.cone_tolerance = 0.0;
    CHECK_THROWS_AS(make_cone_backend(o), ConfigError);
    o = ConeOptions{};
    o.max_passes = 0;
    CHECK_THROWS_AS(make_cone_backend(o), ConfigError);
    AllocationParams params;
    params.tolerance = 1e-8;
    params.slack_penalty = 123.0;
    const ConeOptions from = cone_options_from(params);
    CHECK(from.qp.tolerance == 1e-8);
    CHECK(from.qp.slack_penalty == 123.0);
  }
  SECTION("the factory: active-set with the cone is this back end") {
    AllocationParams params;
    params.solver = AllocationSolver::kActiveSet;
    params.friction = FrictionModel::kCone;
    auto backend = make_allocation_backend(params);
    const QpProblem p = single_foot(Eigen::Vector3d(1, 0, 1), 0.3);
    const QpOutcome& out = backend->solve(p);  // the plain active-set back end would throw
    CHECK(out.status == SolverStatus::kOptimal);
    CHECK(inf_norm(out.x - project_onto_cone(Eigen::Vector3d(1, 0, 1), 0.3)) < 1e-12);
  }
}
