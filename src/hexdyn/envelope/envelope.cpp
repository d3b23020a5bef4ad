// The envelope search (envelope.hpp): probes through the library calls plan_motion and
// run_scene, a scan and a bisection over the riser per cell and criterion.
#include "hexdyn/envelope/envelope.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/planning/plan.hpp"
#include "hexdyn/planning/posture.hpp"

namespace hexdyn {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The first "torque Lx_joint", "friction Lx", "trunk force z", "normal Lx" named in a
/// relaxed sample's message: the constraint that gave way first in the message's order
/// (the largest violation).
std::string first_constraint(const std::string& message) {
  std::string m = message;
  const auto colon = m.find(": ");
  if (colon != std::string::npos) m = m.substr(colon + 2);
  const auto by = m.find(" by ");
  return by == std::string::npos ? m : m.substr(0, by);
}

EnvelopeProbe kinematic_probe(const Scene& scene, EnvelopeProbe p) {
  const RobotModel model = build_robot_model(scene.robot);
  const PostureChoice posture = best_posture(scene, model);
  const KinematicMargin m =
      posture.mode == PostureMode::kAuto
          ? posture.margin
          : motion_kinematic_margin(
                model, plan_motion_with(scene, model, posture.p0_W, posture.foot_lateral_m), 2000);
  p.passed = m.admitted;
  if (!p.passed) {
    p.limit = "leg " + model.leg(m.leg).name + " " + m.constraint;
    std::ostringstream s;
    s << "no posture admits the motion; the best (trunk height " << posture.height_m
      << " m, gait.foot_lateral " << posture.foot_lateral_m << " m) leaves " << m.describe();
    p.message = s.str();
  }
  return p;
}

/// The least μ of one run (envelope.hpp: a friction search's μ*, every dynamic probe's
/// required_friction): the largest required friction over its support samples, with its leg
/// and time; NaN with the first support sample that admits no μ named in `why` (and NaN
/// without /contacts/required_friction, output.required_friction false).
struct RunFriction {
  double mu = kNaN, time_s = kNaN;
  int leg = -1;
  std::string why;
};

RunFriction run_friction(const RunResult& run) {
  const DynamicsResult& d = run.dyn;
  RunFriction f;
  for (int i = 0; i < static_cast<int>(d.required_friction.size()); ++i) {
    bool impact = false;
    for (int leg = 0; leg < run.kin.contact_phase.cols(); ++leg)
      impact = impact ||
               run.kin.contact_phase(i, leg) == static_cast<std::int8_t>(ContactPhase::kImpact);
    if (impact) continue;
    const double mu = d.required_friction[i];
    if (std::isnan(mu)) {
      f.why = "no friction coefficient admits the support sample at t = " +
              std::to_string(run.kin.time_s[i]) + " s: " + d.solver_messages[i];
      return {kNaN, kNaN, -1, f.why};
    }
    if (!(mu <= f.mu)) f = {mu, run.kin.time_s[i], d.required_friction_leg[i], ""};
  }
  return f;
}

EnvelopeProbe dynamic_probe(const Scene& scene, EnvelopeProbe p) {
  const RunResult run = run_scene(scene, nullptr);
  const DynamicsResult& d = run.dyn;
  int support_relaxed = 0, first = -1;
  for (int i = 0; i < static_cast<int>(d.solver_status.size()); ++i) {
    if (d.solver_status[i] == SolverStatus::kOptimal) continue;
    bool impact = false;
    for (int leg = 0; leg < run.kin.contact_phase.cols(); ++leg)
      impact = impact ||
               run.kin.contact_phase(i, leg) == static_cast<std::int8_t>(ContactPhase::kImpact);
    if (impact) continue;
    if (support_relaxed++ == 0) first = i;
  }
  p.passed = support_relaxed == 0;
  p.required_friction = run_friction(run).mu;
  if (!p.passed) {
    const std::string& msg = d.solver_messages[first];
    p.limit = first_constraint(msg);
    std::ostringstream s;
    s << support_relaxed << " relaxed support sample(s), first at t = " << run.kin.time_s[first]
      << " s: " << msg;
    p.message = s.str();
  }
  return p;
}

std::string exception_limit(const std::exception& e) {
  if (dynamic_cast<const ReachError*>(&e)) return "reach";
  if (dynamic_cast<const PlanningError*>(&e)) return "planning";
  if (dynamic_cast<const ConfigError*>(&e)) return "config";
  if (dynamic_cast<const SolverError*>(&e)) return "solver";
  return "error";
}

}  // namespace

