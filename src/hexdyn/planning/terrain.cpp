#include "hexdyn/planning/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

Terrain::Terrain(const TerrainParams& params) : params_(params) {
  if (params_.type != TerrainType::kStairs) return;
  uniform_ = params_.step_list.empty() && params_.nosing_m == 0.0;
  StairEdges e = stair_edges(params_);
  edge_y_m_ = std::move(e.edge_y_m);
  tread_z_m_ = std::move(e.tread_z_m);
  edge_step_ = std::move(e.edge_step);
}

int Terrain::tread_index(double y) const {
  if (uniform_) {
    const double k = std::floor((y - params_.first_riser_y_m) / params_.tread_depth_m) + 1.0;
    return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(params_.steps)));
  }
  return static_cast<int>(std::upper_bound(edge_y_m_.begin(), edge_y_m_.end(), y) -
                          edge_y_m_.begin());
}

double Terrain::height(double x, double y) const {
  switch (params_.type) {
    case TerrainType::kFlat:
      return params_.ground_height_m;
    case TerrainType::kSlope:
      return params_.ground_height_m + std::tan(params_.slope_rad) * (y - params_.slope_origin_y_m);
    case TerrainType::kStairs:
      return tread_z_m_[tread_index(y)];
    case TerrainType::kHeightMap:
      return params_.map->height(x, y);
  }
  return 0.0;
}

Vec3 Terrain::normal(double x, double y) const {
  if (params_.type == TerrainType::kHeightMap) return params_.map->normal(x, y);
  if (params_.type == TerrainType::kSlope)
    return Vec3(0.0, -std::sin(params_.slope_rad), std::cos(params_.slope_rad));
  return Vec3::UnitZ();
}

double Terrain::max_height_along(const Vec3& a, const Vec3& b, double radius_m) const {
  if (params_.type == TerrainType::kHeightMap)
    return params_.map->max_height_along(a.x(), a.y(), b.x(), b.y(), radius_m);
  if (params_.type != TerrainType::kStairs)
    return std::max(height(a.x(), a.y()), height(b.x(), b.y()));
  // Stairs: height depends on y only; the highest tread the widened segment touches.
  const int k_hi = tread_index(std::max(a.y(), b.y()) + radius_m);
  const int k_lo = tread_index(std::min(a.y(), b.y()) - radius_m);
  return *std::max_element(tread_z_m_.begin() + k_lo, tread_z_m_.begin() + k_hi + 1);
}

double Terrain::mean_slope_rad() const { return hexdyn::mean_slope_rad(params_); }

double Terrain::edge_distance(double y) const {
  // Uniform stairs of zero risers are flat ground (a list's zero risers make no edge).
  if (params_.type != TerrainType::kStairs ||
      (params_.step_list.empty() && params_.riser_height_m == 0.0))
    return kInf;
  const int k = tread_index(y), n = edge_count();
  // Tread k spans [edge k, edge k+1); the ground (k = 0) has no edge behind, the last tread
  // none ahead.
  const double start = k == 0 ? -kInf : edge_y_m_[k - 1];
  const double end = k == n ? kInf : edge_y_m_[k];
  return std::min(y - start, end - y);
}

double Terrain::nearest_valid_foothold_y(double y, double margin) const {
  if (const std::optional<double> valid = valid_foothold_y(y, margin)) return *valid;
  throw PlanningError("no foothold near y = " + std::to_string(y) + " m: no tread within one of " +
                      "it is deeper than twice the foothold margin " + std::to_string(margin) +
                      " m");
}

double Terrain::edge_distance_at(double x, double y) const {
  if (params_.type == TerrainType::kHeightMap) return params_.map->clearance(x, y);
  return edge_distance(y);
}

