// Terrain queries (terrain.hpp) against heights, normals and edge distances worked out
// in the test from the parameters: riser positions listed one by one, slope tangents,
// and brute-force scans along segments.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {
namespace {

/// A staircase whose numbers are exact in binary, so that riser positions computed in
/// the test are the very doubles the terrain sees.
TerrainParams test_stairs() {
  TerrainParams p;
  p.type = TerrainType::kStairs;
  p.ground_height_m = 0.125;
  p.riser_height_m = 0.0625;
  p.tread_depth_m = 0.25;
  p.steps = 4;
  p.first_riser_y_m = 0.5;
  return p;
}

/// y of the risers: 0.5, 0.75, 1.0, 1.25.
std::vector<double> riser_positions() { return {0.5, 0.75, 1.0, 1.25}; }

/// Height by counting the risers at or behind y.
double counted_height(double y) {
  int count = 0;
  for (double r : riser_positions())
    if (y >= r) ++count;
  return 0.125 + 0.0625 * count;
}

/// Distance to the nearest edge of the tread containing y, by listing the edges.
double listed_edge_distance(double y) {
  const auto r = riser_positions();
  if (y < r.front()) return r.front() - y;
  if (y >= r.back()) return y - r.back();
  for (std::size_t k = 0; k + 1 < r.size(); ++k)
    if (y >= r[k] && y < r[k + 1]) return std::min(y - r[k], r[k + 1] - y);
  return -1.0;
}

TEST_CASE("stairs: heights on both sides of every riser", "[terrain]") {
  const Terrain terrain(test_stairs());
  const auto risers = riser_positions();
  for (std::size_t k = 0; k < risers.size(); ++k) {
    const double below = 0.125 + 0.0625 * static_cast<double>(k);
    const double above = below + 0.0625;
    for (double x : {-0.3, 0.0, 0.7}) {
      CHECK(terrain.height(x, risers[k] - 1e-9) == below);
      CHECK(terrain.height(x, risers[k] - 0.2) == below);
      CHECK(terrain.height(x, risers[k]) == above);  // at the riser the upper tread counts
      CHECK(terrain.height(x, risers[k] + 1e-9) == above);
      CHECK(terrain.height(x, risers[k] + 0.1) == above);
    }
  }
  // Before the first riser: the ground, however far back.
  CHECK(terrain.height(0.0, -100.0) == 0.125);
  // The top tread is endless.
  for (double y : {1.25, 1.6, 10.0, 1e4}) CHECK(terrain.height(0.2, y) == 0.125 + 4 * 0.0625);
  // Dense comparison with the counted height.
  for (int i = 0; i <= 4000; ++i) {
    const double y = -0.5 + 2.5 * i / 4000.0;
    CHECK(terrain.height(0.1, y) == counted_height(y));
  }
}

TEST_CASE("stairs: normals are +z and the mean slope is atan(h/b)", "[terrain]") {
  const Terrain terrain(test_stairs());
  for (double y : {-1.0, 0.5, 0.6, 0.99, 1.3, 50.0}) CHECK(terrain.normal(0.3, y) == Vec3::UnitZ());
  CHECK(std::abs(terrain.mean_slope_rad() - std::atan(0.0625 / 0.25)) <= 1e-15);
}

TEST_CASE("stairs: max height along a segment crossing several risers", "[terrain]") {
  const Terrain terrain(test_stairs());
  auto scanned = [&](const Vec3& a, const Vec3& b) {
    double m = -std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 20000; ++i) {
      const Vec3 p = a + (b - a) * (i / 20000.0);
      m = std::max(m, counted_height(p.y()));
    }
    return m;
  };
  const std::vector<std::pair<Vec3, Vec3>> segments = {
      {Vec3(0.0, 0.1, 0.3), Vec3(0.2, 1.1, 0.4)},    // crosses three risers
      {Vec3(0.2, 1.1, 0.0), Vec3(0.0, 0.1, 0.0)},    // the same, backwards
      {Vec3(-0.1, 0.55, 0.0), Vec3(0.1, 0.7, 0.0)},  // on one tread
      {Vec3(0.0, -2.0, 0.0), Vec3(0.0, 0.4, 0.0)},   // on the ground
      {Vec3(0.0, 0.3, 0.0), Vec3(0.0, 3.0, 0.0)},    // onto the endless top
      {Vec3(0.0, 0.8, 0.0), Vec3(0.0, 0.8, 0.0)},    // a point
  };
  for (const auto& [a, b] : segments) {
    INFO("a " << a.transpose() << " b " << b.transpose());
    CHECK(terrain.max_height_along(a, b) == scanned(a, b));
  }
  CHECK(terrain.max_height_along(Vec3(0, 0.1, 0), Vec3(0, 1.1, 0)) == 0.125 + 3 * 0.0625);
  // A sphere's shadow: the segment widened by r at both ends, scanned.
  for (double r : {0.01, 0.03, 0.2})
    for (const auto& [a, b] : segments) {
      INFO("r " << r << " a " << a.transpose() << " b " << b.transpose());
      const Vec3 back = a.y() <= b.y() ? a : b, front = a.y() <= b.y() ? b : a;
      CHECK(terrain.max_height_along(a, b, r) ==
            scanned(back - Vec3(0.0, r, 0.0), front + Vec3(0.0, r, 0.0)));
    }
  // 0.03 short of the next riser: only a sphere of radius 0.03 or more reaches it.
  CHECK(terrain.max_height_along(Vec3(0, 0.6, 0), Vec3(0, 0.72, 0), 0.0299) == 0.125 + 0.0625);
  CHECK(terrain.max_height_along(Vec3(0, 0.6, 0), Vec3(0, 0.72, 0), 0.03) == 0.125 + 2 * 0.0625);
}

