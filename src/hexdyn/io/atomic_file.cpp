#include "hexdyn/io/atomic_file.hpp"

#include <fcntl.h>
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

void publish_atomically(const std::string& path,
                        const std::function<void(const std::string& tmp)>& write) {
  const std::string tmp =
      (fs::path(directory_of(path)) /
       ("." + fs::path(path).filename().string() + ".tmp." + std::to_string(::getpid())))
          .string();
  try {
    write(tmp);
    sync_file_to_disk(tmp);
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
