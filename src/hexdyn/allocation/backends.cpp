#include "hexdyn/allocation/backends.hpp"

#include "hexdyn/allocation/active_set_backend.hpp"
#include "hexdyn/allocation/cone_backend.hpp"
#include "hexdyn/allocation/ipopt_backend.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {

std::unique_ptr<AllocationBackend> make_allocation_backend(const AllocationParams& params) {
  switch (params.solver) {
    case AllocationSolver::kIpopt:
      return make_ipopt_backend(ipopt_options_from(params));
    case AllocationSolver::kActiveSet:
      // The exact cone by outer approximation on the active-set QP (allocation/cone_backend.hpp).
      if (params.friction == FrictionModel::kCone)
        return make_cone_backend(cone_options_from(params));
      return make_active_set_backend(active_set_options_from(params));
  }
  throw SolverError("allocation.solver: no back end");
}

}  // namespace hexdyn
