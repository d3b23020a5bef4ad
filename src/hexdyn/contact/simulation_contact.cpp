#include "hexdyn/contact/simulation_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hexdyn/contact/impact.hpp"

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

TerrainContactPoint terrain_contact(const std::vector<double>& y, const std::vector<double>& z,
                                    const Vec3& p, double radius) {
  TerrainContactPoint out;
  double best = std::numeric_limits<double>::infinity();
  Vec3 best_n = Vec3::UnitZ();
  // Nearest segment of the profile in the (y, z) plane.
  for (std::size_t k = 0; k + 1 < y.size(); ++k) {
    const double ay = y[k], az = z[k], by = y[k + 1], bz = z[k + 1];
    const double dy = by - ay, dz = bz - az, len2 = dy * dy + dz * dz;
    if (len2 == 0.0) continue;
    double u = ((p.y() - ay) * dy + (p.z() - az) * dz) / len2;
    u = std::clamp(u, 0.0, 1.0);
    const double cy = ay + u * dy, cz = az + u * dz;
    const double d2 = (p.y() - cy) * (p.y() - cy) + (p.z() - cz) * (p.z() - cz);
    if (d2 < best) {
      best = d2;
      const double len = std::sqrt(len2);
      best_n = Vec3(0.0, -dz / len, dy / len);  // left of the direction of increasing y: up
    }
  }
  // Signed distance: negative below the profile (inside the solid).
  double dist = std::sqrt(best);
  // Height of the profile at p.y (the upper tread at a riser's y).
  double h = z.front();
  for (std::size_t k = 0; k + 1 < y.size(); ++k)
    if (p.y() >= y[k] && p.y() <= y[k + 1] && y[k + 1] > y[k])
      h = z[k] + (z[k + 1] - z[k]) * (p.y() - y[k]) / (y[k + 1] - y[k]);
  if (p.y() > y.back()) h = z.back();
  if (p.z() < h) dist = -dist;
  out.penetration_m = radius - dist;
  out.normal_W = best_n;
  out.point_W = radius > 0.0 ? Vec3(p - radius * best_n) : p;
  return out;
}

}  // namespace hexdyn
