#include "hexdyn/sweep/checkpoint.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <regex>
#include <system_error>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

const char* kLockName = "lock";

std::string errno_text(int err) { return std::strerror(err); }

std::string base_name(const std::string& path) { return fs::path(path).filename().string(); }

/// What a file that is not a regular file is, for messages.
std::string kind_of(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse(const std::string& what, const std::string& path, const std::string& why) {
  throw IoError("cannot use " + what + " '" + path + "': it is " + why +
                "; a checkpoint is a directory of regular files, and hexdyn never follows a "
                "link or writes through anything else there (remove it, or write to another "
                "output)");
}

/// Opens the existing regular file `path` (in the checkpoint directory `dir_fd`) without
/// following a link and without blocking on a FIFO; anything else is refused (IoError).
int open_regular(int dir_fd, const std::string& path, int flags, const std::string& what) {
  const std::string name = base_name(path);
  struct stat st {};
  if (::fstatat(dir_fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
    refuse(what, path, kind_of(st.st_mode));
  const int fd = ::openat(dir_fd, name.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == ELOOP) refuse(what, path, "a symbolic link");
    throw IoError("cannot open " + what + " '" + path + "': " + errno_text(err));
  }
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    refuse(what, path, kind_of(st.st_mode));
  }
  return fd;
}

bool same_file(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/// A read-only view of a whole file (mmap; empty files have no mapping).
class MappedFile {
 public:
  MappedFile(int dir_fd, const std::string& path) {
    const int fd = open_regular(dir_fd, path, O_RDONLY, "checkpoint journal");
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
      const int err = errno;
      ::close(fd);
      throw IoError("cannot read checkpoint journal '" + path + "': " + errno_text(err));
    }
    size_ = static_cast<std::size_t>(st.st_size);
    if (size_ > 0) {
      void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (p == MAP_FAILED) {
        const int err = errno;
        ::close(fd);
        throw IoError("cannot map checkpoint journal '" + path + "': " + errno_text(err));
      }
      data_ = static_cast<const char*>(p);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

bool is_journal_name(const std::string& name, unsigned& number) {
  static const std::regex pattern(R"(^journal-([0-9]{4,9})\.hxj$)");
  std::smatch m;
  if (!std::regex_match(name, m, pattern)) return false;
  number = static_cast<unsigned>(std::stoul(m[1].str()));
  return true;
}

void write_all(int fd, const char* data, std::size_t n, const std::string& path) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      throw IoError("cannot write checkpoint journal '" + path + "': " + errno_text(errno));
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
}

}  // namespace

std::string build_identity() { return std::string("hexdyn ") + kVersion + " (" + kGitCommit + ")"; }

SweepIdentity sweep_identity(const SweepSpec& spec, bool keep_runs) {
  return make_identity(spec.inputs, spec.base_config_yaml, build_identity(), spec.scenario_count(),
                       keep_runs);
}

Checkpoint::Checkpoint(const std::string& output_path, const SweepSpec& spec, bool keep_runs,
                       bool resume)
    : dir_(output_path + ".checkpoint"), identity_(sweep_identity(spec, keep_runs)) {
  // mkdir first and take the lock second, so that two sweeps starting together on one
  // output find each other through the lock whichever of them made the directory.
  if (::mkdir(dir_.c_str(), 0755) != 0) {
    const int err = errno;
    if (err == ENAMETOOLONG)
      throw IoError("output '" + output_path + "': its checkpoint folder '" + dir_ +
                    "' is longer than the file system takes (" + errno_text(err) +
                    "), expected an output file name of at most 244 bytes (255 less "
                    "'.checkpoint')");
    if (err != EEXIST)
      throw IoError("cannot create checkpoint directory '" + dir_ + "': " + errno_text(err));
  }
  // The directory itself, never a link to one: every file in it is opened from this
  // descriptor (openat), so a link put in place of the directory later is never followed.
  dir_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir_fd_ < 0) {
    const int err = errno;
    struct stat st {};
    if (::lstat(dir_.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
      refuse("checkpoint directory", dir_, kind_of(st.st_mode));
    throw IoError("cannot open checkpoint directory '" + dir_ + "': " + errno_text(err));
  }
  try {
    take_lock(spec.inputs);
    scan_journals(spec, resume);
  } catch (...) {
    release_lock();
    ::close(dir_fd_);
    dir_fd_ = -1;
    throw;
  }
}

void Checkpoint::take_lock(const std::vector<InputFile>& inputs) {
  const std::string lock_path = dir_ + "/" + kLockName;
  // A new lock is created (O_EXCL); an existing one must be a regular file of one link.
  lock_fd_ = ::openat(dir_fd_, kLockName, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (lock_fd_ < 0 && errno == EEXIST)
    lock_fd_ = open_regular(dir_fd_, lock_path, O_RDWR, "checkpoint lock");
  if (lock_fd_ < 0) {
    const int err = errno;
    if (err == ELOOP) refuse("checkpoint lock", lock_path, "a symbolic link");
    throw IoError("cannot open checkpoint lock '" + lock_path + "': " + errno_text(err));
  }
  struct stat st {};
  if (::fstat(lock_fd_, &st) != 0 || st.st_nlink != 1) {
    release_lock();
    refuse("checkpoint lock", lock_path, "a file with other (hard) links");
  }
  // A lock is written (the holder's name): never one of the sweep's inputs, moved here.
  if (const InputFile* input = find_input(inputs, static_cast<std::uint64_t>(st.st_dev),
                                          static_cast<std::uint64_t>(st.st_ino))) {
    release_lock();
    refuse("checkpoint lock", lock_path,
           "the " + input->role + " '" + input->path + "' of the sweep");
  }
  int rc = 0;
  do rc = ::flock(lock_fd_, LOCK_EX | LOCK_NB);
  while (rc != 0 && errno == EINTR);
  if (rc != 0) {
    const int err = errno;
    char holder[256] = {0};
    const ssize_t got = ::pread(lock_fd_, holder, sizeof holder - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (err != EWOULDBLOCK)
      throw IoError("cannot lock checkpoint '" + lock_path + "': " + errno_text(err));
    std::string who(holder, got > 0 ? static_cast<std::size_t>(got) : 0);
    while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
    throw IoError("output '" + dir_.substr(0, dir_.size() - std::string(".checkpoint").size()) +
                  "' is being written by a sweep that is still running" +
                  (who.empty() ? std::string() : " (process " + who + ")") +
                  "; wait for it to finish or stop it, or write to another output");
  }
  char host[128] = {0};
  ::gethostname(host, sizeof host - 1);
  const std::string me = std::to_string(::getpid()) + " on " + host + "\n";
  if (::ftruncate(lock_fd_, 0) == 0) {
    const ssize_t w = ::pwrite(lock_fd_, me.data(), me.size(), 0);
    (void)w;  // the holder's name only improves a message
  }
}

void Checkpoint::release_lock() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
  lock_fd_ = -1;
}

void Checkpoint::scan_journals(const SweepSpec& spec, bool resume) {
  std::vector<std::pair<unsigned, std::string>> found;
  unsigned last = 0;
  for (const std::string& name : entry_names()) {
    unsigned number = 0;
    if (name[0] == '.') {
      ::unlinkat(dir_fd_, name.c_str(), 0);  // a temporary of an interrupted run (a link
                                             // itself, never its target)
    } else if (is_journal_name(name, number)) {
      struct stat st {};
      const std::string path = dir_ + "/" + name;
      if (::fstatat(dir_fd_, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
        refuse("checkpoint journal", path, kind_of(st.st_mode));
      found.emplace_back(number, path);
      last = std::max(last, number);
    } else if (name != kLockName) {
      throw ConfigError(dir_ + ": not a checkpoint of this hexdyn (unexpected file '" + name +
                        "'; an older hexdyn's checkpoint cannot be resumed); remove the "
                        "directory to start afresh");
    }
  }
  std::sort(found.begin(), found.end());
  if (!found.empty() && !resume)
    throw ConfigError(dir_ +
                      ": the checkpoint of an interrupted sweep exists; continue it with "
                      "--resume, or remove the directory to start afresh");

  const std::size_t n = spec.scenario_count();
  std::vector<char> seen(found.empty() ? 0 : n, 0);
  std::vector<char> crashed(found.empty() ? 0 : n, 0);
  for (const auto& [number, path] : found) {
    const MappedFile file(dir_fd_, path);
    const JournalScan scan = scan_journal(file.data(), file.size(), path, identity_);
    if (scan.header_ok && scan.header.id != identity_.id)
      throw ConfigError(dir_ + ": the checkpoint belongs to another sweep (" +
                        identity_.difference(scan.header) + ", journal " +
                        fs::path(path).filename().string() +
                        "); remove the directory to start afresh, or write to another output");
    if (scan.foreign_record)
      throw ConfigError(dir_ + ": the checkpoint belongs to another sweep (journal " +
                        fs::path(path).filename().string() +
                        " holds records of another sweep); remove the directory to start "
                        "afresh, or write to another output");
    for (const std::string& d : scan.damage) warnings_.push_back(d);
    const auto journal = static_cast<std::uint32_t>(journals_.size());
    journals_.push_back(path);
    for (const JournalEntry& e : scan.entries) {
      if (e.index >= n) continue;  // cannot happen with a matching identity
      if (e.kind == RecordKind::kCrashAttempt) {
        if (!crashed[e.index]) crash_attempts_.push_back(e.index);
        crashed[e.index] = 1;
        continue;
      }
      if (seen[e.index]) continue;
      std::size_t image_offset = 0, image_size = 0;
      ScenarioRecord r;
      try {
        r = decode_record(file.data() + e.payload_offset, e.payload_size, false, &image_offset,
                          &image_size);
      } catch (const IoError& err) {
        warnings_.push_back(path + ": record of scenario " + scenario_id(spec, e.index) +
                            " unreadable (" + err.what() + "); its scenario is computed again");
        continue;
      }
      if (r.summary.index != e.index) continue;
      seen[e.index] = 1;
      if (image_size > 0) images_[e.index] = {journal, e.payload_offset + image_offset, image_size};
      finished_.push_back(std::move(r.summary));
    }
  }
  // A crash attempt of a scenario finished since then is history.
  std::erase_if(crash_attempts_, [&](std::size_t i) { return seen[i] != 0; });
  char name[32];
  std::snprintf(name, sizeof name, "journal-%04u.hxj", last + 1);
  own_journal_ = dir_ + "/" + name;
}

std::vector<std::string> Checkpoint::entry_names() const {
  std::vector<std::string> names;
  const int fd = ::dup(dir_fd_);
  DIR* d = fd < 0 ? nullptr : ::fdopendir(fd);
  if (d == nullptr) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    throw IoError("cannot list checkpoint directory '" + dir_ + "': " + errno_text(err));
  }
  ::rewinddir(d);
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  ::closedir(d);
  std::sort(names.begin(), names.end());
  return names;
}

void Checkpoint::verify() const {
  const auto lost = [&](const std::string& why) {
    throw CheckpointLost("the checkpoint '" + dir_ + "' is no longer this sweep's: " + why +
                         " (removed by hand, or another sweep took its place); this sweep "
                         "stops without writing its output or touching that checkpoint");
  };
  struct stat mine {
  }, now{};
  if (::fstat(dir_fd_, &mine) != 0 || mine.st_nlink == 0) lost("its directory was removed");
  if (::lstat(dir_.c_str(), &now) != 0 || !same_file(mine, now))
    lost("its directory was removed or replaced");
  if (::fstat(lock_fd_, &mine) != 0 ||
      ::fstatat(dir_fd_, kLockName, &now, AT_SYMLINK_NOFOLLOW) != 0 || !same_file(mine, now))
    lost("its lock was removed or replaced");
  if (journal_fd_ >= 0 &&
      (::fstat(journal_fd_, &mine) != 0 ||
       ::fstatat(dir_fd_, base_name(own_journal_).c_str(), &now, AT_SYMLINK_NOFOLLOW) != 0 ||
       !same_file(mine, now)))
    lost("its journal " + base_name(own_journal_) + " was removed or replaced");
}

Checkpoint::~Checkpoint() {
  try {
    if (journal_fd_ >= 0) flush(false);
  } catch (...) {
  }
  if (journal_fd_ >= 0) ::close(journal_fd_);
  release_lock();
  if (dir_fd_ >= 0) ::close(dir_fd_);
}

std::size_t Checkpoint::journal_count() const { return journals_.size(); }

void Checkpoint::start_buffer() {
  if (journal_fd_ < 0 && buffer_.empty()) {
    const std::vector<char> header = journal_header(identity_);
    buffer_.insert(buffer_.end(), header.begin(), header.end());
  }
}

void Checkpoint::note_image(std::size_t index, std::uint64_t record_at, const char* payload,
                            std::size_t size) {
  if (!identity_.keep_runs) return;
  std::size_t image_offset = 0, image_size = 0;
  (void)decode_record(payload, size, false, &image_offset, &image_size);
  if (image_size > 0)
    images_[index] = {static_cast<std::uint32_t>(journals_.size()),
                      record_at + kRecordHeaderBytes + image_offset, image_size};
}

void Checkpoint::append_row(std::size_t index, const char* payload, std::size_t size) {
  verify();
  start_buffer();
  const std::uint64_t at = journal_size_ + buffer_.size();
  append_journal_record(buffer_, RecordKind::kRow, index, identity_, payload, size);
  note_image(index, at, payload, size);
}

BuiltRecord Checkpoint::append_row_record(std::size_t index, const char* record, std::size_t size) {
  const BuiltRecord r = check_built_record(record, size, RecordKind::kRow, index, identity_);
  verify();
  start_buffer();
  const std::uint64_t at = journal_size_ + buffer_.size();
  buffer_.insert(buffer_.end(), record, record + size);
  note_image(index, at, r.payload, r.size);
  return r;
}

void Checkpoint::append_crash(std::size_t index, const std::string& reason) {
  verify();
  start_buffer();
  append_journal_record(buffer_, RecordKind::kCrashAttempt, index, identity_, reason.data(),
                        reason.size());
}

void Checkpoint::flush(bool sync) {
  verify();  // never a byte into a checkpoint that is not this sweep's
  if (buffer_.empty() && !(sync && journal_fd_ >= 0)) return;
  if (journal_fd_ < 0) {
    journal_fd_ = ::openat(dir_fd_, base_name(own_journal_).c_str(),
                           O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (journal_fd_ < 0)
      throw IoError("cannot create checkpoint journal '" + own_journal_ +
                    "': " + errno_text(errno));
    journals_.push_back(own_journal_);
  }
  write_all(journal_fd_, buffer_.data(), buffer_.size(), own_journal_);
  journal_size_ += buffer_.size();
  buffer_.clear();
  if (sync && ::fdatasync(journal_fd_) != 0)
    throw IoError("cannot sync checkpoint journal '" + own_journal_ + "': " + errno_text(errno));
}

std::vector<char> Checkpoint::run_image(std::size_t index) const {
  const auto it = images_.find(index);
  if (it == images_.end()) return {};
  const ImageAt& at = it->second;
  const std::string& path = at.journal < journals_.size() ? journals_[at.journal] : own_journal_;
  const int fd = open_regular(dir_fd_, path, O_RDONLY, "checkpoint journal");
  std::vector<char> bytes(at.size);
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t r =
        ::pread(fd, bytes.data() + got, bytes.size() - got, static_cast<off_t>(at.offset + got));
    if (r <= 0) {
      if (r < 0 && errno == EINTR) continue;
      ::close(fd);
      throw IoError("cannot read the run of scenario " + std::to_string(index) + " from '" + path +
                    "'");
    }
    got += static_cast<std::size_t>(r);
  }
  ::close(fd);
  return bytes;
}

void Checkpoint::remove() {
  verify();  // never remove a checkpoint that is not this sweep's
  if (journal_fd_ >= 0) ::close(journal_fd_);
  journal_fd_ = -1;
  buffer_.clear();
  // Only what a checkpoint holds, from the directory's descriptor; then the directory,
  // if it still is this one.
  for (const std::string& name : entry_names()) {
    unsigned number = 0;
    if (name[0] == '.' || is_journal_name(name, number) || name == kLockName)
      ::unlinkat(dir_fd_, name.c_str(), 0);
  }
  struct stat mine {
  }, now{};
  const bool same =
      ::fstat(dir_fd_, &mine) == 0 && ::lstat(dir_.c_str(), &now) == 0 && same_file(mine, now);
  const int rc = same ? ::rmdir(dir_.c_str()) : 0;
  const int err = errno;
  release_lock();
  ::close(dir_fd_);
  dir_fd_ = -1;
  if (rc != 0) throw IoError("cannot remove checkpoint '" + dir_ + "': " + errno_text(err));
}

}  // namespace hexdyn
