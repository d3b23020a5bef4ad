#include "hexdyn/config/key_rules.hpp"

#include <cmath>

#include "hexdyn/config/inputs.hpp"

namespace hexdyn::scene_keys {

void check_principal_moments(const Reader& r, const std::string& path, const Vec3& I) {
  if (I.x() + I.y() < I.z() || I.y() + I.z() < I.x() || I.x() + I.z() < I.y())
    r.fail(path, "got [" + fmt(I.x()) + ", " + fmt(I.y()) + ", " + fmt(I.z()) +
                     "], expected principal moments with each at most the sum of the other two");
}

void check_increasing(const Reader& r, const std::string& path, const std::vector<double>& v) {
  if (v[0] >= v[1])
    r.fail(path, "got [" + fmt(v[0]) + ", " + fmt(v[1]) +
                     "], expected [lower, upper] with lower < upper");
}

void check_hips_decreasing(const Reader& r, const std::vector<double>& y) {
  if (!(y[0] > y[1] && y[1] > y[2]))
    r.fail("robot.hips.y", "got [" + fmt(y[0]) + ", " + fmt(y[1]) + ", " + fmt(y[2]) +
                               "], expected [front, middle, rear] decreasing");
}

void check_cycle_durations(const Reader& r, const std::vector<double>& d) {
  const double first = d.front(), mid = d[1];
  bool ok = std::abs(d.back() - first) < 1e-9 && first > mid;
  for (std::size_t i = 1; i + 1 < d.size(); ++i) ok = ok && std::abs(d[i] - mid) < 1e-9;
  if (!ok)
    r.fail("motion.cycle_durations",
           "got " + yaml_for_message(YAML::Node(d)) +
               ", expected [ramp-up, cruise..., ramp-down] with equal cruise cycles and equal "
               "first and last cycles longer than the cruise ones");
  if (2.0 * (first - mid) > first)
    r.fail("motion.cycle_durations", "got " + yaml_for_message(YAML::Node(d)) +
                                         ", expected a first cycle at most twice the cruise "
                                         "cycle (the speed ramp must end inside it)");
}

void check_allocation_tolerance(const Reader& r, double tolerance) {
  // The loosest tolerance at which both back ends still meet the fixed violation threshold
  // (allocation/qp.hpp kViolationThreshold) on the paper scene: from 1e-9 to 1e-5 the
  // active-set and Ipopt runs flag the same 270 of 560 samples; at 1e-4 Ipopt flags 19 more,
  // at 1e-2 the active set 16 more (docs/theory/allocation.md#measured-violation-flags).
  constexpr double kLoosestTolerance = 1e-5;
  if (tolerance > kLoosestTolerance)
    r.fail("allocation.tolerance",
           "got " + fmt(tolerance) + ", expected a number in (0, " + fmt(kLoosestTolerance) +
               "]: looser solves miss the 1e-6 N / N m violation threshold, so samples would be "
               "flagged for the solver's inaccuracy rather than for physics");
}

void check_urdf_path(const Reader& r, const std::string& path) {
  if (path.empty()) r.fail("robot.urdf", "got an empty path, expected the path of a URDF file");
  if (const auto why = why_not_input_file(path))
    r.fail("robot.urdf", "got " + path + ", which " + *why +
                             ", expected a URDF file (relative to the scene file)");
}

void check_stance_radius(const Reader& r, double radius_m) {
  if (!(radius_m > 0.0))
    r.fail("robot.nominal_pose",
           "puts the feet on the coxa axes (stance radius " + fmt(radius_m) +
               " m), expected a pose with the feet outward; or give gait.foot_lateral");
}

void check_reference_length_given(const Reader& r, const std::string& link, bool follow) {
  const std::string key = link + ".reference_length";
  if (follow && !r.given(key))
    r.fail(key, "missing, expected the length (0, 10] m that " + link +
                    ".mass, .inertia and .com are stated for (robot.links_follow_length is "
                    "uniform_density)");
}

void check_swing_fractions(const Reader& r, const GaitParams& g) {
  if (g.lift_fraction + g.lower_fraction >= 0.95)
    r.fail("gait.lower_fraction",
           "got " + fmt(g.lower_fraction) + " with gait.lift_fraction " + fmt(g.lift_fraction) +
               ", expected a sum below 0.95 (time must remain to move forward)");
}

void check_start_form(const Reader& r, bool absolute, bool relative) {
  if (absolute && relative)
    r.fail("motion",
           "got both initial_position and posture, expected one of the two (an absolute start or "
           "one relative to the terrain)");
  if (!absolute && !relative)
    r.fail("motion.posture",
           "missing, expected motion.posture {height, start_y} (relative to the terrain) or "
           "motion.initial_position");
}

void check_timing_form(Reader& r, bool by_durations, bool by_speed, bool by_travel) {
  if (by_durations && by_speed)
    r.fail("motion",
           "got both cycle_durations and peak_speed/cycles/ramp_duration/travel, expected one of "
           "the two forms");
  if (by_travel && r.has("motion.cycles"))
    r.fail("motion.travel", "got " + yaml_inline(r.node("motion.travel")) + " and motion.cycles " +
                                yaml_inline(r.node("motion.cycles")) +
                                ", expected one of them (travel sets the number of cycles; "
                                "motion.cycles: null removes an inherited one)");
}

void check_treads_on_stairs(const Reader& r, int treads, const TerrainParams& t) {
  if (t.type != TerrainType::kStairs)
    r.fail("motion.travel.treads",
           "got " + std::to_string(treads) +
               " on terrain without treads, expected terrain.type stairs (or give "
               "motion.travel.distance)");
}

void check_ramp(const Reader& r, const MotionParams& m, double cruise_time_s) {
  if (m.ramp_duration_s > cruise_time_s)
    r.fail("motion.ramp_duration",
           "got " + fmt(m.ramp_duration_s) + ", expected at most " + fmt(cruise_time_s) +
               " s (the ramps at start and end must not overlap at this speed)");
}

void check_friction_velocity(const Reader& r, const ContactParams& c) {
  if (!(c.friction_velocity_mps > c.stiction_velocity_mps))
    r.fail("contact.friction_velocity", "got " + fmt(c.friction_velocity_mps) +
                                            ", expected more than contact.stiction_velocity (" +
                                            fmt(c.stiction_velocity_mps) + " m/s)");
}

void check_copper_loss(const Reader& r, const Scene& s) {
  if (!s.robot.drive.present && s.allocation.objective == AllocationObjective::kCopperLoss)
    r.fail("allocation.objective",
           "got copper_loss, expected torque_squared: the copper loss needs an actuators section "
           "(docs/user/configuration.md#actuators)");
}

void check_event_step(const Reader& r, const OutputParams& o) {
  if (o.event_step_s > o.sample_step_s)
    r.fail("output.event_step", "got " + fmt(o.event_step_s) +
                                    ", expected at most output.sample_step (" +
                                    fmt(o.sample_step_s) + ")");
}

}  // namespace hexdyn::scene_keys
