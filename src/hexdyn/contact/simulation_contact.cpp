#include "hexdyn/contact/simulation_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/contact/impact.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {

double sliding_friction_coefficient(const ContactParams& c, double s) {
  const double vs = c.stiction_velocity_mps, vd = c.friction_velocity_mps;
  if (s < vs) return -impact_step(s, -vs, c.static_friction, vs, -c.static_friction);
  if (s <= vd) return impact_step(s, vs, c.static_friction, vd, c.dynamic_friction);
  return c.dynamic_friction;
}

double sliding_friction_slope(const ContactParams& c, double s) {
  const double vs = c.stiction_velocity_mps, vd = c.friction_velocity_mps;
  if (s < vs) return -impact_step_derivative(s, -vs, c.static_friction, vs, -c.static_friction);
  if (s <= vd) return impact_step_derivative(s, vs, c.static_friction, vd, c.dynamic_friction);
  return 0.0;
}

FootContactForce foot_contact_force(const ContactParams& c, double delta, const Vec3& n,
                                    const Vec3& v) {
  FootContactForce f;
  if (!(delta > 0.0)) return f;
  const double delta_rate = -n.dot(v);
  const double spring = c.stiffness * std::pow(delta, c.exponent);
  const double fn = impact_normal_force(c, delta, delta_rate);
  f.normal_N = fn;
  f.damping_power_W = (fn - spring) * delta_rate;
  const Mat3 P = Mat3::Identity() - n * n.transpose();
  const Vec3 vt = P * v;
  f.slip_velocity_W = vt;
  const double s = vt.norm();
  // μ(s)/s: its limit 1.5 μ_s / v_s at s → 0 (the STEP's slope at the origin).
  const double mu = sliding_friction_coefficient(c, s);
  const double mu_over_s = s > 1e-12 * c.stiction_velocity_mps
                               ? mu / s
                               : 1.5 * c.static_friction / c.stiction_velocity_mps;
  f.tangential_W = -mu_over_s * fn * vt;
  f.force_W = fn * n + f.tangential_W;
  f.slip_power_W = -f.tangential_W.dot(vt);
  // Linearisation: ∂F_n/∂v and ∂F_n/∂p (unclipped), then the tangential part.
  Vec3 dfn_dv = Vec3::Zero(), dfn_dp = Vec3::Zero();
  if (fn > 0.0) {
    const double step = impact_step(delta, 0.0, 0.0, c.full_damping_depth_m, 1.0);
    const double dstep = impact_step_derivative(delta, 0.0, 0.0, c.full_damping_depth_m, 1.0);
    dfn_dv = -c.damping_max_Nspm * step * n;
    const double dfn_ddelta = c.stiffness * c.exponent * std::pow(delta, c.exponent - 1.0) +
                              c.damping_max_Nspm * dstep * delta_rate;
    dfn_dp = -dfn_ddelta * n;
  }
  const Vec3 t_dir = s > 0.0 ? Vec3(vt / s) : Vec3::Zero();
  const double dmu = sliding_friction_slope(c, s);
  const Mat3 dvt =
      s > 1e-12 * c.stiction_velocity_mps
          ? Mat3(dmu * t_dir * t_dir.transpose() + mu_over_s * (P - t_dir * t_dir.transpose()))
          : Mat3(mu_over_s * P);
  f.dF_dv = n * dfn_dv.transpose() - mu_over_s * vt * dfn_dv.transpose() - fn * dvt * P;
  f.dF_dp = n * dfn_dp.transpose() - mu_over_s * vt * dfn_dp.transpose();
  return f;
}

