#include "hexdyn/planning/posture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>

#include "hexdyn/core/cancel.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/planning/margin_detail.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {
namespace {

using margin_detail::Evaluation;
using margin_detail::FootTrack;
using margin_detail::SampleReferences;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Limiting samples an automatic posture search tries first, per spread (PostureSearch).
constexpr std::size_t kHotSamples = 16;

/// Instants a margin evaluation takes first (margin_detail::MarginRequest): every 8th of a
/// candidate's (~40 ms apart), every 64th of the dense check's (5 ms apart).
constexpr int kSearchStride = 16, kCheckStride = 64;

/// Result of one candidate posture. `margin` is exact when `complete`; otherwise its value_m
/// is below the bound the candidate was evaluated against (search_margin).
struct Candidate {
  double height_m = 0.0, foot_lateral_m = 0.0;
  KinematicMargin margin;
  bool planned = false, complete = true;
  std::string planning_error;
};

/// The search of the automatic posture (posture.hpp). It takes the decisions of a plain scan
/// and golden section over exact margins, with two savings that leave every decision and
/// every reported margin as they are:
///   - the gait and the foot targets of a spread are planned once (FootTrack);
///   - a candidate compared with one whose exact margin is known is evaluated only until a
///     sample falls below that margin (it loses the comparison whatever its other samples),
///     trying first the samples that limited the earlier candidates.
/// A candidate that wins a comparison is always evaluated completely, so the compared
/// margins, the best candidate and its margin are those of complete evaluations.
class PostureSearch {
 public:
  PostureSearch(const Scene& scene, const RobotModel& model,
                std::shared_ptr<const TrunkOffset> offset)
      : scene_(scene), model_(model), terrain_(scene.terrain), offset_(std::move(offset)) {}

  /// The margin of height h and spread w on margin_sample_times(plan, uniform): a candidate's,
  /// complete or, when it is below `below_m`, possibly stopped there; or the dense check of
  /// the chosen posture (Evaluation).
  Candidate evaluate(double h, double w, int uniform, double below_m = -kInf,
                     Evaluation kind = Evaluation::kCandidate) {
    ++evaluations_;
    Candidate c;
    c.height_m = h;
    c.foot_lateral_m = w;
    const PostureParams& p = scene_.motion.posture;
    const Vec3 p0_W = relative_start_position(scene_.terrain, h, p.start_y_m);
    Spread& spread = spread_for(p0_W, w, uniform);
    if (!spread.planned) {
      c.margin.value_m = -kInf;
      c.planning_error = spread.planning_error;
      return c;
    }
    // The trunk exactly as plan_motion_with(scene, model, p0_W, w) plans it.
    MotionParams motion = scene_.motion;
    motion.initial_position_m = p0_W;
    GaitParams gait = scene_.gait;
    gait.foot_lateral_m = w;
    TrunkMotion trunk(motion, gait, terrain_, settle_time_s(scene_, model_));
    if (offset_) trunk.set_offset(offset_);
    c.planned = true;
    margin_detail::MarginRequest request;
    request.below_m = below_m;
    request.hot = &spread.hot;
    request.kind = kind;
    request.stride = kind == Evaluation::kCandidate ? kSearchStride : kCheckStride;
    const margin_detail::MarginEvaluation e =
        margin_detail::bounded_margin(model_, trunk, spread.feet, h, request, spread.refs);
    c.margin = e.margin;
    c.complete = e.complete;
    if (e.limiting_sample >= 0 &&
        std::find(spread.hot.begin(), spread.hot.end(), e.limiting_sample) == spread.hot.end())
      spread.hot.insert(spread.hot.begin(), e.limiting_sample);
    if (spread.hot.size() > kHotSamples) spread.hot.pop_back();
    return c;
  }

