#pragma once
/// \file trunk_offset.hpp
/// The balanced trunk's horizontal offset e(t) from the straight path, world x and y [m]
/// (docs/theory/balance.md#the-offset). It is the solution of the linear inverted pendulum's
/// equation
///
///     e − ë / ω² = u(t)
///
/// for a forcing u given piecewise on breakpoints t_0 = 0 < t_1 < … < t_K = T: on piece k,
/// u(t) = w_k + (w_{k+1} − w_k) x − r_k(x), x = (t − t_k) / (t_{k+1} − t_k) ∈ [0, 1], with w
/// the waypoints of the designed ZMP path and r_k a Chebyshev series (the part of the ZMP the
/// pendulum does not model). With the divergent and convergent components ξ = e + ė/ω and
/// ζ = e − ė/ω at the start of each piece (ξ̇ = ω (ξ − u), ζ̇ = −ω (ζ − u)), e at any t of
/// piece k is
///
///     ξ(t) = e^{−ω(t_{k+1} − t)} ξ_{k+1} + ω ∫_t^{t_{k+1}} e^{−ω(σ − t)} u(σ) dσ
///     ζ(t) = e^{−ω(t − t_k)} ζ_k + ω ∫_{t_k}^t e^{−ω(t − σ)} u(σ) dσ
///     e = (ξ + ζ) / 2,   ė = ω (ξ − ζ) / 2,   ë = ω² (e − u)
///
/// both integrals over decaying exponentials, so no growing mode is ever evaluated. ξ is swept
/// backward from ξ(T) = 0 and ζ forward from ζ(0) = 0, piece by piece; the waypoints make
/// ξ(0) = 0 and ζ(T) = 0 hold as well (balance/balance.hpp), so the offset starts and ends at
/// rest. Outside [0, T] the offset is 0.
///
/// On a piece, ξ and ζ are Chebyshev series in y = 2x − 1, found once per piece: with
/// a = ω (t_{k+1} − t_k) / 2, ξ' = a (ξ − u) in y, and the coefficients of a derivative
/// (2j f_j = c_{j−1} f'_{j−1} − f'_{j+1}, c_0 = 2, else 1) turn it into the tridiagonal system
///
///     −a c_{j−1} ξ_{j−1} + 2j ξ_j + a ξ_{j+1} = a (u_{j+1} − c_{j−1} u_{j−1}),   j = 1 … M,
///
/// closed by ξ(1) = Σ ξ_j = ξ_{k+1}; ζ likewise with y → −y and ζ(−1) = ζ_k. The system is
/// diagonally dominant for a < 2 (2j > 2a; the balanced trunk's pieces have a < 0.5) and carries
/// no growing mode: its solution is O(|u| + |ξ_{k+1}|) whatever a. Past the forcing's degree n
/// the coefficients fall as (a/2)^m / m!, so M = n + m with (a/2)^m / m! < 1e-20 is exact to
/// rounding. The sweeps take each piece's end values from its series, and at() is one Clenshaw
/// sum of e and ė and one of the forcing: no exponential. decaying_integral (16-point
/// Gauss–Legendre, the nodes typed in, no library needed) remains for the waypoints' boundary
/// functionals (balance/balance.cpp).
#include <Eigen/Core>
#include <vector>

namespace hexdyn {

using Vec2 = Eigen::Vector2d;

/// One piece of the forcing: [t0_s, t1_s], its waypoints at both ends and the Chebyshev
/// coefficients of r on x ∈ [0, 1] mapped to [−1, 1] (r(x) = Σ_j c_j T_j(2x − 1)).
struct OffsetPiece {
  double t0_s = 0.0, t1_s = 0.0;
  Vec2 w0 = Vec2::Zero(), w1 = Vec2::Zero();  ///< ZMP waypoints at t0 and t1 [m]
  std::vector<Vec2> r_cheb;                   ///< r's Chebyshev coefficients [m]
};

/// e, ė, ë of the offset at one instant [m, m/s, m/s²], world x and y.
struct OffsetState {
  Vec2 e = Vec2::Zero(), ed = Vec2::Zero(), edd = Vec2::Zero();
};

class TrunkOffset {
 public:
  /// omega_radps > 0; pieces contiguous and increasing, the first at t = 0. Sweeps ξ and ζ.
  TrunkOffset(double omega_radps, std::vector<OffsetPiece> pieces);

  OffsetState at(double t_s) const;
  /// u(t) of the piece holding t (0 outside [0, T]).
  Vec2 forcing(double t_s) const;
  double omega() const { return omega_; }
  double end_s() const { return pieces_.empty() ? 0.0 : pieces_.back().t1_s; }
  const std::vector<OffsetPiece>& pieces() const { return pieces_; }
  /// ξ and ζ at the start of every piece, and ξ, ζ at T (K + 1 entries each).
  const std::vector<Vec2>& xi() const { return xi_; }
  const std::vector<Vec2>& zeta() const { return zeta_; }

 private:
  int piece_at(double t_s) const;
  double omega_ = 1.0;
  std::vector<OffsetPiece> pieces_;
  std::vector<Vec2> xi_, zeta_;
  /// Per piece, the Chebyshev coefficients in y of (e, ė): (ξ + ζ)/2 and ω (ξ − ζ)/2.
  std::vector<std::vector<Eigen::Vector4d>> series_;
};

/// The forcing of `piece` at x ∈ [0, 1].
Vec2 piece_forcing(const OffsetPiece& piece, double x);

/// Which end of [a, b] the weight of decaying_integral decays from.
enum class Decay {
  kFromLower,  ///< ω ∫_a^b e^{−ω(σ − a)} u(σ) dσ (ξ's integral)
  kFromUpper,  ///< ω ∫_a^b e^{−ω(b − σ)} u(σ) dσ (ζ's integral)
};

/// The integral `decay` names, of the piece's forcing u, for t0 ≤ a ≤ b ≤ t1 [m].
Vec2 decaying_integral(const OffsetPiece& piece, double omega, double a_s, double b_s, Decay decay);

/// Chebyshev series Σ c_j T_j(y) at y ∈ [−1, 1] (Clenshaw).
Vec2 chebyshev_value(const std::vector<Vec2>& c, double y);

}  // namespace hexdyn
