#pragma once
/// \file atomic_file.hpp
/// Publishing a file atomically, for every file hexdyn writes (result files, sweep
/// files, the checkpoint manifest and its scenario records): the file is built under a
/// temporary name `.<basename>.tmp.<pid>` in the directory of its final path, forced to
/// disk (fsync) and renamed over the final path only when complete. A reader therefore
/// sees either the old file or the complete new one, never a partial one; temporary
/// names start with '.', so a directory listing can tell them from finished files. A
/// <basename> of more than 239 bytes, with which the temporary name could pass the file
/// systems' 255 bytes (NAME_MAX), is cut in the temporary name to its first 222 bytes, '~'
/// and 16 hexadecimal digits of its SHA-256: any name that may be written has a temporary
/// name that may be written too, one per output and process.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hexdyn {

/// Publishes a file atomically: `write(tmp)` builds it at the temporary path `tmp`, then
/// it is synced to disk and renamed over `path`. Right before the rename `path` is
/// checked again with why_not_replaceable: a device, FIFO, socket, directory or symbolic
/// link that appeared there meanwhile is never replaced (IoError). When `write`, the sync or the
/// rename throws, the temporary file is removed, an existing file at `path` is left untouched, and
/// the exception is rethrown (the sync's and the rename's as IoError naming the path; an
/// IoError naming the temporary path is rethrown naming `path` instead). The temporary
/// file is registered with the signal handlers (interrupt.hpp) while it exists, and a
/// signal received during `write` is never published (Interrupted).
/// Precondition: the directory of `path` exists and is writable.
/// The temporary path is temporary_path_for(path).
void publish_atomically(const std::string& path,
                        const std::function<void(const std::string& tmp)>& write);

/// Why an existing `path` must not be replaced by a published file, or nothing when it
/// may be: nothing when `path` does not exist or is a regular file; otherwise "is a
/// symbolic link", "is a directory", "is a character device", "is a block device", "is a
/// FIFO (named pipe)", "is a socket". Symbolic links are refused, not followed: renaming
/// over a link replaces the link, and following it could replace a file outside the
/// output's folder. Uses lstat(2); other lstat failures than "does not exist" (a name
/// too long, a path through a non-directory, no permission) are returned with the OS
/// reason.
std::optional<std::string> why_not_replaceable(const std::string& path);

/// Removes the temporary files `.<basename>.tmp.<pid>` of `path` left by processes that
/// are gone (kill(pid, 0) fails with ESRCH): only regular files owned by this user, never
/// a link, nor the file of a live process (a pid reused since is taken as live).
/// Returns one line per removed file (docs/user/faults.md#leftovers).
std::vector<std::string> remove_stale_temporaries(const std::string& path);

/// Publishes `size` bytes at `data` as the file `path` (publish_atomically). Throws IoError.
void write_bytes_atomically(const std::string& path, const char* data, std::size_t size);

/// The temporary name of `path` while it is written: `.<basename>.tmp.<pid>` beside it
/// (<basename> cut as above when it is longer than 239 bytes).
std::string temporary_path_for(const std::string& path);

/// Forces a written file's data to disk (fsync) so that a following rename publishes a
/// complete file; throws IoError naming the path.
void sync_file_to_disk(const std::string& path);

}  // namespace hexdyn
