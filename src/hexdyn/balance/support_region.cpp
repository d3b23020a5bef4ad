#include "hexdyn/balance/support_region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hexdyn {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Nearest point of the segment [a, b] to p, and whether it is an interior point.
Vec2 segment_nearest(const Vec2& a, const Vec2& b, const Vec2& p, bool* interior) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double s = len2 > 0.0 ? (p - a).dot(d) / len2 : 0.0;
  *interior = s > 0.0 && s < 1.0;
  return a + std::clamp(s, 0.0, 1.0) * d;
}

/// The polygon clipped to the half-plane n·x ≥ c (Sutherland–Hodgman, one edge).
std::vector<Vec2> clip(const std::vector<Vec2>& poly, const Vec2& n, double c) {
  std::vector<Vec2> out;
  const int m = static_cast<int>(poly.size());
  for (int i = 0; i < m; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % m];
    const double da = n.dot(a) - c, db = n.dot(b) - c;
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

SupportRegion convex_hull(std::vector<Vec2> pts, double tol) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Vec2> unique;
  for (const Vec2& p : pts)
    if (std::none_of(unique.begin(), unique.end(),
                     [&](const Vec2& q) { return (p - q).norm() <= tol; }))
      unique.push_back(p);
  if (unique.size() <= 2) return SupportRegion{unique};
  // Andrew's monotone chain; a point within tol of the line of the last edge is not a corner.
  std::vector<Vec2> hull(2 * unique.size());
  int k = 0;
  const auto keep_turning = [&](const Vec2& p, int floor) {
    while (k >= floor) {
      const Vec2 d = hull[k - 1] - hull[k - 2];
      if (cross(d, p - hull[k - 2]) > tol * d.norm()) break;
      --k;
    }
  };
  for (const Vec2& p : unique) {
    keep_turning(p, 2);
    hull[k++] = p;
  }
  const int lower = k + 1;
  for (int i = static_cast<int>(unique.size()) - 2; i >= 0; --i) {
    keep_turning(unique[i], lower);
    hull[k++] = unique[i];
  }
  hull.resize(k - 1);
  if (hull.size() >= 3) return SupportRegion{hull};
  // Every point within tol of one line: the segment between the two farthest apart.
  Vec2 a = unique.front(), b = unique.back();
  return SupportRegion{{a, b}};
}

SupportRegion shrink(const SupportRegion& r, double margin) {
  const int m = static_cast<int>(r.vertices.size());
  if (m == 1 || margin <= 0.0) return r;
  if (m == 2) {
    const Vec2 a = r.vertices[0], b = r.vertices[1];
    const double len = (b - a).norm();
    if (len <= 2.0 * margin) return SupportRegion{{0.5 * (a + b)}};
    const Vec2 d = (b - a) / len;
    return SupportRegion{{a + margin * d, b - margin * d}};
  }
  std::vector<Vec2> poly = r.vertices;
  for (int i = 0; i < m && !poly.empty(); ++i) {
    const Vec2 a = r.vertices[i], b = r.vertices[(i + 1) % m];
    const Vec2 n = Vec2(-(b - a).y(), (b - a).x()).normalized();  // inward: the polygon is CCW
    poly = clip(poly, n, n.dot(a) + margin);
  }
  if (poly.size() < 3) return SupportRegion{};
  return SupportRegion{poly};
}

SupportRegion shrink_to_fit(const SupportRegion& r, double margin, double* used) {
  double m = margin;
  for (int i = 0; i <= 10; ++i, m *= 0.5) {
    SupportRegion s = shrink(r, m);
    if (!s.empty()) {
      if (used) *used = m;
      return s;
    }
  }
  if (used) *used = 0.0;
  return r;
}

namespace {

/// Whether p lies in the polygon r (on an edge counts): left of or on every edge, the sign
/// of depth() without its square roots.
bool inside(const SupportRegion& r, const Vec2& p) {
  const int m = static_cast<int>(r.vertices.size());
  for (int i = 0; i < m; ++i) {
    const Vec2 a = r.vertices[i], b = r.vertices[(i + 1) % m];
    if (cross(b - a, p - a) < 0.0) return false;
  }
  return true;
}

}  // namespace

Projection project(const SupportRegion& r, const Vec2& p) {
  Projection out;
  const int m = static_cast<int>(r.vertices.size());
  if (m == 1) {
    out.point = r.vertices[0];
    return out;
  }
  if (m >= 3 && inside(r, p)) {
    out.point = p;
    out.derivative.setIdentity();
    return out;
  }
  double best = std::numeric_limits<double>::infinity();
  const int edges = m == 2 ? 1 : m;
  for (int i = 0; i < edges; ++i) {
    const Vec2 a = r.vertices[i], b = r.vertices[(i + 1) % m];
    bool interior = false;
    const Vec2 q = segment_nearest(a, b, p, &interior);
    const double d = (q - p).norm();
    if (d < best) {
      best = d;
      out.point = q;
      const Vec2 t = (b - a).normalized();
      out.derivative = interior ? Mat2(t * t.transpose()) : Mat2::Zero();
    }
  }
  return out;
}

double depth(const SupportRegion& r, const Vec2& p) {
  const int m = static_cast<int>(r.vertices.size());
  if (m == 0) return -std::numeric_limits<double>::infinity();
  if (m == 1) return -(p - r.vertices[0]).norm();
  if (m == 2) {
    bool interior = false;
    return -(segment_nearest(r.vertices[0], r.vertices[1], p, &interior) - p).norm();
  }
  double inside = std::numeric_limits<double>::infinity();
  bool outside = false;
  for (int i = 0; i < m; ++i) {
    const Vec2 a = r.vertices[i], b = r.vertices[(i + 1) % m];
    const double s = cross(b - a, p - a) / (b - a).norm();  // > 0 left of the edge: inside
    inside = std::min(inside, s);
    outside = outside || s < 0.0;
  }
  if (!outside) return inside;
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m; ++i) {
    bool interior = false;
    d = std::min(
        d, (segment_nearest(r.vertices[i], r.vertices[(i + 1) % m], p, &interior) - p).norm());
  }
  return -d;
}

}  // namespace hexdyn
