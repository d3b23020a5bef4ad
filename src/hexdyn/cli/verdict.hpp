#pragma once
/// \file verdict.hpp
/// The one line that ends `hexdyn run` (docs/user/output.md#the-runs-verdict).
#include <string>

#include "hexdyn/core/result.hpp"

namespace hexdyn::cli {

/// "hexdyn: verdict: T samples, R relaxed outside touchdowns (r in them), largest required
/// friction μ (Lk at t = … s) outside touchdowns, S slip samples": the counts of the
/// sweep's row (sweep/scenario.hpp summarize_run), so that a run and a sweep scenario of the
/// same scene say the same. Failed samples and samples no friction coefficient admits are
/// named when there are any.
std::string run_verdict(const RunResult& run);

}  // namespace hexdyn::cli
