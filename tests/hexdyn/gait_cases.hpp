#pragma once
// Gait test helpers shared by the planning and pipeline tests: the hexapod's legs as the
// conventions state them, legs in pairs, a swing counted without the planner, and gait.phases
// written for --set.
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/planning/gait.hpp"

namespace hexdyn::test {

/// The six legs by docs/theory/conventions.md, written out here rather than taken from a
/// model: L1 front left, L2 front right, L3 middle left, L4 middle right, L5 rear left, L6 rear
/// right.
inline std::vector<GaitLeg> hexapod_legs() {
  return {{LegSide::kLeft, 0},  {LegSide::kRight, 0}, {LegSide::kLeft, 1},
          {LegSide::kRight, 1}, {LegSide::kLeft, 2},  {LegSide::kRight, 2}};
}

/// Legs of a robot with `per_side` legs on each side, in the leg order of
/// docs/theory/conventions.md: front to rear, left before right in each pair.
inline std::vector<GaitLeg> paired_legs(int per_side) {
  std::vector<GaitLeg> legs;
  for (int rank = 0; rank < per_side; ++rank) {
    legs.push_back({LegSide::kLeft, rank});
    legs.push_back({LegSide::kRight, rank});
  }
  return legs;
}

/// Whether a leg of lift-off phase phi is in swing at cycle phase tau (swing [phi, phi + 1 − β)
/// modulo 1), counted without the planner.
inline bool swinging(double phi, double beta, double tau) {
  double u = tau - phi;
  while (u < 0.0) u += 1.0;
  while (u >= 1.0) u -= 1.0;
  return u < 1.0 - beta;
}

/// `{L1: φ1, …, L6: φ6}` with every digit (17 significant), for gait.phases.
inline std::string phases_text(const std::vector<double>& phi) {
  std::string s = "{";
  for (int leg = 0; leg < static_cast<int>(phi.size()); ++leg)
    s += (leg ? ", " : "") + leg_name(leg) + ": " + format_number(phi[leg], 17);
  return s + "}";
}

}  // namespace hexdyn::test
