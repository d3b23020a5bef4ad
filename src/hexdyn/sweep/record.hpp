#pragma once
/// \file record.hpp
/// A finished scenario as bytes: the payload of a checkpoint journal record
/// (journal.hpp) and of a result message between ranks (mpi/messages.hpp). Also the
/// checksums both use. Fields are fixed-width integers and float64 in the host's byte
/// order (a checkpoint is resumed by the same build, which its identity checks); strings
/// and byte blocks are a uint64 length then the bytes. Decoding a short or malformed
/// payload throws IoError; nothing here touches a file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hexdyn/sweep/scenario.hpp"

namespace hexdyn {

/// CRC-32 (IEEE 802.3, the polynomial of zlib.crc32), continuing from `crc` (0 to start).
std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc = 0);

/// FNV-1a 64-bit hash of `text`, continuing from `h` (the FNV offset basis to start).
std::uint64_t fnv1a64(std::string_view text, std::uint64_t h = 0xcbf29ce484222325ULL);

/// A finished scenario: its row and, with --keep-runs and status ok, its full result as
/// the bytes of an HDF5 file holding the `hexdyn-result/5` layout under /run
/// (encode_run_image); empty otherwise.
struct ScenarioRecord {
  ScenarioSummary summary;
  std::vector<char> run_image;
};

/// The payload bytes of a record (summary fields, then the run image).
std::vector<char> encode_record(const ScenarioRecord& record);
/// Appends the same bytes to `out`.
void append_record(std::vector<char>& out, const ScenarioRecord& record);
/// Decodes a payload; with `with_image` false the run image is skipped (its offset
/// within the payload is returned in `image_offset`, its size in `image_size`).
ScenarioRecord decode_record(const char* data, std::size_t size, bool with_image = true,
                             std::size_t* image_offset = nullptr,
                             std::size_t* image_size = nullptr);

/// The run of a computed scenario as an HDF5 file image: /run in the `hexdyn-result/5`
/// layout. Built in a temporary file under `scratch_dir` (removed). Throws IoError.
std::vector<char> encode_run_image(const RunResult& run, const std::string& scratch_dir);

/// Group of a run image that holds the kept run.
inline constexpr const char* kRunImageGroup = "/run";

}  // namespace hexdyn
