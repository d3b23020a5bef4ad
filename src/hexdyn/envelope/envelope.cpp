// The envelope search (envelope.hpp): probes through the library calls plan_motion and
// run_scene, a scan and a bisection over the riser per cell and criterion.
#include "hexdyn/envelope/envelope.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

#include "hexdyn/core/errors.hpp"
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
    p.limit = "leg " + leg_name(m.leg) + " " + m.constraint;
    std::ostringstream s;
    s << "no posture admits the motion; the best (trunk height " << posture.height_m
      << " m, gait.foot_lateral " << posture.foot_lateral_m << " m) leaves " << m.describe();
    p.message = s.str();
  }
  return p;
}

EnvelopeProbe dynamic_probe(const Scene& scene, EnvelopeProbe p) {
  const RunResult run = run_scene(scene, nullptr);
  const DynamicsResult& d = run.dyn;
  int support_relaxed = 0, first = -1;
  for (int i = 0; i < static_cast<int>(d.solver_status.size()); ++i) {
    if (d.solver_status[i] == SolverStatus::kOptimal) continue;
    bool impact = false;
    for (int leg = 0; leg < kLegs; ++leg)
      impact = impact ||
               run.kin.contact_phase(i, leg) == static_cast<std::int8_t>(ContactPhase::kImpact);
    if (impact) continue;
    if (support_relaxed++ == 0) first = i;
  }
  p.passed = support_relaxed == 0;
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

EnvelopeResult compute_envelope(const EnvelopeSpec& spec, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  EnvelopeResult out;
  const int C = static_cast<int>(spec.criteria.size());
  const int cells = spec.cell_count();
  out.boundary.resize(static_cast<std::size_t>(cells) * C);
  out.posture_height_m.assign(cells, kNaN);
  out.posture_foot_lateral_m.assign(cells, kNaN);
  out.posture_margin_m.assign(cells, kNaN);
  for (int cell = 0; cell < cells; ++cell) {
    // The kinematic boundary first (when asked): the dynamic criteria fail above it.
    double kinematic_fail = kNaN;
    EnvelopeProbe kinematic_fail_probe;
    for (int ci = 0; ci < C; ++ci) {
      const EnvelopeCriterion c = spec.criteria[ci];
      auto probe = [&](double r) {
        if (c != EnvelopeCriterion::kKinematic && std::isfinite(kinematic_fail) &&
            r >= kinematic_fail - 1e-12) {
          EnvelopeProbe p = kinematic_fail_probe;
          p.criterion = c;
          p.riser_m = r;
          return p;
        }
        out.probes.push_back(evaluate_probe(spec, cell, r, c));
        return out.probes.back();
      };
      EnvelopeBoundary bd;
      bd.riser_max_m = bd.riser_fail_m = kNaN;
      // Scan up to the first failure.
      double pass = kNaN;
      EnvelopeProbe fail;
      bool failed = false;
      const int steps = static_cast<int>(
          std::ceil((spec.riser_to_m - spec.riser_from_m) / spec.riser_step_m - 1e-9));
      for (int k = 0; k <= steps; ++k) {
        const double r = std::min(spec.riser_from_m + k * spec.riser_step_m, spec.riser_to_m);
        const EnvelopeProbe p = probe(r);
        if (!p.passed) {
          fail = p;
          failed = true;
          break;
        }
        pass = r;
      }
      // Bisection between the last success and the first failure.
      if (failed && std::isfinite(pass)) {
        while (fail.riser_m - pass > spec.tolerance_m) {
          const double mid = 0.5 * (pass + fail.riser_m);
          const EnvelopeProbe p = probe(mid);
          if (p.passed)
            pass = mid;
          else
            fail = p;
        }
      }
      bd.riser_max_m = pass;
      if (failed) {
        bd.riser_fail_m = fail.riser_m;
        bd.limit = fail.limit;
        bd.message = fail.message;
      }
      if (c == EnvelopeCriterion::kKinematic) {
        kinematic_fail = bd.riser_fail_m;
        kinematic_fail_probe = fail;
        if (std::isfinite(pass)) {
          try {
            const Scene scene = envelope_probe_scene(spec, cell, pass, c);
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
      }
      out.boundary[static_cast<std::size_t>(cell) * C + ci] = bd;
      if (log) {
        const std::size_t V = spec.peak_speed_mps.size(), B = spec.duty_factor.size(),
                          W = spec.tread_depth_m.size();
        *log << "envelope: ";
        if (spec.cases.size() > 0) *log << spec.cases.labels[cell / (V * B * W)] << ", ";
        *log << "tread " << spec.tread_depth_m[(cell / (V * B)) % W] << " m, duty "
             << spec.duty_factor[(cell / V) % B] << ", speed " << spec.peak_speed_mps[cell % V]
             << " m/s, " << criterion_name(c) << ": riser <= " << bd.riser_max_m * 1e3 << " mm";
        if (failed) *log << ", fails at " << bd.riser_fail_m * 1e3 << " mm: " << bd.message;
        *log << "\n";
      }
    }
  }
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hexdyn
