#include "hexdyn/process/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <system_error>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/process/paths.hpp"
#include "hexdyn/process/sha256.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

/// Longest file name of Linux's file systems [bytes] (NAME_MAX).
constexpr std::size_t kNameMax = 255;
/// Most digits of a process id (a 32-bit pid; Linux's pid_max is at most 2^22).
constexpr std::size_t kPidDigits = 10;

/// What a temporary name holds between '.' and ".tmp.PID": the output's file name, or, when
/// the temporary name could then be longer than kNameMax, the name's first bytes (whole UTF-8
/// characters), '~' and 16 hexadecimal digits of the whole name's SHA-256.
std::string temporary_stem(const std::string& name) {
  const std::size_t fixed =
      std::string_view(".").size() + std::string_view(".tmp.").size() + kPidDigits;
  if (name.size() + fixed <= kNameMax) return name;
  std::size_t keep = kNameMax - fixed - 17;  // '~' and 16 digits
  while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0) == 0x80) --keep;
  return name.substr(0, keep) + "~" + sha256_hex(name.data(), name.size()).substr(0, 16);
}

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
          ("." + temporary_stem(fs::path(path).filename()) + ".tmp." + std::to_string(::getpid())))
      .string();
}

void publish_atomically(const std::string& path,
                        const std::function<void(const std::string& tmp)>& write) {
  const std::string tmp = temporary_path_for(path);
  // A SIGTERM or SIGINT from here on removes the temporary file (interrupt.hpp).
  register_temporary(tmp);
  try {
    write(tmp);
    sync_file_to_disk(tmp);
    check_interrupt();  // the handler removed the temporary file: never publish
    // The target may have changed since the run began: never rename over a special file.
    if (const auto why = why_not_replaceable(path)) throw_output_error(path, *why);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw_output_error(path, "cannot rename '" + tmp + "' to it: " + std::strerror(errno));
  } catch (const Interrupted&) {
    std::error_code ec;
    fs::remove(tmp, ec);
    unregister_temporary(tmp);
    throw;
  } catch (const IoError& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    unregister_temporary(tmp);
    // The temporary name is the writer's business: the message names the output.
    std::string msg = e.what();
    for (std::size_t at = msg.find(tmp); at != std::string::npos; at = msg.find(tmp, at))
      msg.replace(at, tmp.size(), path);
    throw IoError(msg);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    unregister_temporary(tmp);
    throw;
  }
  unregister_temporary(tmp);
}

std::vector<std::string> remove_stale_temporaries(const std::string& path) {
  std::vector<std::string> removed;
  const std::string dir = directory_of(path);
  const std::string prefix = "." + temporary_stem(fs::path(path).filename()) + ".tmp.";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid <= 0 || pid == ::getpid()) continue;
    // Only a process that is gone, and only a regular file of ours (never a link).
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;
    struct stat st {};
    const std::string full = it->path().string();
    if (::lstat(full.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid())
      continue;
    if (::unlink(full.c_str()) == 0)
      removed.push_back("removed '" + full + "', the temporary file of process " + digits +
                        ", which is gone (an interrupted earlier run)");
  }
  return removed;
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
