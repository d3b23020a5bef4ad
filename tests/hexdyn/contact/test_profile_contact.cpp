// terrain_contact's search of the profile (contact/simulation_contact.hpp) against the
// exhaustive scan it prunes: random profiles with y non-decreasing, points near them, on their
// vertices and far away; the pruned search must give the full scan's answer bit for bit.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

#include "hexdyn/contact/simulation_contact.hpp"

using namespace hexdyn;

namespace {

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// Every segment of the profile measured, the height taken from every segment over py: the
/// exhaustive scan that terrain_contact's candidate segments must agree with exactly.
TerrainContactPoint terrain_contact_by_full_scan(const std::vector<double>& y,
                                                 const std::vector<double>& z, const Vec3& p,
                                                 double radius) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::size_t last = y.size() - 2;
  double best = inf, by = 0.0, bz = 0.0;
  std::size_t seg = 0;
  bool vertex = false;
  for (std::size_t k = 0; k <= last; ++k) {
    const double dy = y[k + 1] - y[k], dz = z[k + 1] - z[k], len2 = dy * dy + dz * dz;
    if (len2 == 0.0) continue;
    const double u = ((p.y() - y[k]) * dy + (p.z() - z[k]) * dz) / len2;
    const double uc =
        std::clamp(u, k == 0 && dy > 0.0 ? -inf : 0.0, k == last && dy > 0.0 ? inf : 1.0);
    const double cy = y[k] + uc * dy, cz = z[k] + uc * dz;
    const double d2 = (p.y() - cy) * (p.y() - cy) + (p.z() - cz) * (p.z() - cz);
    const bool v = uc == 0.0 || uc == 1.0;
    if (d2 < best || (d2 == best && vertex && !v)) best = d2, by = cy, bz = cz, seg = k, vertex = v;
  }
  double h = z.front();
  const auto on = [&](std::size_t k) {
    const double dy = y[k + 1] - y[k];
    return dy > 0.0 ? z[k] + (z[k + 1] - z[k]) * (p.y() - y[k]) / dy : z[k + 1];
  };
  if (p.y() < y.front()) {
    h = on(0);
  } else if (p.y() > y.back()) {
    h = on(last);
  } else {
    for (std::size_t k = 0; k <= last; ++k)
      if (p.y() >= y[k] && p.y() <= y[k + 1] && y[k + 1] > y[k]) h = on(k);
  }
  const double dist = p.z() < h ? -std::sqrt(best) : std::sqrt(best);
  TerrainContactPoint out;
  out.penetration_m = radius - dist;
  const auto normal_of = [&](std::size_t k) {
    const double dy = y[k + 1] - y[k], dz = z[k + 1] - z[k], len = std::hypot(dy, dz);
    return Vec3(0.0, -dz / len, dy / len);
  };
  const Vec3 away(0.0, p.y() - by, p.z() - bz);
  if (!vertex) {
    out.normal_W = normal_of(seg);
  } else if (away.norm() > 0.0) {
    out.normal_W = (dist < 0.0 ? -away : away).normalized();
  } else {
    const std::size_t v = (by == y[seg] && bz == z[seg]) ? seg : seg + 1;
    Vec3 sum = Vec3::Zero();
    for (std::size_t k = v > 0 ? v - 1 : 0; k <= v && k + 1 < y.size(); ++k)
      if (y[k + 1] != y[k] || z[k + 1] != z[k]) sum += normal_of(k);
    out.normal_W = sum.norm() > 0.0 ? Vec3(sum.normalized()) : Vec3(Vec3::UnitZ());
  }
  out.point_W = radius > 0.0 ? Vec3(p - radius * out.normal_W) : p;
  return out;
}

}  // namespace

TEST_CASE("terrain_contact measures only the segments that can be nearest: the full scan's answer",
          "[contact]") {
  // Random profiles with y non-decreasing (the precondition): treads, vertical risers up and
  // down, slopes, repeated vertices; points near them, on their vertices, at a riser's exact
  // y and far away. terrain_contact skips the segments farther in y than the segment over the
  // point; the answer must be the exhaustive scan's, bit for bit.
  std::mt19937 rng(4711);
  int compared = 0;
  for (int profile = 0; profile < 200; ++profile) {
    std::vector<double> y{uniform(rng, -1.0, 0.0)}, z{uniform(rng, -0.1, 0.1)};
    const int vertices = 2 + profile % 30;
    while (static_cast<int>(y.size()) < vertices) {
      const double r = uniform(rng, 0.0, 1.0);
      if (r < 0.35) {  // a riser, up or down
        y.push_back(y.back());
        z.push_back(z.back() + uniform(rng, -0.12, 0.15));
      } else if (r < 0.4) {  // a repeated vertex
        y.push_back(y.back());
        z.push_back(z.back());
      } else {  // a tread or a slope
        y.push_back(y.back() + uniform(rng, 0.01, 0.4));
        z.push_back(z.back() + (r < 0.8 ? 0.0 : uniform(rng, -0.1, 0.1)));
      }
    }
    for (int trial = 0; trial < 200; ++trial) {
      const std::size_t k = static_cast<std::size_t>(trial) % y.size();
      Vec3 p(0.0, uniform(rng, y.front() - 0.5, y.back() + 0.5), uniform(rng, -0.4, 0.6));
      if (trial % 7 == 0) p = Vec3(0.0, y[k], z[k]);                              // a vertex
      if (trial % 7 == 1) p = Vec3(0.0, y[k], z[k] + uniform(rng, -0.05, 0.05));  // its y
      if (trial % 7 == 2) p *= 30.0;                                              // far away
      for (double radius : {0.0, 0.01}) {
        const TerrainContactPoint got = terrain_contact(y, z, p, radius);
        const TerrainContactPoint want = terrain_contact_by_full_scan(y, z, p, radius);
        INFO("profile " << profile << " of " << y.size() << " vertices, p = (" << p.y() << ", "
                        << p.z() << "), radius " << radius);
        REQUIRE(got.penetration_m == want.penetration_m);
        REQUIRE(got.normal_W == want.normal_W);
        REQUIRE(got.point_W == want.point_W);
        ++compared;
      }
    }
  }
  CHECK(compared == 80000);
}
