#include "hexdyn/core/stairs.hpp"

#include <algorithm>

namespace hexdyn {

namespace {

double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

}  // namespace

StairEdges stair_edges(const TerrainParams& p) {
  StairEdges e;
  e.tread_z_m.push_back(p.ground_height_m);
  if (p.step_list.empty()) {
    // The nosing moves each edge towards its lower tread: back when rising, ahead when falling.
    const double shift = sign(p.riser_height_m) * p.nosing_m;
    for (int k = 1; k <= p.steps; ++k) {
      e.edge_y_m.push_back(p.first_riser_y_m + (k - 1) * p.tread_depth_m - shift);
      e.tread_z_m.push_back(p.ground_height_m + p.riser_height_m * k);
      e.edge_step.push_back(k);
    }
    return e;
  }
  double y = p.first_riser_y_m, z = p.ground_height_m;
  for (std::size_t k = 0; k < p.step_list.size(); ++k) {
    const StairStep& s = p.step_list[k];
    if (s.riser_m != 0.0) {  // a landing (zero riser) lengthens the tread before it
      z += s.riser_m;
      e.edge_y_m.push_back(y - sign(s.riser_m) * s.nosing_m);
      e.tread_z_m.push_back(z);
      e.edge_step.push_back(static_cast<int>(k) + 1);
    }
    y += s.tread_m;
  }
  return e;
}

std::vector<StairStep> stair_step_list(const TerrainParams& t) {
  if (t.type != TerrainType::kStairs) return {};
  if (!t.step_list.empty()) return t.step_list;
  return std::vector<StairStep>(static_cast<std::size_t>(std::max(t.steps, 0)),
                                StairStep{t.riser_height_m, t.tread_depth_m, t.nosing_m});
}

}  // namespace hexdyn
