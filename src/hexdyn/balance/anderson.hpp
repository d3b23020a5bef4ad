#pragma once
/// \file anderson.hpp
/// Anderson acceleration of the balanced trunk's passes (docs/theory/balance.md#the-passes).
/// Internal to the balance stage.
#include <Eigen/Dense>
#include <vector>

#include "hexdyn/core/common.hpp"

namespace hexdyn {

/// Anderson acceleration of a fixed-point iteration x ← G(x) (Walker & Ni, SIAM J. Numer. Anal.
/// 49 (2011) 1715): from the last `depth` inputs and outputs, the combination whose residual
/// G(x) − x is least in the least-squares sense.
class AndersonMixer {
 public:
  explicit AndersonMixer(int depth) : depth_(depth) {}
  /// out: G(x) of the input the last call returned (or of the first input); replaced by the next
  /// input. `active` false: no mixing, the history restarts (the model changed).
  void mix(std::vector<std::vector<Vec2>>& out, bool active) {
    const Eigen::VectorXd g = flatten(out);
    if (!active || last_in_.size() != g.size()) {
      inputs_.clear();
      outputs_.clear();
      last_in_ = g;
      inputs_.push_back(g);
      outputs_.push_back(g);
      return;
    }
    inputs_.back() = last_in_;
    outputs_.back() = g;
    const int m = static_cast<int>(inputs_.size());
    Eigen::VectorXd next = g;
    if (m >= 2) {
      const Eigen::VectorXd f = g - last_in_;
      Eigen::MatrixXd dF(g.size(), m - 1), dG(g.size(), m - 1);
      for (int i = 0; i + 1 < m; ++i) {
        dF.col(i) = (outputs_[i + 1] - inputs_[i + 1]) - (outputs_[i] - inputs_[i]);
        dG.col(i) = outputs_[i + 1] - outputs_[i];
      }
      const Eigen::VectorXd gamma = dF.completeOrthogonalDecomposition().solve(f);
      next = g - dG * gamma;
    }
    inputs_.push_back(next);
    outputs_.push_back(next);
    if (static_cast<int>(inputs_.size()) > depth_ + 1) {
      inputs_.erase(inputs_.begin());
      outputs_.erase(outputs_.begin());
    }
    last_in_ = next;
    unflatten(next, out);
  }

 private:
  static Eigen::VectorXd flatten(const std::vector<std::vector<Vec2>>& v) {
    std::size_t n = 0;
    for (const auto& row : v) n += 2 * row.size();
    Eigen::VectorXd x(static_cast<Eigen::Index>(n));
    Eigen::Index i = 0;
    for (const auto& row : v)
      for (const Vec2& p : row) {
        x[i++] = p.x();
        x[i++] = p.y();
      }
    return x;
  }
  static void unflatten(const Eigen::VectorXd& x, std::vector<std::vector<Vec2>>& v) {
    Eigen::Index i = 0;
    for (auto& row : v)
      for (Vec2& p : row) {
        p = Vec2(x[i], x[i + 1]);
        i += 2;
      }
  }
  int depth_;
  Eigen::VectorXd last_in_;
  std::vector<Eigen::VectorXd> inputs_, outputs_;
};

}  // namespace hexdyn
