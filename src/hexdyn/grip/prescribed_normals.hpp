/// \file grip/prescribed_normals.hpp
/// The certificate of a sample whose loaded feet are all in their touchdown transients: their
/// normal forces are prescribed, and when no tangential force within mu_max times them closes
/// the trunk rows, no friction coefficient up to mu_max admits the sample
/// (docs/theory/grip.md#prescribed-normal-forces). It settles such samples without a probe.
/// Beside it, from the same scaled trunk rows: their part that no forces meet, which the
/// required friction drops when the allocation's own threshold would keep it
/// (drop_unreachable_trunk_part, docs/theory/grip.md#the-trunk-rows-reach).
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

/// The trunk rows' part that no forces can meet, whatever their bounds, dropped when it is
/// below `limit`. The scaled rows D C x = D b of `qp` (as prescribed_trunk_miss) split D b
/// into its projection onto the range of D C (singular values below 1e-9 of the largest
/// counted as zero) and the rest r, the least miss any forces leave. When
/// 1e-12 < max_i |r_i| ≤ limit, the rows' bounds move to b − r / D (each row by at most
/// `limit` of its scale) and the function returns true; else `qp` is left as it was. Two feet
/// give no moment about the line through them, so on a trot's diagonal a planned wrench whose
/// moment about that line is off by rounding (1e-9 to 1e-7 N m on the balanced Solo-12 trots)
/// has such a part (docs/theory/grip.md#the-trunk-rows-reach).
bool drop_unreachable_trunk_part(QpProblem& qp, double limit);

/// The trunk rows' misses at the forces that come closest to them (the least-squares forces of
/// the scaled rows, tangential bounds aside), largest first, named as describe_violations names
/// rows: "trunk force z by 65.7, trunk moment x by 0.247".
std::string prescribed_trunk_text(const QpProblem& qp);

}  // namespace hexdyn
