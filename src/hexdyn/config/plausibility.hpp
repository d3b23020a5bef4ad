#pragma once
/// \file plausibility.hpp
/// Physical plausibility of a scene's timing, checked after every key is in range
/// (config.cpp) and before anything is planned. Each key has a range of its own, but some
/// combinations inside those ranges describe no physical motion: a duty factor of
/// 0.99999 leaves a 26 µs swing, a 1e-9 lift fraction lifts a foot in a nanosecond.
/// Computed anyway, they give torques of 1e7–1e10 N·m and forces of 1e16 N, flagged but
/// absurd. These checks refuse them with one line naming the key, the value, the bound
/// derived from the scene and why.
///
/// The physical bound: no planned motion may need a foot or trunk acceleration above
/// kMaxPlannedAcceleration = 100 g (981 m/s²). The paper's swings peak at about 3 m/s²
/// and its trunk at 0.2 m/s²; 100 g is some ten times what the paper robot's actuators
/// could give a leg (6 N·m on 0.3 kg at 0.2 m ≈ 100 m/s²), so a scene beyond it is not a
/// hard case but a typing error. The motion laws are those of planning/gait.cpp and
/// planning/motion.cpp: the smootherstep S(u) = 10u³ − 15u⁴ + 6u⁵, whose peak
/// acceleration is (10/√3) h / T² for a move of h in time T.
/// From it, with T_c the shortest (cruise) gait cycle and D = (1 − β) T_c the swing time:
///   lift time   lift_fraction · D  ≥ √(5.77 Δh / a)   (lift by the clearance Δh)
///   lower time  lower_fraction · D ≥ √(5.77 Δh / a)   (descend by at least Δh)
///   swing       D ≥ lift + lower minimum + √(5.77 s / a), s = s0/β the foot's stride
///   speed ramp  T_r ≥ 1.875 v / a                      (the trunk's peak ramp acceleration)
///
/// Not checked: the touchdown speed against the clearance. The planner shortens the
/// descent to 4 Δz / v_td to keep it monotone (gait.cpp), which needs 0.75 v_td² / Δz of
/// acceleration; the hard-case tests use clearances of 1 µm at 0.05 m/s (190 g) on
/// purpose, so that combination stays allowed.
#include <string>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Largest foot or trunk acceleration a planned motion may need [m/s²]: 100 g.
inline constexpr double kMaxPlannedAcceleration = 100.0 * 9.81;

/// Throws ConfigError "SOURCE: key: got V, ... expected ... (why)" for the first timing
/// that violates the bounds above. `scene` holds validated keys (scene_from_yaml).
void check_physical_plausibility(const Scene& scene, const std::string& source);

}  // namespace hexdyn
