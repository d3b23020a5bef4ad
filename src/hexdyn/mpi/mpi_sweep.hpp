#pragma once
/// \file mpi_sweep.hpp
/// `hexdyn sweep` over the ranks of MPI_COMM_WORLD (Open MPI; a plain start without
/// mpirun is one rank). The only part of hexdyn that uses MPI.
///
/// Rank 0 validates the sweep file (every error before any work, one line, exit 2),
/// opens the checkpoint (sweep/checkpoint.hpp) and coordinates: it hands out scenario indices one
/// at a time to whichever rank asks (dynamic work sharing; scenario costs differ a
/// lot), stores every finished scenario in the checkpoint as it arrives, prints
/// progress, and at the end writes the `hexdyn-sweep/1` file from the checkpoint and
/// removes the checkpoint. Rank 0 also computes: a second thread of rank 0 takes
/// scenarios from the same queue while its main thread, the only one calling MPI,
/// polls for requests between 1 ms sleeps (if the MPI library does not allow threads,
/// MPI_THREAD_FUNNELED, rank 0 only coordinates when there are other ranks). Each
/// scenario is `run_scene`, the call behind `hexdyn run`, inside the rank's process.
#include <string>

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

/// True when this process was started by an MPI or Slurm launcher as a rank other than
/// 0 (from OMPI_COMM_WORLD_RANK, PMIX_RANK, PMI_RANK or SLURM_PROCID; MPI is not
/// initialised). The CLI uses it to print an argument error once, not once per rank.
bool launched_as_secondary_rank();

}  // namespace hexdyn
