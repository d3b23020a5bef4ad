#pragma once
/// \file power.hpp
/// The power stage (docs/theory/stages.md#power-and-energy; the paper's P_in of its
/// Fig. 5): joint power from the torques and joint rates, its integral (the energy) piece
/// by piece between the jumps at contact events, and the cost of transport.
#include <vector>

#include "hexdyn/core/result.hpp"

namespace hexdyn {

/// The limit from the left of |τ_k ω_k| [W] (18) at sample `index`, the first sample of
/// a new contact phase (a touchdown, the end of its transient, a lift-off): the power
/// just before the event, where the sampled series holds the value just after it.
struct PowerJump {
  int index = 0;
  VecJ abs_power_left_W = VecJ::Zero();
};

/// Power and energy of a run (the DynamicsResult fields of the same names).
struct PowerResult {
  RowMatrix joint_power;               ///< T×18, P_k = τ_k ω_k [W]
  std::vector<double> total_power_W;   ///< T, Σ_k |τ_k ω_k| [W]
  std::vector<double> energy_joint_J;  ///< 18, ∫ |τ_k ω_k| dt [J]
  double energy_total_J = 0.0;         ///< Σ_k energy_joint_J [J]
  double distance_m = 0.0;             ///< travel for the cost of transport [m]
  double cost_of_transport = 0.0;      ///< E / (m g d)
};

/// Joint power P = τ ω, total P_in = Σ|τ ω|, energies per joint E_k = ∫ |τ_k ω_k| dt and
/// in total E = Σ E_k (= ∫ P_in dt), and the cost of transport E/(m g d). The power jumps
/// at contact events, so each integral is taken piece by piece between the samples of
/// `jumps` (sorted by index), each piece ending on the jump's left limit (integrate_pieces).
/// joint_torque: T×18 [N m] on the samples of kin; total_mass_kg > 0; distance_m > 0.
PowerResult compute_power(const KinematicsResult& kin, const RowMatrix& joint_torque,
                          double total_mass_kg, double distance_m,
                          const std::vector<PowerJump>& jumps);

/// ∫ y dt over the samples t (increasing), y[k·stride], split into pieces at the samples
/// `break_index` (increasing): the piece ending at break k uses `left_value[k]` there in
/// place of the sample, and the next piece starts from the sample. Within a piece: the
/// integral of GSL's Steffen interpolant (a monotone piecewise cubic: third order where
/// the series is smooth, never below 0 for data ≥ 0 and no overshoot at the kinks of
/// |τ ω|); the trapezoid for a piece of one interval.
double integrate_pieces(const std::vector<double>& t, const double* y, int stride,
                        const std::vector<int>& break_index, const std::vector<double>& left_value);

/// integrate_pieces without breaks.
double integrate_series(const std::vector<double>& t, const double* y, int stride = 1);

}  // namespace hexdyn
