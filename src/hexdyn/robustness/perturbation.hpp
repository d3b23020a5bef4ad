#pragma once
/// \file perturbation.hpp
/// The draws of a robustness study (docs/user/robustness.md#perturbations): the errors of
/// each replay's world, from the distributions of the scene's robustness.perturbations
/// (core/robustness_params.hpp).
///
/// Draws are counter-based (docs/theory/robustness.md#draws): the uniform variate of replay r,
/// perturbation p and component k is a hash of (seed, r, p, k), never the state of a sequential
/// generator, so a replay's world depends on its index alone: the same on any number of
/// threads or ranks, and the same world at every scale of a tolerance search (common random
/// numbers). A normal error is truncated at ±bound by inversion of its CDF (one uniform per
/// value); a uniform error is low + u (high − low).
#include <array>
#include <cstdint>
#include <vector>

#include "hexdyn/core/robustness_params.hpp"

namespace hexdyn {

/// The sizes of the per-step, per-link and per-joint draws.
struct DrawSizes {
  int steps = 0, links = 0, joints = 0;
};
/// The number of values one replay draws of `p`.
int draw_count(Perturbation p, const DrawSizes& sizes);

/// The errors of one replay's world: values[p] holds draw_count(p, sizes) numbers, all 0 for a
/// perturbation of kind kNone.
struct WorldDraw {
  std::array<std::vector<double>, kPerturbationCount> values{};
  const std::vector<double>& operator[](Perturbation p) const {
    return values[static_cast<int>(p)];
  }
};

/// The uniform variate in (0, 1) of (seed, replay, stream, index): SplitMix64's finaliser
/// (Steele, Lea and Flood 2014) chained over the four words, its top 53 bits, offset by half a
/// unit so that neither 0 nor 1 is drawn.
double counter_uniform(std::uint64_t seed, std::uint64_t replay, std::uint32_t stream,
                       std::uint32_t index);

/// The value of `d` at the uniform variate u ∈ (0, 1): the inverse of its CDF.
double draw_value(const Distribution& d, double u);

/// The world of replay `replay` (0-based) under `spec`, for the seed `seed`.
WorldDraw draw_world(const PerturbationSpec& spec, const DrawSizes& sizes, std::uint64_t seed,
                     std::uint64_t replay);

}  // namespace hexdyn
