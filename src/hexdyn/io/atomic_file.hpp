#pragma once
/// \file atomic_file.hpp
/// Publishing a file atomically, for every file hexdyn writes (result files, sweep
/// files, the checkpoint manifest and its scenario records): the file is built under a
/// temporary name `.<basename>.tmp.<pid>` in the directory of its final path, forced to
/// disk (fsync) and renamed over the final path only when complete. A reader therefore
/// sees either the old file or the complete new one, never a partial one; temporary
/// names start with '.', so a directory listing can tell them from finished files.
#include <cstddef>
#include <functional>
#include <string>

namespace hexdyn {

/// Publishes a file atomically: `write(tmp)` builds it at the temporary path `tmp`, then
/// it is synced to disk and renamed over `path`. When `write`, the sync or the rename
/// throws, the temporary file is removed, an existing file at `path` is left untouched,
/// and the exception is rethrown (the sync's and the rename's as IoError naming the path).
/// Precondition: the directory of `path` exists and is writable.
void publish_atomically(const std::string& path,
                        const std::function<void(const std::string& tmp)>& write);

/// Publishes `size` bytes at `data` as the file `path` (publish_atomically). Throws IoError.
void write_bytes_atomically(const std::string& path, const char* data, std::size_t size);

/// Forces a written file's data to disk (fsync) so that a following rename publishes a
/// complete file; throws IoError naming the path.
void sync_file_to_disk(const std::string& path);

}  // namespace hexdyn
