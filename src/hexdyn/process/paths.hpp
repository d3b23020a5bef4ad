#pragma once
/// \file paths.hpp
/// File-path helpers shared by the configuration reader, the sweep reader and the writers.
#include <string>

namespace hexdyn {

/// The directory part of a file path: "configs/a.yaml" → "configs", "a.yaml" → ".",
/// "/a.yaml" → "/".
std::string directory_of(const std::string& path);

/// `relative` as named from inside the file `file`: an absolute path unchanged, else
/// joined to directory_of(file) ("configs/sweeps/s.yaml", "base.yaml" →
/// "configs/sweeps/base.yaml"). The result is not normalised and need not exist.
std::string path_beside(const std::string& file, const std::string& relative);

}  // namespace hexdyn
