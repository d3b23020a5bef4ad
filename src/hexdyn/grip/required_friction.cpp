#include "hexdyn/grip/required_friction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "hexdyn/grip/prescribed_normals.hpp"
#include "hexdyn/grip/required_friction_solver.hpp"

namespace hexdyn {
namespace {

/// The message of a sample without μ*: no friction coefficient up to mu_max admits its rows,
/// and, when `why` is not empty, what still fails there.
std::string no_friction_message(double mu_max, const std::string& why) {
  std::ostringstream s;
  s << "required friction: no friction coefficient up to " << mu_max << " admits the rows";
  if (!why.empty()) s << " (" << why << ")";
  return s.str();
}

/// The number of legs with forces when each is a support leg (three forces, its normal force
/// free), else -1 (a leg in its touchdown transient, whose normal force is prescribed).
int support_legs_only(const AllocationLayout& layout) {
  int standing = 0;
  for (int l = 0; l < layout.n_legs; ++l) {
    const int count = layout.legs[l].count;
    if (count == 0) continue;
    if (count != 3) return -1;
    ++standing;
  }
  return standing;
}

}  // namespace

/// Newton on the square system of the active rows in z = (x, μ), from z0; then check.
NewtonEnd RequiredFrictionSolver::Impl::newton(const AllocationLayout& layout,
                                               const std::vector<MuRow>& set, const MuVector& z0) {
  const int n = work.variables();
  if (static_cast<int>(set.size()) != n + 1 || !work.cones.empty()) return NewtonEnd::kFailed;
  z = z0;
  J.resize(n + 1, n + 1);
  MuVector g(n + 1);
  for (int it = 0; it <= opt.newton_iterations + 1; ++it) {
    x = z.head(n);
    set_friction_coefficient(layout, z[n], work);
    for (int i = 0; i <= n; ++i) {
      const MuRow& a = set[static_cast<std::size_t>(i)];
      J.row(i).head(n) = work.C.row(a.row);
      J(i, n) = row_mu_derivative(layout, x, a.row, a.side);
      const double bound = a.side > 0 ? work.upper[a.row] : work.lower[a.row];
      g[i] = work.C.row(a.row).dot(x) - bound;
    }
    if (!lu.compute(J)) return NewtonEnd::kFailed;
    if (it > opt.newton_iterations) break;
    const MuVector step = lu.solve(-g);
    if (!step.allFinite()) return NewtonEnd::kFailed;
    z += step;
    // The residual is bilinear in (x_n, μ), so Newton converges quadratically: after a step
    // below 1e-8 of z the error is at the rounding of z, and the factorisation at this
    // iterate serves the multipliers (signs and the binding leg only).
    if (step.lpNorm<Eigen::Infinity>() <= 1e-8 * (1.0 + z.lpNorm<Eigen::Infinity>())) {
      x = z.head(n);
      set_friction_coefficient(layout, z[n], work);
      return check(layout, set);
    }
  }
  return NewtonEnd::kFailed;
}

/// At Newton's answer z: every row holds (to 1e-9 relative) and the multipliers of min μ,
/// Jᵀλ = e_μ, have the signs of their rows' active sides
/// (docs/theory/grip.md#why-the-newton-answer-is-the-minimum); else what failed first.
NewtonEnd RequiredFrictionSolver::Impl::check(const AllocationLayout& layout,
                                              const std::vector<MuRow>& set) {
  const int n = work.variables();
  const double mu = z[n];
  if (!std::isfinite(mu)) return NewtonEnd::kFailed;
  if (mu < -1e-12) {  // the answer lies at μ = 0 or on another active set
    negative_mu = true;
    return NewtonEnd::kFailed;
  }
  MuVector e = MuVector::Zero(n + 1);
  e[n] = 1.0;
  lambda = lu.solve_transpose(e);
  if (!lambda.allFinite()) return NewtonEnd::kFailed;
  double worst = 0.0;
  bad_row = -1;
  for (int j = 0; j < work.inequalities(); ++j) {
    const double v = work.C.row(j).dot(x);
    const double lo = work.lower[j], hi = work.upper[j];
    const double below = (lo - v) / std::max(1.0, std::abs(lo));
    const double above = (v - hi) / std::max(1.0, std::abs(hi));
    if (below > 1e-9 && below > worst) {
      worst = below;
      bad_row = j;
      bad_side = -1;
    }
    if (above > 1e-9 && above > worst) {
      worst = above;
      bad_row = j;
      bad_side = +1;
    }
  }
  if (bad_row >= 0) return NewtonEnd::kRowViolated;
  const double tol = 1e-9 * lambda.lpNorm<Eigen::Infinity>();
  double most_wrong = tol;
  bool degenerate = false;
  for (int i = 0; i <= n; ++i) {
    const int side = set[static_cast<std::size_t>(i)].side;
    const double wrong = side > 0 ? lambda[i] : side < 0 ? -lambda[i] : 0.0;
    degenerate = degenerate || (side != 0 && std::abs(lambda[i]) <= tol);
    if (wrong > most_wrong) {
      most_wrong = wrong;
      bad_row = i;
    }
  }
  if (bad_row >= 0) return NewtonEnd::kWrongSign;
  // A zero multiplier: a degenerate vertex, where the bilinear rows may still let μ fall
  // along a direction that keeps that row's side (docs/theory/grip.md#degenerate-vertices).
  // The rows of the set settle it when they admit no forces at μ − tolerance (a Farkas
  // certificate); else a probe there, as a bisection's bracket would.
  if (degenerate && mu > opt.tolerance) {
    const bool lower = !infeasible_below(layout, set, mu - opt.tolerance) &&
                       feasible_at(layout, mu - opt.tolerance, x_scratch);
    set_friction_coefficient(layout, mu, work);
    if (lower) return NewtonEnd::kFailed;
  }
  // The binding leg: the friction row whose multiplier carries the most of ∂μ.
  double binding = 0.0;
  newton_leg = -1;
  for (int i = 0; i <= n; ++i) {
    const MuRow& a = set[static_cast<std::size_t>(i)];
    const double share = std::abs(lambda[i] * row_mu_derivative(layout, x, a.row, a.side));
    if (share <= binding) continue;
    for (int l = 0; l < layout.n_legs; ++l) {
      const AllocationLayout::Leg& leg = layout.legs[l];
      if (leg.offset >= 0 && a.row >= leg.friction_row &&
          a.row < leg.friction_row + leg.friction_faces) {
        binding = share;
        newton_leg = l;
      }
    }
  }
  return NewtonEnd::kCertified;
}

/// Whether the rows of `set` alone admit no forces at μ' = mu_low < z's μ (x at z): then no
/// μ ≤ mu_low admits the problem (docs/theory/grip.md#degenerate-vertices). A Farkas
/// certificate: ν with J(x, μ')ᵀ ν = e_μ makes Σ ν_i g_i(·, μ') constant in the forces, equal to
/// its value at x, which the rows' linearity in μ at fixed forces makes about μ' − μ < 0;
/// with σ_i ν_i ≤ 0 on every inequality row of the set, a point that held the rows would
/// make it ≥ 0. Leaves work at mu_low.
bool RequiredFrictionSolver::Impl::infeasible_below(const AllocationLayout& layout,
                                                    const std::vector<MuRow>& set, double mu_low) {
  const int n = work.variables();
  set_friction_coefficient(layout, mu_low, work);
  MuVector g(n + 1);
  for (int i = 0; i <= n; ++i) {
    const MuRow& a = set[static_cast<std::size_t>(i)];
    J.row(i).head(n) = work.C.row(a.row);
    J(i, n) = row_mu_derivative(layout, x, a.row, a.side);
    g[i] = work.C.row(a.row).dot(x) - (a.side > 0 ? work.upper[a.row] : work.lower[a.row]);
  }
  if (!farkas.compute(J)) return false;
  MuVector e = MuVector::Zero(n + 1);
  e[n] = 1.0;
  const MuVector nu = farkas.solve_transpose(e);
  if (!nu.allFinite()) return false;
  // Σ ν_i c_i vanishes only to the rounding of the solve, about 1e-16 ‖ν‖ ‖J‖ (1e-13 with a
  // margin), which a point at the distance of the forces' own size would turn into that much
  // of G: a certificate only where that stays below a quarter of μ − μ'. A multiplier within
  // the same 1e-13 ‖ν‖ of zero is zero to rounding (a row the others determine, such as a
  // second face of a leg without load): its sign is noise, its term within that bound.
  const double zero = 1e-13 * nu.lpNorm<Eigen::Infinity>();
  for (int i = 0; i <= n; ++i)
    if (set[static_cast<std::size_t>(i)].side * nu[i] > zero) return false;
  const double gap = z[n] - mu_low;
  const double rounding =
      zero * J.cwiseAbs().rowwise().sum().maxCoeff() * (1.0 + x.lpNorm<Eigen::Infinity>());
  return rounding < 0.25 * gap && nu.dot(g) < -0.5 * gap;
}

/// The dual simplex's leaving row for the violated row (bad_row, bad_side) entering: with
/// h_i = σ_i g_i ≤ 0 the rows in ≤ form (σ the side) and ν_i = −σ_i λ_i ≥ 0 their
/// multipliers, the entering row's multiplier t moves them as ν − t β, β_i = σ_i σ_j α_i,
/// Jᵀα = ∇g_j; the first inequality row to reach ν_i = 0 leaves. −1 when none can.
int RequiredFrictionSolver::Impl::dual_ratio_leaving(const AllocationLayout& layout,
                                                     const std::vector<MuRow>& set) {
  const int n = work.variables();
  const MuVector alpha = lu.solve_transpose(gradient(layout, bad_row, bad_side));
  int leave = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int i = AllocationLayout::kTrunkRows; i <= n; ++i) {
    const double sigma = set[static_cast<std::size_t>(i)].side;
    const double beta = sigma * bad_side * alpha[i];
    if (!(beta > 1e-12 * alpha.lpNorm<Eigen::Infinity>())) continue;
    const double ratio = -sigma * lambda[i] / beta;
    if (ratio < best) {
      best = ratio;
      leave = i;
    }
  }
  return leave;
}

