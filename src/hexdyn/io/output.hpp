#pragma once
/// \file output.hpp
/// Writing a run as one `hexdyn-result/1` HDF5 file (DESIGN.md §4, schema.hpp).
#include <string>

#include "hexdyn/io/h5io.hpp"
#include "hexdyn/core/result.hpp"

namespace hexdyn {

/// Checks, before any work, that a result can later be written to `path`: its
/// directory exists and is writable (access(2)), and `path` is not a directory.
/// Creates and modifies nothing. Throws IoError with one line naming path and reason.
void check_output_path_writable(const std::string& path);

/// Writes `result` to `path` atomically: the file is built as `.<basename>.tmp.<pid>`
/// in the same directory and renamed over `path` only when complete. On failure the
/// temporary file is removed, an existing file at `path` is left untouched, and the
/// IoError is rethrown.
///
/// Preconditions (checked; a mismatch throws IoError naming the dataset): every
/// kinematic array has result.kin.samples() = T rows and the column count of its
/// dataset (T×3, T×4, T×6 or T×18); when result.dyn.present, the dynamics arrays
/// have T rows (or T entries), energy_joint_J has 18 entries.
/// Dynamics datasets are written only when result.dyn.present. `/impacts/leg` is int32,
/// 1-based (1..6).
void write_result_file(const std::string& path, const RunResult& result);

/// Writes the datasets and /meta of `result` into an open file below the root `prefix`
/// ("" for the file root, "/runs/<id>" inside a sweep file).
void write_result_layout(H5Writer& writer, const RunResult& result, const std::string& prefix = "");

/// Current UTC time as ISO 8601 "YYYY-MM-DDTHH:MM:SSZ".
std::string utc_timestamp_now();

}  // namespace hexdyn
