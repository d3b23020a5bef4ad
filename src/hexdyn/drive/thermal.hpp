#pragma once
/// \file thermal.hpp
/// The two-node thermal model of a joint's motor (docs/theory/drive-train.md#thermal-model):
/// winding (w) and housing (h) over the ambient T_a,
///
///     C_w dT_w/dt = P(t) − (T_w − T_h) / R_wh
///     C_h dT_h/dt = (T_w − T_h) / R_wh − (T_h − T_a) / R_ha
///
/// both nodes at T_a at the first sample, P the copper loss, linear between samples (as the
/// trapezoid rule takes it). Integrated exactly for that P (the modal closed form of the 2×2
/// linear system), so the temperatures at the samples do not depend on the step.
#include <vector>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// One joint's temperatures over a run.
struct ThermalTrace {
  std::vector<double> winding_degC;  ///< T_w at each sample [°C]
  std::vector<double> housing_degC;  ///< T_h at each sample [°C]
  /// The largest T_w over the run, between samples too (P linear there) [°C].
  double peak_winding_degC = 0.0;
  /// The first time T_w reaches the limit [s, on the samples' clock]; +inf: never (reached
  /// false), also when the limit is +inf.
  double time_to_limit_s = kInfinity;
  bool reached = false;
};

/// The temperatures of a joint whose copper loss is loss_W[k·stride] at time_s[k] (T
/// increasing sample times, T ≥ 1; p.present, its resistances and capacities > 0).
ThermalTrace simulate_thermal(const ThermalParams& p, const std::vector<double>& time_s,
                              const double* loss_W, int stride);

}  // namespace hexdyn