EnvelopeProbe evaluate_probe(const EnvelopeSpec& spec, int cell, double riser_m,
                             EnvelopeCriterion c) {
  EnvelopeProbe p;
  p.cell = cell;
  p.criterion = c;
  p.riser_m = riser_m;
  try {
    const Scene scene = envelope_probe_scene(spec, cell, riser_m, c);
    if (c == EnvelopeCriterion::kKinematic) return kinematic_probe(scene, p);
    p = dynamic_probe(scene, p);
    // The allocation lets the torque rows give way first, then the trunk rows, the contact
    // rows last: a run limited by friction shows relaxed trunk rows. With only trunk rows
    // named, the same run with friction lifted as well tells friction from balance (the
    // unilateral contacts of the support legs cannot produce the trunk's motion at all).
    const bool names_limit = p.limit.rfind("torque ", 0) == 0 || p.limit.rfind("friction", 0) == 0;
    if (!p.passed && !names_limit) {
      Scene lifted = scene;
      lifted.contact.friction_coefficient = 10.0;
      lifted.allocation.torque_limit_Nm = 1e6;
      const bool balance = !dynamic_probe(lifted, p).passed;
      std::ostringstream mu;
      mu << scene.contact.friction_coefficient;
      p.limit = (balance ? "balance: " : "friction (mu " + mu.str() + "): ") + p.limit;
      p.message = (balance ? "the support legs cannot produce the trunk motion even without torque "
                             "and friction limits: "
                           : "friction mu = " + mu.str() +
                                 " cannot produce the trunk motion (it can with mu = 10): ") +
                  p.message;
    }
    return p;
  } catch (const Error& e) {
    p.passed = false;
    p.limit = exception_limit(e);
    p.message = e.what();
    return p;
  }
}

namespace {

/// The probes of one cell: run and recorded in out.probes, except for a dynamic criterion
/// at or above the riser where the kinematic criterion failed (the dynamic criteria fail
/// there too: that failure is reused, not recorded again).
struct CellProbes {
  const EnvelopeSpec& spec;
  int cell;
  EnvelopeResult& out;
  double kinematic_fail = kNaN;  ///< [m] the kinematic riser_fail, NaN before it is known
  EnvelopeProbe kinematic_fail_probe;

