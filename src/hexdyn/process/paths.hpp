#pragma once
/// \file paths.hpp
/// File-path helpers shared by the configuration reader, the sweep reader and the writers.
#include <optional>
#include <string>

namespace hexdyn {

/// The directory part of a file path: "configs/a.yaml" → "configs", "a.yaml" → ".",
/// "/a.yaml" → "/".
std::string directory_of(const std::string& path);

/// `relative` as named from inside the file `file`: an absolute path unchanged, else
/// joined to directory_of(file) ("configs/sweeps/s.yaml", "base.yaml" →
/// "configs/sweeps/base.yaml"). The result is not normalised and need not exist.
std::string path_beside(const std::string& file, const std::string& relative);

/// Why `path` cannot be read as an input file, found without opening it, or nothing when it
/// names a regular file (symbolic links followed): "does not exist" (also for a path through
/// a file that is not a folder, or a link to nothing), "is a directory", "is a device", "is a
/// FIFO (named pipe)", "is a socket", "cannot be read (Permission denied)", ... Every reader
/// of an input (scene, URDF, sweep, envelope and result files) says it in these words.
std::optional<std::string> why_not_regular_file(const std::string& path);

}  // namespace hexdyn
