#pragma once
/// \file launch.hpp
/// How the process was started, read from the environment only: no MPI call, no MPI
/// library needed (the command line, cli/main.cpp, uses it for every command, and loads
/// MPI only for `hexdyn sweep`).
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

}  // namespace hexdyn
