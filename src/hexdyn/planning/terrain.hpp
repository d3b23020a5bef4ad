#pragma once
/// \file terrain.hpp
/// Terrain height and surface-normal queries in G0 (z up, the walk along +y): flat ground, a
/// constant slope rising along +y, or a staircase. A staircase is a sequence of treads
/// separated by edges: tread 0 is the ground before the first edge, tread k the one behind
/// the k-th edge, the last endless. Uniform stairs have `steps` risers, the k-th
/// (k = 1..steps) at y = first_riser_y + (k−1)·tread_depth, each lifting the tread behind it
/// by riser_height (< 0: descending). A step list (TerrainParams::step_list) gives each
/// riser and going; a nosing moves a riser's edge by its overhang towards the lower tread
/// (the underside is taken as solid: the terrain stays a height field z(y)). Heights are
/// independent of x (docs/theory/stages.md#terrain) but on a height map: a grid of measured
/// heights z(x, y), bilinear between its nodes (core/height_map.hpp,
/// docs/theory/stages.md#height-maps).
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/core/stairs.hpp"

namespace hexdyn {

/// How far along y a foothold on a height map is searched from where it was wanted [m].
inline constexpr double kFootholdSearch_m = 0.3;

class Terrain {
 public:
  explicit Terrain(const TerrainParams& params);

  /// Terrain height under (x, y) [m]. At an edge's y the tread behind it counts (the upper
  /// one on the way up, the lower one on the way down).
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
  /// Stairs: distance from y to the nearest edge (behind or ahead) of the tread containing
  /// y; +inf on flat ground and slopes [m].
  double edge_distance(double y) const;
  /// The y closest to `y` whose edge distance is at least `margin` (y itself if it is);
  /// nullopt when no tread near y is deep enough (all shallower than 2 · margin).
  std::optional<double> valid_foothold_y(double y, double margin) const;
  /// Distance of (x, y) to the nearest edge: on a height map to the nearest node that is no
  /// foothold (core/height_map.hpp clearance); elsewhere edge_distance(y) [m].
  double edge_distance_at(double x, double y) const;
  /// The y closest to `y` on the line through x whose edge_distance_at is at least `margin`;
  /// on a height map searched node by node up to kFootholdSearch_m either way, elsewhere
  /// valid_foothold_y. nullopt when there is none.
  std::optional<double> valid_foothold_at(double x, double y, double margin) const;
  /// valid_foothold_y, throwing PlanningError naming y when there is none.
  double nearest_valid_foothold_y(double y, double margin) const;
  /// Stairs: index of the tread containing y, 0 = ground before the first edge, k = the
  /// tread behind the k-th edge, edge_count() = the last. Meaningful on stairs only.
  int tread_index(double y) const;
  /// Stairs: number of edges (risers of non-zero height; landings add none).
  int edge_count() const { return static_cast<int>(edge_y_m_.size()); }
  /// Stairs: y of edge k = 1..edge_count() (its nosing's line) [m].
  double edge_y(int k) const { return edge_y_m_[k - 1]; }
  /// Stairs: height of tread k = 0..edge_count() [m].
  double tread_height(int k) const { return tread_z_m_[k]; }
  /// Stairs: the step (1-based, in terrain.steps' count or list) whose riser is edge k.
  int edge_step(int k) const { return edge_step_[k - 1]; }

  const TerrainParams& params() const { return params_; }

 private:
  TerrainParams params_;
  bool uniform_ = false;           ///< uniform stairs without nosing: tread_index by floor
  std::vector<double> edge_y_m_;   ///< stairs: edges in increasing y
  std::vector<double> tread_z_m_;  ///< stairs: edge_count() + 1 tread heights
  std::vector<int> edge_step_;     ///< stairs: the step of each edge
};

/// The terrain's height profile z(y) [m] in G0 as a polyline (/terrain/y, /terrain/z): K ≥ 2
/// vertices with non-decreasing y, linear in between; an edge is two vertices of equal y
/// (the tread before, then the tread behind). Covers [y_min, y_max] (y_min < y_max) and, on
/// stairs, every edge with at least one tread depth (the first going) of ground before the
/// first and of the last tread after the last. Between vertices it equals
/// Terrain(params).height(·, y) everywhere except exactly at an edge's y, where height()
/// takes the tread behind it.
struct TerrainProfile {
  std::vector<double> y_m, z_m;
};
TerrainProfile terrain_profile(const TerrainParams& params, double y_min, double y_max);

/// "flat", "slope" or "stairs" (the `terrain.type` key's words).
std::string terrain_type_name(TerrainType type);

}  // namespace hexdyn
