#pragma once
/// \file mpi_sweep.hpp
/// `hexdyn sweep` over the ranks of MPI_COMM_WORLD (Open MPI; a plain start without
/// mpirun is one rank). The only part of hexdyn that uses MPI.
///
/// Rank 0 validates the sweep file (every error before any work, one line, exit 2; each
/// axis value once, nothing per scenario), opens the checkpoint (sweep/checkpoint.hpp)
/// and sends the sweep to the other ranks, which build each scenario's scene themselves
/// when it starts. Rank 0 coordinates with a SweepCoordinator (sweep/coordinator.hpp):
/// batches of indices sized to the measured cost, costly ones first in the tail, a
/// crashed scenario retried once. Finished scenarios come back in batches and are
/// appended to the checkpoint journal as they arrive; progress lines from the start; at
/// the end rank 0 writes the `hexdyn-sweep/5` file and removes the checkpoint. Rank 0 also
/// computes: a second thread of rank 0 is worker 0 while its main thread, the only one
/// calling MPI, polls for messages between 1 ms waits (if the MPI library does not allow
/// threads, MPI_THREAD_FUNNELED, rank 0 only coordinates when there are other ranks).
/// Every worker computes in a child process (sweep/scenario_process.hpp; set
/// HEXDYN_SWEEP_ISOLATION=none to compute in the rank itself, without crash containment)
/// and waits for messages with MPI_Iprobe and sleeps, never in a spinning blocking call.
#include <string>

#include "hexdyn/process/launch.hpp"  // launched_as_secondary_rank

namespace hexdyn {

/// Options of `hexdyn sweep SWEEP.yaml -o FILE`.
struct SweepOptions {
  std::string sweep_path;
  std::string output_path;
  bool keep_runs = false;            ///< store each scenario's full result under /runs/<id>
  bool resume = false;               ///< continue from `<FILE>.checkpoint/` if present
  bool verbose = false;              ///< one line per finished scenario
  double progress_interval_s = 5.0;  ///< at most one progress line per interval
};

/// Runs the sweep on every rank; initialises and finalises MPI. Messages go to stderr
/// from rank 0 only. Returns the process exit status: 0 when the sweep file is written
/// (failed scenarios are rows, not errors), 2 for a bad sweep file, arguments or
/// output path (before any work), 4 for an internal error.
int run_sweep(const SweepOptions& options);

}  // namespace hexdyn