std::optional<double> Terrain::valid_foothold_at(double x, double y, double margin) const {
  if (params_.type != TerrainType::kHeightMap) return valid_foothold_y(y, margin);
  // The nearest y along the line x = const whose clearance keeps the margin, searched outward
  // node by node up to kFootholdSearch_m either way.
  const double r = params_.map->resolution_m;
  const int n = static_cast<int>(std::ceil(kFootholdSearch_m / r));
  const auto ok = [&](double yy) { return edge_distance_at(x, yy) >= margin; };
  if (ok(y)) return y;
  for (int k = 1; k <= n; ++k) {
    // The nearer of the two sides' first valid points: node steps, then bisection between the
    // last invalid step and the first valid one for the boundary.
    std::optional<double> best;
    for (double s : {1.0, -1.0}) {
      if (!ok(y + s * k * r)) continue;
      double bad = y + s * (k - 1) * r, good = y + s * k * r;
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (bad + good);
        (ok(mid) ? good : bad) = mid;
      }
      if (!best || std::abs(good - y) < std::abs(*best - y)) best = good;
    }
    if (best) return best;
  }
  return std::nullopt;
}

std::optional<double> Terrain::valid_foothold_y(double y, double margin) const {
  if (edge_distance(y) >= margin) return y;
  // Candidates: the valid ends of the tread containing y and of its neighbours.
  const int k = tread_index(y), n = edge_count();
  double best = y, best_d = kInf;
  for (int kk = std::max(0, k - 1); kk <= std::min(n, k + 1); ++kk) {
    const double start = kk == 0 ? -kInf : edge_y_m_[kk - 1];
    const double end = kk == n ? kInf : edge_y_m_[kk];
    if (end - start < 2.0 * margin) continue;
    for (double c : {start + margin, end - margin}) {
      if (!std::isfinite(c) || edge_distance(c) + 1e-12 < margin) continue;
      if (std::abs(c - y) < best_d) {
        best_d = std::abs(c - y);
        best = c;
      }
    }
  }
  if (best_d == kInf) return std::nullopt;
  return best;
}

TerrainProfile terrain_profile(const TerrainParams& p, double y_min, double y_max) {
  const Terrain terrain(p);
  TerrainProfile out;
  auto vertex = [&](double y, double z) {
    out.y_m.push_back(y);
    out.z_m.push_back(z);
  };
  if (p.type == TerrainType::kHeightMap) {  // the map's nodes along x = 0, its ends continued
    const HeightMap& m = *p.map;
    const double start = std::min(y_min, m.y(0)), end = std::max(y_max, m.y(m.ny - 1));
    if (start < m.y(0)) vertex(start, m.height(0.0, start));
    for (int i = 0; i < m.ny; ++i) vertex(m.y(i), m.height(0.0, m.y(i)));
    if (end > m.y(m.ny - 1)) vertex(end, m.height(0.0, end));
    return out;
  }
  if (p.type != TerrainType::kStairs || terrain.edge_count() == 0) {
    vertex(y_min, terrain.height(0.0, y_min));
    vertex(y_max, terrain.height(0.0, y_max));
    return out;
  }
  const int n = terrain.edge_count();
  const double going = p.step_list.empty() ? p.tread_depth_m : p.step_list.front().tread_m;
  const double last_going = p.step_list.empty() ? p.tread_depth_m : p.step_list.back().tread_m;
  const double start = std::min(y_min, terrain.edge_y(1) - going);
  const double end = std::max(y_max, terrain.edge_y(n) + last_going);
  vertex(start, terrain.tread_height(0));
  for (int k = 1; k <= n; ++k) {
    vertex(terrain.edge_y(k), terrain.tread_height(k - 1));
    vertex(terrain.edge_y(k), terrain.tread_height(k));
  }
  vertex(end, terrain.tread_height(n));
  return out;
}

std::string terrain_type_name(TerrainType type) {
  switch (type) {
    case TerrainType::kFlat:
      return "flat";
    case TerrainType::kSlope:
      return "slope";
    case TerrainType::kStairs:
      return "stairs";
    case TerrainType::kHeightMap:
      return "height_map";
  }
  return "unknown";
}

}  // namespace hexdyn
