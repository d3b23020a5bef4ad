#pragma once
/// \file height_map.hpp
/// A measured terrain: heights on a regular grid in G0 (terrain.type height_map;
/// docs/theory/stages.md#height-maps), with what the planner asks of it precomputed once: the
/// nodes a foot may not stand near (edges and steep ground) and each node's distance to them.
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"

namespace hexdyn {

struct HeightMap {
  int nx = 0, ny = 0;         ///< nodes along x (columns) and y (rows), each ≥ 2
  double x0_m = 0.0;          ///< x of column 0 [m]
  double y0_m = 0.0;          ///< y of row 0 [m]
  double resolution_m = 0.0;  ///< node spacing along x and y [m], > 0
  std::vector<double> z_m;    ///< ny × nx heights, row-major: node (i, j) at (x0 + j r, y0 + i r)
  /// ny × nx: the index (row-major) of each node's nearest node that is no foothold (an
  /// edge: a neighbour more than the edge height above or below it; or ground steeper than
  /// the largest slope); −1 when there is none. Filled by prepare_height_map.
  std::vector<int> nearest_bad;

  double x(int j) const { return x0_m + j * resolution_m; }
  double y(int i) const { return y0_m + i * resolution_m; }
  double at(int i, int j) const { return z_m[static_cast<std::size_t>(i) * nx + j]; }
  /// Distance of node (i, j) to its nearest no-foothold node [m]; +inf when there is none.
  double node_clearance(int i, int j) const;
  /// Bilinear height at (x, y), the map's border continued outside it [m].
  double height(double x, double y) const;
  /// Gradient (∂z/∂x, ∂z/∂y) of the bilinear surface at (x, y) (0 outside the map).
  Eigen::Vector2d gradient(double x, double y) const;
  /// Upward unit normal of the bilinear surface at (x, y).
  Vec3 normal(double x, double y) const;
  /// Highest node within `radius` of the horizontal segment a–b, widened by one node spacing
  /// (the bilinear surface lies below its cell's highest node) [m].
  double max_height_along(double ax, double ay, double bx, double by, double radius) const;
  /// Distance of (x, y) to the nearest node that is no foothold [m]: the least distance to the
  /// nearest no-foothold nodes of the four nodes around it (the nearest of all but where the
  /// Voronoi cells of the no-foothold nodes meet within the cell); +inf when there is none.
  double clearance(double x, double y) const;
};

/// Fills map.nearest_bad: a node is no foothold when a 4-neighbour's height
/// differs from its own by more than edge_height_m, or when the central-difference slope at it
/// exceeds max_slope_rad; the distances are exact Euclidean distances between nodes (Felzenszwalb
/// and Huttenlocher's two-pass transform).
void prepare_height_map(HeightMap& map, double edge_height_m, double max_slope_rad);

}  // namespace hexdyn
