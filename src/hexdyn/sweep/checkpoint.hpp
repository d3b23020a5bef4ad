#pragma once
/// \file checkpoint.hpp
/// The checkpoint of a running sweep: the directory `<output>.checkpoint/` with
///   lock               held (flock) by the sweep writing to it, released when its process
///                      dies; holds "pid host" of the holder for messages;
///   journal-NNNN.hxj   one append-only journal per run of the sweep (journal.hpp): a
///                      requeued or resumed job adds one, so the count is the number of
///                      runs, never the number of scenarios;
///   .*                 temporaries (removed when the checkpoint is opened).
/// `--resume` continues from the records of all journals. Every journal header and every
/// record carries the sweep's identity (journal.hpp), so a checkpoint of another sweep is
/// refused whole whatever files of it remain; damaged or truncated records are named in a
/// warning and their scenarios computed again. Not thread-safe.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/sweep/journal.hpp"
#include "hexdyn/sweep/record.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

/// The build as it enters a sweep's identity: "hexdyn VERSION (COMMIT)".
std::string build_identity();

/// The identity of `spec`'s sweep (journal.hpp) with `keep_runs`, as the checkpoint and the
/// workers (who build their rows' journal records) compute it.
SweepIdentity sweep_identity(const SweepSpec& spec, bool keep_runs);

/// The checkpoint directory, its lock or this run's journal is no longer the one this
/// sweep opened (removed, or replaced by another sweep's): the sweep must stop at once,
/// write nothing and remove nothing (docs/user/faults.md#lost-checkpoint). Exit status 2.
class CheckpointLost : public IoError {
 public:
  using IoError::IoError;
};

/// Nothing in a checkpoint follows a link (docs/user/faults.md#links): the directory is
/// opened with O_NOFOLLOW | O_DIRECTORY and every file in it with openat from that
/// descriptor, O_NOFOLLOW, O_EXCL on creation; a link, FIFO, device or other non-regular
/// file in place of the directory, the lock or a journal is refused (IoError naming it),
/// and a lock with other hard links too, before anything is written.
class Checkpoint {
 public:
  /// Opens the checkpoint of `output_path` for `spec` (rank 0, before any work).
  /// - Another live sweep holds the lock: IoError saying so (its process and host).
  /// - Without `resume`, journals present (an interrupted sweep): ConfigError advising
  ///   --resume (or removing the directory; it is not in use).
  /// - With `resume`, any journal (header or intact record) of another identity:
  ///   ConfigError naming what differs; nothing of the checkpoint is used.
  /// Damaged records: warnings(), their scenarios are not finished.
  Checkpoint(const std::string& output_path, const SweepSpec& spec, bool keep_runs, bool resume);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  const std::string& directory() const { return dir_; }
  const SweepIdentity& identity() const { return identity_; }
  /// Rows found finished when the checkpoint was opened (one per scenario, journal order).
  const std::vector<ScenarioSummary>& finished() const { return finished_; }
  /// Scenarios whose process died once in an earlier run (not finished).
  const std::vector<std::size_t>& crash_attempts() const { return crash_attempts_; }
  /// One line per damaged stretch of a journal found when opening.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// Number of journal files, this run's included once it has written.
  std::size_t journal_count() const;

  /// Appends a finished scenario's record (payload of encode_record) to this run's
  /// journal, created at the first append. Buffered: written by flush().
  void append_row(std::size_t index, const char* payload, std::size_t size);
  /// The same for a record a worker built (append_journal_record of kind kRow with this
  /// checkpoint's identity): its header is checked (check_built_record), its bytes appended.
  /// Returns where the record's payload is (inside `record`).
  BuiltRecord append_row_record(std::size_t index, const char* record, std::size_t size);
  /// Appends the first crash of a scenario (`reason`: how its process died).
  void append_crash(std::size_t index, const std::string& reason);
  /// Writes the buffered records to the journal (write(2): a killed process loses none
  /// of them); with `sync`, fsync as well (a crashed machine loses none). Throws IoError.
  void flush(bool sync);
  /// Bytes buffered and not yet flushed.
  std::size_t buffered() const { return buffer_.size(); }

  /// The run image of a finished scenario kept with --keep-runs; empty if none.
  std::vector<char> run_image(std::size_t index) const;
  /// Removes the directory (after the sweep file is complete) and releases the lock:
  /// only its lock, journals and temporaries, from its descriptor, and the directory if
  /// its path still names it. Throws CheckpointLost first when verify() fails.
  void remove();
  /// Throws CheckpointLost unless the path still names this checkpoint's directory (same
  /// device and inode as its descriptor), the directory still holds this sweep's lock
  /// and this run's journal. Called by every append and flush.
  void verify() const;

 private:
  struct ImageAt {
    std::uint32_t journal = 0;
    std::uint64_t offset = 0, size = 0;
  };
  void start_buffer();
  void note_image(std::size_t index, std::uint64_t record_at, const char* payload,
                  std::size_t size);
  void take_lock(const std::vector<InputFile>& inputs);
  void scan_journals(const SweepSpec& spec, bool resume);
  void release_lock();
  /// Names in the directory (from its descriptor), sorted, without "." and "..".
  std::vector<std::string> entry_names() const;

  std::string dir_;
  SweepIdentity identity_;
  std::vector<std::string> journals_;  ///< paths; this run's last once created
  std::vector<ScenarioSummary> finished_;
  std::vector<std::size_t> crash_attempts_;
  std::vector<std::string> warnings_;
  std::unordered_map<std::size_t, ImageAt> images_;
  std::string own_journal_;  ///< path of this run's journal
  int journal_fd_ = -1;
  std::uint64_t journal_size_ = 0;  ///< bytes written to this run's journal
  std::vector<char> buffer_;
  int lock_fd_ = -1;
  int dir_fd_ = -1;  ///< the checkpoint directory, opened without following a link
};

}  // namespace hexdyn
