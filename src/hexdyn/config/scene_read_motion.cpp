// The terrain's, the gait's and the motion's keys (scene_readers.hpp). Paths, ranges and
// defaults come from the table (scene_key_table.hpp); rules across keys from key_rules.hpp.
#include <cmath>
#include <cstdio>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "hexdyn/config/height_map_keys.hpp"
#include "hexdyn/config/key_rules.hpp"
#include "hexdyn/config/scene_readers.hpp"
#include "hexdyn/config/stair_steps.hpp"
#include "hexdyn/config/table_keys.hpp"
#include "hexdyn/core/run_size.hpp"
#include "hexdyn/model/gait_pattern.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn::scene_keys {

void read_terrain(Reader& r, TerrainParams& t) {
  const std::string type = choice_key(r, "terrain.type");
  if (type == "flat") {
    t.type = TerrainType::kFlat;
    t.ground_height_m = number_key(r, "terrain.height");
  } else if (type == "height_map") {
    t.type = TerrainType::kHeightMap;
    read_height_map(r, t);
  } else if (type == "slope") {
    t.type = TerrainType::kSlope;
    t.slope_rad = number_key(r, "terrain.angle");
    t.slope_origin_y_m = number_key(r, "terrain.origin_y");
    t.ground_height_m = number_key(r, "terrain.ground_height");
  } else {
    t.type = TerrainType::kStairs;
    t.first_riser_y_m = number_key(r, "terrain.first_riser_y");
    read_stairs(r, t);
    t.ground_height_m = number_key(r, "terrain.ground_height");
  }
}

namespace {

/// gait.phases: {L1: φ, …, Ln: φ}, every leg of the robot named once, each φ in [0, 1), each read
/// as gait.phases.L<i> by its row; empty when absent (the wave gait's phases). A leg named twice is
/// a duplicate key, refused with the file's lines (config/yaml_load.hpp).
std::vector<double> read_phases(Reader& r, int legs) {
  const std::string key = "gait.phases";
  if (!r.given(key)) {
    (void)r.has(key);  // counted as asked for
    return {};
  }
  std::string names;
  for (int leg = 0; leg < legs; ++leg) names += (leg ? ", " : "") + leg_name(leg);
  const YAML::Node node = r.peek(key);
  if (!node.IsMap()) {
    (void)r.node(key);
    r.fail_value(key, node,
                 "a map {L1: φ, …, " + leg_name(legs - 1) + ": φ} naming every leg once (" + names +
                     "), each φ a lift-off phase in [0, 1)");
  }
  for (const auto& entry : node) {
    const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : "";
    bool known = false;
    for (int leg = 0; leg < legs; ++leg) known = known || name == leg_name(leg);
    if (!known)
      r.fail(key, "got the key " + yaml_for_message(entry.first) + ", expected leg names (" +
                      names + ")");
  }
  std::vector<double> phases;
  for (int leg = 0; leg < legs; ++leg) {
    if (!node[leg_name(leg)].IsDefined())
      r.fail(key, "got " + yaml_for_message(node) + ", expected a map naming every leg once (" +
                      names + "), " + leg_name(leg) + " missing");
    phases.push_back(number_key(r, key + "." + leg_name(leg)));
  }
  return phases;
}

/// The robot's legs by side and rank (model/gait_pattern.hpp): a URDF robot's model, else the
/// YAML robot's, built here; empty when the YAML robot's model cannot be built (its keys'
/// error comes where it is built for the run).
std::vector<GaitLeg> robot_gait_legs(const RobotParams& robot, const LoadedUrdfRobot& urdf) {
  if (urdf.model) return gait_legs(*urdf.model);
  try {
    return gait_legs(build_robot_model(robot));
  } catch (const std::logic_error&) {
    return {};
  }
}

/// gait.pattern with gait.phases (docs/user/configuration.md#gait): custom takes the phases, the
/// other patterns none. Without a pattern the phases mean custom and their absence wave, a
/// choice recorded as the pattern used with `auto.gait.pattern: auto` beside it. A pattern that
/// does not fit the robot's legs is refused in one line (gait_pattern_misfit); the phases of
/// the others are recorded as `auto.gait.phases`, written anew by every read.
void read_pattern(Reader& r, GaitParams& g, std::span<const GaitLeg> legs) {
  const std::string key = "gait.pattern";
  if (r.given(key)) {
    const std::string word = choice_key(r, key);
    for (int i = 0; i <= static_cast<int>(GaitPattern::kCustom); ++i)
      if (gait_pattern_word(static_cast<GaitPattern>(i)) == word) g.pattern = GaitPattern(i);
    const bool custom = g.pattern == GaitPattern::kCustom;
    if (custom && g.liftoff_phases.empty())
      r.fail(key,
             "got custom without gait.phases, expected gait.phases {L1: φ, …} beside it, or "
             "one of wave, trot, pace, bound");
    if (!custom && !g.liftoff_phases.empty())
      r.fail(key, "got " + word + " with gait.phases, expected custom with gait.phases, or " +
                      word + " without them (its phases follow from the legs)");
  } else {
    (void)r.has(key);  // counted as asked for
    g.pattern = g.liftoff_phases.empty() ? GaitPattern::kWave : GaitPattern::kCustom;
    r.record(key, YAML::Node(gait_pattern_word(g.pattern)));
    r.record("auto." + key, "auto");
  }
  if (g.pattern == GaitPattern::kCustom || legs.empty()) return;
  const std::string misfit = gait_pattern_misfit(g.pattern, legs);
  if (!misfit.empty()) r.fail(key, misfit);
  const std::vector<double> phases = gait_pattern_phases(g.pattern, legs, g.duty_factor);
  YAML::Node by_leg(YAML::NodeType::Map);
  for (int leg = 0; leg < static_cast<int>(phases.size()); ++leg)
    by_leg[leg_name(leg)] = phases[leg];
  by_leg.SetStyle(YAML::EmitterStyle::Flow);
  r.record("auto.gait.phases", by_leg);
}

}  // namespace

