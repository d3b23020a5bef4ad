// Support regions of the balanced trunk (balance/support_region.hpp,
// docs/theory/balance.md#support-regions) against brute force: the hull contains every point
// and each of its edges has every point on its inner side; a shrunk polygon's vertices lie at
// least the margin inside every edge of the original, and a point that deep lies in it; the
// projection is no farther than any of many sampled points of the region.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "hexdyn/balance/support_region.hpp"

namespace hexdyn {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Signed distance of p to the line of edge (a, b), positive on its left (inside a CCW hull).
double left_of(const Vec2& a, const Vec2& b, const Vec2& p) {
  return cross2(b - a, p - a) / (b - a).norm();
}

/// Points of the region: its vertices' random convex combinations.
std::vector<Vec2> samples(const SupportRegion& r, std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> out;
  for (int i = 0; i < n; ++i) {
    Vec2 p = Vec2::Zero();
    double sum = 0.0;
    for (const Vec2& v : r.vertices) {
      const double w = -std::log(u(rng) + 1e-300);
      p += w * v;
      sum += w;
    }
    out.push_back(p / sum);
  }
  for (const Vec2& v : r.vertices) out.push_back(v);
  return out;
}

TEST_CASE("support region: the hull holds every foot, edges with all feet inside",
          "[balance][support]") {
  std::mt19937 rng(4403u);
  std::uniform_real_distribution<double> x(-0.3, 0.3);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Vec2> feet;
    const int n = 3 + trial % 6;
    for (int i = 0; i < n; ++i) feet.push_back(Vec2(x(rng), x(rng)));
    const SupportRegion h = convex_hull(feet, 1e-12);
    REQUIRE(h.vertices.size() >= 3);
    const int m = static_cast<int>(h.vertices.size());
    for (int i = 0; i < m; ++i)
      for (const Vec2& f : feet)
        CHECK(left_of(h.vertices[i], h.vertices[(i + 1) % m], f) >= -1e-12);
    for (const Vec2& f : feet) CHECK(depth(h, f) >= -1e-12);
  }
  // Feet in a line give a segment between the outermost two; one foot (or two at one place) a
  // point.
  const SupportRegion line = convex_hull({{0, 0}, {0.1, 0.1}, {0.3, 0.3}, {0.2, 0.2}}, 1e-9);
  REQUIRE(line.vertices.size() == 2);
  CHECK((line.vertices[0] - Vec2(0, 0)).norm() + (line.vertices[1] - Vec2(0.3, 0.3)).norm() <
        1e-15);
  CHECK(convex_hull({{0.1, 0.2}, {0.1, 0.2}}, 1e-9).vertices.size() == 1);
}

TEST_CASE("support region: a shrunk polygon keeps the margin from every edge",
          "[balance][support]") {
  std::mt19937 rng(4404u);
  std::uniform_real_distribution<double> x(-0.3, 0.3);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Vec2> feet;
    for (int i = 0; i < 4; ++i) feet.push_back(Vec2(x(rng), x(rng)));
    const SupportRegion h = convex_hull(feet, 1e-12);
    const double margin = 0.02;
    const SupportRegion s = shrink(h, margin);
    const int m = static_cast<int>(h.vertices.size());
    for (const Vec2& v : s.vertices)
      for (int i = 0; i < m; ++i)
        CHECK(left_of(h.vertices[i], h.vertices[(i + 1) % m], v) >= margin - 1e-12);
    // A point at least the margin deep in the hull lies in the shrunk polygon.
    for (const Vec2& p : samples(h, rng, 200))
      if (depth(h, p) >= margin + 1e-9) CHECK(depth(s, p) >= -1e-12);
  }
  // A segment's ends move in by the margin.
  const SupportRegion seg = shrink(SupportRegion{{{0, 0}, {0.5, 0}}}, 0.1);
  REQUIRE(seg.vertices.size() == 2);
  CHECK((seg.vertices[0] - Vec2(0.1, 0)).norm() < 1e-15);
  CHECK((seg.vertices[1] - Vec2(0.4, 0)).norm() < 1e-15);
}

TEST_CASE("support region: the projection is the nearest point", "[balance][support]") {
  std::mt19937 rng(4405u);
  std::uniform_real_distribution<double> x(-0.4, 0.4);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Vec2> feet;
    const int n = 2 + trial % 4;
    for (int i = 0; i < n; ++i) feet.push_back(Vec2(x(rng), x(rng)));
    const SupportRegion r = convex_hull(feet, 1e-12);
    const auto pts = samples(r, rng, 3000);
    for (int q = 0; q < 10; ++q) {
      const Vec2 p(x(rng), x(rng));
      const Projection pr = project(r, p);
      CHECK(depth(r, pr.point) >= -1e-12);
      double best = 1e300;
      for (const Vec2& s : pts) best = std::min(best, (s - p).norm());
      CHECK((pr.point - p).norm() <= best + 1e-12);
      // The derivative against differences of the projection.
      const double h = 1e-7;
      for (int axis = 0; axis < 2; ++axis) {
        Vec2 d = Vec2::Zero();
        d[axis] = h;
        const Vec2 fd = (project(r, p + d).point - project(r, p - d).point) / (2.0 * h);
        CHECK((pr.derivative.col(axis) - fd).norm() < 1e-5);
      }
    }
  }
}

}  // namespace
}  // namespace hexdyn