  EnvelopeProbe probe(double r, EnvelopeCriterion c) {
    if (c != EnvelopeCriterion::kKinematic && std::isfinite(kinematic_fail) &&
        r >= kinematic_fail - 1e-12) {
      EnvelopeProbe p = kinematic_fail_probe;
      p.criterion = c;
      p.riser_m = r;
      return p;
    }
    out.probes.push_back(evaluate_probe(spec, cell, r, c));
    return out.probes.back();
  }
};

/// One cell's boundary under one criterion: the riser scanned from `from` in steps up to the
/// first failure, then bisected between the last success (pass, NaN if none) and that
/// failure (fail, when failed) to the tolerance.
struct BoundarySearch {
  EnvelopeBoundary bd;
  double pass = kNaN;
  EnvelopeProbe fail;
  bool failed = false;
};

BoundarySearch search_boundary(const EnvelopeSpec& spec, CellProbes& probes, EnvelopeCriterion c) {
  BoundarySearch s;
  s.bd.riser_max_m = s.bd.riser_fail_m = kNaN;
  // Scan up to the first failure.
  const int steps =
      static_cast<int>(std::ceil((spec.riser_to_m - spec.riser_from_m) / spec.riser_step_m - 1e-9));
  for (int k = 0; k <= steps; ++k) {
    const double r = std::min(spec.riser_from_m + k * spec.riser_step_m, spec.riser_to_m);
    const EnvelopeProbe p = probes.probe(r, c);
    if (!p.passed) {
      s.fail = p;
      s.failed = true;
      break;
    }
    s.pass = r;
    s.bd.required_friction = p.required_friction;
  }
  // Bisection between the last success and the first failure.
  if (s.failed && std::isfinite(s.pass)) {
    while (s.fail.riser_m - s.pass > spec.tolerance_m) {
      const double mid = 0.5 * (s.pass + s.fail.riser_m);
      const EnvelopeProbe p = probes.probe(mid, c);
      if (p.passed) {
        s.pass = mid;
        s.bd.required_friction = p.required_friction;
      } else {
        s.fail = p;
      }
    }
  }
  s.bd.riser_max_m = s.pass;
  if (s.failed) {
    s.bd.riser_fail_m = s.fail.riser_m;
    s.bd.limit = s.fail.limit;
    s.bd.message = s.fail.message;
  }
  return s;
}

/// The automatic posture of the cell's scene at the kinematic riser_max pass_m [m], into
/// out's posture fields; left NaN when the scene's posture is not automatic or fails.
void record_posture(const EnvelopeSpec& spec, int cell, double pass_m, EnvelopeResult& out) {
  try {
    const Scene scene = envelope_probe_scene(spec, cell, pass_m, EnvelopeCriterion::kKinematic);
    const RobotModel model = build_robot_model(scene.robot);
    const PostureChoice posture = choose_posture(scene, model);
    if (posture.mode == PostureMode::kAuto) {
      out.posture_height_m[cell] = posture.height_m;
      out.posture_foot_lateral_m[cell] = posture.foot_lateral_m;
      out.posture_margin_m[cell] = posture.margin.value_m;
    }
  } catch (const Error&) {
  }
}

/// One line per cell and criterion: the cell's case, tread [m], duty factor and speed
/// [m/s], the boundary [mm] and why it fails.
void log_boundary(std::ostream& log, const EnvelopeSpec& spec, int cell, EnvelopeCriterion c,
                  const BoundarySearch& s) {
  const std::size_t V = spec.peak_speed_mps.size(), B = spec.duty_factor.size(),
                    W = spec.tread_depth_m.size();
  log << "envelope: ";
  if (spec.cases.size() > 0) log << spec.cases.labels[cell / (V * B * W)] << ", ";
  log << "tread " << spec.tread_depth_m[(cell / (V * B)) % W] << " m, duty "
      << spec.duty_factor[(cell / V) % B] << ", speed " << spec.peak_speed_mps[cell % V] << " m/s, "
      << criterion_name(c) << ": riser <= " << s.bd.riser_max_m * 1e3 << " mm";
  if (s.failed) log << ", fails at " << s.bd.riser_fail_m * 1e3 << " mm: " << s.bd.message;
  log << "\n";
}

/// One riser of a friction search: the run's least μ into out's grids at `at`, and its probe
/// (passed: μ* at most the scene's μ).
EnvelopeProbe friction_search_probe(const EnvelopeSpec& spec, int cell, double riser_m,
                                    std::size_t at, EnvelopeResult& out) {
  EnvelopeProbe p;
  p.cell = cell;
  p.criterion = EnvelopeCriterion::kFriction;
  p.riser_m = riser_m;
  try {
    const Scene scene = envelope_probe_scene(spec, cell, riser_m, p.criterion);
    const RunFriction f = run_friction(run_scene(scene, nullptr));
    p.required_friction = f.mu;
    out.required_friction[at] = f.mu;
    out.required_friction_time_s[at] = f.time_s;
    out.required_friction_leg[at] = f.leg;
    const double mu = scene.contact.friction_coefficient;
    p.passed = f.mu <= mu;
    std::ostringstream m;
    if (std::isnan(f.mu)) {
      p.limit = "balance";
      p.message = f.why;
    } else if (!p.passed) {
      m << f.mu;
      p.limit = "friction (mu* " + m.str() + ")";
      m.str("");
      m << "the support samples need mu = " << f.mu << " (leg "
        << (f.leg >= 0 ? leg_name(f.leg) : std::string("none")) << ", t = " << f.time_s
        << " s), more than the scene's " << mu;
      p.message = m.str();
    }
  } catch (const Error& e) {
    p.passed = false;
    p.limit = exception_limit(e);
    p.message = e.what();
  }
  return p;
}

/// A friction search (envelope.hpp): every cell at every scan riser, and the friction
/// criterion's boundary on the scan.
void friction_search(const EnvelopeSpec& spec, std::ostream* log, EnvelopeResult& out) {
  const std::vector<double> risers = spec.scan_risers();
  const std::size_t R = risers.size(), cells = static_cast<std::size_t>(spec.cell_count());
  out.required_friction.assign(cells * R, kNaN);
  out.required_friction_time_s.assign(cells * R, kNaN);
  out.required_friction_leg.assign(cells * R, -1);
  for (std::size_t cell = 0; cell < cells; ++cell) {
    BoundarySearch s;
    s.bd.riser_max_m = s.bd.riser_fail_m = kNaN;
    for (std::size_t k = 0; k < R; ++k) {
      const int c = static_cast<int>(cell);
      out.probes.push_back(friction_search_probe(spec, c, risers[k], cell * R + k, out));
      const EnvelopeProbe& p = out.probes.back();
      if (p.passed && !s.failed) {
        s.pass = p.riser_m;
        s.bd.required_friction = p.required_friction;
      }
      if (!p.passed && !s.failed) {
        s.failed = true;
        s.fail = p;
        s.bd = {s.pass, p.riser_m, p.limit, p.message, s.bd.required_friction};
      }
    }
    s.bd.riser_max_m = s.pass;
    out.boundary[cell] = s.bd;
    if (log) {
      log_boundary(*log, spec, static_cast<int>(cell), EnvelopeCriterion::kFriction, s);
      *log << "  least mu per riser:";
      for (std::size_t k = 0; k < R; ++k)
        *log << " " << risers[k] * 1e3 << " mm " << out.required_friction[cell * R + k] << ";";
      *log << "\n";
    }
  }
}

}  // namespace

