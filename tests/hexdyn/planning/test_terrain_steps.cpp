// Stairs step by step, descending and with nosings (terrain.hpp, core/stairs.hpp), against
// edges and heights built here from the list by plain running sums, and brute-force scans of
// the height function along y.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {
namespace {

/// A list of steps with a landing, a falling riser, unequal goings and nosings.
TerrainParams listed_stairs() {
  TerrainParams p;
  p.type = TerrainType::kStairs;
  p.ground_height_m = 0.1;
  p.first_riser_y_m = 0.4;
  p.step_list = {{0.05, 0.25, 0.0},  {0.07, 0.3, 0.02},  {0.0, 0.8, 0.0},
                 {0.04, 0.2, 0.025}, {-0.06, 0.3, 0.03}, {-0.05, 0.35, 0.0}};
  p.steps = static_cast<int>(p.step_list.size());
  return p;
}

struct Edge {
  double y, below_behind, above_ahead;  // the edge's y; the tread heights before and after it
};

/// The edges of listed_stairs, by hand: riser k at 0.4 + Σ goings before it, moved by its
/// nosing towards the lower tread; the landing (zero riser) has none.
std::vector<Edge> hand_edges() {
  return {{0.4, 0.1, 0.15},
          {0.65 - 0.02, 0.15, 0.22},
          // 0.95: the landing, no edge; the next riser at 0.95 + 0.8
          {1.75 - 0.025, 0.22, 0.26},
          {1.95 + 0.03, 0.26, 0.20},
          {2.25, 0.20, 0.15}};
}

/// Height by the hand edges: the tread behind the last edge at or before y.
double hand_height(double y) {
  double z = 0.1;
  for (const Edge& e : hand_edges())
    if (y >= e.y) z = e.above_ahead;
  return z;
}

TEST_CASE("step list: edges, heights and the profile equal the hand-built ones", "[terrain]") {
  const Terrain terrain(listed_stairs());
  const auto edges = hand_edges();
  REQUIRE(terrain.edge_count() == static_cast<int>(edges.size()));
  const std::vector<int> steps{1, 2, 4, 5, 6};
  for (int k = 1; k <= terrain.edge_count(); ++k) {
    CHECK(terrain.edge_y(k) == Approx(edges[k - 1].y).margin(1e-15));
    CHECK(terrain.tread_height(k) == Approx(edges[k - 1].above_ahead).margin(1e-15));
    CHECK(terrain.edge_step(k) == steps[k - 1]);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ys(-1.0, 4.0);
  const TerrainProfile prof = terrain_profile(listed_stairs(), -0.5, 3.0);
  for (int i = 0; i < 2000; ++i) {
    const double y = ys(rng);
    bool on_edge = false;
    for (const Edge& e : edges) on_edge = on_edge || std::abs(y - e.y) < 1e-9;
    if (on_edge) continue;
    CHECK(terrain.height(0.3, y) == Approx(hand_height(y)).margin(1e-15));
    if (y > prof.y_m.front() && y < prof.y_m.back()) {
      // The profile's polyline at y: the segment that contains it (edges are vertical).
      const auto it = std::upper_bound(prof.y_m.begin(), prof.y_m.end(), y);
      const std::size_t j = static_cast<std::size_t>(it - prof.y_m.begin());
      const double w = (y - prof.y_m[j - 1]) / (prof.y_m[j] - prof.y_m[j - 1]);
      CHECK(prof.z_m[j - 1] + w * (prof.z_m[j] - prof.z_m[j - 1]) ==
            Approx(hand_height(y)).margin(1e-15));
    }
  }
}

TEST_CASE("step list: edge distance, footholds and the highest terrain under a segment",
          "[terrain]") {
  const Terrain terrain(listed_stairs());
  const auto edges = hand_edges();
  auto hand_edge_distance = [&](double y) {
    double d = std::numeric_limits<double>::infinity();
    // The edges bounding y's tread: the last at or before y and the first after it.
    double behind = -std::numeric_limits<double>::infinity(), ahead = -behind;
    for (const Edge& e : edges) {
      if (e.y <= y) behind = std::max(behind, e.y);
      if (e.y > y) ahead = std::min(ahead, e.y);
    }
    d = std::min(y - behind, ahead - y);
    return d;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ys(-0.5, 3.0), span(0.0, 0.6);
  const double margin = 0.03;
  for (int i = 0; i < 3000; ++i) {
    const double y = ys(rng);
    CHECK(terrain.edge_distance(y) == Approx(hand_edge_distance(y)).margin(1e-14));
    const auto v = terrain.valid_foothold_y(y, margin);
    REQUIRE(v.has_value());  // every tread here is deeper than 2 · margin
    CHECK(hand_edge_distance(*v) >= margin - 1e-12);
    // The nearest valid y: no valid y in a scan lies closer to y.
    if (*v != y)
      for (double s = -0.2; s <= 0.2; s += 1e-3)
        if (hand_edge_distance(y + s) >= margin + 1e-9)
          CHECK(std::abs(s) >= std::abs(*v - y) - 1e-9);
    // Highest terrain under [y, y + s] widened by r: a scan of the hand heights.
    const double s = span(rng), r = (i % 3) * 0.01;
    double scan = -1.0;
    for (int k = 0; k <= 4000; ++k)
      scan = std::max(scan, hand_height(y - r + (s + 2 * r) * k / 4000.0));
    for (const Edge& e : edges)  // an edge inside the span: both of its treads count
      if (e.y >= y - r && e.y <= y + s + r) scan = std::max({scan, e.below_behind, e.above_ahead});
    CHECK(terrain.max_height_along(Vec3(0, y, 0), Vec3(0.2, y + s, 0), r) ==
          Approx(scan).margin(1e-15));
  }
}

TEST_CASE("uniform stairs descending and with a nosing", "[terrain]") {
  TerrainParams p;
  p.type = TerrainType::kStairs;
  p.ground_height_m = 0.5;
  p.riser_height_m = -0.0625;
  p.tread_depth_m = 0.25;
  p.steps = 4;
  p.first_riser_y_m = 0.5;
  const Terrain down(p);
  for (int k = 0; k < 4; ++k) {
    const double y = 0.5 + 0.25 * k;
    CHECK(down.height(0, y - 1e-9) == 0.5 - 0.0625 * k);
    CHECK(down.height(0, y + 1e-9) == 0.5 - 0.0625 * (k + 1));
    // A swing over the edge: the higher tread, behind it, counts.
    CHECK(down.max_height_along(Vec3(0, y - 0.1, 0), Vec3(0, y + 0.1, 0)) == 0.5 - 0.0625 * k);
  }
  // A nosing moves every edge towards the lower tread: ahead on the way down, back on the way up.
  p.nosing_m = 0.03125;
  const Terrain down_nosed(p);
  p.riser_height_m = 0.0625;
  const Terrain up_nosed(p);
  for (int k = 1; k <= 4; ++k) {
    CHECK(down_nosed.edge_y(k) == 0.5 + 0.25 * (k - 1) + 0.03125);
    CHECK(up_nosed.edge_y(k) == 0.5 + 0.25 * (k - 1) - 0.03125);
  }
  CHECK(up_nosed.height(0, 0.5 - 0.02) == 0.5 + 0.0625);        // on the nosing
  CHECK(down_nosed.height(0, 0.5 + 0.02) == 0.5);               // on the nosing
  CHECK(up_nosed.edge_distance(0.6) == Approx(0.71875 - 0.6));  // the next nosing ahead
}

}  // namespace
}  // namespace hexdyn
