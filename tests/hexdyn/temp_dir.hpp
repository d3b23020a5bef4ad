#pragma once
// A fresh folder under the system's temporary directory for one test, removed at scope exit:
// tests/hexdyn/<stage>/test_*.cpp that read or write real files.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace hexdyn::testing {

struct TempDir {
  std::filesystem::path path;
  /// The folder hexdyn_test_<tag>_<pid>, emptied if it exists.
  explicit TempDir(const std::string& tag) {
    path = std::filesystem::temp_directory_path() /
           ("hexdyn_test_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// Writes `text` (bytes as given) to the file `name` in the folder; returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = path / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
};

}  // namespace hexdyn::testing