  /// Best height for spread w: a scan, then golden section around the best scan point. Every
  /// candidate but the first of each phase is evaluated against the candidate it is compared
  /// with, whose margin is exact (see the class comment). The scan's best is the first of its
  /// largest margins in the order of heights, as a scan from the lowest height finds it; its
  /// heights are visited coarse to fine, then nearest to the best so far, so that the best is
  /// found early and most of the others stop at a sample.
  Candidate best_height(double w, double h_lo, double h_hi) {
    constexpr int kScan = 25;
    constexpr int kUniform = 200;
    std::vector<Candidate> scan(kScan);
    std::vector<bool> done(kScan, false);
    int best = -1;
    auto visit = [&](int i) {
      check_cancelled();
      const double below = best < 0 ? -kInf : scan[best].margin.value_m;
      scan[i] = evaluate(h_lo + (h_hi - h_lo) * i / (kScan - 1), w, kUniform, below);
      done[i] = true;
      const double m = scan[i].margin.value_m;
      if (best < 0 || m > scan[best].margin.value_m || (m == scan[best].margin.value_m && i < best))
        best = i;
    };
    for (int i : {0, kScan - 1, (kScan - 1) / 2, (kScan - 1) / 4, 3 * (kScan - 1) / 4}) visit(i);
    for (int n = 5; n < kScan; ++n) {
      int next = -1;
      for (int i = 0; i < kScan; ++i)
        if (!done[i] && (next < 0 || std::abs(i - best) < std::abs(next - best))) next = i;
      visit(next);
    }
    if (!scan[best].planned) return scan[best];
    double a = scan[std::max(best - 1, 0)].height_m,
           b = scan[std::min(best + 1, kScan - 1)].height_m;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    Candidate x1 = evaluate(b - g * (b - a), w, kUniform);
    Candidate x2 = evaluate(a + g * (b - a), w, kUniform, x1.margin.value_m);
    Candidate top = scan[best];
    // The candidate kept from one step to the next won its comparison: it is complete, and
    // the new one is evaluated against it.
    while (b - a > 1e-4) {
      if (x1.margin.value_m >= x2.margin.value_m) {
        b = x2.height_m;
        x2 = x1;
        x1 = evaluate(b - g * (b - a), w, kUniform, x2.margin.value_m);
      } else {
        a = x1.height_m;
        x1 = x2;
        x2 = evaluate(a + g * (b - a), w, kUniform, x1.margin.value_m);
      }
      for (const Candidate* c : {&x1, &x2})
        if (c->margin.value_m > top.margin.value_m) top = *c;
    }
    return top;
  }

  int evaluations() const { return evaluations_; }

 private:
  /// The foot targets of one spread on one sample grid, and the limiting samples seen so far.
  struct Spread {
    double foot_lateral_m = 0.0;
    int uniform = 0;
    bool planned = false;
    std::string planning_error;
    FootTrack feet;
    std::vector<int> hot;
    SampleReferences refs;  ///< the samples' bounds from the heights evaluated so far
  };

  Spread& spread_for(const Vec3& p0_W, double w, int uniform) {
    for (Spread& s : spreads_)
      if (s.foot_lateral_m == w && s.uniform == uniform) return s;
    Spread s;
    s.foot_lateral_m = w;
    s.uniform = uniform;
    try {
      s.feet =
          margin_detail::foot_track(model_, plan_motion_with(scene_, model_, p0_W, w), uniform);
      s.planned = true;
    } catch (const PlanningError& e) {
      s.planning_error = e.what();
    }
    spreads_.push_back(std::move(s));
    return spreads_.back();
  }

  const Scene& scene_;
  const RobotModel& model_;
  Terrain terrain_;
  std::shared_ptr<const TrunkOffset> offset_;  ///< the balanced trunk's, or none
  std::deque<Spread> spreads_;                 // deque: references stay valid as spreads are added
  int evaluations_ = 0;
};

/// The legs' reach, the span of the default height search [m]: the largest of the model's
/// leg_reach_m (the paper robot: the foot distance at zero joint angles, where every leg stands
/// straight out; a chain, any number of joints: the link lengths summed along the chain, hip →
/// second joint → … → last joint → foot, since a leg need not be extended at zero, as Kraby's
/// femur rests at 45°), a sphere foot's radius added.
double leg_length_m(const RobotModel& model) {
  double r = 0.0;
  for (int leg = 0; leg < model.legs(); ++leg)
    r = std::max(r, leg_reach_m(model, leg) + model.foot_radius_m[leg]);
  return r;
}

/// Height of the hip plane above P0, measured vertically [m]: the lowest hip's offset z
/// along the trunk normal over cos α, α the trunk's pitch (the trunk is parallel to the
/// reference line, so a point at z along its normal stands z / cos α higher above the line
/// than P0, wherever it is along the trunk). 0 for the paper robot (its hips lie in the
/// trunk plane); 0.208 m for Kraby, whose trunk frame is at the bottom of its legs.
double hip_plane_offset_m(const Scene& scene, const RobotModel& model) {
  double z = kInf;
  for (int leg = 0; leg < model.legs(); ++leg) z = std::min(z, model.p_hip_B[leg].z());
  const double pitch = TrunkMotion(scene.motion, scene.gait, Terrain(scene.terrain)).pitch_rad();
  return z / std::cos(pitch);
}

/// The heights the automatic posture searches [m, P0 above the reference line]: the
/// scene's height_range or the hip plane's default, its lower end raised to the trunk
/// clearance (clear_m, which may lie above hi_m: then nothing can be searched).
struct HeightRange {
  double lo_m = 0.0, hi_m = 0.0, clear_m = 0.0;
};

HeightRange searched_heights(const Scene& scene, const RobotModel& model) {
  const PostureParams& p = scene.motion.posture;
  const double hip_m = hip_plane_offset_m(scene, model);
  HeightRange r{p.height_min_m, p.height_max_m, 0.0};
  if (!(r.lo_m < r.hi_m)) {
    r.lo_m = -hip_m;
    r.hi_m = leg_length_m(model) - hip_m;
  }
  r.clear_m = terrain_rise_above_reference(scene.terrain) + p.trunk_clearance_m - hip_m;
  r.lo_m = std::max(r.lo_m, r.clear_m);
  return r;
}

/// A step list's reference line: through the first tread's centre at the mean slope.
double list_reference_height(const TerrainParams& t, double y) {
  const StairStep& first = t.step_list.front();
  const double centre_y = t.first_riser_y_m + 0.5 * first.tread_m;
  return t.ground_height_m + first.riser_m + std::tan(mean_slope_rad(t)) * (y - centre_y);
}

}  // namespace

