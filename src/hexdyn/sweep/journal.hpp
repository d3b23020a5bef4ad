#pragma once
/// \file journal.hpp
/// The checkpoint journal of a sweep (`hexdyn-sweep-journal/2`): an append-only file of
/// checksummed records, written by the sweep's coordinator while scenarios finish, read
/// by `--resume`. The checkpoint directory (checkpoint.hpp) holds one journal per run of
/// the sweep (a requeued job adds one), never one file per scenario.
///
/// Layout (integers little-endian, the host order of every supported machine):
///
///     header  (H bytes)   "HXDJRN02", uint32 H, uint32 number of inputs I, identity
///                         (SweepIdentity: uint64 id, base_scene, build, scenarios,
///                         keep_runs), then I inputs, each three texts (uint32 length,
///                         bytes): role, absolute path, SHA-256 in hexadecimal; then the
///                         CRC-32 of the H − 4 bytes before it
///     record  (repeated)  magic 0x31525848 ("HXR1"), uint32 kind, uint64 scenario index,
///                         uint64 identity id, uint64 payload size P, P payload bytes
///                         (record.hpp), CRC-32 of everything after the magic
///
/// Every record carries the sweep's identity, so that a journal whose header was lost
/// still cannot lend its records to another sweep. A record whose checksum fails, or that
/// is cut short, is reported and skipped; reading resumes at the next record magic whose
/// record checks. A journal of format 1 ("HXDJRN01", before the inputs were hashed) is
/// recognised and refused as the checkpoint of an older hexdyn.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hexdyn/config/inputs.hpp"

namespace hexdyn {

/// What a checkpoint belongs to (docs/user/sweeps.md#what-a-checkpoint-belongs-to): the
/// SHA-256 of every input file's content (SweepSpec::inputs: the sweep file, the base
/// scene, every inherited file, every URDF named by the base or by an axis value), and
/// hashes (FNV-1a 64) of the resolved base scene and of the build (version and git
/// commit), with --keep-runs and the number of scenarios. `id` combines them all.
struct SweepIdentity {
  std::uint64_t id = 0;
  std::uint64_t base_scene = 0, build = 0, scenarios = 0;
  bool keep_runs = false;
  /// Each input's role, absolute path and SHA-256 (InputFile::path is the absolute path).
  std::vector<InputFile> inputs;
  int format = 2;  ///< journal format the identity was read from (1: no inputs recorded)
  /// Empty when equal, else what differs, as one line for the user: the first input whose
  /// content changed ("the URDF /abs/robot.urdf changed since the checkpoint was made
  /// (SHA-256 0a1b2c3d4e5f… then, 5f4e3d2c1b0a… now)"), or that is read only by one of
  /// the two, then the base scene, --keep-runs, the build and the number of scenarios.
  /// `other` is the checkpoint's identity, *this the sweep's now.
  std::string difference(const SweepIdentity& other) const;
};

SweepIdentity make_identity(const std::vector<InputFile>& inputs,
                            const std::string& base_config_yaml, const std::string& build,
                            std::uint64_t scenarios, bool keep_runs);

/// Record kinds.
enum class RecordKind : std::uint32_t {
  kRow = 1,           ///< a finished scenario: payload from record.hpp
  kCrashAttempt = 2,  ///< the scenario's process died once; payload: the reason (text)
};

/// Largest journal header accepted when reading [bytes] (a few hundred per input).
inline constexpr std::size_t kMaxJournalHeaderBytes = std::size_t{1} << 20;
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
