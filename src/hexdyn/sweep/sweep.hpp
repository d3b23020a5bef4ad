#pragma once
/// \file sweep.hpp
/// Parameter sweeps without MPI (docs/user/sweeps.md; the file layout:
/// docs/user/output.md), one header per concern:
///   spec.hpp              the sweep file, its grid of scenarios, each value validated once;
///   scenario_factory.hpp  a scenario's scene, built when it starts from the base tree;
///   scenario.hpp          one scenario run as a summary row (status, metrics);
///   scenario_process.hpp  scenarios in a child process (crash containment);
///   coordinator.hpp       who computes what next (adaptive batches, costly first, retries);
///   record.hpp            a finished scenario as bytes, checksums;
///   journal.hpp           the checkpoint journal's format;
///   checkpoint.hpp        the checkpoint directory: journals, identity, lock;
///   sweep_file.hpp        the `hexdyn-sweep/5` writer (layout in io/schema.hpp);
///   progress.hpp          progress lines.
/// The distribution over ranks is in mpi/mpi_sweep.hpp. This header includes them all.
#include "hexdyn/sweep/checkpoint.hpp"
#include "hexdyn/sweep/coordinator.hpp"
#include "hexdyn/sweep/journal.hpp"
#include "hexdyn/sweep/progress.hpp"
#include "hexdyn/sweep/record.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/scenario_process.hpp"
#include "hexdyn/sweep/spec.hpp"
#include "hexdyn/sweep/sweep_file.hpp"
#include "hexdyn/sweep/validate.hpp"
