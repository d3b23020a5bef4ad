#include "hexdyn/process/paths.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
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

std::optional<std::string> why_not_regular_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return std::string("does not exist");
    return std::string("cannot be read (") + std::strerror(errno) + ")";
  }
  if (S_ISREG(st.st_mode)) return std::nullopt;
  if (S_ISDIR(st.st_mode)) return std::string("is a directory");
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return std::string("is a device");
  if (S_ISFIFO(st.st_mode)) return std::string("is a FIFO (named pipe)");
  if (S_ISSOCK(st.st_mode)) return std::string("is a socket");
  return std::string("is not a regular file");
}

}  // namespace hexdyn
