#pragma once
/// \file friction.hpp
/// The friction polygon inscribed in the cone √(f_t1² + f_t2²) ≤ μ f_n, and the one place that
/// writes the faces of a cone as rows: the inscribed polygon of the Ipopt back end's start for
/// cone problems (allocation/ipopt_backend.cpp), the cutting planes of the cone back end
/// (allocation/cone_backend.cpp) and the outer polygons of the required friction
/// (grip/required_friction_cone.cpp) are each a set of rows d·t − reach·n ≤ 0 at given
/// directions d.
#include <cmath>
#include <limits>
#include <string>

#include "hexdyn/allocation/qp.hpp"

namespace hexdyn {

/// Faces of the polygon used where the exact cone cannot be: an inscribed 16-gon, within
/// 2% of the circle.
inline constexpr int kInscribedConeFaces = 16;

/// Face f (0 ≤ f < faces) of the inscribed N-gon (N = faces ≥ 3): the half-plane
///   cos a · f_t1 + sin a · f_t2 ≤ reach · f_n,   a = 2π f / N,   reach = μ cos(π/N).
/// Any face of a cone has this form with its own direction (cos a, sin a) and reach.
struct FrictionFace {
  double cos_a = 1.0;  ///< coefficient of f_t1
  double sin_a = 0.0;  ///< coefficient of f_t2
  double reach = 0.0;  ///< distance of the face per newton of normal force, μ cos(π/N)
};

inline FrictionFace inscribed_friction_face(int f, int faces, double mu) {
  const double a = 2.0 * M_PI * f / faces;
  return FrictionFace{std::cos(a), std::sin(a), mu * std::cos(M_PI / faces)};
}

/// Writes `faces` faces of cone c as the inequality rows first … first + faces − 1 of qp: row
/// first + f is the half-space
///   d.cos_a · x[c.tangent1] + d.sin_a · x[c.tangent2] − d.reach · x[c.normal] ≤ 0,
///   d = face_of(f),
/// with lower bound −∞ and the cone's slack weight c.penalty; the row's other entries are left
/// as they are (zero in the rows that copy_problem_values appends). With `cone_name` (not
/// null), each row is named "<cone_name> face <f + 1>". Returns the row after the last face.
template <class FaceOf>
int write_cone_faces(const SecondOrderCone& c, int first, int faces, FaceOf&& face_of,
                     const std::string* cone_name, QpProblem& qp) {
  for (int f = 0; f < faces; ++f) {
    const int row = first + f;
    const FrictionFace d = face_of(f);
    qp.C(row, c.tangent1) = d.cos_a;
    qp.C(row, c.tangent2) = d.sin_a;
    qp.C(row, c.normal) = -d.reach;
    qp.lower[row] = -std::numeric_limits<double>::infinity();
    qp.upper[row] = 0.0;
    qp.ineq_penalty[row] = c.penalty;
    if (cone_name)
      qp.ineq_names[static_cast<std::size_t>(row)] = *cone_name + " face " + std::to_string(f + 1);
  }
  return first + faces;
}

}  // namespace hexdyn
