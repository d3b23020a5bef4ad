#pragma once
/// \file output.hpp
/// Writing a run as one `hexdyn-result/5` HDF5 file (schema.hpp; docs/user/output.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/result.hpp"

namespace hexdyn {

class H5Writer;       // io/h5io.hpp
struct ResultLayout;  // io/result_layout.hpp

/// Checks, before any work, that an output file may later be published at `out`
/// (publish_atomically), and throws IoError with one line naming `out` and the reason
/// (the OS's words where the OS refused) when not:
/// - `out` is a new path, or an existing regular file: a directory, device, FIFO, socket
///   or symbolic link is never replaced (why_not_replaceable; symbolic links are refused,
///   not resolved, so no file outside the output's folder is ever replaced);
/// - `out` is not the same file as any of `inputs` (every file the command read, with the
///   identity it had when read: config/inputs.hpp), compared by identity (st_dev, st_ino), so
///   that another name or a hard link of an input is refused too; also not the file now at
///   an input's absolute path, nor a recorded input's path when nothing is there
///   (check_not_input). A
///   command that reads a hexdyn file (the replay reads a result) lists that file and the
///   inputs its /meta input_sha256 records (config/inputs.hpp recorded_inputs), so that no
///   command writes onto the files a result was computed from;
/// - the folder of `out` exists and a file can be created in it: the temporary file of
///   `out` (temporary_path_for) is created with O_EXCL and removed again, so a missing
///   folder, a read-only or virtual file system (/proc, /sys), a name too long or a
///   full inode table are found before any computing.
/// Leaves the file system as it found it, except that temporary files of `out` left by
/// earlier runs whose process is gone are removed and named on stderr, one line each
/// (remove_stale_temporaries; docs/user/faults.md#leftovers).
void check_output_target(const std::string& out, const std::vector<InputFile>& inputs);

/// Throws IoError "cannot write output 'PATH': it is the URDF 'X' read by this command …"
/// when the file at `path` (links followed) is one of `inputs`: by the identity each had
/// when read, or as the file now at its absolute path; when nothing is at `path`, when
/// `path` names a recorded input's absolute path (folder links resolved; InputFile::recorded).
/// Every writer calls it before it writes into or renames over an existing file.
void check_not_input(const std::string& path, const std::vector<InputFile>& inputs);

/// Writes `result` to `path` atomically, after check_output_target(path, inputs): the file
/// is built as `.<basename>.tmp.<pid>`
/// in the same directory and renamed over `path` only when complete. On failure the
/// temporary file is removed, an existing file at `path` is left untouched, and the
/// IoError is rethrown.
///
/// Preconditions (checked; a mismatch throws IoError naming the dataset): every
/// kinematic array has result.kin.samples() = T rows and the column count of its
/// dataset (T×3, T×4, T×6 or T×18); when result.dyn.present, the dynamics arrays
/// have T rows (or T entries), energy_joint_J has 18 entries.
/// A result computed for a sweep's summary alone (RunResult::summary_only) throws IoError.
/// Dynamics datasets are written only when result.dyn.present. `/impacts/leg` is int32,
/// 0-based (0..5). Every dataset is labelled (io/labels.hpp).
void write_result_file(const std::string& path, const RunResult& result,
                       const std::vector<InputFile>& inputs = {});

/// Whether a resolved scene configuration (YAML, Scene::resolved_yaml) asks for compressed
/// datasets: its output.compression is `deflate` or absent (not `none`).
bool compressed_output(const std::string& resolved_yaml);

/// Writes the datasets and /meta of `result` into an open file below the root `prefix`
/// ("" for the file root, "/runs/<id>" inside a sweep file): result_layout(result)
/// (result_layout.hpp), then write_layout. `dimension_scales` false leaves the
/// dimension scales out (a kept run's image, labelled once copied: label_result_group).
void write_result_layout(H5Writer& writer, const RunResult& result, const std::string& prefix = "",
                         bool dimension_scales = true);

/// Writes a layout's attributes (creating their groups) and datasets below `prefix`, and
/// labels them (io/labels.hpp).
void write_layout(H5Writer& writer, const ResultLayout& layout, const std::string& prefix = "",
                  bool dimension_scales = true);

/// Refuses a run of more than kLargeResultSamples output samples unless `allow_large`:
/// throws ConfigError naming the count and the estimated file size of a robot of `legs` legs
/// and `joints` joints (`hexdyn run --allow-large`, hexdyn.run(..., allow_large=True)).
void check_run_size(std::size_t samples, int legs, int joints, bool allow_large);

/// Result files of more samples than this are refused before computing unless the run
/// is asked for explicitly (`hexdyn run --allow-large`): about 290 MB, 200 times the
/// paper run, and beyond it a typing error (output.impact_samples: 100000 gives 1.1 M
/// samples and a 1.7 GB file) is far likelier than a wish.
inline constexpr std::size_t kLargeResultSamples = 200000;

/// Size of a `hexdyn-result/5` file of `samples` samples of a robot of `legs` legs and
/// `joints` joints (the shapes' L and J) [bytes], estimated from the schema: every
/// per-sample dataset's row (schema.hpp shapes and element types, about 1.45 kB for 6 legs
/// and 18 joints) plus 32 bytes per solver message and 64 kB for /meta and /model, uncompressed:
/// the memory the writer holds while it builds the file (io/h5io.hpp), and an upper bound
/// of the file, which compression makes about half as large
/// (tests/hexdyn/cli/test_cli_outputs.cpp).
double estimated_result_file_bytes(std::size_t samples, std::size_t legs, std::size_t joints);

/// Creates the group `meta_path` and writes the attributes every hexdyn file's /meta opens
/// with (schema.hpp): `schema` = `schema_name`, `schema_version`, `version`, `git_commit`
/// and `created_utc` (now). The caller adds its layout's own attributes.
void write_meta_header(H5Writer& writer, const std::string& meta_path, const char* schema_name,
                       std::int64_t schema_version);

/// Current UTC time as ISO 8601 "YYYY-MM-DDTHH:MM:SSZ".
std::string utc_timestamp_now();

}  // namespace hexdyn
