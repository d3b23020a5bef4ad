#pragma once
/// \file comm_detail.hpp
/// The MPI plumbing of the sweep (mpi_sweep.cpp): the session, point-to-point messages of
/// bytes and collectives that wait without spinning. Internal: not installed.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <vector>

namespace hexdyn::mpi_detail {

/// MPI_Init_thread / MPI_Finalize for the lifetime of the sweep.
///
/// The sequential MUMPS that Ipopt links exports dummy MPI_Init, MPI_Comm_rank,
/// MPI_Finalize and MPI_Wtime (rank 0 of 1, no-op finalise), and it comes before
/// libmpi in the executable's symbol lookup order. This file therefore calls the
/// profiling entry points PMPI_Comm_rank and PMPI_Finalize, which only the MPI library
/// defines, and never MPI_Init or MPI_Wtime; the constructor checks that the ranks it
/// sees are 0..size−1 once each.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// True if threads other than the main one may exist (they never call MPI).
  bool threads_allowed() const { return thread_level_ >= MPI_THREAD_FUNNELED; }

 private:
  int thread_level_ = MPI_THREAD_SINGLE, rank_ = 0, size_ = 1;
};

/// Sends a byte block to rank `dest`. Throws Error above MPI's int count.
void send(const std::vector<char>& bytes, int dest, int tag);

/// Receives the message announced by `st` (from MPI_Iprobe).
std::vector<char> receive(const MPI_Status& st);

/// Waits for a non-blocking request without spinning (Open MPI's blocking calls poll at
/// full speed): MPI_Test with sleeps growing from 50 µs to 10 ms.
void quiet_wait(MPI_Request& req);

/// MPI_Bcast from rank 0 of a byte block, waiting quietly.
void broadcast_bytes(std::vector<char>& bytes);

/// MPI_Bcast from rank 0 of a status, waiting quietly.
void broadcast_status(int& status);

/// Waits for every rank without spinning.
void quiet_barrier();

}  // namespace hexdyn::mpi_detail
