#pragma once
/// \file checkpoint.hpp
/// Per-scenario checkpoint records of a running sweep and the checkpoint directory that
/// holds them, with its manifest and lock. Each record is published atomically
/// (io/atomic_file.hpp), so a record present is complete; `--resume` continues from them.
#include <cstddef>
#include <string>
#include <vector>

#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

/// Group of a checkpoint record that holds the kept run (`hexdyn-result/1` layout).
inline constexpr const char* kCheckpointRunGroup = "/run";

/// A scenario as a checkpoint file (`hexdyn-sweep-checkpoint/1`, HDF5): /meta (schema,
/// index), /summary/* (the row) and, when the run is kept, /run/* in the
/// `hexdyn-result/1` layout. Built in a temporary file under `scratch_dir` (which must
/// be writable) and returned as the file's bytes, so that it can travel between ranks.
std::vector<char> encode_checkpoint(const ScenarioOutcome& outcome, const std::string& scratch_dir);

/// Reads the row of a checkpoint file; throws IoError if it is not one.
ScenarioSummary read_checkpoint_summary(const std::string& path);

/// The checkpoint directory of a sweep output, `<output>.checkpoint/`: a manifest
/// naming the sweep it belongs to, one `<id>.h5` per finished scenario (written to a
/// temporary name and renamed, so a file present is complete) and a lock held while
/// a sweep runs. Not thread-safe; store() does not call HDF5.
class Checkpoint {
 public:
  /// Opens the checkpoint of `output_path` for `spec` (rank 0, before any work).
  /// Without `resume`: an existing directory is an error (an interrupted sweep would
  /// be lost). With `resume`: an existing directory must have been made by the same
  /// sweep (same sweep file text, same resolved base scene, same --keep-runs, same
  /// hexdyn version and commit), else ConfigError; a missing one starts afresh.
  /// Leftover temporary files are removed; unreadable scenario files are removed and
  /// recomputed. Throws IoError if the directory is locked by a running sweep.
  Checkpoint(const std::string& output_path, const SweepSpec& spec, bool keep_runs, bool resume);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  const std::string& directory() const { return dir_; }
  /// Indices found finished when the checkpoint was opened, ascending.
  const std::vector<std::size_t>& finished() const { return finished_; }
  /// Path of scenario `index`'s file.
  std::string scenario_path(std::size_t index) const;
  /// Writes a scenario's checkpoint bytes atomically (temporary name, fsync, rename).
  void store(std::size_t index, const std::vector<char>& bytes);
  /// Removes the directory (after the sweep file is complete) and releases the lock.
  void remove();

 private:
  /// Checks or writes the manifest and lists the finished scenarios (lock held).
  void scan(const SweepSpec& spec, bool keep_runs);

  std::string dir_;
  const SweepSpec* spec_;
  std::vector<std::size_t> finished_;
  int lock_fd_ = -1;
};

}  // namespace hexdyn
