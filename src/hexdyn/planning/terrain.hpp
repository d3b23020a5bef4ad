#pragma once
/// \file terrain.hpp
/// Terrain height and surface-normal queries in G0 (z up, climbing along +y):
/// flat ground, a constant slope rising along +y, or a staircase of `steps` risers
/// whose k-th riser (k = 1..steps) stands at y = first_riser_y + (k−1)·tread_depth
/// and lifts the tread behind it by riser_height. Heights are independent of x.
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

class Terrain {
 public:
  explicit Terrain(const TerrainParams& params);

  /// Terrain height under (x, y) [m]. At a riser's y the upper tread counts.
  double height(double x, double y) const;
  /// Upward unit normal of the surface a foot stands on at (x, y): +z on treads.
  Vec3 normal(double x, double y) const;
  /// Highest terrain under the horizontal segment from a to b (z ignored) [m]. With
  /// radius_m = r > 0, under the shadow of a sphere of radius r whose contact point follows
  /// the segment: on stairs the segment widened by r at both ends along y. On flat ground
  /// and slopes r changes nothing: a sphere's vertical clearance above a plane is that of its
  /// contact point (docs/theory/stages.md#motion-planning).
  double max_height_along(const Vec3& a, const Vec3& b, double radius_m = 0.0) const;
  /// Mean inclination along +y [rad]: atan(h_s/b_s) on stairs
  /// (docs/theory/conventions.md#trunk-orientation-bryant-angles).
  double mean_slope_rad() const;
  /// Stairs: distance from y to the nearest tread edge (nosing behind, riser ahead)
  /// of the tread containing y; +inf on flat ground and slopes [m].
  double edge_distance(double y) const;
  /// The y closest to `y` whose edge distance is at least `margin` (y itself if it is);
  /// nullopt when no tread is deep enough (a tread shallower than 2 · margin).
  std::optional<double> valid_foothold_y(double y, double margin) const;
  /// valid_foothold_y, throwing PlanningError naming y when there is none.
  double nearest_valid_foothold_y(double y, double margin) const;
  /// Stairs: index of the tread containing y, 0 = ground before the first riser, k = the
  /// tread above the k-th riser (step k), steps = top. Meaningful on stairs only.
  int tread_index(double y) const;

  const TerrainParams& params() const { return params_; }

 private:
  TerrainParams params_;
};

/// The terrain's height profile z(y) [m] in G0 as a polyline (/terrain/y, /terrain/z): K ≥ 2
/// vertices with non-decreasing y, linear in between; a vertical riser is two vertices of
/// equal y (lower, then upper). Covers [y_min, y_max] (y_min < y_max) and, on stairs, every
/// riser with at least one tread depth of ground before the first and of top tread after the
/// last. Between vertices it equals Terrain(params).height(·, y) everywhere except exactly
/// at a riser's y, where height() takes the upper tread.
struct TerrainProfile {
  std::vector<double> y_m, z_m;
};
TerrainProfile terrain_profile(const TerrainParams& params, double y_min, double y_max);

/// "flat", "slope" or "stairs" (the `terrain.type` key's words).
std::string terrain_type_name(TerrainType type);

}  // namespace hexdyn