/// The primal simplex's entering row when active row bad_row (an index in the set) leaves:
/// along d with J d = −σ e_r (the other active rows held), the inactive row whose bound is
/// reached first. False when none is.
bool RequiredFrictionSolver::Impl::primal_ratio_entering(const AllocationLayout& layout,
                                                         const std::vector<MuRow>& set,
                                                         MuRow& enter) {
  const int n = work.variables();
  MuVector e = MuVector::Zero(n + 1);
  e[bad_row] = -set[static_cast<std::size_t>(bad_row)].side;
  const MuVector d = lu.solve(e);
  double best = std::numeric_limits<double>::infinity();
  for (int j = AllocationLayout::kTrunkRows; j < work.inequalities(); ++j) {
    bool in_set = false;
    for (const MuRow& a : set) in_set = in_set || a.row == j;
    if (in_set) continue;
    const double rate = gradient(layout, j, +1).dot(d);
    const double v = work.C.row(j).dot(x);
    if (rate > 0.0 && work.upper[j] < kQpInfinity) {
      const double step = std::max(0.0, work.upper[j] - v) / rate;
      if (step < best) {
        best = step;
        enter = {j, +1};
      }
    }
    const double rate_down = -gradient(layout, j, -1).dot(d);
    if (rate_down > 0.0 && work.lower[j] > -kQpInfinity) {
      const double step = std::max(0.0, v - work.lower[j]) / rate_down;
      if (step < best) {
        best = step;
        enter = {j, -1};
      }
    }
  }
  return std::isfinite(best);
}

