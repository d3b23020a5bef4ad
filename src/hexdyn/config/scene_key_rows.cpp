// The rows of the scene keys besides the robot's (scene_key_table.hpp): terrain, gait,
// motion, contact, replay, allocation and output (docs/user/configuration.md#keys-by-group).
#include "hexdyn/config/scene_key_rows.hpp"

#include <cmath>

#include "hexdyn/config/run_limits.hpp"
#include "hexdyn/core/run_size.hpp"
#include "hexdyn/core/value_bounds.hpp"

namespace hexdyn {

using namespace scene_keys;
namespace f = key_fields;

namespace {

/// A measured terrain: a grid of heights from a file.
void add_height_map_rows(std::deque<SceneKey>& t) {
  const SectionRows add{t, "terrain"};
  add({.path = "terrain.height_map.file",
       .kind = KeyKind::kText,
       .required = true,
       .allowed_text = "a `.npy` file (a 2-D float64 or float32 array) or an HDF5 file (`.h5`, "
                       "`.hdf5`), relative to the scene file",
       .when = "height_map",
       .meaning = "the heights: row i, column j at (origin x + j resolution, origin y + i "
                  "resolution), at most 4e7 of them, every one finite "
                  "([docs/theory/stages.md](docs/theory/stages.md#height-maps))"});
  add({.path = "terrain.height_map.dataset",
       .kind = KeyKind::kText,
       .default_text = "`elevation`",
       .allowed_text = "a dataset path in the HDF5 file",
       .when = "height_map",
       .meaning = "the 2-D dataset of heights in an HDF5 file (grid_map's layer name by default)"});
  add({.path = "terrain.height_map.resolution",
       .range = positive(10.0),
       .unit = "m",
       .required = true,
       .when = "height_map",
       .meaning = "spacing of the nodes along x and y"});
  add({.path = "terrain.height_map.origin",
       .kind = KeyKind::kNumbers,
       .range = closed(-1e4, 1e4),
       .min_count = 2,
       .max_count = 2,
       .unit = "m",
       .required = true,
       .when = "height_map",
       .meaning = "[x, y] of node (row 0, column 0) in G0"});
  add({.path = "terrain.height_map.edge_height",
       .range = positive(1.0),
       .unit = "m",
       .when = "height_map",
       .meaning = "a node whose neighbour is more than this above or below it is an edge: "
                  "footholds keep gait.foothold_margin from it",
       .field = f::number<&Scene::terrain, &TerrainParams::map_edge_height_m>()});
  add({.path = "terrain.height_map.max_slope",
       .range = open_interval(0.0, M_PI / 2),
       .unit = "rad",
       .when = "height_map",
       .meaning = "ground steeper than this takes no foothold either",
       .field = f::number<&Scene::terrain, &TerrainParams::map_max_slope_rad>()});
  add({.path = "terrain.height_map.slope",
       .range = open_interval(-M_PI / 3, M_PI / 3),
       .unit = "rad",
       .default_text = "the least-squares fit",
       .when = "height_map",
       .meaning = "inclination of the reference line the trunk follows; by default that of the "
                  "least-squares line through every node"});
}

/// The stairs' keys beyond the uniform ones: the nosing and the perturbations of a list.
void add_stairs_extra(std::deque<SceneKey>& t) {
  const SectionRows add{t, "terrain"};
  add({.path = "terrain.nosing",
       .range = nonnegative(10.0),
       .unit = "m",
       .when = "stairs",
       .meaning = "overhang of every tread's edge over the riser below, less than a tread; an "
                  "entry's `nosing` overrides it",
       .field = f::number<&Scene::terrain, &TerrainParams::nosing_m>()});
  add({.path = "terrain.riser_scale",
       .range = closed(0.0, 10.0),
       .unit = "1",
       .default_text = "1",
       .when = "stairs",
       .meaning = "factor on every riser (a sweep axis that scales a list of steps)"});
  add({.path = "terrain.step_offset.step",
       .kind = KeyKind::kInteger,
       .range = closed(0, 100000),
       .unit = "1",
       .default_text = "0",
       .when = "stairs",
       .meaning = "the step (from 1) whose riser terrain.step_offset.riser changes; 0 none"});
  add({.path = "terrain.step_offset.riser",
       .range = closed(-1.0, 1.0),
       .unit = "m",
       .default_text = "0",
       .when = "stairs",
       .meaning = "added to that step's riser (after riser_scale): one worn or odd step, a "
                  "sweep axis"});
}

void add_terrain(std::deque<SceneKey>& t) {
  const SectionRows add{t, "terrain"};
  add({.path = "terrain.type",
       .kind = KeyKind::kChoice,
       .choices = "stairs flat slope height_map",
       .required = true,
       .meaning = "which keys below apply"});
  add({.path = "terrain.riser_height",
       .range = closed(-1.0, 1.0),
       .unit = "m",
       .required = true,
       .when = "stairs",
       .meaning = "riser h_s: > 0 climbs along +y, < 0 descends, 0 is flat ground; with a "
                  "list of steps, the riser of an entry that gives none (then optional)"});
  add({.path = "terrain.tread_depth",
       .range = positive(10.0),
       .unit = "m",
       .required = true,
       .when = "stairs",
       .meaning = "tread b_s (the going, riser to riser); with a list of steps, the tread of an "
                  "entry that gives none (then optional)"});
  add({.path = "terrain.steps",
       .kind = KeyKind::kText,
       .unit = "1",
       .required = true,
       .allowed_text = "a count in [1, 100000], or a list of 1 to 100000 entries, each "
                       "`{riser: h, tread: b, nosing: n}` (h in [−1, 1] m, b in (0, 10] m, n in "
                       "[0, 10] m and less than the tread it overhangs) or `{landing: L}` (L in "
                       "(0, 100] m)",
       .when = "stairs",
       .meaning = "the risers: a count of uniform ones, or step by step (a landing is a flat "
                  "of length L); the last tread is endless "
                  "([docs/theory/stages.md](docs/theory/stages.md#terrain))"});
  add_stairs_extra(t);
  add({.path = "terrain.first_riser_y",
       .range = closed(-100.0, 100.0),
       .unit = "m",
       .required = true,
       .when = "stairs",
       .meaning = "y of the first riser"});
  add({.path = "terrain.ground_height",
       .range = closed(-100.0, 100.0),
       .unit = "m",
       .when = "stairs, slope",
       .meaning = "height before the first riser / the foot of the slope",
       .field = f::number<&Scene::terrain, &TerrainParams::ground_height_m>()});
  add({.path = "terrain.height",
       .range = closed(-100.0, 100.0),
       .unit = "m",
       .when = "flat",
       .meaning = "ground height",
       .field = f::number<&Scene::terrain, &TerrainParams::ground_height_m>()});
  add({.path = "terrain.angle",
       .range = open_interval(-M_PI / 3, M_PI / 3),
       .unit = "rad",
       .required = true,
       .when = "slope",
       .meaning = "inclination, rising along +y"});
  add({.path = "terrain.origin_y",
       .range = closed(-100.0, 100.0),
       .unit = "m",
       .when = "slope",
       .meaning = "y where the slope leaves the ground",
       .field = f::number<&Scene::terrain, &TerrainParams::slope_origin_y_m>()});
}

void add_gait(std::deque<SceneKey>& t) {
  const SectionRows add{t, "gait"};
  add({.path = "gait.duty_factor",
       .range = {0.5, 1.0, false, true},
       .unit = "1",
       .required = true,
       .meaning = "β, each leg's support fraction: ½ tripod, 2/3 tetrapod, 3/4 and 5/6 "
                  "wave gaits (any value in the range runs)",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::duty_factor>()});
  add({.path = "gait.stroke",
       .range = positive(2.0),
       .unit = "m",
       .required = true,
       .meaning = "s0, a foot's travel relative to the trunk per stance; the trunk "
                  "advances s0/β per cycle (`motion.travel` may shorten it, "
                  "[motion](#travel-instead-of-cycles))",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::stroke_m>()});
  add({.path = "gait.foot_lateral",
       .range = positive(2.0),
       .unit = "m",
       .required = true,
       .default_text = "required (URDF robot: the nominal stance radius)",
       .meaning = "horizontal distance of the footholds from the hips along each leg's "
                  "outward direction"});
  add({.path = "gait.foothold_margin",
       .range = nonnegative(1.0),
       .unit = "m",
       .meaning = "smallest distance of a foothold from every nosing and riser (a "
                  "sphere foot's: of the sphere, horizontally)",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::foothold_margin_m>()});
  add({.path = "gait.swing_clearance",
       .range = positive(1.0),
       .unit = "m",
       .required = true,
       .meaning = "Δh over the highest terrain under the swing path",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::swing_clearance_m>()});
  add({.path = "gait.touchdown_speed",
       .range = nonnegative(10.0),
       .unit = "m/s",
       .required = true,
       .meaning = "downward foot speed at touchdown (it drives the impact transient)",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::touchdown_speed_mps>()});
  add({.path = "gait.lift_fraction",
       .range = open_interval(0.0, 1.0),
       .unit = "1",
       .meaning = "share of the swing spent lifting",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::lift_fraction>()});
  add({.path = "gait.lower_fraction",
       .range = open_interval(0.0, 1.0),
       .unit = "1",
       .meaning = "share of the swing spent lowering (shortened if needed); "
                  "`lift_fraction + lower_fraction` < 0.95",
       .read = KeyRead::kTable,
       .field = f::number<&Scene::gait, &GaitParams::lower_fraction>()});
  add({.path = "gait.swing_profile",
       .kind = KeyKind::kChoice,
       .choices = "staged blended",
       .meaning = "`staged`: the foot lifts, moves across at the apex, then descends (the "
                  "paper); `blended`: it moves across over the whole swing while it lifts and "
                  "descends, with a fraction of the peak horizontal acceleration, for fast gaits; "
                  "a path that would not clear the terrain is an error "
                  "([docs/theory/stages.md](docs/theory/stages.md#swing-profiles))",
       .read = KeyRead::kTable,
       .field = f::choice<&Scene::gait, &GaitParams::swing_profile>()});
}

/// The gait's phases: the pattern, or the phases given (model/gait_pattern.hpp).
void add_gait_phases(std::deque<SceneKey>& t) {
  const SectionRows add{t, "gait"};
  add({.path = "gait.pattern",
       .kind = KeyKind::kChoice,
       .choices = "wave trot pace bound custom",
       .default_text = "`custom` with `gait.phases`, else `wave`",
       .meaning = "how the legs' lift-off phases follow from their sides and ranks: the wave "
                  "gait (the crawl on four legs), diagonal pairs, the sides, front against "
                  "rear, or `gait.phases`; a pattern the robot's legs do not fit is an error "
                  "([docs/theory/stages.md](docs/theory/stages.md#gait-patterns))"});
  add({.path = "gait.phases",
       .kind = KeyKind::kText,
       .default_text = "—",
       .allowed_text = "a map `{L1: φ1, …, Ln: φn}` naming each of the robot's n legs once, "
                       "each φ in [0, 1)",
       .meaning = "each leg's lift-off phase, the fraction of a cycle at which it lifts off "
                  "(it swings for 1 − β of a cycle), with `gait.pattern: custom` only; `-v` "
                  "prints the phases of every pattern "
                  "([docs/theory/stages.md](docs/theory/stages.md#gait-planning))"});
  t.push_back({.path = "gait.phases.*",
               .instances = "L1 L2 L3 L4 L5 L6 L7 L8",
               .range = {0.0, 1.0, false, true},
               .unit = "1",
               .required = true});
}

void add_motion_start(std::deque<SceneKey>& t) {
  const SectionRows add{t, "motion-start"};
  add({.path = "motion.initial_position",
       .kind = KeyKind::kNumbers,
       .range = closed(-100.0, 100.0),
       .min_count = 3,
       .max_count = 3,
       .unit = "m",
       .default_text = "—",
       .meaning = "P0, the trunk frame's origin, at t = 0 in the world frame"});
  add({.path = "motion.posture.start_y",
       .range = closed(-100.0, 100.0),
       .unit = "m",
       .required = true,
       .default_text = "required with `posture`",
       .meaning = "y of P0 at t = 0 from the terrain's origin (first riser; foot of a "
                  "slope; y = 0 on flat ground), negative before it"});
  add({.path = "motion.posture.height",
       .range = closed(-100.0, 100.0),
       .unit = "m",
       .required = true,
       .default_text = "required with `posture`",
       .allowed_text = "[−100, 100] m, or `auto`",
       .meaning = "height of P0 above the terrain's reference line, or chosen "
                  "automatically"});
  add({.path = "motion.posture.height_range",
       .kind = KeyKind::kNumbers,
       .range = closed(-10.0, 10.0),
       .min_count = 2,
       .max_count = 2,
       .unit = "m",
       .default_text = "derived from the legs' reach",
       .allowed_text = "`[lower, upper]` in [−10, 10] m, lower < upper",
       .meaning = "`auto` only: the heights searched"});
  add({.path = "motion.posture.target_margin",
       .range = nonnegative(1.0),
       .unit = "m",
       .meaning = "`auto` only: below this kinematic margin `gait.foot_lateral` is "
                  "searched too",
       .field =
           f::number<&Scene::motion, &MotionParams::posture, &PostureParams::target_margin_m>()});
  add({.path = "motion.posture.trunk_clearance",
       .range = closed(-1.0, 10.0),
       .unit = "m",
       .meaning = "`auto` only: the least vertical gap between the trunk and the highest "
                  "terrain under it",
       .field =
           f::number<&Scene::motion, &MotionParams::posture, &PostureParams::trunk_clearance_m>()});
  add({.path = "motion.posture.foot_lateral",
       .kind = KeyKind::kNumbers,
       .range = positive(2.0),
       .min_count = 2,
       .max_count = 2,
       .unit = "m",
       .default_text = "not searched",
       .allowed_text = "`[lower, upper]` in (0, 2] m, lower ≤ upper",
       .meaning = "`auto` only: the range `gait.foot_lateral` may be chosen from"});
}

void add_motion_timing(std::deque<SceneKey>& t) {
  const SectionRows add{t, "motion-timing"};
  add({.path = "motion.cycle_durations",
       .kind = KeyKind::kNumbers,
       .range = positive(1e4),
       .min_count = 3,
       .max_count = kMaxCycles,
       .unit = "s",
       .default_text = "—",
       .meaning = "`[ramp-up, cruise, ..., cruise, ramp-down]`: equal cruise cycles, "
                  "equal first and last cycles longer than a cruise cycle and at most "
                  "twice as long"});
  add({.path = "motion.peak_speed",
       .range = positive(10.0),
       .unit = "m/s",
       .required = true,
       .default_text = "required without `cycle_durations`",
       .meaning = "cruise speed of the trunk along the slope"});
  add({.path = "motion.cycles",
       .kind = KeyKind::kInteger,
       .range = closed(1, kMaxCycles),
       .unit = "1",
       .required = true,
       .default_text = "required without `cycle_durations` and `travel`",
       .meaning = "gait cycles; the trunk advances one stride s0/β per cycle"});
  add({.path = "motion.travel",
       .kind = KeyKind::kText,
       .default_text = "—",
       .allowed_text = "`{distance: D}` with D in (0, 1e4] m, or `{treads: N}` with N in "
                       "[1, 100000] (stairs only)",
       .meaning = "the trunk's travel along the slope instead of `cycles`: D, or N treads "
                  "(N b_s across and N h_s up, N √(b_s² + h_s²) along the slope; on a list "
                  "of steps b_s is its mean going and h_s/b_s its mean slope); the cycles follow "
                  "from it ([below](#travel-instead-of-cycles))"});
  t.push_back(
      {.path = "motion.travel.distance", .range = positive(1e4), .unit = "m", .required = true});
  t.push_back({.path = "motion.travel.treads",
               .kind = KeyKind::kInteger,
               .range = closed(1, 100000),
               .unit = "1",
               .required = true});
  add({.path = "motion.trunk",
       .kind = KeyKind::kChoice,
       .choices = "straight balanced",
       .meaning = "`straight`: the trunk moves along the mean slope at a constant height and "
                  "attitude (the paper); `balanced`: that path plus a horizontal offset that "
                  "keeps the whole robot's ZMP in the support of the stance feet, standing "
                  "still on all of them for 2 √(l / g) at each end, l the longest leg's reach "
                  "([docs/theory/balance.md](docs/theory/balance.md))",
       .field = f::choice<&Scene::motion, &MotionParams::trunk>()});
  add({.path = "motion.balance_margin",
       .range = nonnegative(1.0),
       .unit = "m",
       .when = "balanced",
       .meaning = "the balanced trunk's stability margin: the ZMP path's least distance "
                  "from the edges of the support, where the feet leave room for it",
       .field = f::number<&Scene::motion, &MotionParams::balance_margin_m>()});
  add({.path = "motion.ramp_duration",
       .range = positive(1e4),
       .unit = "s",
       .required = true,
       .default_text = "required without `cycle_durations`",
       .meaning = "C² speed ramps from rest at the start and to rest at the end; at most "
                  "the cruise time cycles·stride/peak_speed"});
}

}  // namespace

void add_terrain_gait_motion_rows(std::deque<SceneKey>& table) {
  add_terrain(table);
  add_height_map_rows(table);
  add_gait(table);
  add_gait_phases(table);
  add_motion_start(table);
  add_motion_timing(table);
}

}  // namespace hexdyn
