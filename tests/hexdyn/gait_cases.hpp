#pragma once
// Gait test helpers shared by the planning and pipeline tests: the hexapod's legs as the
// conventions state them, and gait.phases written for --set.
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

/// `{L1: φ1, …, L6: φ6}` with every digit (17 significant), for gait.phases.
inline std::string phases_text(const std::vector<double>& phi) {
  std::string s = "{";
  for (int leg = 0; leg < static_cast<int>(phi.size()); ++leg)
    s += (leg ? ", " : "") + leg_name(leg) + ": " + format_number(phi[leg], 17);
  return s + "}";
}

}  // namespace hexdyn::test