/// Newton from z0 on `set`, exchanging one row at a time while it fails (at most
/// kMaxExchanges times): a violated row enters by the dual simplex's ratio test, an active
/// row whose multiplier has the wrong sign leaves by the primal one. True with the answer
/// in z and the set remembered for the next sample.
bool RequiredFrictionSolver::Impl::solve_from(const AllocationLayout& layout,
                                              std::vector<MuRow> set, const MuVector& z0) {
  constexpr int kMaxExchanges = 24;
  MuVector start = z0;  // z0 may be warm_z, which a success overwrites
  for (int exchange = 0;; ++exchange) {
    const NewtonEnd end = newton(layout, set, start);
    if (end == NewtonEnd::kCertified) {
      remember(set);
      return true;
    }
    if (end == NewtonEnd::kFailed || exchange == kMaxExchanges) return false;
    if (end == NewtonEnd::kRowViolated) {
      const int leave = dual_ratio_leaving(layout, set);
      if (leave < 0) return false;
      set[static_cast<std::size_t>(leave)] = {bad_row, bad_side};
    } else {
      MuRow enter;
      if (bad_row < AllocationLayout::kTrunkRows || !primal_ratio_entering(layout, set, enter))
        return false;
      set[static_cast<std::size_t>(bad_row)] = enter;
    }
    start = z;
  }
}

