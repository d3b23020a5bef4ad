#pragma once
/// \file robustness_bounds.hpp
/// Whether every world a robustness study can draw (core/robustness_params.hpp) is physical
/// and applies to its scene (docs/user/robustness.md#perturbations): what the scene reader
/// checks of robustness.perturbations, and what bounds a tolerance search's scales
/// (robustness/robustness.hpp).
#include <optional>
#include <string>

#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// The first problem of `spec` on `scene`: the key (robustness.perturbations.NAME) and what is
/// wrong ("errors up to 0.06 m could reverse the riser of step 1 (0.05 m), expected ..."). A
/// riser error as large as a riser, a tread that could become no deeper than its nosing, a
/// negative nosing or payload, μ_s or μ_d at or below zero, a relative error at or below −1,
/// step errors off stairs, actuator errors without actuators, payload_com without payload_mass.
struct PerturbationProblem {
  std::string key, message;
};
std::optional<PerturbationProblem> perturbation_problem(const PerturbationSpec& spec,
                                                        const Scene& scene);

}  // namespace hexdyn
