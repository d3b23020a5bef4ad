#pragma once
/// \file waypoints.hpp
/// The balanced trunk's ZMP waypoints (docs/theory/balance.md#the-waypoints): the points of the
/// ZMP path at the breakpoints, each in its support region, nearest their targets under the two
/// conditions that start and end the offset at rest. Internal to the balance stage.
#include <vector>

#include "hexdyn/balance/support_region.hpp"

namespace hexdyn {

/// The two boundary functionals of a piece's waypoint hat functions and of its s: for a weight
/// exp(−ω t) (start) and exp(−ω (T − t)) (end), each scaled by ω (trunk_offset.hpp).
struct Functionals {
  std::vector<Vec2> a;  ///< per waypoint: (start, end) weight
  Vec2 s_start = Vec2::Zero(), s_end = Vec2::Zero();
};

/// The waypoints nearest the targets g (weights c > 0, one per waypoint) inside their regions
/// whose functionals equal F's s parts (the two at-rest conditions per axis), by the exact
/// projection below; `residual` receives the conditions' relative residual [world x, y, m].
std::vector<Vec2> solve_waypoints(const std::vector<SupportRegion>& region,
                                  const std::vector<Vec2>& g, const std::vector<double>& c,
                                  const Functionals& F, double* residual);

/// Waypoints that keep the ZMP path smooth: ADMM on Σ c_k |w_k − g_k|² + β Σ |w_{k+1} − w_k|² /
/// Δ_k (β = 16/ω², Δ_k = span_s[k] > 0, one fewer than the waypoints) with each waypoint in its
/// region and the two conditions, polished by solve_waypoints.
std::vector<Vec2> smooth_waypoints(const std::vector<SupportRegion>& region,
                                   const std::vector<Vec2>& g, const std::vector<double>& c,
                                   const std::vector<double>& span_s, const Functionals& F,
                                   double omega, double* residual);

}  // namespace hexdyn
