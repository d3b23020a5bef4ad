#pragma once
/// \file lane_sums.hpp
/// Sums over the generalised coordinates in one fixed order, for the replay
/// (replay.cpp, replay_report.cpp): whatever the robot's size and the compiler's vector width,
/// the order of Eigen's reductions of fixed size with two-lane packets, which the replay of a
/// hexapod has always had (its results stay the same bit for bit).
#include <Eigen/Core>
#include <cmath>

#include "hexdyn/core/common.hpp"

namespace hexdyn::replay_sums {

/// Σ term(k), k = start … start + n − 1 (n ≥ 1), split in halves: term(start) alone, else the
/// sum of the first ⌊n/2⌋ terms plus the sum of the others.
template <class Term>
double halves_sum(const Term& term, Eigen::Index start, Eigen::Index n) {
  if (n == 1) return term(start);
  const Eigen::Index half = n / 2;
  return halves_sum(term, start, half) + halves_sum(term, start + half, n - half);
}

/// Σ term(k), k = 0 … n − 1, in two lanes: the even and the odd terms of the first 2⌊n/2⌋
/// each summed in halves, the lanes added, then the last term when n is odd.
template <class Term>
double lane_sum(const Term& term, Eigen::Index n) {
  if (n < 2) return n == 1 ? term(0) : 0.0;
  const Eigen::Index pairs = n / 2;
  const double even = halves_sum([&](Eigen::Index p) { return term(2 * p); }, 0, pairs);
  const double odd = halves_sum([&](Eigen::Index p) { return term(2 * p + 1); }, 0, pairs);
  const double sum = even + odd;
  return 2 * pairs == n ? sum : sum + term(n - 1);
}

/// a · b (equal sizes) by lane_sum.
template <class A, class B>
double lane_dot(const A& a, const B& b) {
  return lane_sum([&](Eigen::Index k) { return a[k] * b[k]; }, a.size());
}

/// Σ |a_k b_k| (the power of torques a at rates b) by lane_sum.
template <class A, class B>
double lane_abs_dot(const A& a, const B& b) {
  return lane_sum([&](Eigen::Index k) { return std::abs(a[k] * b[k]); }, a.size());
}

}  // namespace hexdyn::replay_sums
