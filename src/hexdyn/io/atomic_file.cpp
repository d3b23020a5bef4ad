#include "hexdyn/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/paths.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void throw_output_error(const std::string& path, const std::string& reason) {
  throw IoError("cannot write output '" + path + "': " + reason);
}

}  // namespace

std::optional<std::string> why_not_replaceable(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return std::nullopt;
    return std::string(std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return std::nullopt;
  if (S_ISLNK(st.st_mode))
    return std::string(
        "is a symbolic link (hexdyn replaces only regular files; name the link's target)");
  if (S_ISDIR(st.st_mode)) return std::string("is a directory");
  if (S_ISCHR(st.st_mode)) return std::string("is a character device");
  if (S_ISBLK(st.st_mode)) return std::string("is a block device");
  if (S_ISFIFO(st.st_mode)) return std::string("is a FIFO (named pipe)");
  if (S_ISSOCK(st.st_mode)) return std::string("is a socket");
  return std::string("is not a regular file");
}

std::string temporary_path_for(const std::string& path) {
  return (fs::path(directory_of(path)) /
          ("." + fs::path(path).filename().string() + ".tmp." + std::to_string(::getpid())))
      .string();
}

void publish_atomically(const std::string& path,
                        const std::function<void(const std::string& tmp)>& write) {
  const std::string tmp = temporary_path_for(path);
  try {
    write(tmp);
    sync_file_to_disk(tmp);
    // The target may have changed since the run began: never rename over a special file.
    if (const auto why = why_not_replaceable(path)) throw_output_error(path, *why);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw_output_error(path, "cannot rename '" + tmp + "' to it: " + std::strerror(errno));
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void write_bytes_atomically(const std::string& path, const char* data, std::size_t size) {
  publish_atomically(path, [&](const std::string& tmp) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) throw_output_error(tmp, std::strerror(errno));
    std::size_t done = 0;
    while (done < size) {
      const ssize_t n = ::write(fd, data + done, size - done);
      if (n < 0) {
        if (errno == EINTR) continue;
        const int err = errno;
        ::close(fd);
        throw_output_error(tmp, std::strerror(err));
      }
      done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0)
      throw_output_error(tmp, std::string("close failed: ") + std::strerror(errno));
  });
}

void sync_file_to_disk(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw_output_error(path, std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw_output_error(path, std::string("fsync failed: ") + std::strerror(err));
}

}  // namespace hexdyn
