#include "hexdyn/config/config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "hexdyn/config/actuators.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/plausibility.hpp"
#include "hexdyn/config/robot_config.hpp"
#include "hexdyn/config/run_limits.hpp"
#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/stance_keys.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/run_size.hpp"
#include "hexdyn/core/value_bounds.hpp"
#include "hexdyn/model/link_scaling.hpp"
#include "hexdyn/model/stance.hpp"

namespace hexdyn {
namespace {

using namespace scene_keys;

/// The value of every optional scene key that is absent: the field's initial value in
/// core/scene.hpp, read from a default-constructed Scene, the one table of defaults.
const Scene& defaults() {
  static const Scene d;
  return d;
}

/// The words of the defaults that are choices (robot.leg_inertia, contact.model, ...).
std::string word(LegInertia v) { return v == LegInertia::kMassless ? "massless" : "full"; }
std::string word(ContactModel v) { return v == ContactModel::kRigid ? "rigid" : "compliant"; }
std::string word(FrictionModel v) {
  return v == FrictionModel::kCone       ? "cone"
         : v == FrictionModel::kPyramid8 ? "pyramid8"
                                         : "pyramid4";
}
std::string word(OutputGrid v) { return v == OutputGrid::kUniform ? "uniform" : "adaptive"; }
std::string compression_word(bool compress) { return compress ? "deflate" : "none"; }

BodyParams read_body(Reader& r, const std::string& path, bool has_com_default,
                     const Vec3& com_default) {
  BodyParams b;
  b.mass_kg = r.number(path + ".mass", positive(kMaxBodyMass_kg));
  b.inertia_kgm2 = r.vec3(path + ".inertia", positive(kMaxPrincipalInertia_kgm2));
  const Vec3& I = b.inertia_kgm2;
  if (I.x() + I.y() < I.z() || I.y() + I.z() < I.x() || I.x() + I.z() < I.y()) {
    r.fail(path + ".inertia",
           "got [" + fmt(I.x()) + ", " + fmt(I.y()) + ", " + fmt(I.z()) +
               "], expected principal moments with each at most the sum of the other two");
  }
  b.com_m = r.vec3(path + ".com", closed(-kMaxRobotCoordinate_m, kMaxRobotCoordinate_m),
                   has_com_default ? &com_default : nullptr);
  return b;
}

/// robot.foot_offset of legs L1 … L6 (config/robot_config.hpp): one [x, y, z] for every leg,
/// six in leg order, or a map by leg name with every leg.
std::array<Vec3, kLegs> read_foot_offsets(Reader& r) {
  const std::string key = "robot.foot_offset";
  const Range range = closed(-kMaxRobotCoordinate_m, kMaxRobotCoordinate_m);
  const YAML::Node node = r.peek(key);
  std::array<Vec3, kLegs> out;
  if (node.IsMap()) {  // every leg by name
    for (const auto& kv : node) {
      const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "?";
      if (name.size() != 2 || name[0] != 'L' || name[1] < '1' || name[1] > '6')
        r.fail(key + "." + name, "unknown leg, allowed here: L1, L2, L3, L4, L5, L6");
    }
    for (int leg = 0; leg < kLegs; ++leg) out[leg] = r.vec3(key + "." + leg_name(leg), range);
    return out;
  }
  const std::string expected =
      "[x, y, z], six [x, y, z] in the order L1 … L6 of /model/leg_names, or a map {L1: [x, y, "
      "z], …, L6: [x, y, z]}, each coordinate " +
      range.describe() + " m";
  r.refuse_quoted_numbers(key, node, range.describe() + " m");
  if (!node.IsSequence() || node.size() == 0) r.fail_value(key, node, expected);
  if (!node[0].IsSequence()) {  // one point for every leg
    if (node.size() != 3) r.fail_value(key, node, expected);
    out.fill(r.vec3(key, range));
    return out;
  }
  r.node(key);  // asked for: read below
  if (node.size() != kLegs) r.fail_value(key, node, expected);
  YAML::Node resolved(YAML::NodeType::Sequence);
  for (int leg = 0; leg < kLegs; ++leg) {
    const YAML::Node p = node[leg];
    double v[3] = {0.0, 0.0, 0.0};
    bool ok = p.IsSequence() && p.size() == 3;
    for (std::size_t i = 0; ok && i < 3; ++i)
      ok = p[i].IsScalar() && YAML::convert<double>::decode(p[i], v[i]) && std::isfinite(v[i]) &&
           range.contains(v[i]);
    if (!ok) r.fail_value(key, node, expected + " (" + leg_name(leg) + " is not)");
    out[leg] = Vec3(v[0], v[1], v[2]);
    YAML::Node xyz(YAML::NodeType::Sequence);
    for (double x : v) xyz.push_back(x);
    xyz.SetStyle(YAML::EmitterStyle::Flow);
    resolved.push_back(xyz);
  }
  r.record(key, resolved);
  return out;
}

/// robot: {urdf: ...}: the robot read from its URDF (config/robot_config.hpp). Returns the
/// nominal stance radius, gait.foot_lateral's default [m].
double read_urdf_robot_keys(Reader& r, RobotParams& p, LoadedUrdfRobot& loaded) {
  UrdfRobotKeys k;
  k.path = r.string_or("robot.urdf", "");
  if (k.path.empty()) r.fail("robot.urdf", "got an empty path, expected the path of a URDF file");
  if (const auto why = why_not_input_file(k.path))
    r.fail("robot.urdf", "got " + k.path + ", which " + *why +
                             ", expected a URDF file (relative to the scene file)");
  k.trunk_link = r.string_or("robot.trunk_link", "");
  const std::string def_axis = "+x";
  k.forward_axis = r.choice("robot.forward_axis", {"+x", "-x", "+y", "-y"}, &def_axis);
  k.foot_links = r.strings_or_none("robot.foot_links", kLegs);
  if (r.has("robot.foot_offset")) k.foot_offset_m = read_foot_offsets(r);
  if (r.has("robot.foot_radius"))
    k.foot_radius_m = r.number("robot.foot_radius", closed(0.0, kMaxFootRadius_m));
  k.nominal_pose_rad = read_nominal_pose(r);
  k.ik_min_margin_m = p.ik_min_margin_m =
      r.number_or("robot.ik_min_margin", defaults().robot.ik_min_margin_m, nonnegative(0.1));
  loaded = load_urdf_robot(k);
  p.urdf = loaded.robot;
  check_nominal_pose(r, k.nominal_pose_rad, *loaded.robot);
  p.stance = loaded.stance;
  record_stance(r, loaded.stance);
  if (!(loaded.stance_radius_m > 0.0))
    r.fail("robot.nominal_pose",
           "puts the feet on the coxa axes (stance radius " + fmt(loaded.stance_radius_m) +
               " m), expected a pose with the feet outward; or give gait.foot_lateral");
  return loaded.stance_radius_m;
}

void read_robot(Reader& r, RobotParams& p, LoadedUrdfRobot& loaded) {
  if (r.has("robot.urdf")) {
    read_urdf_robot_keys(r, p, loaded);
    return;
  }
  p.trunk = read_body(r, "robot.trunk", true, Vec3::Zero());
  p.payload = read_body(r, "robot.payload", true, Vec3::Zero());
  // How each link's mass, COM and inertia follow its length (model/link_scaling.hpp): with
  // uniform_density they are stated for robot.<link>.reference_length (required) and
  // stretched to robot.<link>.length; the COM's default is the reference's mid-length.
  const std::string def_rule = "none";
  const bool follow =
      r.choice("robot.links_follow_length", {"none", "uniform_density"}, &def_rule) != "none";
  const char* names[kJointsPerLeg] = {"coxa", "femur", "tibia"};
  for (int j = 0; j < kJointsPerLeg; ++j) {
    const std::string base = std::string("robot.") + names[j];
    p.link_length_m[j] = r.number(base + ".length", positive(kMaxRobotCoordinate_m));
    p.joint_offset_m[j] = r.number(base + ".offset", nonnegative(1.0));
    const std::string ref_key = base + ".reference_length";
    if (follow && !r.given(ref_key))
      r.fail(ref_key, "missing, expected the length (0, 10] m that " + base +
                          ".mass, .inertia and .com are stated for (robot.links_follow_length is "
                          "uniform_density)");
    const double ref_length =
        r.has(ref_key) ? r.number(ref_key, positive(10.0)) : p.link_length_m[j];
    p.link[j] =
        read_body(r, base, true, Vec3(0.5 * (follow ? ref_length : p.link_length_m[j]), 0.0, 0.0));
    if (follow) p.link[j] = stretch_link(p.link[j], p.link_length_m[j] / ref_length);
    const auto lim = r.numbers(base + ".limits", 2, 2, closed(-M_PI, M_PI));
    if (lim[0] >= lim[1])
      r.fail(base + ".limits", "got [" + fmt(lim[0]) + ", " + fmt(lim[1]) +
                                   "], expected [lower, upper] with lower < upper");
    p.joint_min_rad[j] = lim[0];
    p.joint_max_rad[j] = lim[1];
  }
  const double hip_x = r.number("robot.hips.x", positive(5.0));
  const auto hip_y = r.numbers("robot.hips.y", 3, 3, closed(-5.0, 5.0));
  if (!(hip_y[0] > hip_y[1] && hip_y[1] > hip_y[2]))
    r.fail("robot.hips.y", "got [" + fmt(hip_y[0]) + ", " + fmt(hip_y[1]) + ", " + fmt(hip_y[2]) +
                               "], expected [front, middle, rear] decreasing");
  const double hip_z = r.number_or("robot.hips.z", 0.0, closed(-5.0, 5.0));
  const std::vector<double> zero3{0.0, 0.0, 0.0};
  const auto yaw = r.numbers("robot.hips.yaw", 3, 3, {-M_PI / 2, M_PI / 2, true, true}, &zero3);
  for (int leg = 0; leg < kLegs; ++leg) {
    const int row = leg / 2;  // 0 front, 1 middle, 2 rear
    const bool left = is_left(leg);
    p.hip_position_m[leg] = Vec3(left ? -hip_x : hip_x, hip_y[row], hip_z);
    // Yaw offsets are given for the right legs (positive turns the leg forward);
    // left legs mirror them.
    p.hip_yaw_rad[leg] = left ? M_PI - yaw[row] : yaw[row];
  }
  p.ik_min_margin_m =
      r.number_or("robot.ik_min_margin", defaults().robot.ik_min_margin_m, nonnegative(0.1));
  p.foot_radius_m = r.number_or("robot.foot_radius", defaults().robot.foot_radius_m,
                                closed(0.0, kMaxFootRadius_m));
  const std::string def_legs = word(defaults().robot.leg_inertia);
  p.leg_inertia = r.choice("robot.leg_inertia", {"full", "massless"}, &def_legs) == "massless"
                      ? LegInertia::kMassless
                      : LegInertia::kFull;
}

void read_terrain(Reader& r, TerrainParams& t) {
  const std::string type = r.choice("terrain.type", {"stairs", "flat", "slope"});
  if (type == "flat") {
    t.type = TerrainType::kFlat;
    t.ground_height_m =
        r.number_or("terrain.height", defaults().terrain.ground_height_m, closed(-100.0, 100.0));
  } else if (type == "slope") {
    t.type = TerrainType::kSlope;
    t.slope_rad = r.number("terrain.angle", {-M_PI / 3, M_PI / 3, true, true});
    t.slope_origin_y_m =
        r.number_or("terrain.origin_y", defaults().terrain.slope_origin_y_m, closed(-100.0, 100.0));
    t.ground_height_m = r.number_or("terrain.ground_height", defaults().terrain.ground_height_m,
                                    closed(-100.0, 100.0));
  } else {
    t.type = TerrainType::kStairs;
    t.riser_height_m = r.number("terrain.riser_height", nonnegative(1.0));
    t.tread_depth_m = r.number("terrain.tread_depth", positive(10.0));
    t.steps = r.integer("terrain.steps", 1, 100000);
    t.first_riser_y_m = r.number("terrain.first_riser_y", closed(-100.0, 100.0));
    t.ground_height_m = r.number_or("terrain.ground_height", defaults().terrain.ground_height_m,
                                    closed(-100.0, 100.0));
  }
}

void read_gait(Reader& r, GaitParams& g, const LoadedUrdfRobot& urdf) {
  g.duty_factor = r.number("gait.duty_factor", {0.5, 1.0, false, true});
  g.stroke_m = r.number("gait.stroke", positive(2.0));
  // A URDF robot's footholds default to its nominal stance radius (config/robot_config.hpp),
  // an automatic choice the resolved configuration records beside the value.
  if (urdf.robot && !r.given("gait.foot_lateral")) r.record("auto.gait.foot_lateral", "auto");
  g.foot_lateral_m = urdf.robot
                         ? r.number_or("gait.foot_lateral", urdf.stance_radius_m, positive(2.0))
                         : r.number("gait.foot_lateral", positive(2.0));
  g.foothold_margin_m =
      r.number_or("gait.foothold_margin", defaults().gait.foothold_margin_m, nonnegative(1.0));
  g.swing_clearance_m = r.number("gait.swing_clearance", positive(1.0));
  g.touchdown_speed_mps = r.number("gait.touchdown_speed", nonnegative(10.0));
  g.lift_fraction =
      r.number_or("gait.lift_fraction", defaults().gait.lift_fraction, {0.0, 1.0, true, true});
  g.lower_fraction =
      r.number_or("gait.lower_fraction", defaults().gait.lower_fraction, {0.0, 1.0, true, true});
  if (g.lift_fraction + g.lower_fraction >= 0.95)
    r.fail("gait.lower_fraction",
           "got " + fmt(g.lower_fraction) + " with gait.lift_fraction " + fmt(g.lift_fraction) +
               ", expected a sum below 0.95 (time must remain to move forward)");
}

/// The trunk's start: motion.initial_position (absolute) or motion.posture (relative to the
/// terrain, or auto). The definitions are those of planning/posture.hpp.
void read_posture(Reader& r, MotionParams& m) {
  const bool absolute = r.has("motion.initial_position");
  const bool relative = r.given("motion.posture");
  if (!relative) (void)r.has("motion.posture");  // a null posture counts as absent
  if (absolute && relative)
    r.fail("motion",
           "got both initial_position and posture, expected one of the two (an absolute start or "
           "one relative to the terrain)");
  PostureParams& p = m.posture;
  if (!relative) {
    if (!absolute)
      r.fail("motion.posture",
             "missing, expected motion.posture {height, start_y} (relative to the terrain) or "
             "motion.initial_position");
    p.mode = PostureMode::kAbsolute;
    m.initial_position_m = r.vec3("motion.initial_position", closed(-100.0, 100.0));
    return;
  }
  p.start_y_m = r.number("motion.posture.start_y", closed(-100.0, 100.0));
  if (!r.holds_word("motion.posture.height", "auto")) {
    p.mode = PostureMode::kRelative;
    p.height_m = r.number("motion.posture.height", closed(-100.0, 100.0));
    return;
  }
  p.mode = PostureMode::kAuto;
  // Search range of the height; [0, 0] lets planning derive it from the legs' reach.
  const std::vector<double> no_range{0.0, 0.0};
  const auto h = r.numbers("motion.posture.height_range", 2, 2, closed(-10.0, 10.0), &no_range);
  if (h != no_range && !(h[0] < h[1]))
    r.fail("motion.posture.height_range",
           "got " + yaml_inline(YAML::Node(h)) + ", expected [lower, upper] with lower < upper");
  p.height_min_m = h[0];
  p.height_max_m = h[1];
  p.target_margin_m = r.number_or("motion.posture.target_margin",
                                  defaults().motion.posture.target_margin_m, nonnegative(1.0));
  p.trunk_clearance_m =
      r.number_or("motion.posture.trunk_clearance", defaults().motion.posture.trunk_clearance_m,
                  closed(-1.0, 10.0));
  p.vary_foot_lateral = r.given("motion.posture.foot_lateral");
  if (p.vary_foot_lateral) {
    const auto w = r.numbers("motion.posture.foot_lateral", 2, 2, positive(2.0));
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
/// (docs/user/configuration.md#travel-instead-of-cycles). The cycles are the fewest whose strides
/// of the given stroke cover it, n = ⌈D / stride⌉; the stride then shrinks to D / n (gait.stroke
/// scaled by the same factor, never lengthened), so that the trunk travels exactly D
/// whatever the duty factor and speed. Returns n and adapts g.stroke_m; the resolved scene
/// records the stroke used, and the stroke asked beside it (auto.gait.stroke).
int read_travel(Reader& r, GaitParams& g, const TerrainParams& t, double stride_along_slope) {
  const YAML::Node travel = r.node("motion.travel");
  if (!travel.IsMap())
    r.fail_value("motion.travel", travel, "a map {distance: D} (m) or {treads: N}");
  for (const auto& kv : travel)
    if (kv.first.Scalar() != "distance" && kv.first.Scalar() != "treads")
      r.fail("motion.travel." + kv.first.Scalar(), "unknown key, allowed here: distance, treads");
  const bool by_distance = travel["distance"].IsDefined() && !travel["distance"].IsNull();
  const bool by_treads = travel["treads"].IsDefined() && !travel["treads"].IsNull();
  if (by_distance == by_treads)
    r.fail_value("motion.travel", travel,
                 "exactly one of distance (m along the slope) and treads (a number of treads)");
  const double cos_slope = std::cos(mean_slope_rad(t));
  double distance = 0.0;
  if (by_distance) {
    distance = r.number("motion.travel.distance", positive(1e4));
  } else {
    const int treads = r.integer("motion.travel.treads", 1, 100000);
    if (t.type != TerrainType::kStairs)
      r.fail("motion.travel.treads",
             "got " + std::to_string(treads) +
                 " on terrain without treads, expected terrain.type stairs (or give "
                 "motion.travel.distance)");
    distance = treads * t.tread_depth_m / cos_slope;  // one tread: b_s across, h_s up
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

void read_motion(Reader& r, GaitParams& g, const TerrainParams& t, MotionParams& m) {
  read_posture(r, m);
  // Stride: trunk travel per gait cycle along the slope (s0/β horizontally).
  const double stride_along_slope = (g.stroke_m / g.duty_factor) / std::cos(mean_slope_rad(t));
  const bool by_durations = r.has("motion.cycle_durations");
  const bool by_travel = r.given("motion.travel");
  const bool by_speed = r.has("motion.peak_speed") || r.has("motion.cycles") ||
                        r.has("motion.ramp_duration") || by_travel;
  if (by_durations && by_speed)
    r.fail("motion",
           "got both cycle_durations and peak_speed/cycles/ramp_duration/travel, expected one of "
           "the two forms");
  if (by_travel && r.has("motion.cycles"))
    r.fail("motion.travel", "got " + yaml_inline(r.node("motion.travel")) + " and motion.cycles " +
                                yaml_inline(r.node("motion.cycles")) +
                                ", expected one of them (travel sets the number of cycles; "
                                "motion.cycles: null removes an inherited one)");
  if (by_durations) {
    m.cycle_durations_s = r.numbers("motion.cycle_durations", 3, kMaxCycles, positive(1e4));
    const auto& d = m.cycle_durations_s;
    const double first = d.front(), mid = d[1];
    bool ok = std::abs(d.back() - first) < 1e-9 && first > mid;
    for (std::size_t i = 1; i + 1 < d.size(); ++i) ok = ok && std::abs(d[i] - mid) < 1e-9;
    if (!ok)
      r.fail("motion.cycle_durations",
             "got " + yaml_for_message(YAML::Node(d)) +
                 ", expected [ramp-up, cruise..., ramp-down] with equal cruise cycles and equal "
                 "first and last cycles longer than the cruise ones");
    m.cycles = static_cast<int>(d.size());
    m.peak_speed_mps = stride_along_slope / mid;
    m.ramp_duration_s = 2.0 * (first - mid);
    if (m.ramp_duration_s > first)
      r.fail("motion.cycle_durations", "got " + yaml_for_message(YAML::Node(d)) +
                                           ", expected a first cycle at most twice the cruise "
                                           "cycle (the speed ramp must end inside it)");
  } else {
    m.cycles = by_travel ? read_travel(r, g, t, stride_along_slope)
                         : r.integer("motion.cycles", 1, kMaxCycles);
    m.peak_speed_mps = r.number("motion.peak_speed", positive(10.0));
    m.ramp_duration_s = r.number("motion.ramp_duration", positive(1e4));
    const double cruise_time =
        m.cycles * (g.stroke_m / g.duty_factor) / std::cos(mean_slope_rad(t)) / m.peak_speed_mps;
    if (m.ramp_duration_s > cruise_time)
      r.fail("motion.ramp_duration",
             "got " + fmt(m.ramp_duration_s) + ", expected at most " + fmt(cruise_time) +
                 " s (the ramps at start and end must not overlap at this speed)");
    m.cycle_durations_s.clear();
  }
}

void read_contact(Reader& r, ContactParams& c) {
  const std::string def_model = word(defaults().contact.model);
  c.model = r.choice("contact.model", {"compliant", "rigid"}, &def_model) == "rigid"
                ? ContactModel::kRigid
                : ContactModel::kCompliant;
  c.stiffness = r.number("contact.stiffness", positive(1e15));
  c.exponent = r.number("contact.exponent", closed(1.0, 5.0));
  c.damping_max_Nspm = r.number("contact.damping_max", nonnegative(1e12));
  c.full_damping_depth_m = r.number("contact.full_damping_depth", positive(1.0));
  c.friction_coefficient = r.number("contact.friction_coefficient", positive(10.0));
  c.static_friction =
      r.number_or("contact.static_friction", c.friction_coefficient, positive(10.0));
  c.dynamic_friction =
      r.number_or("contact.dynamic_friction", c.static_friction, closed(0.0, c.static_friction));
  c.stiction_velocity_mps = r.number_or("contact.stiction_velocity",
                                        defaults().contact.stiction_velocity_mps, positive(10.0));
  c.friction_velocity_mps = r.number_or(
      "contact.friction_velocity",
      std::max(defaults().contact.friction_velocity_mps, 10.0 * c.stiction_velocity_mps),
      positive(100.0));
  if (!(c.friction_velocity_mps > c.stiction_velocity_mps))
    r.fail("contact.friction_velocity", "got " + fmt(c.friction_velocity_mps) +
                                            ", expected more than contact.stiction_velocity (" +
                                            fmt(c.stiction_velocity_mps) + " m/s)");
}

void read_replay(Reader& r, ReplayParams& p) {
  const ReplayParams d;
  p.kp_Nmprad = r.number_or("replay.kp", d.kp_Nmprad, nonnegative(1e9));
  p.kd_Nmsprad = r.number_or("replay.kd", d.kd_Nmsprad, nonnegative(1e9));
  p.step_s = r.number_or("replay.step", d.step_s, positive(0.1));
  p.tolerance = r.number_or("replay.tolerance", d.tolerance, positive(10.0));
}

void read_allocation(Reader& r, AllocationParams& a, const LoadedUrdfRobot& urdf) {
  const std::string def_friction = word(defaults().allocation.friction);
  const std::string friction =
      r.choice("allocation.friction", {"pyramid4", "pyramid8", "cone"}, &def_friction);
  a.friction = friction == "cone"       ? FrictionModel::kCone
               : friction == "pyramid8" ? FrictionModel::kPyramid8
                                        : FrictionModel::kPyramid4;
  // auto = active-set: the dual active-set QP for the pyramids, and for the exact cone the
  // same QP under sequential outer approximation (allocation/cone.hpp); ipopt: the NLP
  // reference for every friction model.
  const std::string def_solver = "auto";
  const std::string solver =
      r.choice("allocation.solver", {"auto", "active-set", "ipopt"}, &def_solver);
  a.solver = solver == "ipopt" ? AllocationSolver::kIpopt : AllocationSolver::kActiveSet;
  if (solver == "auto") {  // resolved as the back end used, the request beside it
    r.record("allocation.solver", "active-set");
    r.record("auto.allocation.solver", "auto");
  }
  // A URDF robot: its effort limits per joint unless the scene gives one limit for all
  // (allocation.torque_limit: effort names the default).
  if (urdf.robot && r.absent_or_word("allocation.torque_limit", "effort")) {
    a.joint_torque_limit_Nm = urdf.effort_limit_Nm;
    a.torque_limit_Nm = 0.0;
    for (double e : urdf.effort_limit_Nm) a.torque_limit_Nm = std::max(a.torque_limit_Nm, e);
  } else {
    a.torque_limit_Nm = r.number("allocation.torque_limit", positive(kMaxJointEffort_Nm));
  }
  a.min_normal_force_N = r.number_or("allocation.min_normal_force",
                                     defaults().allocation.min_normal_force_N, nonnegative(1e6));
  // The loosest tolerance at which both back ends still meet the fixed violation threshold
  // (allocation/qp.hpp kViolationThreshold) on the paper scene: from 1e-9 to 1e-5 the
  // active-set and Ipopt runs flag the same 270 of 560 samples; at 1e-4 Ipopt flags 19 more,
  // at 1e-2 the active set 16 more (docs/theory/allocation.md#measured-violation-flags).
  constexpr double kLoosestTolerance = 1e-5;
  a.tolerance = r.number_or("allocation.tolerance", defaults().allocation.tolerance, positive());
  if (a.tolerance > kLoosestTolerance)
    r.fail("allocation.tolerance",
           "got " + fmt(a.tolerance) + ", expected a number in (0, " + fmt(kLoosestTolerance) +
               "]: looser solves miss the 1e-6 N / N m violation threshold, so samples would be "
               "flagged for the solver's inaccuracy rather than for physics");
  a.slack_penalty =
      r.number_or("allocation.slack_penalty", defaults().allocation.slack_penalty, positive(1e12));
  // Last, where read_drive_train records it when only actuators give it: a resolved
  // configuration read again resolves to the same text.
  if (r.given("allocation.objective")) {
    const std::string objective =
        r.choice("allocation.objective", {"torque_squared", "copper_loss"});
    a.objective = objective == "copper_loss" ? AllocationObjective::kCopperLoss
                                             : AllocationObjective::kTorqueSquared;
  }
}

/// actuators: (config/actuators.hpp) with the robot's joint names and URDF friction, and
/// allocation.objective's dependence on it: copper_loss needs actuators; with them, the
/// objective is recorded in the resolved configuration.
void read_drive_train(Reader& r, Scene& s, const LoadedUrdfRobot& urdf) {
  JointFacts joints;
  if (urdf.robot) {
    joints.names = urdf.joint_names;
    joints.damping_Nmsprad = urdf.damping_Nmsprad;
    joints.friction_Nm = urdf.friction_Nm;
  } else {
    for (int l = 0; l < kLegs; ++l)
      for (int j = 0; j < kJointsPerLeg; ++j) joints.names[joint_index(l, j)] = joint_name(l, j);
  }
  s.actuators = read_actuators(r, joints);
  if (s.actuators.present)
    r.record("allocation.objective", YAML::Node(objective_word(s.allocation.objective)));
  else if (s.allocation.objective == AllocationObjective::kCopperLoss)
    r.fail("allocation.objective",
           "got copper_loss, expected torque_squared: the copper loss needs an actuators section "
           "(docs/user/configuration.md#actuators)");
}

/// `auto:`: what a scene asked hexdyn to choose, as the resolved configuration of an
/// earlier run records it beside the values chosen
/// (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration). A record
/// only: carried into the resolved configuration unchanged, never read as a setting.
void read_auto_requests(Reader& r) {
  if (!r.has("auto")) return;
  const YAML::Node& requests = r.node("auto");
  if (!requests.IsMap())
    r.fail_value("auto", requests,
                 "a map of the keys hexdyn chose and what was asked (a resolved configuration's "
                 "record)");
  r.record("auto", YAML::Clone(requests));
}

void read_output(Reader& r, OutputParams& o) {
  o.sample_step_s = r.number("output.sample_step", positive(kMaxSampleStep_s));
  const std::string def_grid = word(defaults().output.grid);
  o.grid = r.choice("output.grid", {"uniform", "adaptive"}, &def_grid) == "uniform"
               ? OutputGrid::kUniform
               : OutputGrid::kAdaptive;
  const int def_samples = defaults().output.impact_samples;
  o.impact_samples = r.integer("output.impact_samples", 1, 100000, &def_samples);
  o.event_step_s =
      r.number_or("output.event_step", defaults().output.event_step_s, positive(100.0));
  o.tolerance = r.number_or("output.tolerance", defaults().output.tolerance, closed(0.0, 0.1));
  const std::string def_compression = compression_word(defaults().output.compress);
  o.compress = r.choice("output.compression", {"deflate", "none"}, &def_compression) == "deflate";
  const std::string def_required = defaults().output.required_friction ? "true" : "false";
  o.required_friction =
      r.choice("output.required_friction", {"true", "false"}, &def_required) == "true";
  if (o.event_step_s > o.sample_step_s)
    r.fail("output.event_step", "got " + fmt(o.event_step_s) +
                                    ", expected at most output.sample_step (" +
                                    fmt(o.sample_step_s) + ")");
}

/// `resolved` with its `auto:` record, if any, moved to the end (after the settings).
YAML::Node requests_last(YAML::Node resolved) {
  if (!resolved["auto"].IsDefined()) return resolved;
  const YAML::Node requests = YAML::Clone(resolved["auto"]);
  resolved.remove("auto");
  resolved["auto"] = requests;
  return resolved;
}

}  // namespace

std::vector<std::string> split_key_path(const std::string& path) {
  std::vector<std::string> keys;
  if (path.empty()) return keys;
  for (std::size_t begin = 0;;) {  // "a." names an empty key after a
    const std::size_t dot = path.find('.', begin);
    keys.push_back(path.substr(begin, dot == std::string::npos ? dot : dot - begin));
    if (dot == std::string::npos) return keys;
    begin = dot + 1;
  }
}

Override parse_override(const std::string& text) {
  // Bound for the result file's /meta, like a file's text (config/inputs.hpp).
  const std::size_t bad = first_non_utf8(text);
  if (bad != std::string::npos) require_utf8(text, "--set " + text.substr(0, bad) + "...");
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set " + text + ": expected key.path=value");
  // p/q as in sweep files: "--set gait.duty_factor=3/4".
  return {text.substr(0, eq), fraction_to_number_text(text.substr(eq + 1))};
}

void apply_override(YAML::Node& root, const Override& ov, const std::string& source_name) {
  const YAML::Node value = parse_yaml_checked(ov.value, "--set " + ov.key_path + "=" + ov.value);
  const auto keys = split_key_path(ov.key_path);
  for (const auto& k : keys)
    if (k.empty()) throw ConfigError("--set " + ov.key_path + ": empty key in the path");
  YAML::Node cur = root;
  std::string so_far;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    so_far += (so_far.empty() ? "" : ".") + keys[i];
    YAML::Node next = cur[keys[i]];
    if (!next.IsDefined() || next.IsNull()) {
      cur[keys[i]] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[keys[i]]);
    } else if (!next.IsMap()) {
      throw ConfigError(source_name + ": --set " + ov.key_path + ": " + so_far +
                        " is not a mapping");
    }
    cur.reset(next);
  }
  cur[keys.back()] = value;
}

Scene scene_from_yaml(const YAML::Node& root, const std::string& source_name, bool emit_resolved) {
  return scene_from_tree(SceneTree(root), source_name, emit_resolved);
}

Scene scene_from_tree(const SceneTree& tree, const std::string& source_name, bool emit_resolved) {
  Scene s;
  s.source_path = source_name;
  Reader r(tree, source_name, emit_resolved);
  s.name = r.string_or("name", defaults().name);
  read_auto_requests(r);
  LoadedUrdfRobot urdf;
  read_robot(r, s.robot, urdf);
  read_terrain(r, s.terrain);
  read_gait(r, s.gait, urdf);
  if (urdf.robot && !r.given("gait.foot_lateral"))  // the stance sets the footholds
    s.warnings = stance_fallback_warnings(urdf.stance);
  read_motion(r, s.gait, s.terrain, s.motion);
  read_contact(r, s.contact);
  read_replay(r, s.replay);
  read_allocation(r, s.allocation, urdf);
  read_drive_train(r, s, urdf);
  read_output(r, s.output);
  r.check_unknown();
  check_physical_plausibility(s, source_name);  // timings that no physical motion has
  // Before anything is planned or allocated: the motion's duration and output samples.
  check_run_size_limits(s, source_name,
                        !s.motion.cycle_durations_s.empty() ? "motion.cycle_durations"
                        : r.given("motion.travel")          ? "motion.travel"
                                                            : "motion.cycles");
  if (!emit_resolved) return s;
  YAML::Emitter out;
  out << requests_last(r.resolved());
  s.resolved_yaml = std::string(out.c_str()) + "\n";
  return s;
}

namespace {

/// A number as YAML text that reads back to the same double.
YAML::Node exact_number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return YAML::Node(std::string(buf));
}

/// `node[key]`, made a map when absent or not a map.
YAML::Node child_map(YAML::Node node, const std::string& key) {
  if (!node[key].IsMap()) node[key] = YAML::Node(YAML::NodeType::Map);
  return node[key];
}

}  // namespace

std::string with_chosen_posture(const std::string& resolved_yaml, double height_m,
                                double foot_lateral_m) {
  YAML::Node root = YAML::Load(resolved_yaml);
  YAML::Node posture = root["motion"]["posture"];
  if (!posture.IsMap()) return resolved_yaml;
  YAML::Node requests = child_map(child_map(child_map(root, "auto"), "motion"), "posture");
  for (const char* key :
       {"height", "height_range", "target_margin", "trunk_clearance", "foot_lateral"}) {
    if (!posture[key].IsDefined()) continue;
    requests[key] = YAML::Clone(posture[key]);
    posture.remove(key);
  }
  posture["height"] = exact_number(height_m);
  // gait.foot_lateral is a choice only when the search could vary it (a foot_lateral range).
  if (requests["foot_lateral"].IsDefined()) {
    YAML::Node gait = child_map(root, "gait");
    YAML::Node gait_requests = child_map(root["auto"], "gait");
    if (!gait_requests["foot_lateral"].IsDefined() && gait["foot_lateral"].IsDefined())
      gait_requests["foot_lateral"] = YAML::Clone(gait["foot_lateral"]);
    gait["foot_lateral"] = exact_number(foot_lateral_m);
  }
  YAML::Emitter out;
  out << requests_last(root);
  return std::string(out.c_str()) + "\n";
}

Scene load_scene_from_string(const std::string& yaml_text, const std::string& source_name,
                             const std::vector<Override>& overrides) {
  YAML::Node root = parse_yaml_text(yaml_text, source_name);
  for (const auto& ov : overrides) apply_override(root, ov, source_name);
  Scene s = scene_from_yaml(root, source_name);
  s.input_sha256 = input_sha256_text(scene_inputs({}, root));  // the URDF, if any
  return s;
}

Scene load_scene(const std::string& path, const std::vector<Override>& overrides,
                 std::vector<InputFile>* inputs) {
  // Each file read once: the digests are those of the bytes the scene was built from.
  const InputFreeze freeze;
  std::vector<std::string> files;
  YAML::Node root = load_scene_tree(path, &files);
  for (const auto& ov : overrides) apply_override(root, ov, path);
  std::vector<InputFile> read = scene_inputs(files, root);
  Scene s = scene_from_yaml(root, path);
  s.input_sha256 = input_sha256_text(read);
  if (inputs) *inputs = without_texts(std::move(read));
  return s;
}

}  // namespace hexdyn
