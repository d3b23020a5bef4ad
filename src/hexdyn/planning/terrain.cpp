#include "hexdyn/planning/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

Terrain::Terrain(const TerrainParams& params) : params_(params) {}

int Terrain::tread_index(double y) const {
  const double k = std::floor((y - params_.first_riser_y_m) / params_.tread_depth_m) + 1.0;
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(params_.steps)));
}

double Terrain::height(double /*x*/, double y) const {
  switch (params_.type) {
    case TerrainType::kFlat:
      return params_.ground_height_m;
    case TerrainType::kSlope:
      return params_.ground_height_m + std::tan(params_.slope_rad) * (y - params_.slope_origin_y_m);
    case TerrainType::kStairs:
      return params_.ground_height_m + params_.riser_height_m * tread_index(y);
  }
  return 0.0;
}

Vec3 Terrain::normal(double /*x*/, double /*y*/) const {
  if (params_.type == TerrainType::kSlope)
    return Vec3(0.0, -std::sin(params_.slope_rad), std::cos(params_.slope_rad));
  return Vec3::UnitZ();
}

double Terrain::max_height_along(const Vec3& a, const Vec3& b, double radius_m) const {
  if (params_.type != TerrainType::kStairs)
    return std::max(height(a.x(), a.y()), height(b.x(), b.y()));
  // Stairs: height depends on y only and is monotone non-decreasing in y.
  return height(0.0, std::max(a.y(), b.y()) + radius_m);
}

double Terrain::mean_slope_rad() const { return hexdyn::mean_slope_rad(params_); }

double Terrain::edge_distance(double y) const {
  if (params_.type != TerrainType::kStairs || params_.riser_height_m == 0.0)
    return std::numeric_limits<double>::infinity();
  const int k = tread_index(y);
  const double inf = std::numeric_limits<double>::infinity();
  // Tread k spans [y_r + (k−1) b, y_r + k b); the ground (k = 0) has no nosing behind,
  // the top tread (k = steps) no riser ahead.
  const double start = k == 0 ? -inf : params_.first_riser_y_m + (k - 1) * params_.tread_depth_m;
  const double end = k == params_.steps ? inf : params_.first_riser_y_m + k * params_.tread_depth_m;
  return std::min(y - start, end - y);
}

double Terrain::nearest_valid_foothold_y(double y, double margin) const {
  if (const std::optional<double> valid = valid_foothold_y(y, margin)) return *valid;
  throw PlanningError("no foothold near y = " + std::to_string(y) + " m: tread depth " +
                      std::to_string(params_.tread_depth_m) +
                      " m is less than twice the foothold margin " + std::to_string(margin) + " m");
}

std::optional<double> Terrain::valid_foothold_y(double y, double margin) const {
  if (edge_distance(y) >= margin) return y;
  if (2.0 * margin > params_.tread_depth_m) return std::nullopt;
  // Candidates: the valid ends of the tread containing y and of its neighbours.
  const double b = params_.tread_depth_m, y0 = params_.first_riser_y_m;
  double best = y, best_d = std::numeric_limits<double>::infinity();
  const int k = tread_index(y);
  for (int kk = std::max(0, k - 1); kk <= std::min(params_.steps, k + 1); ++kk) {
    const double start = y0 + (kk - 1) * b, end = y0 + kk * b;
    for (double c : {start + margin, end - margin}) {
      if (edge_distance(c) + 1e-12 < margin) continue;
      if (std::abs(c - y) < best_d) {
        best_d = std::abs(c - y);
        best = c;
      }
    }
  }
  return best;
}

TerrainProfile terrain_profile(const TerrainParams& p, double y_min, double y_max) {
  const Terrain terrain(p);
  TerrainProfile out;
  auto vertex = [&](double y, double z) {
    out.y_m.push_back(y);
    out.z_m.push_back(z);
  };
  if (p.type != TerrainType::kStairs) {
    vertex(y_min, terrain.height(0.0, y_min));
    vertex(y_max, terrain.height(0.0, y_max));
    return out;
  }
  const double last_riser_y = p.first_riser_y_m + (p.steps - 1) * p.tread_depth_m;
  const double start = std::min(y_min, p.first_riser_y_m - p.tread_depth_m);
  const double end = std::max(y_max, last_riser_y + p.tread_depth_m);
  vertex(start, p.ground_height_m);
  for (int k = 1; k <= p.steps; ++k) {
    const double y = p.first_riser_y_m + (k - 1) * p.tread_depth_m;
    vertex(y, p.ground_height_m + (k - 1) * p.riser_height_m);
    vertex(y, p.ground_height_m + k * p.riser_height_m);
  }
  vertex(end, p.ground_height_m + p.steps * p.riser_height_m);
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
  }
  return "unknown";
}

}  // namespace hexdyn
