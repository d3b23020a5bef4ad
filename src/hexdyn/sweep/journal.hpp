#pragma once
/// \file journal.hpp
/// The checkpoint journal of a sweep (`hexdyn-sweep-journal/1`): an append-only file of
/// checksummed records, written by the sweep's coordinator while scenarios finish, read
/// by `--resume`. The checkpoint directory (checkpoint.hpp) holds one journal per run of
/// the sweep (a requeued job adds one), never one file per scenario.
///
/// Layout (integers little-endian, the host order of every supported machine):
///
///     header  (64 bytes)  "HXDJRN01", identity (SweepIdentity: id, sweep_file,
///                         base_scene, build, scenarios, keep_runs + 7 zero bytes),
///                         CRC-32 of the 56 bytes before it, 4 zero bytes
///     record  (repeated)  magic 0x31525848 ("HXR1"), uint32 kind, uint64 scenario index,
///                         uint64 identity id, uint64 payload size P, P payload bytes
///                         (record.hpp), CRC-32 of everything after the magic
///
/// Every record carries the sweep's identity, so that a journal whose header was lost
/// still cannot lend its records to another sweep. A record whose checksum fails, or that
/// is cut short, is reported and skipped; reading resumes at the next record magic whose
/// record checks.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hexdyn {

/// What a checkpoint belongs to: hashes (FNV-1a 64) of the sweep file's text, of the
/// resolved base scene, and of the build (version and git commit), with --keep-runs and
/// the number of scenarios. `id` combines them all.
struct SweepIdentity {
  std::uint64_t id = 0;
  std::uint64_t sweep_file = 0, base_scene = 0, build = 0, scenarios = 0;
  bool keep_runs = false;
  /// Empty when equal, else what differs, as a reason for the user.
  std::string difference(const SweepIdentity& other) const;
};

SweepIdentity make_identity(const std::string& sweep_yaml, const std::string& base_config_yaml,
                            const std::string& build, std::uint64_t scenarios, bool keep_runs);

/// Record kinds.
enum class RecordKind : std::uint32_t {
  kRow = 1,           ///< a finished scenario: payload from record.hpp
  kCrashAttempt = 2,  ///< the scenario's process died once; payload: the reason (text)
};

inline constexpr std::size_t kJournalHeaderBytes = 64;
inline constexpr std::size_t kRecordHeaderBytes = 32;  ///< magic .. payload size
inline constexpr std::size_t kRecordTrailerBytes = 4;  ///< CRC-32

/// The header bytes of a journal of `identity`.
std::vector<char> journal_header(const SweepIdentity& identity);

/// Appends one record (header, payload, checksum) to `out`.
void append_journal_record(std::vector<char>& out, RecordKind kind, std::uint64_t index,
                           const SweepIdentity& identity, const char* payload, std::size_t size);

/// The payload of a record built by append_journal_record elsewhere (a worker builds the
/// records of its rows, checksum included, so that rank 0 only appends their bytes).
struct BuiltRecord {
  const char* payload = nullptr;
  std::size_t size = 0;
};
/// Checks a record's header (magic, `kind`, `index`, `identity`'s id) and its length
/// against `size`; the checksum is its builder's and is checked when the journal is read.
/// Throws Error naming what does not match.
BuiltRecord check_built_record(const char* record, std::size_t size, RecordKind kind,
                               std::uint64_t index, const SweepIdentity& identity);

/// A record found in a journal: where its payload is.
struct JournalEntry {
  RecordKind kind = RecordKind::kRow;
  std::uint64_t index = 0;
  std::size_t payload_offset = 0;  ///< from the start of the file
  std::size_t payload_size = 0;
};

/// What read_journal found.
struct JournalScan {
  bool header_ok = false;             ///< the header's checksum held
  SweepIdentity header;               ///< when header_ok
  std::vector<JournalEntry> entries;  ///< intact records of the expected identity, file order
  std::vector<std::string> damage;    ///< one line per damaged or truncated stretch
  /// A record with an intact checksum but another identity (a foreign journal).
  bool foreign_record = false;
};

/// Reads the journal file's bytes (`data`, `size`) named `name` in messages, expecting
/// records of identity `expected.id`.
JournalScan scan_journal(const char* data, std::size_t size, const std::string& name,
                         const SweepIdentity& expected);

}  // namespace hexdyn