void read_gait(Reader& r, Scene& s, const LoadedUrdfRobot& urdf) {
  read_table_keys(r, s, "gait");
  GaitParams& g = s.gait;
  g.liftoff_phases = read_phases(r, robot_leg_count(urdf));
  read_pattern(r, g, robot_gait_legs(s.robot, urdf));
  // A URDF robot's footholds default to its nominal stance radius (config/robot_config.hpp),
  // an automatic choice the resolved configuration records beside the value.
  if (urdf.robot && !r.given("gait.foot_lateral")) r.record("auto.gait.foot_lateral", "auto");
  g.foot_lateral_m = urdf.robot ? number_key_or(r, "gait.foot_lateral", urdf.stance_radius_m)
                                : number_key(r, "gait.foot_lateral");
  check_swing_fractions(r, g);
}

namespace {

/// The trunk's start: motion.initial_position (absolute) or motion.posture (relative to the
/// terrain, or auto). The definitions are those of planning/posture.hpp.
void read_posture(Reader& r, MotionParams& m) {
  const bool absolute = r.has("motion.initial_position");
  const bool relative = r.given("motion.posture");
  if (!relative) (void)r.has("motion.posture");  // a null posture counts as absent
  check_start_form(r, absolute, relative);
  PostureParams& p = m.posture;
  if (!relative) {
    p.mode = PostureMode::kAbsolute;
    m.initial_position_m = vec3_key(r, "motion.initial_position");
    return;
  }
  p.start_y_m = number_key(r, "motion.posture.start_y");
  if (!r.holds_word("motion.posture.height", "auto")) {
    p.mode = PostureMode::kRelative;
    p.height_m = number_key(r, "motion.posture.height");
    return;
  }
  p.mode = PostureMode::kAuto;
  // Search range of the height; [0, 0] lets planning derive it from the legs' reach.
  const std::vector<double> no_range{0.0, 0.0};
  const auto h = numbers_key(r, "motion.posture.height_range", &no_range);
  if (h != no_range) check_increasing(r, "motion.posture.height_range", h);
  p.height_min_m = h[0];
  p.height_max_m = h[1];
  p.target_margin_m = number_key(r, "motion.posture.target_margin");
  p.trunk_clearance_m = number_key(r, "motion.posture.trunk_clearance");
  p.vary_foot_lateral = r.given("motion.posture.foot_lateral");
  if (p.vary_foot_lateral) {
    const auto w = numbers_key(r, "motion.posture.foot_lateral");
    if (!(w[0] <= w[1]))
      r.fail("motion.posture.foot_lateral",
             "got " + yaml_inline(YAML::Node(w)) +
                 ", expected [lower, upper] with lower <= upper (the range auto may choose "
                 "gait.foot_lateral from)");
    p.foot_lateral_min_m = w[0];
    p.foot_lateral_max_m = w[1];
  }
}

/// motion.travel: {distance: D} or {treads: N}, the trunk's travel along the slope
/// (docs/user/configuration.md#travel-instead-of-cycles). The cycles are the fewest whose
/// strides of the given stroke cover it, n = ⌈D / stride⌉; the stride then shrinks to D / n
/// (gait.stroke scaled by the same factor, never lengthened), so that the trunk travels
/// exactly D whatever the duty factor and speed. Returns n and adapts g.stroke_m; the resolved
/// scene records the stroke used, and the stroke asked beside it (auto.gait.stroke).
int read_travel(Reader& r, GaitParams& g, const TerrainParams& t, double stride_along_slope) {
  const YAML::Node travel = r.node("motion.travel");
  if (!travel.IsMap())
    r.fail_value("motion.travel", travel, "a map {distance: D} (m) or {treads: N}");
  for (const auto& kv : travel)
    if (kv.first.Scalar() != "distance" && kv.first.Scalar() != "treads")
      r.fail_unknown("motion.travel." + kv.first.Scalar(), {"distance", "treads"});
  const bool by_distance = travel["distance"].IsDefined() && !travel["distance"].IsNull();
  const bool by_treads = travel["treads"].IsDefined() && !travel["treads"].IsNull();
  if (by_distance == by_treads)
    r.fail_value("motion.travel", travel,
                 "exactly one of distance (m along the slope) and treads (a number of treads)");
  const double cos_slope = std::cos(mean_slope_rad(t));
  double distance = 0.0;
  if (by_distance) {
    distance = number_key(r, "motion.travel.distance");
  } else {
    const int treads = integer_key(r, "motion.travel.treads");
    check_treads_on_stairs(r, treads, t);
    // One tread: b_s across, h_s up; on a list of steps its mean going.
    double going = t.tread_depth_m;
    if (!t.step_list.empty()) {
      going = 0.0;
      for (const StairStep& s : t.step_list) going += s.tread_m / t.step_list.size();
    }
    distance = treads * going / cos_slope;
  }
  const double ratio = distance / stride_along_slope;
  const double n = std::max(1.0, std::ceil(ratio - 1e-9));
  if (n > kMaxCycles)
    r.fail("motion.travel", "got " + fmt(distance) + " m, " + fmt(n) +
                                " cycles of gait.stroke, expected at most " +
                                std::to_string(kMaxCycles) + " cycles");
  // Strides that cover D to 1e-9 keep the stroke as given (the paper's 3 treads: 3 cycles).
  if (std::abs(n - ratio) > 1e-9 * n) {
    const double stroke = (distance / n) * cos_slope * g.duty_factor;
    r.record("auto.gait.stroke", YAML::Node(g.stroke_m));
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", stroke);
    r.record("gait.stroke", YAML::Node(std::string(text)));
    g.stroke_m = stroke;
  }
  return static_cast<int>(n);
}

}  // namespace