namespace {

/// The feature of the profile nearest to a point in the (y, z) plane: a face (a segment's
/// interior, or the outer ray of an end segment) or a vertex.
struct NearestFeature {
  double distance2 = std::numeric_limits<double>::infinity();  ///< squared distance [m²]
  double cy = 0.0, cz = 0.0;  ///< the nearest point of the profile [m]
  std::size_t segment = 0;    ///< the segment it was found on (from vertex segment..segment+1)
  bool vertex = false;        ///< the nearest point is a vertex (not a face's interior)
};

/// Outward unit normal (y, z) of segment k: left of the direction of increasing y, so up on a
/// tread, −y on a rising riser, +y on a falling one.
Vec3 segment_normal(const std::vector<double>& y, const std::vector<double>& z, std::size_t k) {
  const double dy = y[k + 1] - y[k], dz = z[k + 1] - z[k];
  const double len = std::hypot(dy, dz);
  return Vec3(0.0, -dz / len, dy / len);
}

/// Squared distance from (py, pz) to segment k of the polyline (the first and last segments
/// continued as rays beyond the ends, unless vertical) and its nearest point; false for a
/// segment of zero length.
bool segment_distance(const std::vector<double>& y, const std::vector<double>& z, std::size_t k,
                      double py, double pz, NearestFeature& out) {
  const std::size_t last = y.size() - 2;
  const double dy = y[k + 1] - y[k], dz = z[k + 1] - z[k], len2 = dy * dy + dz * dz;
  if (len2 == 0.0) return false;
  const double u = ((py - y[k]) * dy + (pz - z[k]) * dz) / len2;
  const double lo = k == 0 && dy > 0.0 ? -std::numeric_limits<double>::infinity() : 0.0;
  const double hi = k == last && dy > 0.0 ? std::numeric_limits<double>::infinity() : 1.0;
  const double uc = std::clamp(u, lo, hi);
  const double cy = y[k] + uc * dy, cz = z[k] + uc * dz;
  out = {(py - cy) * (py - cy) + (pz - cz) * (pz - cz), cy, cz, k, uc == 0.0 || uc == 1.0};
  return true;
}

/// The segments [first, last] that can hold the nearest feature to (py, pz), y non-decreasing:
/// the segment over py bounds the distance by d, and a segment whose y-span lies farther than d
/// from py is farther than d from the point. The end segments (rays) are always candidates.
std::pair<std::size_t, std::size_t> candidate_segments(const std::vector<double>& y,
                                                       const std::vector<double>& z, double py,
                                                       double pz) {
  const std::size_t last = y.size() - 2;
  if (!std::isfinite(py) || !std::isfinite(pz)) return {0, last};
  const auto index = [&](auto it) { return static_cast<std::size_t>(it - y.begin()); };
  const std::size_t above = index(std::upper_bound(y.begin(), y.end(), py));
  const std::size_t k0 = std::min(last, above == 0 ? 0 : above - 1);
  NearestFeature f;
  const double d = segment_distance(y, z, k0, py, pz, f)
                       ? std::sqrt(f.distance2)
                       : std::hypot(py - y[k0], pz - z[k0]);  // a point: still a bound
  const std::size_t from = index(std::lower_bound(y.begin(), y.end(), py - d));
  const std::size_t to = index(std::upper_bound(y.begin(), y.end(), py + d));
  return {from == 0 ? 0 : std::min(last, from - 1), to == 0 ? 0 : std::min(last, to - 1)};
}

/// The nearest feature of the polyline (its first and last segments continued as rays beyond
/// the ends, unless vertical) to (py, pz). On a tie a face wins over a vertex, and of two
/// faces (or vertices) the first. Only the candidate segments are measured, in order: a
/// segment left out is farther than the one over py, so the result is the full scan's.
NearestFeature nearest_feature(const std::vector<double>& y, const std::vector<double>& z,
                               double py, double pz) {
  NearestFeature best;
  const std::size_t last = y.size() - 2;
  const auto [from, to] = candidate_segments(y, z, py, pz);
  const auto consider = [&](std::size_t k) {
    NearestFeature f;
    if (!segment_distance(y, z, k, py, pz, f)) return;
    if (f.distance2 < best.distance2 || (f.distance2 == best.distance2 && best.vertex && !f.vertex))
      best = f;
  };
  if (from > 0) consider(0);
  for (std::size_t k = from; k <= to; ++k) consider(k);
  if (to < last) consider(last);
  return best;
}

/// Height of the profile at py [m]: linear between vertices, the later segment at a shared y
/// (the upper tread at a rising riser's y), the end segments continued beyond the ends.
double profile_height(const std::vector<double>& y, const std::vector<double>& z, double py) {
  const std::size_t last = y.size() - 2;
  auto on = [&](std::size_t k) {
    const double dy = y[k + 1] - y[k];
    return dy > 0.0 ? z[k] + (z[k + 1] - z[k]) * (py - y[k]) / dy : z[k + 1];
  };
  if (py < y.front()) return on(0);
  if (py > y.back()) return on(last);
  // The segments whose y-span holds py (y non-decreasing): from the one before the first y ≥ py
  // to the one at the last y ≤ py; the last of them with a positive span gives the height.
  const auto index = [&](auto it) { return static_cast<std::size_t>(it - y.begin()); };
  const std::size_t first_at = index(std::lower_bound(y.begin(), y.end(), py));
  const std::size_t past = index(std::upper_bound(y.begin(), y.end(), py));
  double h = z.front();
  for (std::size_t k = first_at == 0 ? 0 : first_at - 1; k + 1 < y.size() && k + 1 <= past; ++k)
    if (py >= y[k] && py <= y[k + 1] && y[k + 1] > y[k]) h = on(k);
  return h;
}

/// The outward unit normal at the nearest feature f of a point at signed distance `dist` (> 0
/// outside): a face's normal; at a vertex the direction from the vertex to an outside point
/// (from an inside point to the vertex), or on the vertex itself the mean of the normals of
/// the faces that meet there.
Vec3 feature_normal(const std::vector<double>& y, const std::vector<double>& z,
                    const NearestFeature& f, const Vec3& p, double dist) {
  if (!f.vertex) return segment_normal(y, z, f.segment);
  const Vec3 away(0.0, p.y() - f.cy, p.z() - f.cz);
  if (away.norm() > 0.0) return (dist < 0.0 ? -away : away).normalized();
  const std::size_t v = (f.cy == y[f.segment] && f.cz == z[f.segment]) ? f.segment : f.segment + 1;
  Vec3 sum = Vec3::Zero();
  for (std::size_t k = v > 0 ? v - 1 : 0; k <= v && k + 1 < y.size(); ++k)
    if (y[k + 1] != y[k] || z[k + 1] != z[k]) sum += segment_normal(y, z, k);
  return sum.norm() > 0.0 ? Vec3(sum.normalized()) : Vec3(Vec3::UnitZ());
}

}  // namespace

