#pragma once
/// \file messages.hpp
/// The messages between the ranks of a sweep (mpi_sweep.cpp) as bytes, without MPI:
/// the sweep itself (broadcast once, so that every rank builds its scenarios' scenes
/// itself), a batch of scenario indices to compute (or the order to stop), and a batch
/// of finished scenarios back (each with its record, record.hpp, or the crash that
/// ended its process). Fields are int64 and float64 in the host's byte order (all ranks
/// of one job run the same binary), strings and byte blocks as an int64 length then the
/// bytes. Unpacking a truncated message throws hexdyn::Error.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/sweep/journal.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

/// What a worker needs of the sweep: name, base scene tree and paths, axes (keys,
/// values, labels), and the sweep's identity as rank 0's checkpoint has it (with
/// --keep-runs in it), under which the worker builds its rows' journal records. The
/// validation results (SweepAxis::errors) stay on rank 0.
std::vector<char> pack_spec(const SweepSpec& spec, const SweepIdentity& identity);
SweepSpec unpack_spec(const std::vector<char>& bytes, SweepIdentity& identity);

/// A batch of scenario indices to compute, in order.
std::vector<char> pack_work(const std::vector<std::size_t>& indices);
/// The message that stops a worker rank.
std::vector<char> pack_stop();
/// The indices of a work message; nothing for the stop message.
std::optional<std::vector<std::size_t>> unpack_work(const std::vector<char>& bytes);

/// A worker's notice that it received `signal` (SIGTERM, SIGINT) and stopped computing.
std::vector<char> pack_interrupted(int signal);
/// The signal of such a notice.
int unpack_interrupted(const std::vector<char>& bytes);

/// A finished scenario on its way to the coordinator.
struct Finished {
  std::size_t index = 0;
  double cost_s = 0.0;        ///< scene construction + physics [s], for the scheduling
  bool crashed = false;       ///< its process died (payload empty, reason set)
  std::string reason;         ///< how the process died
  std::vector<char> payload;  ///< the row's journal record (journal.hpp; encode_record payload)
};

/// Appends one finished scenario to a result message under construction (start with an
/// empty vector).
void append_result(std::vector<char>& message, const Finished& f);
/// The finished scenarios of a result message, in order.
std::vector<Finished> unpack_results(const std::vector<char>& bytes);

/// Refuses, in one line (hexdyn::Error), the row of scenario `id` from rank `rank` whose
/// per-joint metrics have another size (ScenarioSummary::joints, which its record carries)
/// than the sweep's robot's `joints` (0: not known, nothing refused; a row of no computed run
/// has none).
void check_row_joints(const ScenarioSummary& row, int joints, const std::string& id, int rank);

}  // namespace hexdyn