TEST_CASE("stairs: edge distance to the nearest nosing or riser", "[terrain]") {
  const Terrain terrain(test_stairs());
  for (int i = 0; i <= 3000; ++i) {
    const double y = -0.5 + 2.5 * i / 3000.0;
    INFO("y " << y);
    CHECK(std::abs(terrain.edge_distance(y) - listed_edge_distance(y)) <= 1e-15);
  }
  CHECK(terrain.edge_distance(0.625) == 0.125);  // mid-tread
  CHECK(terrain.edge_distance(0.5) == 0.0);      // on a riser
  CHECK(terrain.edge_distance(-3.0) == 3.5);     // ground: only the first riser ahead
  CHECK(terrain.edge_distance(5.25) == 4.0);     // top: only the last nosing behind
}

TEST_CASE("stairs: nearest valid foothold keeps valid points, moves the others to the margin",
          "[terrain]") {
  const Terrain terrain(test_stairs());
  const double margin = 0.03;
  int moved = 0;
  for (int i = 0; i <= 3000; ++i) {
    const double y = -0.2 + 2.0 * i / 3000.0;
    const double yv = terrain.nearest_valid_foothold_y(y, margin);
    INFO("y " << y << " -> " << yv);
    if (listed_edge_distance(y) >= margin) {
      CHECK(yv == y);
      continue;
    }
    ++moved;
    // Nearest edge and the side of it y is on; the nearest valid point is the margin
    // away from that edge on the same side (the other side is farther).
    double edge = riser_positions().front();
    for (double r : riser_positions())
      if (std::abs(r - y) < std::abs(edge - y)) edge = r;
    CHECK(std::abs(listed_edge_distance(yv) - margin) <= 1e-12);
    if (y != edge) {
      const double expected = edge + (y > edge ? margin : -margin);
      CHECK(std::abs(yv - expected) <= 1e-12);
      CHECK(std::abs(yv - y) < margin);
    } else {
      CHECK(std::abs(std::abs(yv - edge) - margin) <= 1e-12);
    }
  }
  CHECK(moved > 100);
  // Exactly on a riser: either side is as near.
  const double on_riser = terrain.nearest_valid_foothold_y(0.75, margin);
  CHECK(std::abs(std::abs(on_riser - 0.75) - margin) <= 1e-12);
}