TerrainContactPoint terrain_contact(const std::vector<double>& y, const std::vector<double>& z,
                                    const Vec3& p, double radius) {
  if (y.size() < 2 || z.size() != y.size())
    throw ConfigError("terrain contact: the profile has " + std::to_string(y.size()) + " y and " +
                      std::to_string(z.size()) + " z values, expected K >= 2 of each");
  const NearestFeature f = nearest_feature(y, z, p.y(), p.z());
  // Signed distance: negative below the profile (inside the solid).
  double dist = std::sqrt(f.distance2);
  if (p.z() < profile_height(y, z, p.y())) dist = -dist;
  TerrainContactPoint out;
  out.penetration_m = radius - dist;
  out.normal_W = feature_normal(y, z, f, p, dist);
  out.point_W = radius > 0.0 ? Vec3(p - radius * out.normal_W) : p;
  return out;
}

namespace {

/// The distance of p from the nearest bounding box of the map's cells that overlap the square
/// of half-side h around (p_x, p_y) [m]: each box spans its cell horizontally (a border cell's
/// outward, where the map's border continues) and its nodes' heights vertically. The bilinear
/// surface over a cell lies in its box, so no point of the surface within that square is
/// nearer to p.
double nearest_cell_box(const HeightMap& map, const Vec3& p, double h) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const auto cell = [&](double v, double v0, int n) {
    return std::clamp(static_cast<int>(std::floor((v - v0) / map.resolution_m)), 0, n - 2);
  };
  const auto gap = [](double v, double lo, double hi) { return std::max({lo - v, 0.0, v - hi}); };
  double best = kInf;
  for (int i = cell(p.y() - h, map.y0_m, map.ny); i <= cell(p.y() + h, map.y0_m, map.ny); ++i)
    for (int j = cell(p.x() - h, map.x0_m, map.nx); j <= cell(p.x() + h, map.x0_m, map.nx); ++j) {
      const double z0 = map.at(i, j), z1 = map.at(i, j + 1), z2 = map.at(i + 1, j),
                   z3 = map.at(i + 1, j + 1);
      const double dx =
          gap(p.x(), j == 0 ? -kInf : map.x(j), j == map.nx - 2 ? kInf : map.x(j + 1));
      const double dy =
          gap(p.y(), i == 0 ? -kInf : map.y(i), i == map.ny - 2 ? kInf : map.y(i + 1));
      const double dz = gap(p.z(), std::min({z0, z1, z2, z3}), std::max({z0, z1, z2, z3}));
      best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  return best;
}

}  // namespace

TerrainContactPoint height_map_contact(const HeightMap& map, const Vec3& p, double radius) {
  TerrainContactPoint out;
  out.normal_W = map.normal(p.x(), p.y());
  const double d = (p.z() - map.height(p.x(), p.y())) * out.normal_W.z();
  out.penetration_m = radius - d;
  // The tangent plane of a steep cell reaches far beyond the cell: under a sphere high above a
  // slab's foot, or beside it, it would report a contact with the slab's side. A centre above
  // the surface is outside the solid, and a touching sphere touches within r of it, so it is
  // no deeper than r less its distance from the nearest cell box there (on a plane the tangent
  // plane's depth is never the larger; out of contact, and below the surface, it is kept).
  // d ≥ 0 is p_z ≥ z(p_x, p_y): the normal points up.
  if (out.penetration_m > 0.0 && d >= 0.0)
    out.penetration_m = std::min(out.penetration_m, radius - nearest_cell_box(map, p, radius));
  out.point_W = radius > 0.0 ? Vec3(p - radius * out.normal_W) : p;
  return out;
}

}  // namespace hexdyn
