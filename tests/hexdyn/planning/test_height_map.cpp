// Height maps (core/height_map.hpp) and the terrain queries on them (planning/terrain.hpp),
// against second computations: a plane and a paraboloid sampled on a grid (bilinear heights
// and gradients in closed form), a brute-force scan of every node for the clearance and the
// highest node under a segment.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "hexdyn/core/height_map.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {
namespace {

HeightMap grid(int nx, int ny, double x0, double y0, double r, double (*f)(double, double)) {
  HeightMap m;
  m.nx = nx;
  m.ny = ny;
  m.x0_m = x0;
  m.y0_m = y0;
  m.resolution_m = r;
  for (int i = 0; i < ny; ++i)
    for (int j = 0; j < nx; ++j) m.z_m.push_back(f(x0 + j * r, y0 + i * r));
  return m;
}

double plane(double x, double y) { return 0.3 + 0.2 * x - 0.1 * y; }

TEST_CASE("height map: a plane is reproduced exactly, with its normal", "[terrain][height_map]") {
  HeightMap m = grid(21, 31, -0.5, -1.0, 0.05, plane);
  prepare_height_map(m, 0.02, 0.35);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xs(-0.49, 0.49), ys(-0.99, 0.49);
  const Vec3 n = Vec3(-0.2, 0.1, 1.0).normalized();
  for (int k = 0; k < 500; ++k) {
    const double x = xs(rng), y = ys(rng);
    CHECK(m.height(x, y) == Approx(plane(x, y)).margin(1e-14));
    CHECK((m.normal(x, y) - n).norm() <= 1e-12);
  }
  // A gentle plane has no edge: every node keeps an infinite clearance.
  for (int i = 0; i < m.ny; ++i)
    for (int j = 0; j < m.nx; ++j) CHECK(std::isinf(m.node_clearance(i, j)));
}

double bowl(double x, double y) { return x * x + 0.5 * y * y; }

TEST_CASE("height map: bilinear heights and gradients inside each cell", "[terrain][height_map]") {
  const double r = 0.1;
  const HeightMap m = grid(11, 11, 0.0, 0.0, r, bowl);
  // Inside the cell [0.3, 0.4] × [0.5, 0.6]: the bilinear interpolant of the four corners.
  const double x = 0.33, y = 0.58, u = (x - 0.3) / r, w = (y - 0.5) / r;
  const double z00 = bowl(0.3, 0.5), z10 = bowl(0.4, 0.5), z01 = bowl(0.3, 0.6),
               z11 = bowl(0.4, 0.6);
  const double z = (1 - u) * (1 - w) * z00 + u * (1 - w) * z10 + (1 - u) * w * z01 + u * w * z11;
  CHECK(m.height(x, y) == Approx(z).epsilon(1e-14));
  const double dzdx = ((1 - w) * (z10 - z00) + w * (z11 - z01)) / r;
  const double dzdy = ((1 - u) * (z01 - z00) + u * (z11 - z10)) / r;
  CHECK(m.gradient(x, y).x() == Approx(dzdx).epsilon(1e-12));
  CHECK(m.gradient(x, y).y() == Approx(dzdy).epsilon(1e-12));
  // Outside the grid the border continues.
  CHECK(m.height(-1.0, 0.55) == Approx(m.height(0.0, 0.55)).epsilon(1e-14));
}

/// A map of flat ground with a raised block: its sides are edges.
HeightMap blocks() {
  HeightMap m;
  m.nx = 40;
  m.ny = 50;
  m.resolution_m = 0.02;
  m.x0_m = -0.4;
  m.y0_m = 0.0;
  for (int i = 0; i < m.ny; ++i)
    for (int j = 0; j < m.nx; ++j)
      m.z_m.push_back(i >= 20 && i < 30 && j >= 10 && j < 25 ? 0.05 : 0.0);
  return m;
}

TEST_CASE("height map: clearances are exact distances to the nearest no-foothold node",
          "[terrain][height_map]") {
  HeightMap m = blocks();
  prepare_height_map(m, 0.02, 0.35);
  // Brute force: the nodes with a neighbour 0.05 above or below, or a steep central slope.
  std::vector<std::pair<int, int>> bad;
  for (int i = 0; i < m.ny; ++i)
    for (int j = 0; j < m.nx; ++j) {
      bool b = false;
      for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int a = i + di, c = j + dj;
        if (a >= 0 && a < m.ny && c >= 0 && c < m.nx && std::abs(m.at(a, c) - m.at(i, j)) > 0.02)
          b = true;
      }
      if (b) bad.emplace_back(i, j);
    }
  REQUIRE(bad.size() > 20);
  // Between nodes: the distance to the nearest no-foothold node, exact at almost every point
  // (the nearest of the four corners' nearest), never an overestimate by more than a cell.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> xs(-0.4, 0.38), ys(0.0, 0.98);
  int exact = 0;
  for (int k = 0; k < 2000; ++k) {
    const double x = xs(rng), y = ys(rng);
    double d = std::numeric_limits<double>::infinity();
    for (const auto& [a, c] : bad) d = std::min(d, std::hypot(m.x(c) - x, m.y(a) - y));
    const double got = m.clearance(x, y);
    CHECK(got >= d - 1e-12);
    CHECK(got <= d + m.resolution_m);
    if (std::abs(got - d) <= 1e-12) ++exact;
  }
  CHECK(exact >= 1950);
  for (int i = 0; i < m.ny; ++i)
    for (int j = 0; j < m.nx; ++j) {
      double d = std::numeric_limits<double>::infinity();
      for (const auto& [a, c] : bad) d = std::min(d, std::hypot(a - i, c - j) * m.resolution_m);
      CHECK(m.node_clearance(i, j) == Approx(d).margin(1e-12));
    }
}

TEST_CASE("height map: the highest node under a segment, and footholds clear of edges",
          "[terrain][height_map]") {
  auto m = std::make_shared<HeightMap>(blocks());
  prepare_height_map(*m, 0.02, 0.35);
  TerrainParams p;
  p.type = TerrainType::kHeightMap;
  p.map = m;
  const Terrain terrain(p);
  // Across the block: its top; beside it, more than a cell and the radius away: the ground.
  CHECK(terrain.max_height_along(Vec3(0.0, 0.1, 0), Vec3(0.0, 0.9, 0)) == 0.05);
  CHECK(terrain.max_height_along(Vec3(0.2, 0.1, 0), Vec3(0.2, 0.9, 0)) == 0.0);
  CHECK(terrain.max_height_along(Vec3(0.2, 0.1, 0), Vec3(0.2, 0.9, 0), 0.2) == 0.05);
  // A foothold wanted on the block's edge moves along y to keep the margin.
  const double margin = 0.05;
  const auto y = terrain.valid_foothold_at(0.0, 0.4, margin);  // the block's near side
  REQUIRE(y.has_value());
  CHECK(terrain.edge_distance_at(0.0, *y) >= margin);
  CHECK(std::abs(*y - 0.4) <= 0.1);
  // The terrain's height is the map's; its normal the map's.
  CHECK(terrain.height(0.0, 0.5) == 0.05);
  CHECK(terrain.normal(0.3, 0.2) == Vec3::UnitZ());
}

}  // namespace
}  // namespace hexdyn
