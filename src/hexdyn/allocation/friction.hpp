#pragma once
/// \file friction.hpp
/// The friction polygon inscribed in the cone √(f_t1² + f_t2²) ≤ μ f_n, one home for every
/// place that linearises the cone: the friction pyramids of the allocation problem, the
/// polygon that stands in for the exact cone at an impact foot (whose f_n is fixed), and
/// the Ipopt back end's polygon start for cone problems.
#include <cmath>

namespace hexdyn {

/// Faces of the polygon used where the exact cone cannot be: an inscribed 16-gon, within
/// 2% of the circle.
inline constexpr int kInscribedConeFaces = 16;

/// Face f (0 ≤ f < faces) of the inscribed N-gon (N = faces ≥ 3): the half-plane
///   cos a · f_t1 + sin a · f_t2 ≤ reach · f_n,   a = 2π f / N,   reach = μ cos(π/N).
struct FrictionFace {
  double cos_a = 1.0;  ///< coefficient of f_t1
  double sin_a = 0.0;  ///< coefficient of f_t2
  double reach = 0.0;  ///< distance of the face per newton of normal force, μ cos(π/N)
};

inline FrictionFace inscribed_friction_face(int f, int faces, double mu) {
  const double a = 2.0 * M_PI * f / faces;
  return FrictionFace{std::cos(a), std::sin(a), mu * std::cos(M_PI / faces)};
}

}  // namespace hexdyn
