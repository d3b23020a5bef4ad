#pragma once
/// \file launch.hpp
/// How the process was started, read from the environment only: no MPI call, no MPI
/// library needed (the command line, cli/dispatch.cpp, uses it for every command, and loads
/// MPI only for `hexdyn sweep`).
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace hexdyn {

/// True when this process was started by an MPI or Slurm launcher as a rank other than
/// 0 (from OMPI_COMM_WORLD_RANK, PMIX_RANK, PMI_RANK or SLURM_PROCID; MPI is not
/// initialised). The CLI uses it to print an argument error once, not once per rank.
inline bool launched_as_secondary_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && *value != '\0') return std::strcmp(value, "0") != 0;
  }
  return false;
}

/// A rank started by a launcher (mpirun, orted, srun) dies with it: PR_SET_PDEATHSIG, then a
/// check that the launcher did not die in between (docs/user/faults.md#orphans). Open MPI puts
/// each rank in its own process group, so a kill -9 of the launcher's group would leave
/// the ranks running and holding the checkpoint's lock.
inline void die_with_launcher() {
  bool launched = false;
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    launched = launched || std::getenv(name) != nullptr;
  if (!launched) return;
  const pid_t parent = ::getppid();
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // The launcher died between the look at it and prctl: no signal will come.
  if (::getppid() != parent) ::_exit(128 + SIGKILL);
}

}  // namespace hexdyn
