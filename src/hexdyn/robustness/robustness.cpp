// The robustness study (robustness.hpp): one plan, many replays on perturbed worlds.
#include "hexdyn/robustness/robustness.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "hexdyn/config/robustness_bounds.hpp"
#include "hexdyn/contact/simulation_contact.hpp"
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/run.hpp"

namespace hexdyn {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// What every replay of a study shares, read-only (the model and plan are the StudyPlan's,
/// which outlives the study).
struct Study {
  const Scene& scene;
  const RobotModel& model;
  const ReplayPlan& plan;
  DrawSizes sizes;
  FailureBounds bounds;
  std::uint64_t seed = 1;
  LegArray<Vec3> start_feet_W{};  ///< the plan's foot points (sphere centres) at its first instant
  /// The joint PD of every replay: the scene's, resolved for the planned robot (the controller
  /// does not know a world's payload).
  ReplayParams gains{};
};

/// How far the robot must start above its planned first state on the terrain of `plan` so that
/// no foot sinks deeper into it than into the plan's own terrain (docs/theory/robustness.md#
/// worlds): the largest extra penetration of the first instant's feet, or 0.
double start_lift(const Study& s, const ReplayPlan& plan) {
  double lift = 0.0;
  for (int l = 0; l < s.model.legs(); ++l) {
    const double r = s.model.foot_radius_m[l];
    const Vec3& c = s.start_feet_W[l];
    const double nominal =
        std::max(0.0, terrain_contact(s.plan.terrain_y_m, s.plan.terrain_z_m, c, r).penetration_m);
    const double world =
        plan.terrain_map ? height_map_contact(*plan.terrain_map, c, r).penetration_m
                         : terrain_contact(plan.terrain_y_m, plan.terrain_z_m, c, r).penetration_m;
    lift = std::max(lift, world - nominal);
  }
  return lift;
}

/// The replay of the plan on the world of `draw`, classified.
ReplayOutcome replay_world(const Study& s, const WorldDraw& draw) {
  const World w = perturbed_world(s.model, s.scene.contact, s.scene.terrain, s.plan, draw);
  const bool same_terrain = w.terrain_map == s.plan.terrain_map &&
                            w.terrain_y_m == s.plan.terrain_y_m &&
                            w.terrain_z_m == s.plan.terrain_z_m;
  ReplayResult r;
  if (same_terrain) {
    r = replay_plan(w.model, w.contact, s.gains, w.terrain, s.plan);
  } else {
    ReplayPlan plan = s.plan;  // the same torques and angles, on the world's terrain
    plan.terrain_y_m = w.terrain_y_m;
    plan.terrain_z_m = w.terrain_z_m;
    plan.terrain_map = w.terrain_map;
    plan.base.front().p_W.z() += start_lift(s, plan);
    r = replay_plan(w.model, w.contact, s.gains, w.terrain, plan);
  }
  return classify_replay(r, s.plan, w, s.scene.terrain, s.bounds);
}

/// Calls f(i) for i in [0, n) on `threads` threads (this one among them), each i once; the
/// first exception stops the others' next calls and is rethrown here. This thread reports
/// progress, in `n` replays.
template <class F>
void parallel_for(int n, int threads, F f) {
  std::atomic<int> next{0}, done{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](bool reporting) {
    for (int i = next++; i < n; i = next++) {
      try {
        f(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = n;
        return;
      }
      ++done;
      if (reporting) report_progress("replays", done.load(), n, "replays");
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(threads, n); ++t) pool.emplace_back(work, false);
  work(true);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// The success fraction of `replays` replays of `spec` from draw 0, and their outcomes.
double success_fraction(const Study& s, const PerturbationSpec& spec, int replays, int threads) {
  std::vector<char> ok(static_cast<std::size_t>(replays), 0);
  parallel_for(replays, threads, [&](int i) {
    const WorldDraw d = draw_world(spec, s.sizes, s.seed, static_cast<std::uint64_t>(i));
    ok[static_cast<std::size_t>(i)] = replay_world(s, d).reached_top ? 1 : 0;
  });
  long n = 0;
  for (char c : ok) n += c;
  return static_cast<double>(n) / replays;
}

/// The largest scale ≤ `max_scale` of `p`'s distribution alone whose worlds are all physical
/// (config/robustness_bounds.hpp), by bisection.
double physical_scale(const Scene& scene, Perturbation p, double max_scale) {
  const auto physical = [&](double scale) {
    PerturbationSpec alone;
    alone[p] = scene.robustness.perturbations[p].scaled(scale);
    return !perturbation_problem(alone, scene);
  };
  if (physical(max_scale)) return max_scale;
  double lo = 0.0, hi = max_scale;
  for (int k = 0; k < 60; ++k) (physical(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

/// The tolerated scale of `p` alone (ToleranceSearch), the nominal plan's outcome at scale 0.
ToleranceResult tolerated(const Study& s, Perturbation p, bool nominal_ok, int threads) {
  const RobustnessParams& spec = s.scene.robustness;
  const ToleranceSearch& q = spec.search;
  auto fraction = [&](double scale) {
    PerturbationSpec alone;
    alone[p] = spec.perturbations[p].scaled(scale);
    return success_fraction(s, alone, q.replays, threads);
  };
  ToleranceResult t;
  t.perturbation = p;
  t.max_scale = physical_scale(s.scene, p, q.max_scale);
  double lo = 0.0, hi = t.max_scale, p_lo = nominal_ok ? 1.0 : 0.0;
  const double p_hi = hi > 0.0 ? fraction(hi) : p_lo;
  t.probes = 1;
  if (p_hi >= q.target) {
    lo = hi;
    p_lo = p_hi;
    t.censored = true;
  } else if (nominal_ok) {
    for (int k = 0; k < q.bisections; ++k, ++t.probes) {
      const double mid = 0.5 * (lo + hi), f = fraction(mid);
      if (f >= q.target) {
        lo = mid;
        p_lo = f;
      } else {
        hi = mid;
      }
    }
  }
  t.scale = lo;
  t.p_success = p_lo;
  t.magnitude = lo * spec.perturbations[p].largest_magnitude();
  return t;
}

/// The study of `plan` under `scene`'s robustness: section, with the first instant's feet by
/// forward kinematics of the plan (a sphere foot's centre).
Study make_study(const Scene& scene, const StudyPlan& plan) {
  Study s{scene, plan.model, plan.plan, {}, scene.robustness.failure, scene.robustness.seed};
  s.sizes = world_draw_sizes(s.model, scene.terrain);
  s.gains = resolved_gains(scene.replay, s.model);
  if (std::isnan(s.bounds.drift_m))
    s.bounds.drift_m = arrival_tolerance(scene.terrain).horizontal_m;
  BodyPoses poses;
  forward_kinematics_tree(s.model, s.plan.q_rad.front(), poses);
  const BaseState& b = s.plan.base.front();
  for (int l = 0; l < s.model.legs(); ++l)
    s.start_feet_W[l] = b.p_W + b.W_R_B * tree_foot_position_B(s.model, poses, l);
  return s;
}

}  // namespace

int study_replays(const Scene& scene) {
  return scene.robustness.replays > 0 ? scene.robustness.replays : kDefaultRobustnessReplays;
}

StudyPlan plan_of_run(const RobotModel& model, const RunResult& run) {
  StudyPlan p{model, plan_from_result(model, run), run.joint_names};
  for (int l = 0; static_cast<int>(p.joint_names.size()) < model.joints() && l < model.legs(); ++l)
    for (int j = 0; j < model.leg(l).n_joints; ++j)
      p.joint_names.push_back(joint_name(l, j, model.leg(l).n_joints));
  return p;
}

RobustnessResult run_robustness(const Scene& scene, int threads, RunResult* plan) {
  const auto start = Clock::now();
  Scene planned = scene;
  planned.output.summary_only = false;  // the study needs the whole plan
  RunResult run = run_scene(planned);
  const StudyPlan study_plan = plan_of_run(build_robot_model(scene.robot), run);
  if (plan) *plan = std::move(run);
  RobustnessResult out = run_robustness(scene, study_plan, threads);
  out.plan_seconds = seconds_since(start) - out.seconds;
  out.seconds = seconds_since(start);
  return out;
}

RobustnessResult run_robustness(const Scene& scene, const StudyPlan& plan, int threads) {
  const auto start = Clock::now();
  const RobustnessParams& spec = scene.robustness;
  const int replays = study_replays(scene);
  RobustnessResult out;
  const Study s = make_study(scene, plan);
  out.joint_names = plan.joint_names;
  out.sizes = s.sizes;
  out.bounds = s.bounds;
  const auto n = static_cast<std::size_t>(replays);
  out.draws.resize(n);
  out.outcomes.resize(n);
  parallel_for(replays, threads, [&](int i) {
    const auto k = static_cast<std::size_t>(i);
    out.draws[k] = draw_world(spec.perturbations, s.sizes, s.seed, k);
    out.outcomes[k] = replay_world(s, out.draws[k]);
  });
  for (const ReplayOutcome& o : out.outcomes) {
    ++out.counts[static_cast<std::size_t>(o.failure)];
    if (o.reached_top) ++out.successes;
  }
  out.p_success = static_cast<double>(out.successes) / replays;
  out.interval = wilson_interval(out.successes, replays);
  if (spec.search.enabled) {
    const bool nominal_ok = replay_world(s, draw_world({}, s.sizes, s.seed, 0)).reached_top;
    for (Perturbation p : spec.perturbations.active())
      out.tolerance.push_back(tolerated(s, p, nominal_ok, threads));
  }
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace hexdyn
