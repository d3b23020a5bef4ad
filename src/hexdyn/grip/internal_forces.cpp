#include "hexdyn/grip/internal_forces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hexdyn/grip/required_friction.hpp"

namespace hexdyn {
namespace {

/// Marks the friction faces among the inequality rows of `qp`.
void mark_faces(const QpProblem& qp, const AllocationLayout& layout, std::vector<char>& face) {
  face.assign(static_cast<std::size_t>(qp.inequalities()), 0);
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    for (int f = 0; leg.friction_row >= 0 && f < leg.friction_faces; ++f)
      face[static_cast<std::size_t>(leg.friction_row + f)] = 1;
  }
}

/// The largest s in [0, 1] for which every row but the friction faces and the trunk rows
/// holds at x_a + s dx (x_a holds them; a row x_a meets only within its tolerance gives 0).
double largest_step(const QpProblem& qp, const Eigen::VectorXd& x_a, const Eigen::VectorXd& dx,
                    const std::vector<char>& face) {
  double s = 1.0;
  for (int i = AllocationLayout::kTrunkRows; i < qp.inequalities(); ++i) {
    if (face[static_cast<std::size_t>(i)]) continue;
    const double d = qp.C.row(i).dot(dx);
    if (d == 0.0) continue;
    const double c0 = qp.C.row(i).dot(x_a);
    const double bound = d > 0.0 ? qp.upper[i] : qp.lower[i];
    if (std::isfinite(bound)) s = std::min(s, std::max(0.0, (bound - c0) / d));
  }
  return s;
}

}  // namespace

double internal_force_use(const QpProblem& qp, const AllocationLayout& layout,
                          const Eigen::VectorXd& x_a, InternalForceWorkspace& ws, int& leg) {
  constexpr int R = AllocationLayout::kTrunkRows;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // The normal forces' weight against the tangential ones: internal forces that squeeze the
  // feet move normal force too, which the torque rows may not allow.
  constexpr double kNormalWeight = 0.1;
  const int n = qp.variables();
  leg = -1;
  if (n <= R || qp.inequalities() < R) return kInf;
  // With D the objective's diagonal and d = D x_a on the tangential forces (0 on the normal
  // ones): dx = −D⁻¹ (d + Cᵀ λ), (C D⁻¹ Cᵀ) λ = −C D⁻¹ d.
  ws.inverse_weight.setZero(n);
  ws.gradient.setZero(n);
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& foot = layout.legs[l];
    if (foot.count == 0) continue;
    const double normal = foot.count == 3 ? x_a[foot.offset + 2] : foot.known_normal_force_N;
    const double f2 = std::max(normal * normal, 1e-12);
    for (int t = 0; t < 2; ++t) {
      ws.inverse_weight[foot.offset + t] = f2;
      ws.gradient[foot.offset + t] = x_a[foot.offset + t] / f2;
    }
    if (foot.count == 3) ws.inverse_weight[foot.offset + 2] = f2 / (kNormalWeight * kNormalWeight);
  }
  ws.trunk_t = qp.C.topRows(R).transpose();
  ws.scaled = ws.inverse_weight.asDiagonal() * ws.trunk_t;
  ws.schur.noalias() = ws.trunk_t.transpose() * ws.scaled;
  ws.schur.diagonal().array() += 1e-12 * std::max(1.0, ws.schur.trace());
  ws.ldlt.compute(ws.schur);
  ws.trial = ws.inverse_weight.cwiseProduct(ws.gradient);  // D⁻¹ d
  ws.lambda.noalias() = -(ws.trunk_t.transpose() * ws.trial);
  ws.ldlt.solveInPlace(ws.lambda);
  ws.dx = -ws.trial;
  ws.dx.noalias() -= ws.scaled * ws.lambda;
  if (!ws.dx.allFinite()) return kInf;
  mark_faces(qp, layout, ws.face);
  const double s = largest_step(qp, x_a, ws.dx, ws.face);
  double best = kInf;
  for (const double part : {1.0, 0.5, 0.0}) {
    ws.trial = x_a + (part * s) * ws.dx;
    int trial_leg = -1;
    const double use = friction_use(qp, layout, ws.trial, &trial_leg);
    if (!(use < best)) continue;
    best = use;
    leg = trial_leg;
    ws.x = ws.trial;
  }
  return best;
}

}  // namespace hexdyn
