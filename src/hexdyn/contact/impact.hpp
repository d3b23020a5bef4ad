#pragma once
/// \file impact.hpp
/// The compliant normal contact law (paper eq. 7–8, the MSC.ADAMS IMPACT function) and
/// the touchdown transient it produces (docs/theory/contact.md).
///
/// Sign conventions: δ = z1 − z is the penetration of the foot into the terrain [m],
/// positive in contact; δ̇ [m/s] is positive while the foot moves into the terrain.
/// Forces are the terrain's push on the foot along the surface normal [N], never negative.
#include <string>
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Cubic STEP of paper eq. 8 (ADAMS STEP): h0 for x ≤ x0, h1 for x ≥ x1, and
/// h0 + (h1 − h0)·Δ²(3 − 2Δ) with Δ = (x − x0)/(x1 − x0) in between. C¹ in x.
/// If x1 ≤ x0 the step is a jump at x0 (h0 below, h1 from x0 on).
double impact_step(double x, double x0, double h0, double x1, double h1);

/// x-derivative of `impact_step` (0 outside (x0, x1)).
double impact_step_derivative(double x, double x0, double h0, double x1, double h1);

/// Normal force of the IMPACT law [N] (docs/theory/contact.md#compliant-impact-law):
///   F_n = max(0, K δ^e + C_max · STEP(δ; 0 → 0, p → 1) · δ̇)  for δ > 0,  0 otherwise.
/// delta_m: penetration δ [m]; delta_rate_mps: δ̇ [m/s], > 0 moving into the terrain.
/// The clip removes the sticky pull of the damper on a fast rebound.
/// Preconditions (not checked here, checked by `simulate_touchdown`): K > 0, e ≥ 1,
/// C_max ≥ 0, p > 0.
double impact_normal_force(const ContactParams& c, double delta_m, double delta_rate_mps);

/// Penetration at rest under a normal force [m]: δ = (F/K)^(1/e); 0 for F ≤ 0.
double static_penetration(const ContactParams& c, double normal_force_N);

/// Integration settings of the touchdown transient.
struct ImpactOptions {
  /// Relative tolerance of the state (penetration, its rate, impulse).
  double relative_tolerance = 1e-10;
  /// Absolute tolerance, in units of the natural scales of the impact: the
  /// penetration D of the undamped impact, the approach speed v and the momentum m v.
  double absolute_tolerance = 1e-10;
  /// Guard: the integration stops (flagged `truncated`) after this contact time [s].
  double max_duration_s = 1.0;
  /// Guard: the integration stops (flagged `truncated`) after this many ODE steps.
  long max_steps = 200000;
  /// Output sampling: a step is at most (undamped contact time)/samples_per_contact_time,
  /// or (elapsed time)/samples_per_contact_time once the contact lasts longer than that,
  /// so linear interpolation of the samples stays within ~1e-4 of the peak force.
  int samples_per_contact_time = 256;
  /// Loaded touchdowns: the transient has settled once its force is within this fraction of
  /// the load and would not leave that band within one undamped contact time at its rate.
  double settle_band = 0.02;
};

/// One touchdown transient of a foot of effective mass m along the surface normal.
struct ImpactTransient {
  bool occurred = false;      ///< false for a zero (or separating) approach speed
  bool truncated = false;     ///< a guard stopped the integration before the end
  double load_N = 0.0;        ///< the load L the leg takes over (0: the paper's transient)
  double load_delay_s = 0.0;  ///< from the foot's first contact to the load's start [s]
  /// Touchdown to the end: the first return of F_n to zero, or loaded, its settling at L.
  double duration_s = 0.0;
  double peak_force_N = 0.0;       ///< largest F_n, located to solver precision
  double time_of_peak_s = 0.0;     ///< since touchdown
  double impulse_Ns = 0.0;         ///< ∫ F_n dt over the transient (integrated as a state)
  double rebound_speed_mps = 0.0;  ///< −δ̇ at the end (≥ 0 when the foot moves away)
  double max_penetration_m = 0.0;  ///< largest δ
  long steps = 0;                  ///< accepted ODE steps
  std::string message;             ///< why the integration ended, in words
  /// Dense samples, increasing time from 0 (touchdown) to duration_s, including the
  /// instants of peak force, of maximum penetration and of the end.
  std::vector<double> t_s;            ///< [s] since touchdown
  std::vector<double> force_N;        ///< F_n [N]
  std::vector<double> penetration_m;  ///< δ [m]
};

/// Integrates the touchdown transient m δ̈ = L − F_n(δ, δ̇) from δ = 0, δ̇ = approach speed,
/// in scaled variables with GSL's adaptive drivers: the explicit Runge–Kutta–Cash–Karp
/// (4, 5) pair while the scaled damping allows output-sized steps, otherwise the implicit
/// 4th-order Gauss stepper (rk4imp) with the analytic Jacobian.
/// L = load_N is the load the leg takes over (docs/theory/contact.md#loaded-touchdowns),
/// acting from load_delay_s after the first contact on (a step): L = 0 gives the paper's
/// transient, in which gravity and the leg's drive are left out (its force is what the impact
/// adds to the quasi-static support). With L > 0 the transient ends when it has settled
/// (ImpactOptions::settle_band): its force is then L's, not zero.
///
/// The transient ends at the first return of F_n to zero after touchdown, located within
/// the step by regula falsi with the Illinois modification (falling back to bisection when
/// a secant point leaves the bracket), as are the force peak (zero of Ḟ_n) and the
/// largest penetration (zero of δ̇). The end comes when the foot leaves the surface
/// (δ = 0) or the damper cancels the spring on rebound (the max(0,·) clip). After a clip the foot
/// moves away freely; any later force while δ < p is below K p^e and is ignored.
///
/// effective_mass_kg: foot's effective mass along the normal, > 0.
/// approach_speed_mps: δ̇ at touchdown; ≤ 0 gives `occurred = false` and zero force.
/// Throws ConfigError for non-physical contact parameters (K ≤ 0, e < 1, C_max < 0,
/// p ≤ 0, non-finite values) and SolverError for a non-positive or non-finite mass, a
/// non-finite speed or a negative or non-finite load or delay. Guards (`max_duration_s`,
/// `max_steps`) give `truncated = true` with the samples so far; the result is always finite.
ImpactTransient simulate_touchdown(const ContactParams& c, double effective_mass_kg,
                                   double approach_speed_mps, const ImpactOptions& options = {},
                                   double load_N = 0.0, double load_delay_s = 0.0);

/// F_n at time t after touchdown [N], linear interpolation of the dense samples;
/// 0 before touchdown and after the end of the transient.
double transient_force_at(const ImpactTransient& tr, double t_since_touchdown_s);

/// δ at time t after touchdown [m], linear interpolation of the dense samples;
/// 0 before touchdown and after the end (afterwards the leg is a support leg, whose
/// penetration follows from its force by `static_penetration`).
double transient_penetration_at(const ImpactTransient& tr, double t_since_touchdown_s);

}  // namespace hexdyn