TEST_CASE("stairs: no foothold when the tread is shallower than twice the margin", "[terrain]") {
  TerrainParams p = test_stairs();
  p.tread_depth_m = 0.03;
  const Terrain terrain(p);
  // Inside the flight neither the tread nor its neighbours can take the foot.
  CHECK_THROWS_AS(terrain.nearest_valid_foothold_y(0.545, 0.02), PlanningError);
  CHECK_THROWS_WITH(terrain.nearest_valid_foothold_y(0.545, 0.02), Catch::Contains("y = 0.545"));
  CHECK_FALSE(terrain.valid_foothold_y(0.55, 0.02).has_value());
  // On the first tread the ground before it is a neighbour deep enough: 0.48, margin behind
  // the first riser (a shallow tread does not condemn the deep ones beside it).
  CHECK(std::abs(terrain.nearest_valid_foothold_y(0.51, 0.02) - 0.48) <= 1e-12);
  const std::optional<double> mid = terrain.valid_foothold_y(0.51, 0.015);  // 2 · margin = depth
  REQUIRE(mid.has_value());
  CHECK(std::abs(*mid - 0.515) <= 1e-12);
  // Far from the stairs the ground is deep enough.
  CHECK(terrain.nearest_valid_foothold_y(-1.0, 0.02) == -1.0);
}

TEST_CASE("flat ground: constant height, +z normal, no edges", "[terrain]") {
  TerrainParams p;
  p.type = TerrainType::kFlat;
  p.ground_height_m = -0.3;
  const Terrain terrain(p);
  for (double y : {-10.0, 0.0, 0.25, 7.0}) {
    CHECK(terrain.height(1.0, y) == -0.3);
    CHECK(terrain.normal(1.0, y) == Vec3::UnitZ());
    CHECK(std::isinf(terrain.edge_distance(y)));
    CHECK(terrain.nearest_valid_foothold_y(y, 0.02) == y);
  }
  CHECK(terrain.max_height_along(Vec3(0, -1, 0), Vec3(0, 3, 0)) == -0.3);
  CHECK(terrain.mean_slope_rad() == 0.0);
}

TEST_CASE("slope: heights along the incline and normals perpendicular to it", "[terrain]") {
  for (double angle : {0.2, -0.35, 0.6}) {
    TerrainParams p;
    p.type = TerrainType::kSlope;
    p.slope_rad = angle;
    p.slope_origin_y_m = 0.4;
    p.ground_height_m = 0.1;
    const Terrain terrain(p);
    const Vec3 along(0.0, std::cos(angle), std::sin(angle));
    for (double y : {-1.0, 0.0, 0.4, 1.3, 4.0}) {
      INFO("angle " << angle << " y " << y);
      // Travelling d along the incline from its origin rises d sin(a) over d cos(a).
      const double d = (y - 0.4) / std::cos(angle);
      CHECK(std::abs(terrain.height(-0.2, y) - (0.1 + d * std::sin(angle))) <= 1e-14);
      const Vec3 n = terrain.normal(-0.2, y);
      CHECK(std::abs(n.norm() - 1.0) <= 1e-15);
      CHECK(std::abs(n.dot(along)) <= 1e-15);
      CHECK(std::abs(n.x()) <= 1e-15);
      CHECK(n.z() > 0.0);
      // The surface tangent from two height samples is perpendicular too.
      const Vec3 tangent(0.0, 0.01, terrain.height(0.0, y + 0.01) - terrain.height(0.0, y));
      CHECK(std::abs(n.dot(tangent.normalized())) <= 1e-12);
    }
    // Highest point of a segment: the upper end, found by scanning.
    const Vec3 a(0.0, -0.5, 0.0), b(0.3, 1.5, 0.0);
    double m = -1e9;
    for (int i = 0; i <= 1000; ++i)
      m = std::max(m, terrain.height(0.0, a.y() + (b.y() - a.y()) * i / 1000.0));
    CHECK(std::abs(terrain.max_height_along(a, b) - m) <= 1e-14);
    CHECK(std::isinf(terrain.edge_distance(0.3)));
    CHECK(terrain.mean_slope_rad() == angle);
  }
}