/// The candidate active set at (x_at, mu), in `candidate`: the trunk rows, then the inequality
/// rows in order of their distance to active (slack over the norm of the row of C: a distance
/// in force space, comparable across torque, normal-force and friction rows), each taken only
/// when its row of J is linearly independent of those taken, until there are n + 1; false
/// when the problem has too few variables or cones. Without independent rows enough, and for
/// the exact cone's polygons (whose clustered faces are nearly dependent by design, and whose
/// rounds follow the answer's force directions from one round to the next), the n + 1 − 6
/// nearest by slack relative to max(1, |bound|).
bool RequiredFrictionSolver::Impl::active_set_at(const AllocationLayout& layout,
                                                 const Eigen::Ref<const Eigen::VectorXd>& x_at,
                                                 double mu) {
  const int n = work.variables(), m = work.inequalities();
  const int extra = n + 1 - AllocationLayout::kTrunkRows;
  if (extra <= 0 || !work.cones.empty() || m - AllocationLayout::kTrunkRows < extra) return false;
  set_friction_coefficient(layout, mu, work);
  const bool polygon = (work.structure & kConePolygonKey) != 0;
  slack.clear();
  for (int j = AllocationLayout::kTrunkRows; j < m; ++j) {
    const double v = work.C.row(j).dot(x_at);
    const double inf = std::numeric_limits<double>::infinity();
    const double hi = work.upper[j], lo = work.lower[j];
    const double norm = work.C.row(j).norm();
    if (!(norm > 0.0) && !polygon) continue;  // a constant row: no force moves it
    const double su = polygon ? 1.0 / std::max(1.0, std::abs(hi)) : 1.0 / norm;
    const double sd = polygon ? 1.0 / std::max(1.0, std::abs(lo)) : 1.0 / norm;
    const double up = hi < kQpInfinity ? (hi - v) * su : inf;
    const double down = lo > -kQpInfinity ? (v - lo) * sd : inf;
    slack.emplace_back(std::min(up, down), up <= down ? j : -1 - j);
  }
  if (static_cast<int>(slack.size()) < extra) return false;
  std::sort(slack.begin(), slack.end());
  x = x_at;  // gradient() reads the forces from x
  candidate.clear();
  for (int j = 0; j < AllocationLayout::kTrunkRows; ++j) add_if_independent(layout, {j, 0});
  if (static_cast<int>(candidate.size()) == AllocationLayout::kTrunkRows && !polygon)
    for (std::size_t i = 0; i < slack.size() && static_cast<int>(candidate.size()) <= n; ++i) {
      const int code = slack[i].second;
      add_if_independent(layout, code >= 0 ? MuRow{code, +1} : MuRow{-1 - code, -1});
    }
  if (static_cast<int>(candidate.size()) == n + 1) return true;
  candidate.clear();
  for (int j = 0; j < AllocationLayout::kTrunkRows; ++j) candidate.push_back({j, 0});
  for (int i = 0; i < extra; ++i) {
    const int code = slack[static_cast<std::size_t>(i)].second;
    candidate.push_back(code >= 0 ? MuRow{code, +1} : MuRow{-1 - code, -1});
  }
  return true;
}

