// Defaults of the optional scene keys (config/config.cpp): a scene that gives only the keys a
// scene must give resolves every optional key to the initial value of its field in
// core/scene.hpp, the one table of defaults, read from a default-constructed Scene; and its
// resolved configuration, read back, spells those values out.
#include <catch2/catch.hpp>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {
namespace {

/// configs/paper.yaml with every optional key left out (no name, no ik_min_margin,
/// leg_inertia, ground_height, foothold_margin, lift and lower fractions, contact.model,
/// allocation.solver, friction, min_normal_force, tolerance, slack_penalty, and only
/// output.sample_step of the output keys).
std::string required_keys_only(const std::string& terrain, const std::string& start) {
  std::string robot =
      "robot:\n  trunk: {mass: 0.65, inertia: [1.66e-2, 2.52e-3, 1.69e-2], com: [0, 0, 0]}\n"
      "  payload: {mass: 4.244, inertia: [9.0e-3, 3.0e-3, 11.0e-3], com: [0, 0, 0]}\n";
  for (const char* link : {"coxa", "femur", "tibia"}) {
    const std::string l = link;
    const std::string limits = l == "tibia" ? "[-2.8, 0.0]" : "[-1.5, 1.5]";
    const std::string length = l == "coxa" ? "0.085" : l == "femur" ? "0.120" : "0.100";
    robot += "  " + l + ": {mass: 0.1, inertia: [2.0e-5, 8.7e-5, 10.0e-5], length: " + length +
             ", offset: 0.01, com: [0.04, 0, 0], limits: " + limits + "}\n";
  }
  robot += "  hips: {x: 0.08, y: [0.2, 0.0, -0.2], yaw: [0.0, 0.0, 0.0]}\n";
  return robot + "terrain:\n" + terrain +
         "gait: {duty_factor: 0.5, stroke: 0.125, foot_lateral: 0.17, swing_clearance: 0.002, "
         "touchdown_speed: 0.05}\n"
         "motion:\n" +
         start +
         "  cycle_durations: [3.0, 2.6, 3.0]\n"
         "contact: {stiffness: 3.98e11, exponent: 2.2, damping_max: 1.0e4, "
         "full_damping_depth: 1.0e-5, friction_coefficient: 0.3}\n"
         "allocation: {torque_limit: 6.0}\n"
         "output: {sample_step: 0.05}\n";
}

const std::string kStairs =
    "  {type: stairs, riser_height: 0.05, tread_depth: 0.25, steps: 12, first_riser_y: 0.0}\n";
const std::string kAbsoluteStart = "  initial_position: [0.0, 0.412, 0.235]\n";

/// Every optional field of `s` against the same field of the table `d`.
void check_optional_fields(const Scene& s, const Scene& d) {
  CHECK(s.name == d.name);
  CHECK(s.robot.ik_min_margin_m == d.robot.ik_min_margin_m);
  CHECK(s.robot.leg_inertia == d.robot.leg_inertia);
  CHECK(s.terrain.ground_height_m == d.terrain.ground_height_m);
  CHECK(s.gait.foothold_margin_m == d.gait.foothold_margin_m);
  CHECK(s.gait.lift_fraction == d.gait.lift_fraction);
  CHECK(s.gait.lower_fraction == d.gait.lower_fraction);
  CHECK(s.contact.model == d.contact.model);
  CHECK(s.allocation.solver == d.allocation.solver);
  CHECK(s.allocation.friction == d.allocation.friction);
  CHECK(s.allocation.min_normal_force_N == d.allocation.min_normal_force_N);
  CHECK(s.allocation.tolerance == d.allocation.tolerance);
  CHECK(s.allocation.slack_penalty == d.allocation.slack_penalty);
  CHECK(s.output.grid == d.output.grid);
  CHECK(s.output.impact_samples == d.output.impact_samples);
  CHECK(s.output.event_step_s == d.output.event_step_s);
  CHECK(s.output.tolerance == d.output.tolerance);
  CHECK(s.output.compress == d.output.compress);
}

TEST_CASE("config: a scene of required keys only takes the defaults of core/scene.hpp",
          "[config][defaults]") {
  const Scene d;  // the table
  const Scene s = load_scene_from_string(required_keys_only(kStairs, kAbsoluteStart), "min.yaml");
  check_optional_fields(s, d);
  // The resolved configuration spells the defaults out: read back, it is the same scene.
  const Scene again = load_scene_from_string(s.resolved_yaml, "resolved.yaml");
  check_optional_fields(again, d);
  CHECK(again.resolved_yaml == s.resolved_yaml);
}

TEST_CASE("config: terrain and posture defaults come from core/scene.hpp", "[config][defaults]") {
  const Scene d;
  SECTION("flat ground: terrain.height") {
    const Scene s =
        load_scene_from_string(required_keys_only("  {type: flat}\n", kAbsoluteStart), "flat.yaml");
    CHECK(s.terrain.ground_height_m == d.terrain.ground_height_m);
  }
  SECTION("a slope: terrain.origin_y and ground_height") {
    const Scene s = load_scene_from_string(
        required_keys_only("  {type: slope, angle: 0.1}\n", kAbsoluteStart), "slope.yaml");
    CHECK(s.terrain.slope_origin_y_m == d.terrain.slope_origin_y_m);
    CHECK(s.terrain.ground_height_m == d.terrain.ground_height_m);
  }
  SECTION("an automatic posture: target_margin and trunk_clearance") {
    const Scene s = load_scene_from_string(
        required_keys_only(kStairs, "  posture: {height: auto, start_y: -0.3}\n"), "auto.yaml");
    REQUIRE(s.motion.posture.mode == PostureMode::kAuto);
    CHECK(s.motion.posture.target_margin_m == d.motion.posture.target_margin_m);
    CHECK(s.motion.posture.trunk_clearance_m == d.motion.posture.trunk_clearance_m);
  }
}

}  // namespace
}  // namespace hexdyn
