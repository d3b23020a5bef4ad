#include "hexdyn/mpi/comm_detail.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <limits>
#include <string>
#include <thread>

#include "hexdyn/core/errors.hpp"

namespace hexdyn::mpi_detail {

MpiSession::MpiSession() {
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &thread_level_);
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  long long mine = rank_, sum = 0;
  MPI_Allreduce(&mine, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (sum != static_cast<long long>(size_) * (size_ - 1) / 2) {
    std::cerr << "hexdyn: internal error: MPI ranks are not distinct (MPI symbols shadowed "
                 "by another library?)\n";
    MPI_Abort(MPI_COMM_WORLD, 4);
  }
}

MpiSession::~MpiSession() { PMPI_Finalize(); }

void send(const std::vector<char>& bytes, int dest, int tag) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("sweep: message of " + std::to_string(bytes.size()) + " bytes exceeds MPI's limit");
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

std::vector<char> receive(const MPI_Status& st) {
  int count = 0;
  MPI_Get_count(&st, MPI_BYTE, &count);
  std::vector<char> bytes(static_cast<std::size_t>(count));
  MPI_Recv(bytes.data(), count, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return bytes;
}

void quiet_wait(MPI_Request& req) {
  auto pause = std::chrono::microseconds(50);
  for (int done = 0;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(10000));
  }
}

void broadcast_bytes(std::vector<char>& bytes) {
  long long size = static_cast<long long>(bytes.size());
  MPI_Request req;
  MPI_Ibcast(&size, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD, &req);
  quiet_wait(req);
  bytes.resize(static_cast<std::size_t>(size));
  if (size > std::numeric_limits<int>::max()) throw Error("sweep: sweep description too large");
  MPI_Ibcast(bytes.data(), static_cast<int>(size), MPI_BYTE, 0, MPI_COMM_WORLD, &req);
  quiet_wait(req);
}

void broadcast_status(int& status) {
  MPI_Request req;
  MPI_Ibcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD, &req);
  quiet_wait(req);
}

void quiet_barrier() {
  MPI_Request req;
  MPI_Ibarrier(MPI_COMM_WORLD, &req);
  quiet_wait(req);
}

}  // namespace hexdyn::mpi_detail
