#include "hexdyn/model/gait_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hexdyn {
namespace {

double frac(double x) { return x - std::floor(x); }

constexpr GaitPattern kPatterns[] = {GaitPattern::kWave, GaitPattern::kTrot, GaitPattern::kPace,
                                     GaitPattern::kBound, GaitPattern::kCustom};

/// Legs on the left and on the right.
struct SideCounts {
  int left = 0, right = 0;
};

/// The counts of each side, after checking that the ranks of each side are 0 … n_s − 1, each
/// once (std::invalid_argument otherwise).
SideCounts side_counts(std::span<const GaitLeg> legs) {
  SideCounts n;
  for (const GaitLeg& g : legs) ++(g.side == LegSide::kLeft ? n.left : n.right);
  std::vector<int> seen(legs.size(), 0);  // legs of each rank: the left's, then the right's
  for (const GaitLeg& g : legs) {
    const bool left = g.side == LegSide::kLeft;
    const int n_side = left ? n.left : n.right;
    if (g.rank < 0 || g.rank >= n_side || ++seen[(left ? 0 : n.left) + g.rank] > 1)
      throw std::invalid_argument("gait legs: rank " + std::to_string(g.rank) + " on a side of " +
                                  std::to_string(n_side) +
                                  " legs; the ranks of a side are 0 … n − 1, each once");
  }
  return n;
}

/// What `pattern` needs that the sides do not have; empty when it fits.
std::string unmet_need(GaitPattern pattern, SideCounts n) {
  const bool both = n.left > 0 && n.right > 0;
  switch (pattern) {
    case GaitPattern::kWave:
    case GaitPattern::kCustom:
      return {};
    case GaitPattern::kTrot:
      if (both && n.left == n.right) return {};
      return "trot pairs each leg with a diagonal neighbour on the other side and needs as many "
             "legs on each side";
    case GaitPattern::kPace:
      if (both) return {};
      return "pace swings the left legs against the right legs and needs legs on both sides";
    case GaitPattern::kBound:
      if (both && n.left == n.right && n.left % 2 == 0) return {};
      return "bound swings the front half of each side against the rear half, the front pair "
             "together, and needs an even number of legs on each side, as many on both";
  }
  return {};
}

}  // namespace

std::vector<GaitLeg> gait_legs(const RobotModel& model) {
  std::vector<GaitLeg> legs;
  for (int leg = 0; leg < model.legs(); ++leg)
    legs.push_back({model.leg(leg).side, model.leg(leg).row});
  return legs;
}

std::string gait_pattern_word(GaitPattern pattern) {
  switch (pattern) {
    case GaitPattern::kWave:
      return "wave";
    case GaitPattern::kTrot:
      return "trot";
    case GaitPattern::kPace:
      return "pace";
    case GaitPattern::kBound:
      return "bound";
    case GaitPattern::kCustom:
      return "custom";
  }
  return "?";
}

std::vector<double> wave_gait_phases(std::span<const GaitLeg> legs, double beta) {
  const SideCounts n = side_counts(legs);
  const double s = 1.0 - beta;
  // Six legs: frac(o + k * s) with k = 2, 1, 0 gives the bits of frac(0.5 + 2.0 * s),
  // frac(2.0 * s), frac(0.5 + s), frac(s), 0.5 and 0.0: 0.0 + x = x, 1.0 * s = s and
  // 0.0 * s = +0 exactly for a finite s ≥ 0 (tests/hexdyn/planning/test_gait_phases.cpp).
  std::vector<double> phase;
  phase.reserve(legs.size());
  for (const GaitLeg& g : legs) {
    const bool left = g.side == LegSide::kLeft;
    const double offset = left ? 0.5 : 0.0;
    const int behind = (left ? n.left : n.right) - 1 - g.rank;  // legs behind it on its side
    phase.push_back(frac(offset + static_cast<double>(behind) * s));
  }
  return phase;
}

std::string gait_pattern_misfit(GaitPattern pattern, std::span<const GaitLeg> legs) {
  const SideCounts n = side_counts(legs);
  const std::string need = unmet_need(pattern, n);
  if (need.empty()) return {};
  std::string fit;
  for (GaitPattern p : kPatterns)
    if (unmet_need(p, n).empty()) fit += (fit.empty() ? "" : ", ") + gait_pattern_word(p);
  return "got " + gait_pattern_word(pattern) + " for a robot of " + std::to_string(legs.size()) +
         " legs (" + std::to_string(n.left) + " on the left, " + std::to_string(n.right) +
         " on the right): " + need + "; patterns that fit: " + fit;
}

std::vector<double> gait_pattern_phases(GaitPattern pattern, std::span<const GaitLeg> legs,
                                        double duty_factor) {
  if (pattern == GaitPattern::kCustom)
    throw std::invalid_argument("gait pattern custom: its phases are gait.phases");
  if (pattern == GaitPattern::kWave) return wave_gait_phases(legs, duty_factor);
  const std::string misfit = gait_pattern_misfit(pattern, legs);
  if (!misfit.empty()) throw std::invalid_argument("gait.pattern: " + misfit);
  const SideCounts n = side_counts(legs);
  std::vector<double> phase;
  phase.reserve(legs.size());
  for (const GaitLeg& g : legs) {
    const bool left = g.side == LegSide::kLeft;
    bool late = false;  // lifts off at ½ rather than 0
    if (pattern == GaitPattern::kTrot) late = (g.rank + (left ? 1 : 0)) % 2 == 1;
    if (pattern == GaitPattern::kPace) late = left;
    if (pattern == GaitPattern::kBound) late = 2 * g.rank < (left ? n.left : n.right);
    phase.push_back(late ? 0.5 : 0.0);
  }
  return phase;
}

std::vector<double> liftoff_phases(const GaitParams& gait, std::span<const GaitLeg> legs) {
  if (gait.pattern == GaitPattern::kCustom || !gait.liftoff_phases.empty()) {
    if (gait.liftoff_phases.size() != legs.size())
      throw std::invalid_argument(
          "gait pattern custom: " + std::to_string(gait.liftoff_phases.size()) +
          " phases in gait.phases for " + std::to_string(legs.size()) + " legs");
    return gait.liftoff_phases;
  }
  return gait_pattern_phases(gait.pattern, legs, gait.duty_factor);
}

}  // namespace hexdyn
