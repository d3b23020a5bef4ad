#pragma once
/// \file stick_slip.hpp
/// Friction that holds (docs/theory/replay.md#stick-slip): the tangential law of forward
/// simulation with stiction, `contact.friction_law: stick_slip`. A reset-integrator (bristle)
/// model after Haessig & Friedland (1991): each foot in contact carries a tangential
/// deflection z, the stretch of a spring of stiffness k_t (contact.tangential_stiffness) from
/// an anchor on the terrain, in parallel with a damper c_t (contact.tangential_damping).
///
/// - **Stick**: F_t = −k_t z − c_t v_t, and ż = v_t: the anchor stays put, so a foot loaded
///   below μ_s F_n holds still (it moves only by the spring's deflection, which does not grow
///   under a constant load).
/// - **Slip**: once |k_t z + c_t v_t| exceeds μ_s F_n, the foot slides: F_t = −μ_d F_n z/|z|,
///   and the anchor is dragged so that k_t |z| = μ_d F_n. The foot sticks again when the stick
///   force it would need is within μ_d F_n.
/// - **Over a step** (the replay's linearly implicit step): a return mapping. Each foot is first
///   taken as sticking (stick_affine); a foot whose stick force at the step's end exceeds its
///   cap (friction_cap) slides instead, at μ_d F_n along that force (slip_affine), and the step
///   is solved again; then settle_stick_slip moves the anchor.
/// - The anchor's motion is the slip (its displacement, distance and the energy it
///   dissipates); the spring's elastic deflection is not.
///
/// Frames: world G0; n is the terrain's outward unit normal at the contact point, v_t the
/// tangential velocity of the foot's material point there, z ⟂ n.
#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// One foot's tangential state: its spring's deflection and whether it slides.
struct TangentialContact {
  Vec3 deflection_W = Vec3::Zero();  ///< z ⟂ n [m]: the foot's point less its anchor
  bool sliding = false;
};

/// The energy held in the tangential spring, ½ k_t |z|² [J].
double tangential_spring_energy(const ContactParams& c, const TangentialContact& s);

/// The tangential force at a state: the stick force −k_t z − c_t v_t while sticking and within
/// μ_s F_n; else the slip force μ_d F_n against z (against the trial force when z = 0). Zero
/// for F_n = 0. `normal_W` unit, `slip_velocity_W` ⟂ n [m/s], `normal_N` ≥ 0 [N].
Vec3 stick_slip_force(const ContactParams& c, const TangentialContact& s, const Vec3& normal_W,
                      double normal_N, const Vec3& slip_velocity_W);

/// The tangential force over a step of length h as an affine function of the foot's velocity
/// v at the step's end, F_t(v) = a + B v.
struct AffineTangentialForce {
  Vec3 a_N = Vec3::Zero();
  Mat3 B_Nspm = Mat3::Zero();
};

/// Sticking over the step: the spring at the step's end and the damper, −k_t (z + h P v) −
/// c_t P v: a = −k_t z, B = −(h k_t + c_t) P, with P = I − n nᵀ and z taken in the plane ⟂ n.
AffineTangentialForce stick_affine(const ContactParams& c, const TangentialContact& s,
                                   const Vec3& normal_W, double h_s);

/// Sliding over the step: μ_d F_n(v) along the unit tangent `force_direction_W`, with the
/// normal force's own affine form over the step F_n(v) = fn0 + g·v: a = μ_d fn0 e, B = μ_d e gᵀ.
AffineTangentialForce slip_affine(const ContactParams& c, const Vec3& force_direction_W,
                                  double normal_N0, const Vec3& normal_gradient_Nspm);

/// The largest tangential force the foot's mode allows at the normal force F_n ≥ 0 [N]: μ_s F_n
/// while it sticks, μ_d F_n while it slides.
double friction_cap(const ContactParams& c, const TangentialContact& s, double normal_N);

/// The state after an accepted step of length h that ended with the normal force `normal_N`
/// and the tangential velocity `slip_velocity_W` ⟂ n. Stuck (slip_force_direction null): z + h
/// v_t. Slid with its force along the unit tangent e (slip_force_direction): the anchor is
/// dragged so that the spring carries μ_d F_n against e (a spring still short of that
/// stretches first), and the foot slides on. `slip_W` is the anchor's displacement.
struct TangentialUpdate {
  TangentialContact next;
  Vec3 slip_W = Vec3::Zero();
};
TangentialUpdate settle_stick_slip(const ContactParams& c, const TangentialContact& s,
                                   const Vec3& normal_W, double normal_N,
                                   const Vec3& slip_velocity_W, double h_s,
                                   const Vec3* slip_force_direction_W);

}  // namespace hexdyn
