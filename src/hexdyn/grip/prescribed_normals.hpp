/// \file grip/prescribed_normals.hpp
/// The certificate of a sample whose loaded feet are all in their touchdown transients: their
/// normal forces are prescribed, and when no tangential force within mu_max times them closes
/// the trunk rows, no friction coefficient up to mu_max admits the sample
/// (docs/theory/grip.md#prescribed-normal-forces). It settles such samples without a probe.
#pragma once

#include <string>

#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/allocation/qp.hpp"

namespace hexdyn {

/// A lower bound on the trunk rows' scaled miss ‖D (C x − b)‖₂ over every x the sample allows
/// at μ ≤ mu_max, when each leg with variables is in its touchdown transient: its only
/// variables its tangential forces, inside the circle of radius mu_max f̄_n that holds every
/// face or cone of the friction model, so ‖x‖ ≤ X = mu_max √(Σ f̄_n²). C x = b are the first
/// AllocationLayout::kTrunkRows inequality rows of `qp` (lower = upper = b), D their scales
/// 1 / max(1, |b_i|). For every left singular vector u of D C (σ_u its singular value, 0 beyond
/// the rank) the miss is at least |uᵀ D b| − σ_u X; the best such bound is returned. 0 when the
/// sample has a support leg, whose normal force has no upper bound.
double prescribed_trunk_miss(const QpProblem& qp, const AllocationLayout& layout, double mu_max);

/// A miss of prescribed_trunk_miss that certifies the sample: 100 times the largest a probe
/// accepts (√6 · kProbeThreshold, each row held to 1e-8 of its scale), far above the
/// decomposition's rounding.
inline constexpr double kCertifiedTrunkMiss = 1e-6;

/// The trunk rows' misses at the forces that come closest to them (the least-squares forces of
/// the scaled rows, tangential bounds aside), largest first, named as describe_violations names
/// rows: "trunk force z by 65.7, trunk moment x by 0.247".
std::string prescribed_trunk_text(const QpProblem& qp);

}  // namespace hexdyn