/// Appends row a to `candidate` when its row of J at x is linearly independent of those of
/// the rows there (Gram-Schmidt, twice for rounding, against their orthonormal rows in
/// `basis`): a set with two dependent rows (opposite faces of a leg without normal force, for
/// example) makes J singular.
void RequiredFrictionSolver::Impl::add_if_independent(const AllocationLayout& layout, MuRow a) {
  const int k = static_cast<int>(candidate.size());
  MuVector v = gradient(layout, a.row, a.side == 0 ? +1 : a.side);
  const double scale = v.lpNorm<Eigen::Infinity>();
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < k; ++i) v -= basis.col(i).dot(v) * basis.col(i);
  const double left = v.norm();
  if (!(left > 1e-9 * scale)) return;
  if (k == 0) basis.resize(v.size(), v.size());
  basis.col(k) = v / left;
  candidate.push_back(a);
}

void RequiredFrictionSolver::Impl::remember(const std::vector<MuRow>& set) {
  has_warm = true;
  warm_structure = work.structure;
  warm_n = work.variables();
  warm_m = work.inequalities();
  warm_set = set;
  warm_z = z;
}

/// The upper end of the bracket: the allocation's own friction use when it holds every row,
/// else the probe at mu_max (false, with the message, when even that fails).
bool RequiredFrictionSolver::Impl::upper_end(const AllocationLayout& layout,
                                             const Eigen::VectorXd* allocation, double& hi,
                                             Eigen::VectorXd& x_hi) {
  if (allocation) {
    x_hi = *allocation;
    hi = friction_use(work, layout, x_hi);
    if (std::isfinite(hi)) return true;
  }
  std::string why;
  bool feasible = feasible_at(layout, opt.mu_max, x_hi, opt.reasons ? &why : nullptr);
  // Rows that no forces meet by less than the allocation's own verdict threshold (three feet
  // in a line, whose moment about it is off by rounding): μ* of the rows without that part.
  // Only where every loaded foot is a support foot: a touchdown transient's prescribed normal
  // forces leave misses of newtons, not of rounding. One or two feet had that part dropped
  // before any probe (solve_polygonal, the only caller of the bisection).
  if (!feasible && support_legs_only(layout) > 2 &&
      drop_unreachable_trunk_part(work, kViolationThreshold))
    feasible = feasible_at(layout, opt.mu_max, x_hi, opt.reasons ? &why : nullptr);
  if (!feasible) {
    out.mu = std::numeric_limits<double>::quiet_NaN();
    out.method = RequiredFrictionMethod::kNone;
    out.message = no_friction_message(opt.mu_max, why);
    return false;
  }
  hi = std::min(opt.mu_max, friction_use(work, layout, x_hi));
  return true;
}

/// Newton from the rows nearest to active at the bracket's feasible end (x_hi, hi); true
/// when it is certified inside [lo, hi].
bool RequiredFrictionSolver::Impl::newton_in_bracket(const AllocationLayout& layout,
                                                     const Eigen::VectorXd& x_hi, double lo,
                                                     double hi) {
  const int n = work.variables();
  if (!active_set_at(layout, x_hi, hi)) return false;
  MuVector z0(n + 1);
  z0 << x_hi, hi;
  if (!solve_from(layout, candidate, z0) || z[n] < lo - 1e-9 || z[n] > hi + 1e-9) return false;
  out.mu = std::max(0.0, z[n]);
  out.leg = newton_leg;
  out.method = RequiredFrictionMethod::kBisectionThenNewton;
  answer_x = z.head(n);
  return true;
}

