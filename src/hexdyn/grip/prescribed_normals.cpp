#include "hexdyn/grip/prescribed_normals.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "hexdyn/core/sizes.hpp"
#include "hexdyn/grip/required_friction_solver.hpp"

namespace hexdyn {
namespace {

constexpr int R = AllocationLayout::kTrunkRows;
/// The trunk rows of a sample, at most three forces a leg: sized on the stack.
using TrunkRows = Eigen::Matrix<double, R, Eigen::Dynamic, 0, R, kMaxLegForces>;
using TrunkVector = Eigen::Matrix<double, R, 1>;

/// The trunk rows of `qp` scaled by 1 / max(1, |b_i|): D C into M, D b into b, the scales into
/// `scale`. False when a trunk row is not an equality of finite value.
bool scaled_trunk_rows(const QpProblem& qp, TrunkRows& M, TrunkVector& b, TrunkVector& scale) {
  M.resize(R, qp.variables());
  for (int i = 0; i < R; ++i) {
    if (!(qp.lower[i] == qp.upper[i]) || !std::isfinite(qp.lower[i])) return false;
    scale[i] = std::max(1.0, std::abs(qp.lower[i]));
    M.row(i) = qp.C.row(i) / scale[i];
    b[i] = qp.lower[i] / scale[i];
  }
  return true;
}

}  // namespace

double prescribed_trunk_miss(const QpProblem& qp, const AllocationLayout& layout, double mu_max) {
  const int n = qp.variables();
  if (n == 0 || n > kMaxLegForces || qp.inequalities() < R) return 0.0;
  double radius2 = 0.0;
  int counted = 0;
  for (int l = 0; l < layout.n_legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    if (leg.count == 0) continue;
    if (leg.count != 2 || (leg.friction_faces == 0 && leg.cone < 0)) return 0.0;
    radius2 += leg.known_normal_force_N * leg.known_normal_force_N;
    counted += leg.count;
  }
  TrunkRows M;
  TrunkVector b, scale;
  if (counted != n || !scaled_trunk_rows(qp, M, b, scale)) return 0.0;
  const double X = mu_max * std::sqrt(radius2);
  const Eigen::JacobiSVD<TrunkRows> svd(M, Eigen::ComputeFullU);
  double best = 0.0;
  for (int k = 0; k < R; ++k) {
    const double sigma = k < svd.singularValues().size() ? svd.singularValues()[k] : 0.0;
    best = std::max(best, std::abs(svd.matrixU().col(k).dot(b)) - sigma * X);
  }
  return best;
}

bool drop_unreachable_trunk_part(QpProblem& qp, double limit) {
  const int n = qp.variables();
  if (n == 0 || n > kMaxLegForces || qp.inequalities() < R) return false;
  TrunkRows M;
  TrunkVector b, scale;
  if (!scaled_trunk_rows(qp, M, b, scale)) return false;
  const Eigen::JacobiSVD<TrunkRows> svd(M, Eigen::ComputeFullU);
  const auto& sigma = svd.singularValues();
  TrunkVector r = b;
  for (int k = 0; k < sigma.size(); ++k)
    if (sigma[k] > 1e-9 * sigma[0]) r -= svd.matrixU().col(k).dot(b) * svd.matrixU().col(k);
  const double largest = r.lpNorm<Eigen::Infinity>();
  if (!(largest > 1e-12 && largest <= limit)) return false;
  for (int i = 0; i < R; ++i) qp.lower[i] = qp.upper[i] = (b[i] - r[i]) * scale[i];
  return true;
}

std::string prescribed_trunk_text(const QpProblem& qp) {
  TrunkRows M;
  TrunkVector b, scale;
  if (qp.variables() > kMaxLegForces || !scaled_trunk_rows(qp, M, b, scale)) return {};
  const Eigen::VectorXd x = Eigen::JacobiSVD<Eigen::MatrixXd>(
                                Eigen::MatrixXd(M), Eigen::ComputeThinU | Eigen::ComputeThinV)
                                .solve(b);
  const TrunkVector miss = (M * x - b).cwiseProduct(scale).cwiseAbs();
  std::vector<int> rows;
  for (int i = 0; i < R; ++i)
    if (miss[i] > kProbeThreshold * scale[i]) rows.push_back(i);
  std::stable_sort(rows.begin(), rows.end(), [&](int a, int c) { return miss[a] > miss[c]; });
  std::ostringstream text;
  text << std::setprecision(3);  // as describe_violations
  for (std::size_t k = 0; k < rows.size(); ++k)
    text << (k ? ", " : "") << qp.ineq_name(rows[k]) << " by " << miss[rows[k]];
  return text.str();
}

}  // namespace hexdyn
