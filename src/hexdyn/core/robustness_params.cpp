#include "hexdyn/core/robustness_params.hpp"

#include <algorithm>

namespace hexdyn {
namespace {

struct Row {
  const char* name;
  const char* unit;
  PerturbationExtent extent;
  bool relative;
};
// clang-format off
constexpr std::array<Row, kPerturbationCount> kRows{{
    {"riser_height", "m", PerturbationExtent::kPerStep, false},
    {"tread_depth", "m", PerturbationExtent::kPerStep, false},
    {"nosing", "m", PerturbationExtent::kPerStep, false},
    {"friction", "1", PerturbationExtent::kOnce, false},
    {"payload_mass", "kg", PerturbationExtent::kOnce, false},
    {"payload_com", "m", PerturbationExtent::kXyz, false},
    {"trunk_mass", "1", PerturbationExtent::kOnce, true},
    {"link_mass", "1", PerturbationExtent::kPerLink, true},
    {"torque_constant", "1", PerturbationExtent::kPerJoint, true},
    {"resistance", "1", PerturbationExtent::kPerJoint, true},
    {"joint_friction", "1", PerturbationExtent::kPerJoint, true},
    {"foot_placement", "m", PerturbationExtent::kOnce, false},
    {"contact_stiffness", "1", PerturbationExtent::kOnce, true},
}};
// clang-format on

const Row& row(Perturbation p) { return kRows[static_cast<std::size_t>(p)]; }

}  // namespace

const char* perturbation_name(Perturbation p) { return row(p).name; }
const char* perturbation_unit(Perturbation p) { return row(p).unit; }
PerturbationExtent perturbation_extent(Perturbation p) { return row(p).extent; }
bool perturbation_relative(Perturbation p) { return row(p).relative; }

Distribution Distribution::scaled(double s) const {
  Distribution d = *this;
  d.sigma *= s;
  d.bound *= s;
  d.low *= s;
  d.high *= s;
  return d;
}

double Distribution::largest_magnitude() const {
  switch (kind) {
    case DistributionKind::kNormal:
      return sigma > 0.0 ? bound : 0.0;
    case DistributionKind::kUniform:
      return std::max(std::abs(low), std::abs(high));
    case DistributionKind::kNone:
      break;
  }
  return 0.0;
}

double Distribution::lowest() const {
  return kind == DistributionKind::kUniform ? low : -largest_magnitude();
}

double Distribution::highest() const {
  return kind == DistributionKind::kUniform ? high : largest_magnitude();
}

std::vector<Perturbation> PerturbationSpec::active() const {
  std::vector<Perturbation> out;
  for (int p = 0; p < kPerturbationCount; ++p)
    if (of[static_cast<std::size_t>(p)].kind != DistributionKind::kNone)
      out.push_back(static_cast<Perturbation>(p));
  return out;
}

}  // namespace hexdyn
