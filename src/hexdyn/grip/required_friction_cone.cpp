// The exact cone's required friction by outer polygons (grip/required_friction.hpp,
// docs/theory/grip.md#the-exact-cone): RequiredFrictionSolver::Impl's polygon rounds.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hexdyn/allocation/friction.hpp"
#include "hexdyn/grip/required_friction_solver.hpp"

namespace hexdyn {

/// The cone's polygon problem (file comment): `qp` with each support leg's cone replaced by
/// kConeFaces supporting half-spaces d·t ≤ μ f_n at the directions cone_angle[l], appended
/// leg by leg after the problem's rows; `cone_layout` says where they are.
void RequiredFrictionSolver::Impl::load_cone_polygon(const QpProblem& qp,
                                                     const AllocationLayout& layout) {
  int cones = 0;
  for (int l = 0; l < layout.n_legs; ++l) cones += layout.legs[l].cone >= 0;
  const bool named =
      copy_problem_values(qp, work, kConeFaces * cones, qp.structure | kConePolygonKey);
  cone_layout = layout;
  int row = qp.inequalities();
  for (int l = 0; l < layout.n_legs; ++l) {
    AllocationLayout::Leg& leg = cone_layout.legs[l];
    if (leg.cone < 0) continue;
    const SecondOrderCone& c = qp.cones[static_cast<std::size_t>(leg.cone)];
    leg.cone = -1;
    leg.friction_row = row;
    leg.friction_faces = kConeFaces;
    leg.face_reach = 1.0;  // supporting half-spaces: the polygon contains the cone
    const auto face = [&](int f) {
      return FrictionFace{std::cos(cone_angle[l][f]), std::sin(cone_angle[l][f]), c.mu};
    };
    row = write_cone_faces(c, row, kConeFaces, face, named ? &c.name : nullptr, work);
  }
  set_friction_coefficient(cone_layout, qp.cones.empty() ? 0.0 : qp.cones.front().mu, work);
}

/// Leg l's polygon faces: eight clustered around the direction `a` of its tangential force (a,
/// a ± δ, a ± 2δ, a ± 3δ, a + 4δ) and eight every 45° from a + 22.5°, so that every direction
/// is covered to within 1/cos(22.5°) of the cone.
void RequiredFrictionSolver::Impl::cluster_faces(int l, double a, double delta) {
  static_assert(kConeFaces == 16);
  const double fine[8] = {0.0,          delta,       -delta,       2.0 * delta,
                          -2.0 * delta, 3.0 * delta, -3.0 * delta, 4.0 * delta};
  for (int f = 0; f < 8; ++f) cone_angle[l][f] = a + fine[f];
  for (int f = 0; f < 8; ++f) cone_angle[l][8 + f] = a + M_PI / 8.0 + f * M_PI / 4.0;
  cone_center[l] = a;
  cone_spacing[l] = delta;
}

/// μ* under the exact cone by outer polygons (file comment): the polygon's μ* is a lower
/// bound, the cone use of its forces an upper bound. While they differ by more than the
/// tolerance, each cone leg's faces gather around its force's direction, their spacing δ
/// shrinking fourfold a round (the polygon's excess over the cone near the direction is
/// about μ δ²/2), or widening to the step when the direction moved farther than the faces.
void RequiredFrictionSolver::Impl::solve_cone(const QpProblem& qp, const AllocationLayout& layout,
                                              const Eigen::VectorXd* allocation) {
  constexpr int kMaxRounds = 40;
  double best_upper = std::numeric_limits<double>::infinity();
  int best_leg = -1;
  if (allocation) best_upper = friction_use(qp, layout, *allocation, &best_leg);
  for (int l = 0; l < layout.n_legs; ++l) cluster_faces(l, cone_center[l], M_PI / 8.0);
  for (int round = 0; round < kMaxRounds; ++round) {
    load_cone_polygon(qp, layout);
    solve_polygonal(cone_layout, allocation);
    if (!std::isfinite(out.mu)) return;  // no μ for the outer polygon: none for the cone
    const double lower =
        out.mu - (out.method == RequiredFrictionMethod::kBisection ? opt.tolerance : 0.0);
    int leg = -1;
    const double upper = friction_use(qp, layout, answer_x, &leg);
    if (upper < best_upper) {
      best_upper = upper;
      best_leg = leg;
    }
    if (best_upper - lower <= opt.tolerance) break;
    for (int l = 0; l < layout.n_legs; ++l) {
      const AllocationLayout::Leg& g = layout.legs[l];
      if (g.cone < 0) continue;
      const double t1 = answer_x[g.offset], t2 = answer_x[g.offset + 1];
      const double a = std::hypot(t1, t2) > 0.0 ? std::atan2(t2, t1) : cone_center[l];
      const double moved = std::abs(std::remainder(a - cone_center[l], 2.0 * M_PI));
      // A direction within the clustered faces (±4δ) narrows them; one beyond widens them.
      const double delta = moved > 4.0 * cone_spacing[l] ? std::min(M_PI / 8.0, moved)
                                                         : std::max(1e-9, 0.25 * cone_spacing[l]);
      cluster_faces(l, a, delta);
    }
  }
  out.mu = best_upper;
  out.leg = best_leg;
}

}  // namespace hexdyn