/// Bisection on feasibility (file comment), from the allocation's friction use down, the
/// first probes around `guess` (the previous sample's μ*, when there is one), with a Newton
/// attempt from the rows nearest to active each time the bracket has narrowed a hundredfold.
void RequiredFrictionSolver::Impl::bisect(const AllocationLayout& layout,
                                          const Eigen::VectorXd* allocation, double guess) {
  Eigen::VectorXd x_hi, x_probe;
  double hi = 0.0, lo = 0.0;
  if (!upper_end(layout, allocation, hi, x_hi)) return;
  const auto probe = [&](double mu) {
    if (feasible_at(layout, mu, x_probe)) {
      hi = std::min(mu, friction_use(work, layout, x_probe));
      x_hi = x_probe;
    } else {
      lo = mu;
    }
  };
  // A caller that needs μ* only from `enough` up: an upper end below it, or one feasible
  // probe just below it, settles the sample (μ* ≤ its bound < enough); an infeasible probe
  // starts the bracket there.
  if (enough > 0.0 && work.cones.empty()) {
    if (hi < enough) {
      int leg = -1;
      friction_use(work, layout, x_hi, &leg);
      settle_below(hi, x_hi, leg);
      return;
    }
    if (!enough_infeasible && probe_below_enough(layout)) return;
    lo = below_enough();
  }
  // Newton from the upper end, whose exchanges walk like a simplex method to the answer's
  // rows; then from a probe just above the previous sample's μ*: most samples end here.
  if (work.cones.empty() && newton_in_bracket(layout, x_hi, lo, hi)) return;
  if (negative_mu && lo == 0.0) probe(0.0);
  if (guess > 0.0 && guess < hi && lo == 0.0 && hi > opt.tolerance) {
    probe(std::min(hi, guess * 1.01 + 1e-6));
    if (lo == 0.0 && newton_in_bracket(layout, x_hi, 0.0, hi)) return;
    if (lo == 0.0) probe(guess * 0.99);
  }
  // A Newton attempt each time the bracket has narrowed fourfold (a probe costs about one
  // allocation, a Newton attempt from a nearer upper end a fraction of it); under the exact
  // cone, whose polygon rounds follow the answer's force directions, each hundredfold.
  const bool polygon = (work.structure & kConePolygonKey) != 0;
  double newton_width = polygon ? 1e-2 : 0.25 * (hi - lo);
  while (hi - lo > opt.tolerance) {
    if (hi - lo <= newton_width && work.cones.empty()) {
      if (newton_in_bracket(layout, x_hi, lo, hi)) return;
      newton_width = polygon ? 1e-2 * newton_width : 0.25 * (hi - lo);
    }
    probe(0.5 * (lo + hi));
  }
  out.mu = hi;
  out.method = RequiredFrictionMethod::kBisection;
  answer_x = x_hi;
  friction_use(work, layout, x_hi, &out.leg);
  if (!work.cones.empty() || !newton_in_bracket(layout, x_hi, lo, hi)) has_warm = false;
}

RequiredFrictionSolver::RequiredFrictionSolver(std::unique_ptr<AllocationBackend> backend,
                                               const RequiredFrictionOptions& options)
    : impl_(std::make_unique<Impl>(std::move(backend), options)) {}

RequiredFrictionSolver::~RequiredFrictionSolver() = default;

/// The probe just below `enough`: true, with the sample settled by the probe's friction use,
/// when it is feasible; else false, and enough_infeasible marks it for the bisection.
bool RequiredFrictionSolver::Impl::probe_below_enough(const AllocationLayout& layout) {
  Eigen::VectorXd& x_probe = x_scratch;
  if (!feasible_at(layout, below_enough(), x_probe)) {
    enough_infeasible = true;
    return false;
  }
  int leg = -1;
  const double use = friction_use(work, layout, x_probe, &leg);
  settle_below(std::min(below_enough(), use), x_probe, leg);
  return true;
}

