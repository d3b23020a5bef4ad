#pragma once
/// \file simulation_contact.hpp
/// Foot–terrain contact for forward simulation (docs/theory/replay.md#contact): where a foot
/// touches the terrain, and the force the terrain then exerts on it.
///
/// - Normal: the paper's compliant law (eq. 7–8), the function the touchdown transient
///   integrates (impact.hpp `impact_normal_force`), at the penetration δ along the surface
///   normal and its rate δ̇.
/// - Tangential: regularised Coulomb friction after MSC.ADAMS' contact friction, with a static
///   coefficient μ_s, a dynamic coefficient μ_d and two transition speeds v_s < v_d
///   (ContactParams::friction_*): F_t = −μ(s) F_n v_t / s for the slip speed s = |v_t|, with
///   μ(s) = −STEP(s, −v_s, μ_s, v_s, −μ_s) for s < v_s (through zero, odd in the velocity),
///   STEP(s, v_s, μ_s, v_d, μ_d) for v_s ≤ s ≤ v_d, and μ_d beyond (STEP: impact_step).
///
/// Frames: world G0; the normal n is the terrain's outward unit normal at the contact point;
/// v is the velocity of the foot's material point at the contact point.
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/height_map.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// The friction coefficient μ(s) ≥ 0 of the tangential law at slip speed s ≥ 0 [m/s] (file
/// comment); 0 at s = 0.
double sliding_friction_coefficient(const ContactParams& c, double slip_speed_mps);

/// dμ/ds at slip speed s ≥ 0 (one-sided at the transitions).
double sliding_friction_slope(const ContactParams& c, double slip_speed_mps);

/// The contact force at one foot and what it dissipates, with its linearisation for an
/// implicit integrator.
struct FootContactForce {
  double normal_N = 0.0;                ///< F_n ≥ 0 [N]
  Vec3 tangential_W = Vec3::Zero();     ///< F_t ⟂ n [N]
  Vec3 force_W = Vec3::Zero();          ///< F_n n + F_t [N]
  Vec3 slip_velocity_W = Vec3::Zero();  ///< v_t = v − (n·v) n while in contact, else 0 [m/s]
  /// Power of the normal force's non-conservative part, (F_n − K δ^e) δ̇ ≥ 0 [W]: what the
  /// damper (or the clip, on a fast rebound) takes from the motion.
  double damping_power_W = 0.0;
  double slip_power_W = 0.0;  ///< −F_t · v_t ≥ 0 [W]
  Mat3 dF_dv = Mat3::Zero();  ///< ∂F/∂v at fixed position [N s/m]
  Mat3 dF_dp = Mat3::Zero();  ///< ∂F/∂p of the contact point at fixed velocity [N/m]
};

/// The force of the terrain on a foot whose contact point penetrates the terrain by δ =
/// `penetration_m` along the unit normal `normal_W` and moves at `velocity_W` (file comment).
/// δ ≤ 0: no contact, all zero. The derivatives hold where the law is smooth (one-sided at
/// its switches) and take the normal as fixed (a flat face).
FootContactForce foot_contact_force(const ContactParams& c, double penetration_m,
                                    const Vec3& normal_W, const Vec3& velocity_W);

/// Where a foot meets the terrain's height profile (planning/terrain.hpp terrain_profile: a
/// polyline z(y), every x alike; treads, risers and slopes are its segments).
struct TerrainContactPoint {
  double penetration_m = 0.0;     ///< δ > 0 inside the terrain, ≤ 0 outside
  Vec3 normal_W = Vec3::UnitZ();  ///< outward unit normal of the nearest face
  Vec3 point_W = Vec3::Zero();    ///< contact point: the deepest point of the foot
};

/// The contact of a point foot at p_W (radius 0) or of a sphere foot of centre p_W and radius
/// `radius_m` with the profile (y_m, z_m, K ≥ 2 vertices, y non-decreasing, the solid below;
/// the first and last segments continue as rays beyond the ends unless vertical, as the
/// ground before the first riser and the endless top tread do). In the (y, z) plane: the
/// nearest feature of the profile to p (to the centre) is a face (a segment's interior) or a
/// vertex (a nosing, seen from outside; a riser's foot, from inside); the signed distance d
/// of p is negative below the profile (the upper tread counts at a rising riser's y); δ = r −
/// d; n is the face's outward normal, or at a vertex the unit vector from the vertex to p
/// (from p to the vertex when p is inside; on the vertex itself the mean of its two faces'
/// normals); the contact point is p − r n, or for a point foot p itself.
/// Throws ConfigError when K < 2 or the sizes of y_m and z_m differ.
TerrainContactPoint terrain_contact(const std::vector<double>& y_m, const std::vector<double>& z_m,
                                    const Vec3& p_W, double radius_m);

/// The contact of a point foot at p_W (radius 0) or of a sphere foot of centre p_W and radius
/// `radius_m` with a height map (core/height_map.hpp; docs/theory/replay.md#height-maps): the
/// surface's point below p is taken as the nearest, its bilinear normal n as the face's, and
/// the distance of p to the tangent plane there, d = (p_z − z(p_x, p_y)) n_z, as the signed
/// distance: δ = r − d, the contact point p − r n; for p above the surface a positive δ at most
/// r less p's distance from the nearest bounding box of the cells within r of it horizontally
/// (a steep cell's tangent plane reaches far beyond it). Exact on a plane; on a curved or
/// stepped map an approximation whose error grows with the curvature under the foot.
TerrainContactPoint height_map_contact(const HeightMap& map, const Vec3& p_W, double radius_m);

}  // namespace hexdyn
