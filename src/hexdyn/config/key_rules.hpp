#pragma once
/// \file key_rules.hpp
/// Internal to config/: the rules a scene's keys obey beyond each key's own range or choices
/// (those are rows of scene_key_table.hpp), in one place. Each throws ConfigError through the
/// reader, one line naming the key, the value and what is allowed
/// (docs/user/configuration.md#checks-across-keys). The rules:
///
/// Shapes of one key's value
///   - check_principal_moments   robot.*.inertia: each moment at most the sum of the others
///   - check_increasing          robot.*.limits, height_range: [lower, upper], lower < upper
///   - check_hips_decreasing     robot.hips.y: [front, middle, rear] decreasing
///   - check_cycle_durations     motion.cycle_durations: [ramp-up, cruise..., ramp-down]
///   - check_allocation_tolerance  allocation.tolerance: at most the loosest that meets the
///                                 violation threshold
/// Across keys
///   - check_urdf_path, check_stance_radius   robot.urdf and the stance it gives
///   - check_reference_length_given   uniform_density needs each link's reference_length
///   - check_swing_fractions     gait.lift_fraction + gait.lower_fraction < 0.95
///   - check_start_form          motion.initial_position or motion.posture, one of them
///   - check_timing_form         motion.cycle_durations or the speed keys; travel or cycles
///   - check_treads_on_stairs    motion.travel.treads needs stairs
///   - check_ramp                motion.ramp_duration at most the cruise time
///   - check_friction_velocity   contact.friction_velocity above contact.stiction_velocity
///   - check_copper_loss         allocation.objective copper_loss needs actuators
///   - check_event_step          output.event_step at most output.sample_step
/// Of the whole scene (after every key is read)
///   - check_physical_plausibility   plausibility.hpp: no motion beyond 100 g
///   - check_run_size_limits         run_limits.hpp: cycles, duration, samples
#include <string>
#include <vector>

#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn::scene_keys {

void check_principal_moments(const Reader& r, const std::string& path, const Vec3& I);
void check_increasing(const Reader& r, const std::string& path, const std::vector<double>& v);
void check_hips_decreasing(const Reader& r, const std::vector<double>& y);
void check_cycle_durations(const Reader& r, const std::vector<double>& d);
void check_allocation_tolerance(const Reader& r, double tolerance);

void check_urdf_path(const Reader& r, const std::string& path);
void check_stance_radius(const Reader& r, double radius_m);
void check_reference_length_given(const Reader& r, const std::string& link, bool follow);
void check_swing_fractions(const Reader& r, const GaitParams& g);
/// `absolute`: motion.initial_position given; `relative`: motion.posture given.
void check_start_form(const Reader& r, bool absolute, bool relative);
void check_timing_form(Reader& r, bool by_durations, bool by_speed, bool by_travel);
void check_treads_on_stairs(const Reader& r, int treads, const TerrainParams& t);
void check_ramp(const Reader& r, const MotionParams& m, double cruise_time_s);
void check_friction_velocity(const Reader& r, const ContactParams& c);
void check_copper_loss(const Reader& r, const Scene& s);
void check_event_step(const Reader& r, const OutputParams& o);

}  // namespace hexdyn::scene_keys
