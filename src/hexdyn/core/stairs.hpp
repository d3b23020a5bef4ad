#pragma once
/// \file stairs.hpp
/// A staircase's edges in G0 (docs/theory/stages.md#terrain), for the terrain queries
/// (planning/terrain.hpp) and the checks of a step list (config/stair_steps.hpp).
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// The edges of a staircase: edge_y_m in increasing y unless a nosing overhangs a whole tread
/// (the scene reader refuses that); tread_z_m one longer (tread 0 the ground before the first
/// edge, tread k the one behind edge k); edge_step the step (1-based, in the count or the
/// list) whose riser each edge is.
struct StairEdges {
  std::vector<double> edge_y_m, tread_z_m;
  std::vector<int> edge_step;
};

/// The edges of `params` (stairs): uniform stairs have one per riser (one of zero height
/// included), a step list one per riser of non-zero height (a landing adds its going to the
/// tread before it). A nosing moves its edge by the overhang towards the lower tread: back
/// (−y) on a rising riser, ahead on a falling one.
StairEdges stair_edges(const TerrainParams& params);

/// The staircase of `params` step by step: its step_list, or `steps` copies of the uniform
/// riser, tread and nosing; empty off stairs.
std::vector<StairStep> stair_step_list(const TerrainParams& params);

}  // namespace hexdyn