EnvelopeResult compute_envelope(const EnvelopeSpec& spec, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  EnvelopeResult out;
  const int C = static_cast<int>(spec.criteria.size());
  const int cells = spec.cell_count();
  out.boundary.resize(static_cast<std::size_t>(cells) * C);
  out.posture_height_m.assign(cells, kNaN);
  out.posture_foot_lateral_m.assign(cells, kNaN);
  out.posture_margin_m.assign(cells, kNaN);
  if (spec.search == EnvelopeSearch::kFriction) {
    friction_search(spec, log, out);
    out.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
  for (int cell = 0; cell < cells; ++cell) {
    report_progress("envelope", cell, cells, "cells");
    // The kinematic boundary first (when asked): the dynamic criteria fail above it.
    CellProbes probes{spec, cell, out, kNaN, EnvelopeProbe{}};
    for (int ci = 0; ci < C; ++ci) {
      const EnvelopeCriterion c = spec.criteria[ci];
      const BoundarySearch s = search_boundary(spec, probes, c);
      if (c == EnvelopeCriterion::kKinematic) {
        probes.kinematic_fail = s.bd.riser_fail_m;
        probes.kinematic_fail_probe = s.fail;
        if (std::isfinite(s.pass)) record_posture(spec, cell, s.pass, out);
      }
      out.boundary[static_cast<std::size_t>(cell) * C + ci] = s.bd;
      if (log) log_boundary(*log, spec, cell, c, s);
    }
  }
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hexdyn
