#include "hexdyn/contact/stick_slip.hpp"

#include <algorithm>

namespace hexdyn {

namespace {

/// The unit vector along x, or along the fallback when x is zero (zero when both are).
Vec3 direction(const Vec3& x, const Vec3& fallback) {
  if (x.norm() > 0.0) return x.normalized();
  if (fallback.norm() > 0.0) return fallback.normalized();
  return Vec3::Zero();
}

/// z in the plane ⟂ n (the face under a foot turns as it rolls over a nosing).
Vec3 in_plane(const Vec3& z, const Vec3& n) { return z - n.dot(z) * n; }

}  // namespace

double tangential_spring_energy(const ContactParams& c, const TangentialContact& s) {
  return 0.5 * c.tangential_stiffness_Npm * s.deflection_W.squaredNorm();
}

Vec3 stick_slip_force(const ContactParams& c, const TangentialContact& s, const Vec3& n, double fn,
                      const Vec3& vt) {
  if (!(fn > 0.0)) return Vec3::Zero();
  const Vec3 z = in_plane(s.deflection_W, n);
  const Vec3 trial = -c.tangential_stiffness_Npm * z - c.tangential_damping_Nspm * vt;
  if (s.sliding) return -c.dynamic_friction * fn * direction(z, -trial);
  const double cap = c.static_friction * fn;
  return trial.norm() <= cap ? trial : Vec3(cap * trial.normalized());
}

AffineTangentialForce stick_affine(const ContactParams& c, const TangentialContact& s,
                                   const Vec3& n, double h) {
  AffineTangentialForce out;
  const Mat3 P = Mat3::Identity() - n * n.transpose();
  out.a_N = -c.tangential_stiffness_Npm * in_plane(s.deflection_W, n);
  out.B_Nspm = -(h * c.tangential_stiffness_Npm + c.tangential_damping_Nspm) * P;
  return out;
}

AffineTangentialForce slip_affine(const ContactParams& c, const Vec3& e, double fn0,
                                  const Vec3& g) {
  AffineTangentialForce out;
  out.a_N = c.dynamic_friction * fn0 * e;
  out.B_Nspm = c.dynamic_friction * e * g.transpose();
  return out;
}

double friction_cap(const ContactParams& c, const TangentialContact& s, double fn) {
  return (s.sliding ? c.dynamic_friction : c.static_friction) * std::max(0.0, fn);
}

TangentialUpdate settle_stick_slip(const ContactParams& c, const TangentialContact& s,
                                   const Vec3& n, double fn, const Vec3& vt, double h,
                                   const Vec3* slip_force_direction) {
  const Vec3 z1 = in_plane(s.deflection_W, n) + h * vt;
  TangentialUpdate out;
  if (!slip_force_direction) {
    out.next = {z1, false};
    return out;
  }
  // Slid: the anchor is dragged so that the spring carries at most μ_d F_n, against the force.
  const double reach = std::max(0.0, c.dynamic_friction * fn / c.tangential_stiffness_Npm);
  const Vec3 z = z1.norm() <= reach ? z1 : Vec3(-reach * *slip_force_direction);
  out.next = {z, fn > 0.0};
  out.slip_W = z1 - z;
  return out;
}

}  // namespace hexdyn
