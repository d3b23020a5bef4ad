// Whether every world a robustness study can draw is physical (robustness_bounds.hpp).
#include "hexdyn/config/robustness_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hexdyn/core/stairs.hpp"

namespace hexdyn {
namespace {

using P = Perturbation;

std::string text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// Every world the distributions can draw must be physical and apply to the scene.
std::optional<PerturbationProblem> step_problem(const PerturbationSpec& spec,
                                                const TerrainParams& terrain) {
  const std::vector<StairStep> list = stair_step_list(terrain);
  const std::string root = "robustness.perturbations.";
  for (P p : {P::kRiserHeight, P::kTreadDepth, P::kNosing})
    if (spec[p].kind != DistributionKind::kNone && list.empty())
      return PerturbationProblem{
          root + perturbation_name(p),
          "the scene's terrain is not a staircase, expected terrain.type stairs (its steps "
          "are perturbed)"};
  const Distribution &h = spec[P::kRiserHeight], &b = spec[P::kTreadDepth], &n = spec[P::kNosing];
  for (std::size_t k = 0; k < list.size(); ++k) {
    const StairStep& s = list[k];
    const std::string step = " of step " + std::to_string(k + 1);
    if (s.riser_m != 0.0 && h.largest_magnitude() >= std::abs(s.riser_m))
      return PerturbationProblem{root + "riser_height",
                                 "errors up to " + text(h.largest_magnitude()) +
                                     " m could reverse the riser" + step + " (" + text(s.riser_m) +
                                     " m), expected a bound below its height"};
    if (s.nosing_m + n.lowest() < 0.0)
      return PerturbationProblem{root + "nosing", "errors down to " + text(n.lowest()) +
                                                      " m would make the nosing" + step + " (" +
                                                      text(s.nosing_m) + " m) negative"};
    if (s.tread_m + b.lowest() <= s.nosing_m + n.highest())
      return PerturbationProblem{
          root + (b.kind != DistributionKind::kNone ? "tread_depth" : "nosing"),
          "the tread" + step + " (" + text(s.tread_m) + " m) could become no deeper than its " +
              "nosing, expected errors that keep every tread deeper than its nosing"};
  }
  return std::nullopt;
}

std::optional<PerturbationProblem> body_problem(const PerturbationSpec& spec, const Scene& s) {
  const std::string root = "robustness.perturbations.";
  for (int i = 0; i < kPerturbationCount; ++i) {
    const auto p = static_cast<P>(i);
    if (perturbation_relative(p) && spec[p].lowest() <= -1.0)
      return PerturbationProblem{
          root + perturbation_name(p),
          "relative errors down to " + text(spec[p].lowest()) +
              " would make the quantity zero or negative, expected errors above -1"};
  }
  if (spec[P::kPayloadMass].lowest() < 0.0)
    return PerturbationProblem{root + "payload_mass",
                               "errors down to " + text(spec[P::kPayloadMass].lowest()) +
                                   " kg, expected a payload of at least 0 kg (a mass added)"};
  if (spec[P::kPayloadCom].kind != DistributionKind::kNone &&
      spec[P::kPayloadMass].kind == DistributionKind::kNone)
    return PerturbationProblem{root + "payload_com",
                               "a payload position needs robustness.perturbations.payload_mass"};
  const double mu = std::min(s.contact.static_friction, s.contact.dynamic_friction);
  if (mu + spec[P::kFriction].lowest() <= 0.0)
    return PerturbationProblem{root + "friction",
                               "errors down to " + text(spec[P::kFriction].lowest()) +
                                   " would leave no friction (the smaller of μ_s and μ_d is " +
                                   text(mu) + "), expected a smaller decrease"};
  for (P p : {P::kTorqueConstant, P::kResistance, P::kJointFriction})
    if (spec[p].kind != DistributionKind::kNone && !s.robot.drive.present)
      return PerturbationProblem{
          root + perturbation_name(p),
          "the scene has no actuators: (an actuator's error needs its drive train)"};
  return std::nullopt;
}

}  // namespace

std::optional<PerturbationProblem> perturbation_problem(const PerturbationSpec& spec,
                                                        const Scene& scene) {
  if (auto p = step_problem(spec, scene.terrain)) return p;
  return body_problem(spec, scene);
}

}  // namespace hexdyn
