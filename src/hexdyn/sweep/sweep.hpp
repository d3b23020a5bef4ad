#pragma once
/// \file sweep.hpp
/// Parameter sweeps without MPI (DESIGN.md §4), one header per concern:
///   spec.hpp        the sweep file, its grid of scenarios and each scenario's scene;
///   scenario.hpp    one scenario run as a summary row (status, metrics);
///   checkpoint.hpp  per-scenario checkpoint records, the checkpoint directory and lock;
///   sweep_file.hpp  the `hexdyn-sweep/1` writer (layout in io/schema.hpp);
///   progress.hpp    progress lines.
/// The distribution over ranks is in mpi/mpi_sweep.hpp. This header includes all five.
#include "hexdyn/sweep/checkpoint.hpp"
#include "hexdyn/sweep/progress.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"
#include "hexdyn/sweep/sweep_file.hpp"
