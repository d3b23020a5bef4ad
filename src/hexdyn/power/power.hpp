#pragma once
/// \file power.hpp
/// The power stage (docs/theory/stages.md#power-and-energy; the paper's P_in of its
/// Fig. 5): joint power from the torques and joint rates, its integral over the stored
/// samples by the piecewise-cubic rule of quadrature.hpp on the adaptive grid or the trapezoid
/// rule on the uniform grid (the energy; docs/theory/output-grid.md#energy-from-the-samples),
/// the energy of each gait cycle, and the cost of transport.
#include <vector>

#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/power/quadrature.hpp"

namespace hexdyn {

/// Power and energy of a run (the DynamicsResult fields of the same names).
struct PowerResult {
  RowMatrix joint_power;               ///< T×joints, P_k = τ_k ω_k [W]
  std::vector<double> total_power_W;   ///< T, Σ_k |τ_k ω_k| [W]
  std::vector<double> energy_joint_J;  ///< joints, ∫|τ_k ω_k| over the samples by the rule [J]
  double energy_total_J = 0.0;         ///< ∫ total_power_W over the samples by the rule [J]
  std::vector<double> energy_cycle_J;  ///< Y, per gait cycle; sums to energy_total_J [J]
  /// Joints: the positive and negative parts of ∫τ_k ω_k, (E_k ± W_k) / 2 with W_k the signed
  /// integral by the same rule (CubicTarget::signed_integral, or the trapezoid): ≥ 0 and ≤ 0 [J].
  std::vector<double> positive_work_joint_J, negative_work_joint_J;
  double positive_work_J = 0.0, negative_work_J = 0.0;  ///< sums over the joints [J]
  double distance_m = 0.0;                              ///< travel for the cost of transport [m]
  double cost_of_transport = 0.0;                       ///< E / (m g d)
};

/// Joint power P = τ ω, total P_in = Σ|τ ω|, the energies over the samples of kin (the
/// samples include the left limit of every contact event on the adaptive grid, so each jump of
/// the power is resolved) by `rule`, and the cost of transport E/(m g d):
/// - Quadrature::kCubic (the adaptive grid): E_k = cubic_abs_integral of τ_k ω_k over the
///   pieces between kin.sample_kind's left limits (power/quadrature.hpp), E = Σ_k E_k, E per
///   gait cycle Σ_k cubic_abs_integral_between each cycle_start_s and the next (the last to
///   the end);
/// - Quadrature::kTrapezoid (the uniform grid): E_k = trapezoid of |τ_k ω_k|, E = trapezoid
///   of P_in (= Σ E_k up to rounding), E per gait cycle by trapezoid_between.
/// joint_torque: T×joints [N m] on the samples of kin; total_mass_kg > 0; distance_m > 0;
/// cycle_start_s: increasing [s], first 0 (may be empty: no cycles). known (may be null): the
/// output grid's last assessment (power/grid_error.hpp), whose first terms (one a joint) are τ_k
/// ω_k on these samples; its interval integrals are taken when its grid is kin.time_s (the same
/// numbers, to the bit, as computing them again).
PowerResult compute_power(const KinematicsResult& kin, const RowMatrix& joint_torque,
                          double total_mass_kg, double distance_m,
                          const std::vector<double>& cycle_start_s,
                          Quadrature rule = Quadrature::kCubic,
                          const CubicEstimates* known = nullptr);

/// The rule the energies of a run on `grid` are integrated by: the piecewise cubic on the
/// adaptive grid, whose left-limit samples split the series at their jumps; the trapezoid on the
/// uniform grid, which has no event samples (a cubic across a jump would ring).
Quadrature energy_rule(OutputGrid grid);

/// The jump intervals of kin's samples for the piecewise-cubic rule: T entries, 1 at a
/// left-limit sample (kin.sample_kind 1; none when sample_kind is empty).
std::vector<char> jump_intervals(const KinematicsResult& kin);

/// Trapezoid rule ∫ y dt over all samples t (increasing), y[k·stride].
double trapezoid(const std::vector<double>& t, const double* y, int stride = 1);

/// Trapezoid rule over [a, b] ⊆ [t.front(), t.back()] (a ≤ b) of the piecewise-linear
/// interpolant of the samples (t, y): a bound between two samples takes the linearly
/// interpolated value there, so that the integrals over adjacent intervals add up to the
/// trapezoid over their union.
double trapezoid_between(const std::vector<double>& t, const double* y, double a, double b);

}  // namespace hexdyn
