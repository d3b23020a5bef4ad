#include "hexdyn/process/paths.hpp"

#include <filesystem>

namespace hexdyn {

std::string directory_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

std::string path_beside(const std::string& file, const std::string& relative) {
  if (!relative.empty() && relative.front() == '/') return relative;
  const std::string dir = directory_of(file);
  return (dir == "/" ? std::string() : dir) + "/" + relative;
}

}  // namespace hexdyn
