#pragma once
/// \file messages.hpp
/// The messages between the ranks of a sweep (mpi_sweep.cpp) as bytes, without MPI: a
/// scenario to compute (or the order to stop) from rank 0, and a finished scenario with
/// its checkpoint record back. Fields are int64 and float64 in the host's byte order
/// (all ranks of one job run the same binary), strings and byte blocks as an int64
/// length then the bytes. Unpacking a truncated message throws hexdyn::Error.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

/// A scenario handed to a rank: its input and whether to keep its full result.
struct Work {
  ScenarioInput input;
  bool keep_runs = false;
};

std::vector<char> pack_work(const ScenarioInput& in, bool keep_runs);
/// The message that stops a worker rank.
std::vector<char> pack_stop();
/// The scenario of a work message; nothing for the stop message.
std::optional<Work> unpack_work(const std::vector<char>& bytes);

/// A finished scenario on its way to the checkpoint.
struct Finished {
  std::size_t index = 0;
  ScenarioStatus status = ScenarioStatus::kOk;
  std::string message;
  double wall_time_s = 0.0;
  int rank = 0;
  std::vector<char> checkpoint;  ///< encode_checkpoint bytes
};

std::vector<char> pack_result(const Finished& f);
/// `rank` is the sender, recorded in Finished::rank (not part of the message).
Finished unpack_result(const std::vector<char>& bytes, int rank);

}  // namespace hexdyn
