#pragma once
/// \file allocation/ipopt_backend.hpp
/// The Ipopt back end of the allocation (the reference solver, and the one for the exact
/// friction cone). The only part of hexdyn that links Ipopt (target hexdyn_allocation_ipopt).
#include <memory>
#include <string>

#include "hexdyn/allocation/qp.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

struct IpoptOptions {
  /// Ipopt `tol` and `constr_viol_tol` (penalised runs also `compl_inf_tol` =
  /// 1e-3·tolerance). Rows count as violated beyond max(1e-6, 1e3·tolerance) relative to
  /// max(1, |bound|).
  double tolerance = 1e-9;
  int max_iterations = 200;       ///< per attempt
  double max_cpu_seconds = 10.0;  ///< per attempt
  /// ρ of the L1 penalty ρ Σ w_i s_i on the slacks of relaxed rows and cones (row units).
  /// Exact (the relaxed solution equals the strict one when that exists) once ρ w_i
  /// exceeds the rows' multipliers, i.e. the marginal cost of each bound.
  double slack_penalty = 1e6;
  bool warm_start = true;  ///< warm start from the previous solution of the same size
  /// ε of the smooth cone μ n ≥ √(t1² + t2² + ε²) − ε handed to Ipopt: exact at the apex,
  /// at most ε [N] of tangential excess elsewhere.
  double cone_smoothing_N = 1e-9;
  /// Ipopt `dual_inf_tol`: the absolute (unscaled) stationarity error allowed at the
  /// answer, on top of `tol`, which Ipopt tests on its scaled problem. Ipopt's default 1
  /// leaves `tol` in charge. It binds only where Ipopt converges by its own test: penalised
  /// runs at a tolerance of 1e-12 end at Ipopt's acceptable level instead (their
  /// compl_inf_tol is out of reach beside penalty terms ρ w up to 1e9, and their objective
  /// is scaled by ~1e-7), a few µN from the optimum at worst on the paper run with the
  /// cone. Lowered for the tests' reference (tests/hexdyn/allocation/test_cone.cpp).
  double dual_inf_tol = 1.0;
  std::string linear_solver = "mumps";
};

/// Maps the scene's allocation settings to the Ipopt options.
IpoptOptions ipopt_options_from(const AllocationParams& params);

/// Ipopt through its C++ TNLP interface; the application is created and initialised once.
/// Each solve tries the problem as posed (warm-started from the previous solution when the
/// sizes match), then the penalised problem if that fails; after a relaxed solve it goes to
/// the penalised problem directly while the sizes stay the same (its solution is the
/// strict optimum when no slack is needed). Details in ipopt_backend.cpp.
/// Throws ConfigError for non-positive options and SolverError if Ipopt cannot start.
std::unique_ptr<AllocationBackend> make_ipopt_backend(const IpoptOptions& options = {});

}  // namespace hexdyn