/// μ* of `work` (no cones) by Newton from the previous sample's active set, else bisection;
/// the answer's forces in answer_x.
void RequiredFrictionSolver::Impl::solve_polygonal(const AllocationLayout& layout,
                                                   const Eigen::VectorXd* allocation) {
  const int n = work.variables();
  // On one or two feet (the trunk rows never of full rank) the rows' part no force meets is
  // dropped before any probe, so that every probe and Newton's check see rows that can hold
  // (drop_unreachable_trunk_part).
  const int standing = support_legs_only(layout);
  if (standing > 0 && standing <= 2) drop_unreachable_trunk_part(work, kViolationThreshold);
  const bool alike =
      has_warm && warm_structure == work.structure && warm_n == n && warm_m == work.inequalities();
  // The previous sample's active set, else the rows nearest to active at its answer (which
  // the cone's polygon rounds need, their faces having turned since). A failed attempt leaves
  // warm_z as it was. After a sample without μ* (a touchdown transient whose trunk rows fail
  // at any μ) the set is older than the previous sample, and a relaxed sample goes to the
  // probe at mu_max first, which settles the next NaN at once.
  const bool after_nan = last_nan && allocation == nullptr;
  // A caller that needs μ* only from `enough` up: a sample whose allocation holds (and whose
  // friction use did not settle it: solve) is tried first with the probe just below
  // `enough`; the active set of a sample so settled is not carried.
  enough_infeasible = false;
  if (allocation && enough > 0.0 && work.cones.empty() && probe_below_enough(layout)) {
    last_nan = false;
    return;
  }
  if (alike && !after_nan) {
    // An answer above mu_max is no answer (μ* is NaN there): the bisection's probe at mu_max
    // says so, with its message.
    if ((solve_from(layout, warm_set, warm_z) ||
         (active_set_at(layout, warm_z.head(n), warm_z[n]) &&
          solve_from(layout, candidate, warm_z))) &&
        z[n] <= opt.mu_max) {
      out.mu = std::max(0.0, z[n]);
      out.leg = newton_leg;
      out.method = RequiredFrictionMethod::kNewton;
      last_mu = out.mu;
      last_nan = false;
      answer_x = z.head(n);
      return;
    }
  }
  bisect(layout, allocation, alike ? warm_z[n] : last_mu);
  last_nan = !std::isfinite(out.mu);
  if (!last_nan && out.method != RequiredFrictionMethod::kBelow) last_mu = out.mu;
}

bool RequiredFrictionSolver::needs_more_than(const AllocationLayout& layout, double mu) {
  Impl& s = *impl_;
  if (!s.work.cones.empty()) return false;
  return !s.feasible_at(layout, mu, s.x_scratch);
}

const RequiredFriction& RequiredFrictionSolver::solve(const QpProblem& qp,
                                                      const AllocationLayout& layout,
                                                      const Eigen::VectorXd* allocation,
                                                      double enough) {
  Impl& s = *impl_;
  s.out = RequiredFriction{};
  s.enough = enough;
  s.negative_mu = false;
  const int n = qp.variables();
  if (n == 0) {
    s.out.mu = std::numeric_limits<double>::quiet_NaN();
    s.out.message = "required friction: no foot on the ground";
    return s.out;
  }
  if (layout.constant_excess_Nm > kViolationThreshold) {
    s.out.mu = std::numeric_limits<double>::quiet_NaN();
    s.out.message =
        "required friction: no friction coefficient helps (" + layout.constant_violation + ")";
    return s.out;
  }
  if (prescribed_trunk_miss(qp, layout, s.opt.mu_max) > kCertifiedTrunkMiss) {
    // No probe needed: every loaded foot's normal force is prescribed, and no tangential force
    // closes the trunk rows (a touchdown transient's samples under the paper's impact).
    s.out.mu = std::numeric_limits<double>::quiet_NaN();
    s.out.method = RequiredFrictionMethod::kNone;
    s.out.message = no_friction_message(
        s.opt.mu_max, s.opt.reasons ? prescribed_trunk_text(qp) +
                                          " at the least miss: every loaded foot's normal "
                                          "force is prescribed"
                                    : std::string());
    s.last_nan = true;
    return s.out;
  }
  if (qp.cones.empty()) {
    // A held sample whose allocation uses less friction than `enough` is settled before its
    // problem is copied: the faces' directions, all friction_use reads, do not depend on μ.
    int leg = -1;
    const double use = allocation && enough > 0.0 ? friction_use(qp, layout, *allocation, &leg)
                                                  : std::numeric_limits<double>::infinity();
    if (use < enough) {
      s.settle_below(use, *allocation, leg);
      s.last_nan = false;
      return s.out;
    }
    s.load(qp);
    // Before the probe just below `enough`: the allocation's forces moved along the trunk rows'
    // null space to the least tangential forces, which often use less (internal_forces.hpp).
    if (allocation && enough > 0.0) {
      const double moved = internal_force_use(qp, layout, *allocation, s.internal, leg);
      if (moved < s.below_enough()) {
        s.settle_below(moved, s.internal.x, leg);
        s.last_nan = false;
        return s.out;
      }
    }
    s.solve_polygonal(layout, allocation);
  } else {
    s.solve_cone(qp, layout, allocation);
  }
  return s.out;
}

}  // namespace hexdyn