void read_motion(Reader& r, GaitParams& g, const TerrainParams& t, MotionParams& m) {
  read_posture(r, m);
  m.trunk =
      choice_key(r, "motion.trunk") == "balanced" ? TrunkPath::kBalanced : TrunkPath::kStraight;
  m.balance_margin_m = number_key(r, "motion.balance_margin");
  // Stride: trunk travel per gait cycle along the slope (s0/β horizontally).
  const double stride_along_slope = (g.stroke_m / g.duty_factor) / std::cos(mean_slope_rad(t));
  const bool by_durations = r.has("motion.cycle_durations");
  const bool by_travel = r.given("motion.travel");
  const bool by_speed = r.has("motion.peak_speed") || r.has("motion.cycles") ||
                        r.has("motion.ramp_duration") || by_travel;
  check_timing_form(r, by_durations, by_speed, by_travel);
  if (by_durations) {
    m.cycle_durations_s = numbers_key(r, "motion.cycle_durations");
    const auto& d = m.cycle_durations_s;
    check_cycle_durations(r, d);
    m.cycles = static_cast<int>(d.size());
    m.peak_speed_mps = stride_along_slope / d[1];
    m.ramp_duration_s = 2.0 * (d.front() - d[1]);
    return;
  }
  m.cycles = by_travel ? read_travel(r, g, t, stride_along_slope) : integer_key(r, "motion.cycles");
  m.peak_speed_mps = number_key(r, "motion.peak_speed");
  m.ramp_duration_s = number_key(r, "motion.ramp_duration");
  check_ramp(
      r, m,
      m.cycles * (g.stroke_m / g.duty_factor) / std::cos(mean_slope_rad(t)) / m.peak_speed_mps);
  m.cycle_durations_s.clear();
}

}  // namespace hexdyn::scene_keys
