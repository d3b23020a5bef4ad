#include "hexdyn/config/key_units.hpp"

#include <array>
#include <string_view>
#include <utility>

namespace hexdyn {
namespace {

using Entry = std::pair<std::string_view, std::string_view>;

/// Exact keys (docs/user/configuration.md#keys-by-group).
constexpr std::array kExact{
    Entry{"robot.hips.x", "m"},
    Entry{"robot.hips.y", "m"},
    Entry{"robot.hips.z", "m"},
    Entry{"robot.hips.yaw", "rad"},
    Entry{"robot.ik_min_margin", "m"},
    Entry{"robot.foot_offset", "m"},
    Entry{"robot.foot_offset.L1", "m"},
    Entry{"robot.foot_offset.L2", "m"},
    Entry{"robot.foot_offset.L3", "m"},
    Entry{"robot.foot_offset.L4", "m"},
    Entry{"robot.foot_offset.L5", "m"},
    Entry{"robot.foot_offset.L6", "m"},
    Entry{"robot.foot_radius", "m"},
    Entry{"robot.nominal_pose", "rad"},
    Entry{"terrain.riser_height", "m"},
    Entry{"terrain.tread_depth", "m"},
    Entry{"terrain.steps", "1"},
    Entry{"terrain.first_riser_y", "m"},
    Entry{"terrain.ground_height", "m"},
    Entry{"terrain.height", "m"},
    Entry{"terrain.angle", "rad"},
    Entry{"terrain.origin_y", "m"},
    Entry{"gait.duty_factor", "1"},
    Entry{"gait.stroke", "m"},
    Entry{"gait.foot_lateral", "m"},
    Entry{"gait.foothold_margin", "m"},
    Entry{"gait.swing_clearance", "m"},
    Entry{"gait.touchdown_speed", "m/s"},
    Entry{"gait.lift_fraction", "1"},
    Entry{"gait.lower_fraction", "1"},
    Entry{"motion.initial_position", "m"},
    Entry{"motion.posture.start_y", "m"},
    Entry{"motion.posture.height", "m"},
    Entry{"motion.posture.height_range", "m"},
    Entry{"motion.posture.target_margin", "m"},
    Entry{"motion.posture.trunk_clearance", "m"},
    Entry{"motion.posture.foot_lateral", "m"},
    Entry{"motion.cycle_durations", "s"},
    Entry{"motion.peak_speed", "m/s"},
    Entry{"motion.cycles", "1"},
    Entry{"motion.ramp_duration", "s"},
    Entry{"contact.exponent", "1"},
    Entry{"contact.damping_max", "N s/m"},
    Entry{"contact.full_damping_depth", "m"},
    Entry{"contact.friction_coefficient", "1"},
    Entry{"contact.static_friction", "1"},
    Entry{"contact.dynamic_friction", "1"},
    Entry{"contact.stiction_velocity", "m/s"},
    Entry{"contact.friction_velocity", "m/s"},
    Entry{"replay.kp", "N m/rad"},
    Entry{"replay.kd", "N m s/rad"},
    Entry{"replay.step", "s"},
    Entry{"replay.tolerance", "1"},
    Entry{"allocation.torque_limit", "N m"},
    Entry{"allocation.min_normal_force", "N"},
    Entry{"allocation.tolerance", "1"},
    Entry{"allocation.slack_penalty", "1"},
    Entry{"output.sample_step", "s"},
    Entry{"output.impact_samples", "1"},
    Entry{"output.event_step", "s"},
    Entry{"output.tolerance", "1"},
};

/// Keys of a body or link (robot.trunk, robot.payload, robot.coxa, ...): by last part.
constexpr std::array kBodySuffix{
    Entry{".mass", "kg"},  Entry{".inertia", "kg m^2"}, Entry{".com", "m"},
    Entry{".length", "m"}, Entry{".offset", "m"},       Entry{".limits", "rad"},
};

}  // namespace

std::string scene_key_units(const std::string& key) {
  for (const auto& [k, u] : kExact)
    if (key == k) return std::string(u);
  if (key.rfind("robot.", 0) == 0)
    for (const auto& [suffix, u] : kBodySuffix)
      if (key.size() > suffix.size() && key.ends_with(suffix)) return std::string(u);
  return "";
}

}  // namespace hexdyn