double reference_line_height(const TerrainParams& t, double y) {
  switch (t.type) {
    case TerrainType::kStairs:
      if (t.step_list.empty())
        return t.ground_height_m +
               t.riser_height_m * ((y - t.first_riser_y_m) / t.tread_depth_m + 0.5);
      return list_reference_height(t, y);
    case TerrainType::kSlope:
    case TerrainType::kHeightMap:
      return t.ground_height_m + std::tan(t.slope_rad) * (y - t.slope_origin_y_m);
    case TerrainType::kFlat:
      return t.ground_height_m;
  }
  return 0.0;
}

double terrain_rise_above_reference(const TerrainParams& t) {
  if (t.type == TerrainType::kHeightMap) {  // the highest node above the line
    double rise = 0.0;
    for (int i = 0; i < t.map->ny; ++i)
      for (int j = 0; j < t.map->nx; ++j)
        rise = std::max(rise, t.map->at(i, j) - reference_line_height(t, t.map->y(i)));
    return rise;
  }
  if (t.type != TerrainType::kStairs) return 0.0;
  if (t.step_list.empty() && t.nosing_m == 0.0) return 0.5 * std::abs(t.riser_height_m);
  // The highest corner of a tread above the line: at the tread's start or end.
  const Terrain terrain(t);
  double rise = 0.0;
  for (int k = 0; k <= terrain.edge_count(); ++k) {
    for (int end = 0; end < 2; ++end) {
      const int e = k + end;  // the edge at the tread's start (k) or end (k + 1)
      if (e < 1 || e > terrain.edge_count()) continue;
      rise = std::max(rise, terrain.tread_height(k) - reference_line_height(t, terrain.edge_y(e)));
    }
  }
  return rise;
}

double terrain_origin_y(const TerrainParams& t) {
  switch (t.type) {
    case TerrainType::kStairs:
      return t.first_riser_y_m;
    case TerrainType::kSlope:
      return t.slope_origin_y_m;
    case TerrainType::kFlat:
    case TerrainType::kHeightMap:
      return 0.0;
  }
  return 0.0;
}

Vec3 relative_start_position(const TerrainParams& t, double height_m, double start_y_m) {
  const double y = terrain_origin_y(t) + start_y_m;
  return Vec3(0.0, y, reference_line_height(t, y) + height_m);
}

std::string KinematicMargin::describe() const {
  std::ostringstream s;
  s << "leg " << leg_name(leg) << " at t = " << t_s << " s: " << constraint << " (margin "
    << value_m << " m)";
  return s.str();
}

