#pragma once
/// \file gait_pattern.hpp
/// Gait patterns (gait.pattern, docs/theory/stages.md#gait-patterns): each leg's lift-off phase
/// φ ∈ [0, 1), the fraction of a cycle at which it lifts off, from its side and its rank on that
/// side counted from the front (r = 0 the front leg; a side of n_s legs). Each leg then swings
/// once per cycle, from φ for 1 − β of a cycle (planning/gait.hpp). With s = 1 − β and [left] 1
/// on the left side, 0 on the right:
///   wave   φ = frac(o + (n_s − 1 − r) s), o = ½ on the left, 0 on the right: on each side the
///          wave runs from rear to front, each leg lifting when the one behind it touches down,
///          the left side half a cycle after the right (Song and Waldron). Six legs:
///          φ6 = 0, φ4 = 1−β, φ2 = 2(1−β), φ5 = ½, φ3 = ½+(1−β), φ1 = ½+2(1−β) (mod 1); at
///          β = ½ the paper's tripod, legs 2-3-6 swing first, then 1-4-5. Four legs at β = ¾:
///          the crawl, rear right, front right, rear left, front left.
///   trot   φ = ½ ((r + [left]) mod 2): the diagonal pairs of a quadruped; on six legs the
///          alternating tripod, equal to the wave's phases at β = ½ (legs 2-3-6 at 0, 1-4-5 at ½).
///   pace   φ = ½ [left]: the left legs against the right legs.
///   bound  φ = ½ [r < n_s/2]: the front half of each side against the rear half, the rear
///          half first (as the wave's rear legs).
///   custom φ as gait.phases gives them.
/// trot, pace and bound put each leg at 0 or ½, so at β ≥ ½ one group stands while the other
/// swings: no flight phase. A pattern fits a robot when its formula names every leg in a
/// group that has a partner: trot and bound pair the sides, so they need legs on both and
/// as many on each; pace needs both sides; bound needs an even number of legs on each side.
/// wave and custom fit any robot (gait_pattern_misfit).
#include <span>
#include <string>
#include <vector>

#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// A leg's place in a gait pattern: its side (LegSide) and its rank on that side counted from
/// the front (0 the front leg).
struct GaitLeg {
  LegSide side = LegSide::kLeft;
  int rank = 0;
};

/// The model's legs in leg order, each with the side and front-to-rear row of its leg table
/// (RobotModel::leg; for a hexapod L1 front left, L2 front right, … L6 rear right,
/// docs/theory/conventions.md).
std::vector<GaitLeg> gait_legs(const RobotModel& model);

/// The word of a pattern, as gait.pattern writes it ("wave", "trot", …).
std::string gait_pattern_word(GaitPattern pattern);

/// Lift-off phases φ ∈ [0, 1) of the wave gait (file comment), one per leg of `legs`, in its
/// order. The ranks on each side must be 0 … n_s − 1, each once (std::invalid_argument
/// otherwise). For a hexapod's gait_legs() these are the six expressions of the file comment,
/// operation for operation.
std::vector<double> wave_gait_phases(std::span<const GaitLeg> legs, double duty_factor);

/// Why `pattern` does not fit the legs, one line to follow the key path "gait.pattern: ": the
/// pattern, the leg count and the legs on each side, what the pattern needs and the patterns
/// that fit ("got bound for a robot of 6 legs (3 on the left, 3 on the right): bound …");
/// empty when it fits. custom and wave fit every robot.
std::string gait_pattern_misfit(GaitPattern pattern, std::span<const GaitLeg> legs);

/// Lift-off phases of a pattern other than custom (file comment), one per leg of `legs`, in
/// its order. std::invalid_argument for custom, for ranks that do not number each side's
/// legs 0 … n_s − 1 once, and for a pattern that does not fit (gait_pattern_misfit).
std::vector<double> gait_pattern_phases(GaitPattern pattern, std::span<const GaitLeg> legs,
                                        double duty_factor);

/// The lift-off phases a plan uses: gait.phases for the pattern custom (and whenever they are
/// given), else gait_pattern_phases of gait.pattern for `legs` and gait.duty_factor.
std::vector<double> liftoff_phases(const GaitParams& gait, std::span<const GaitLeg> legs);

}  // namespace hexdyn
