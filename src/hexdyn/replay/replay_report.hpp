#pragma once
/// \file replay_report.hpp
/// The report of a replay (docs/theory/replay.md#what-the-replay-reports): drift at the cycle
/// ends, tracking error, the totals, the electrical energy beside the plan's, and arrival.
#include "hexdyn/core/scene.hpp"
#include "hexdyn/replay/replay.hpp"

namespace hexdyn {

/// Fills r's report from its samples (r.t_s … r.electrical_J) and the plan it replayed;
/// `completed`: the replay reached the plan's last instant.
void finish_report(const ReplayPlan& plan, const TerrainParams& terrain,
                   const DriveTrainParams& drive, bool completed, ReplayResult& r);

}  // namespace hexdyn