/// The polyline's height at y: linear between the vertices around y (the upper of two
/// vertices of equal y, as Terrain::height at a riser).
double polyline_height(const TerrainProfile& p, double y) {
  for (std::size_t k = p.y_m.size() - 1; k > 0; --k)
    if (p.y_m[k - 1] <= y && y <= p.y_m[k]) {
      if (p.y_m[k] == p.y_m[k - 1]) return p.z_m[k];
      const double w = (y - p.y_m[k - 1]) / (p.y_m[k] - p.y_m[k - 1]);
      return p.z_m[k - 1] + w * (p.z_m[k] - p.z_m[k - 1]);
    }
  return std::numeric_limits<double>::quiet_NaN();
}

TEST_CASE("terrain profile: the polyline equals the height function at random y", "[terrain]") {
  TerrainParams slope;
  slope.type = TerrainType::kSlope;
  slope.slope_rad = 0.2;
  slope.slope_origin_y_m = 0.3;
  slope.ground_height_m = 0.01;
  TerrainParams flat;
  flat.type = TerrainType::kFlat;
  flat.ground_height_m = -0.02;
  std::mt19937 rng(21);
  for (const TerrainParams& params : {test_stairs(), slope, flat}) {
    const Terrain terrain(params);
    const double y_min = -0.4, y_max = 0.9;  // inside the stairs: the profile still covers all
    const TerrainProfile p = terrain_profile(params, y_min, y_max);
    REQUIRE(p.y_m.size() == p.z_m.size());
    REQUIRE(p.y_m.size() >= 2);
    CHECK(p.y_m.front() <= y_min);
    CHECK(p.y_m.back() >= y_max);
    for (std::size_t k = 1; k < p.y_m.size(); ++k) CHECK(p.y_m[k] >= p.y_m[k - 1]);
    std::uniform_real_distribution<double> y_of(p.y_m.front(), p.y_m.back());
    for (int i = 0; i < 2000; ++i) {
      const double y = y_of(rng);
      INFO("type " << static_cast<int>(params.type) << " y " << y);
      CHECK(polyline_height(p, y) == Approx(terrain.height(0.0, y)).margin(1e-12));
    }
    if (params.type == TerrainType::kStairs) {
      // Every riser, vertical: two vertices at its y, from the tread below to the one above;
      // ground before the first and top tread after the last, a tread depth at least.
      const std::vector<double> risers = riser_positions();
      REQUIRE(p.y_m.size() == 2 * risers.size() + 2);
      for (std::size_t k = 0; k < risers.size(); ++k) {
        CHECK(p.y_m[1 + 2 * k] == risers[k]);
        CHECK(p.y_m[2 + 2 * k] == risers[k]);
        CHECK(p.z_m[1 + 2 * k] == 0.125 + 0.0625 * k);
        CHECK(p.z_m[2 + 2 * k] == 0.125 + 0.0625 * (k + 1));
      }
      CHECK(p.y_m.front() <= 0.25);
      CHECK(p.y_m.back() >= 1.5);
      CHECK(p.z_m.back() == 0.125 + 4 * 0.0625);
    } else {
      CHECK(p.y_m.size() == 2);
    }
  }
  CHECK(terrain_type_name(TerrainType::kStairs) == "stairs");
  CHECK(terrain_type_name(TerrainType::kSlope) == "slope");
  CHECK(terrain_type_name(TerrainType::kFlat) == "flat");
}

}  // namespace
}  // namespace hexdyn