std::vector<double> margin_sample_times(const MotionPlan& plan, int uniform) {
  const double T = plan.trunk.duration_s();
  const int n = std::max(uniform, 2);
  std::vector<double> t;
  for (int i = 0; i < n; ++i) t.push_back(T * i / (n - 1));
  for (const LegPlan& leg : plan.gait.legs)
    for (const Swing& sw : leg.swings) {
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      for (double u : {0.0, sw.lift_end_u, sw.lower_start_u}) t.push_back(sw.t_liftoff_s + u * D);
      t.push_back(sw.t_touchdown_s);
    }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

KinematicMargin motion_kinematic_margin(const RobotModel& model, const MotionPlan& plan,
                                        int uniform) {
  return margin_detail::full_margin(model, plan.trunk,
                                    margin_detail::foot_track(model, plan, uniform));
}

PostureChoice choose_posture(const Scene& scene, const RobotModel& model, PostureCheck check,
                             std::shared_ptr<const TrunkOffset> offset) {
  PostureChoice c = best_posture(scene, model, check, std::move(offset));
  if (c.mode != PostureMode::kAuto || c.margin.admitted) return c;
  const double h_lo = searched_heights(scene, model).lo_m;
  std::ostringstream msg;
  msg << "no trunk posture admits the motion (motion.posture.height: auto): the best, height "
      << c.height_m << " m above the terrain's reference line with gait.foot_lateral "
      << c.foot_lateral_m << " m, leaves " << c.margin.describe()
      << "; required: reach margin >= robot.ik_min_margin (" << model.ik_min_margin_m
      << " m) and every joint inside its limits";
  if (c.height_m - h_lo < 1e-3)
    msg << " (the height is the lowest the trunk clearance allows: " << h_lo
        << " m = riser/2 + motion.posture.trunk_clearance - the hip plane's height above P0)";
  throw ReachError(msg.str());
}

PostureChoice best_posture(const Scene& scene, const RobotModel& model, PostureCheck check,
                           std::shared_ptr<const TrunkOffset> offset) {
  const PostureParams& p = scene.motion.posture;
  PostureChoice c;
  c.mode = p.mode;
  c.foot_lateral_m = scene.gait.foot_lateral_m;
  if (p.mode == PostureMode::kAbsolute) {
    c.p0_W = scene.motion.initial_position_m;
    c.height_m = c.p0_W.z() - reference_line_height(scene.terrain, c.p0_W.y());
    return c;
  }
  if (p.mode == PostureMode::kRelative) {
    c.height_m = p.height_m;
    c.p0_W = relative_start_position(scene.terrain, p.height_m, p.start_y_m);
    return c;
  }
  PostureSearch search(scene, model, std::move(offset));
  // Heights are P0's; the default range and the trunk clearance are the hip plane's. The
  // trunk keeps its clearance above the terrain: no height below it is searched.
  const HeightRange range = searched_heights(scene, model);
  const double h_clear = range.clear_m, h_hi = range.hi_m, h_lo = range.lo_m;
  if (h_clear >= h_hi) {
    std::ostringstream msg;
    msg << "no trunk posture admits the motion (motion.posture.height: auto): the trunk clearance "
           "needs a height of at "
           "least "
        << h_clear << " m above the terrain's reference line (highest terrain "
        << terrain_rise_above_reference(scene.terrain)
        << " m above it + motion.posture.trunk_clearance " << p.trunk_clearance_m
        << " m), above the searched range's top " << h_hi << " m";
    throw ReachError(msg.str());
  }
  Candidate best = search.best_height(scene.gait.foot_lateral_m, h_lo, h_hi);
  if (p.vary_foot_lateral && best.margin.value_m < p.target_margin_m) {
    constexpr int kSpreads = 9;
    for (int i = 0; i < kSpreads; ++i) {
      const double w =
          p.foot_lateral_min_m + (p.foot_lateral_max_m - p.foot_lateral_min_m) * i / (kSpreads - 1);
      Candidate c_w = search.best_height(w, h_lo, h_hi);
      if (c_w.margin.value_m > best.margin.value_m) best = c_w;
    }
  }
  if (!best.planned) throw PlanningError(best.planning_error);
  // The chosen posture on a dense grid (a sample at least every 5 ms).
  const double duration_s =
      TrunkMotion(scene.motion, scene.gait, Terrain(scene.terrain), settle_time_s(scene, model))
          .duration_s();
  const int dense_uniform = static_cast<int>(std::ceil(duration_s / 0.005)) + 1;
  Candidate dense =
      search.evaluate(best.height_m, best.foot_lateral_m, dense_uniform, -kInf,
                      check == PostureCheck::kMargin ? Evaluation::kCheck : Evaluation::kAdmission);
  c.evaluations = search.evaluations();
  if (!dense.margin.admitted && check == PostureCheck::kAdmission)  // the margin for the error
    dense = search.evaluate(best.height_m, best.foot_lateral_m, dense_uniform, -kInf,
                            Evaluation::kCheck);
  c.height_m = best.height_m;
  c.foot_lateral_m = best.foot_lateral_m;
  c.p0_W = relative_start_position(scene.terrain, best.height_m, p.start_y_m);
  c.margin = dense.margin;
  return c;
}

}  // namespace hexdyn
