#pragma once
/// \file support_region.hpp
/// Convex regions of the horizontal plane (world x, y) for the balanced trunk
/// (docs/theory/balance.md#support-regions): the convex hull of the stance feet, a polygon, a
/// segment (two feet, or feet in a line) or a point, shrunk by the stability margin, and the
/// nearest point of a region with the derivative of that projection.
#include <vector>

#include "hexdyn/planning/trunk_offset.hpp"

namespace hexdyn {

using Mat2 = Eigen::Matrix2d;

/// A convex region: vertices counter-clockwise, 3 or more (a polygon with area), 2 (a segment)
/// or 1 (a point); none: empty.
struct SupportRegion {
  std::vector<Vec2> vertices;
  bool empty() const { return vertices.empty(); }
};

/// The convex hull of `points` [m]: points closer than tol_m merged, points within tol_m of a
/// hull edge's line dropped (so that feet in a line give a segment).
SupportRegion convex_hull(std::vector<Vec2> points, double tol_m);

/// The region shrunk by margin_m ≥ 0: a polygon's edges moved inward by it (an empty result
/// when it is narrower than 2 margin_m), a segment's ends moved toward each other by it (its
/// midpoint when shorter than 2 margin_m), a point unchanged.
SupportRegion shrink(const SupportRegion& region, double margin_m);

/// shrink() with the largest margin of margin_m, margin_m / 2, margin_m / 4, … (ten halvings,
/// then 0) that leaves the region non-empty; `used_m` (may be null) receives it.
SupportRegion shrink_to_fit(const SupportRegion& region, double margin_m, double* used_m);

/// The nearest point of a non-empty region to p, and the derivative of that map at p: the
/// identity inside a polygon, the projector onto the edge's direction on an edge or a
/// segment's interior, zero at a vertex or a point.
struct Projection {
  Vec2 point = Vec2::Zero();
  Mat2 derivative = Mat2::Zero();
};
Projection project(const SupportRegion& region, const Vec2& p);

/// Signed depth of p in the region [m]: its distance to the boundary inside a polygon
/// (positive), minus its distance to the region outside it; for a segment or a point (no
/// interior) minus the distance.
double depth(const SupportRegion& region, const Vec2& p);

}  // namespace hexdyn
