#pragma once
/// \file allocation/backends.hpp
/// The one place that knows every allocation back end: the scene's `allocation.solver`
/// (already resolved from `auto` by the configuration) names the one to create.
/// Compiled into hexdyn_allocation_ipopt, since one of the back ends is Ipopt.
#include <memory>

#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Creates the allocation back end named by `params.solver`, with its options from `params`.
std::unique_ptr<AllocationBackend> make_allocation_backend(const AllocationParams& params);

}  // namespace hexdyn
