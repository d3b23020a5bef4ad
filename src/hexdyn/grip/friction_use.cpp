// The friction a force distribution uses and the rows that set it (grip/required_friction.hpp):
// set_friction_coefficient, leg_friction_use, friction_use and slipping_legs, shared by the
// required friction's solver and the pipeline's grip fields.
#include <algorithm>
#include <cmath>
#include <limits>

#include "hexdyn/grip/required_friction.hpp"

namespace hexdyn {

void set_friction_coefficient(const AllocationLayout& layout, double mu, QpProblem& qp) {
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    if (leg.offset < 0) continue;
    for (int f = 0; f < leg.friction_faces; ++f) {
      const int row = leg.friction_row + f;
      if (leg.count == 3)
        qp.C(row, leg.offset + 2) = -mu * leg.face_reach;
      else
        qp.upper[row] = mu * leg.face_reach * leg.known_normal_force_N;
    }
    if (leg.cone >= 0) qp.cones[static_cast<std::size_t>(leg.cone)].mu = mu;
  }
}

double leg_friction_use(const QpProblem& qp, const AllocationLayout& layout,
                        const Eigen::VectorXd& x, int l) {
  const AllocationLayout::Leg& leg = layout.legs[l];
  if (leg.offset < 0 || (leg.friction_faces == 0 && leg.cone < 0)) return -1.0;
  const double t1 = x[leg.offset], t2 = x[leg.offset + 1];
  const double fn = leg.count == 3 ? x[leg.offset + 2] : leg.known_normal_force_N;
  // The largest tangential reach over the leg's faces (or the cone's |t|) per unit f_n.
  double reach = 0.0;
  if (leg.cone >= 0) {
    reach = std::hypot(t1, t2);
  } else {
    for (int f = 0; f < leg.friction_faces; ++f) {
      const int row = leg.friction_row + f;
      reach = std::max(
          reach, (qp.C(row, leg.offset) * t1 + qp.C(row, leg.offset + 1) * t2) / leg.face_reach);
    }
  }
  // A leg whose forces are below the allocation's violation threshold carries nothing: its
  // ratio of two rounding-sized numbers says nothing of friction.
  if (reach <= 0.0 || std::max(reach, std::abs(fn)) <= kViolationThreshold) return 0.0;
  return fn > 0.0 ? reach / fn : std::numeric_limits<double>::infinity();
}

double friction_use(const QpProblem& qp, const AllocationLayout& layout, const Eigen::VectorXd& x,
                    int* leg_out) {
  double worst = -1.0;
  int worst_leg = -1;
  for (int l = 0; l < layout.n_legs; ++l) {
    const double use = leg_friction_use(qp, layout, x, l);
    if (use > worst) {
      worst = use;
      worst_leg = l;
    }
  }
  if (leg_out) *leg_out = worst_leg;
  return std::max(worst, 0.0);
}

LegArray<bool> slipping_legs(const QpProblem& qp, const AllocationLayout& layout,
                             const Eigen::VectorXd& x) {
  LegArray<bool> slips{};
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    if (leg.offset < 0) continue;
    for (int f = 0; f < leg.friction_faces && !slips[l]; ++f) {
      const int row = leg.friction_row + f;
      const double excess = qp.C.row(row).dot(x) - qp.upper[row];
      slips[l] = excess > kViolationThreshold * std::max(1.0, std::abs(qp.upper[row]));
    }
    if (leg.cone >= 0) {
      const SecondOrderCone& c = qp.cones[static_cast<std::size_t>(leg.cone)];
      const double excess = std::hypot(x[c.tangent1], x[c.tangent2]) - c.mu * x[c.normal];
      slips[l] = slips[l] || excess > kViolationThreshold * std::max(1.0, c.mu * x[c.normal]);
    }
  }
  return slips;
}

}  // namespace hexdyn
