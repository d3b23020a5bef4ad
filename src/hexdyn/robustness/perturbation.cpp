#include "hexdyn/robustness/perturbation.hpp"

#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>

namespace hexdyn {
namespace {

std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

int draw_count(Perturbation p, const DrawSizes& sizes) {
  switch (perturbation_extent(p)) {
    case PerturbationExtent::kOnce:
      return 1;
    case PerturbationExtent::kPerStep:
      return sizes.steps;
    case PerturbationExtent::kPerLink:
      return sizes.links;
    case PerturbationExtent::kPerJoint:
      return sizes.joints;
    case PerturbationExtent::kXyz:
      return 3;
  }
  return 0;
}

double counter_uniform(std::uint64_t seed, std::uint64_t replay, std::uint32_t stream,
                       std::uint32_t index) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ replay);
  h = splitmix64(h ^ ((static_cast<std::uint64_t>(stream) << 32) | index));
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

double draw_value(const Distribution& d, double u) {
  switch (d.kind) {
    case DistributionKind::kUniform:
      return d.low + u * (d.high - d.low);
    case DistributionKind::kNormal: {
      if (!(d.sigma > 0.0) || !(d.bound > 0.0)) return 0.0;
      // Truncated to [−b, b]: u maps onto [Φ(−b/σ), Φ(b/σ)], whose inverse is the value.
      const double c = gsl_cdf_ugaussian_P(d.bound / d.sigma);
      const double lo = 1.0 - c;  // Φ(−b/σ), exact by symmetry
      const double x = d.sigma * gsl_cdf_ugaussian_Pinv(lo + u * (c - lo));
      return std::clamp(x, -d.bound, d.bound);
    }
    case DistributionKind::kNone:
      break;
  }
  return 0.0;
}

WorldDraw draw_world(const PerturbationSpec& spec, const DrawSizes& sizes, std::uint64_t seed,
                     std::uint64_t replay) {
  WorldDraw w;
  for (int p = 0; p < kPerturbationCount; ++p) {
    const auto kind = static_cast<Perturbation>(p);
    const Distribution& d = spec[kind];
    std::vector<double>& v = w.values[static_cast<std::size_t>(p)];
    v.assign(static_cast<std::size_t>(draw_count(kind, sizes)), 0.0);
    if (d.kind == DistributionKind::kNone) continue;
    for (std::size_t k = 0; k < v.size(); ++k)
      v[k] = draw_value(d, counter_uniform(seed, replay, static_cast<std::uint32_t>(p),
                                           static_cast<std::uint32_t>(k)));
  }
  return w;
}

}  // namespace hexdyn
