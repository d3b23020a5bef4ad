#include "hexdyn/config/inputs.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/sha256.hpp"

namespace hexdyn {
namespace {

/// The process's kept inputs (InputFreeze), by absolute path.
struct Store {
  std::mutex mutex;
  int freezes = 0;
  std::map<std::string, InputFile> files;
};

Store& store() {
  static Store s;
  return s;
}

std::string absolute_of(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(path, ec);
  return ec ? path : abs.lexically_normal().string();
}

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device";
  if (S_ISSOCK(mode)) return "is a socket";
  return "is not a regular file";
}

/// The signature an HDF5 file's superblock starts with.
constexpr char kHdf5Signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};

std::string binary_file(std::ptrdiff_t nul_offset) {
  return "is a binary file (a NUL byte at offset " + std::to_string(nul_offset) + "), not text";
}

/// Why the open file `fd` of `size` bytes is no text, or nothing: an HDF5 file (its signature
/// at offset 0, 512, 1024, 2048, …: where HDF5 looks for the superblock), or a binary file (a
/// NUL byte in its first 4 kB). Looked at before the size, so that a large result file is
/// named as what it is.
std::optional<std::string> why_not_text(int fd, std::uint64_t size) {
  char head[4096];
  ssize_t n = 0;
  do n = ::pread(fd, head, sizeof head, 0);
  while (n < 0 && errno == EINTR);
  if (n < 0) return std::nullopt;  // the read that follows names the reason
  for (std::uint64_t at = 0; at + sizeof kHdf5Signature <= size; at = at == 0 ? 512 : 2 * at) {
    char sig[sizeof kHdf5Signature];
    const bool in_head = at + sizeof sig <= static_cast<std::uint64_t>(n);
    if (in_head)
      std::memcpy(sig, head + at, sizeof sig);
    else if (::pread(fd, sig, sizeof sig, static_cast<off_t>(at)) != sizeof sig)
      break;
    if (std::memcmp(sig, kHdf5Signature, sizeof sig) == 0)
      return std::string("is an HDF5 file (a result, sweep or envelope file?), not text");
  }
  if (const void* nul = std::memchr(head, '\0', static_cast<std::size_t>(n)))
    return binary_file(static_cast<const char*>(nul) - head);
  return std::nullopt;
}

InputFile read_from_disk(const std::string& path, const std::string& absolute,
                         std::size_t max_bytes, const std::string& expected, bool binary) {
  require_utf8(absolute, path + ": the file's path");
  // Special files are refused by their type before opening: a FIFO would block the
  // open, a device such as /dev/zero would never end.
  if (const auto why = why_not_regular_file(path))
    throw ConfigError(path + ": " + *why + ", expected " + expected);
  Fd f;
  f.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (f.fd < 0)
    throw ConfigError(path + ": cannot read it (" + std::strerror(errno) + "), expected " +
                      expected);
  struct stat st {};
  if (::fstat(f.fd, &st) != 0 || !S_ISREG(st.st_mode))  // replaced since the stat above
    throw ConfigError(path + ": " + kind_of(st.st_mode) + ", expected " + expected);
  if (const auto why =
          binary ? std::nullopt : why_not_text(f.fd, static_cast<std::uint64_t>(st.st_size)))
    throw ConfigError(path + ": " + *why + ", expected " + expected);
  char limit[32];
  std::snprintf(limit, sizeof limit, "%.3g MiB", static_cast<double>(max_bytes) / (1 << 20));
  const std::string too_big = path + ": larger than " + std::to_string(max_bytes) + " bytes (" +
                              limit + "), expected " + expected + " of at most that size";
  if (static_cast<unsigned long long>(st.st_size) > max_bytes) throw ConfigError(too_big);
  auto text = std::make_shared<std::string>();
  text->reserve(static_cast<std::size_t>(st.st_size));
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw ConfigError(path + ": cannot read it (" + std::strerror(errno) + "), expected " +
                        expected);
    if (n == 0) break;
    text->append(buf, static_cast<std::size_t>(n));
    if (text->size() > max_bytes) throw ConfigError(too_big);  // grew while read
  }
  if (const void* nul = binary ? nullptr : std::memchr(text->data(), '\0', text->size()))
    throw ConfigError(path + ": " + binary_file(static_cast<const char*>(nul) - text->data()) +
                      ", expected " + expected);
  if (!binary) require_utf8(*text, path);
  InputFile file;
  file.path = path;
  file.absolute = absolute;
  file.sha256 = sha256_hex(text->data(), text->size());
  file.device = static_cast<std::uint64_t>(st.st_dev);
  file.inode = static_cast<std::uint64_t>(st.st_ino);
  file.text = std::move(text);
  return file;
}

}  // namespace

namespace {

/// read_input_text and read_input_bytes: text checked or not.
InputFile read_input(const std::string& path, std::size_t max_bytes, const std::string& expected,
                     bool binary) {
  const std::string absolute = absolute_of(path);
  Store& s = store();
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (s.freezes > 0) {
      const auto kept = s.files.find(absolute);
      if (kept != s.files.end()) {
        if (kept->second.text->size() > max_bytes)  // kept by a reader of a larger limit
          throw ConfigError(path + ": larger than " + std::to_string(max_bytes) +
                            " bytes, expected " + expected + " of at most that size");
        InputFile file = kept->second;
        file.path = path;
        return file;
      }
    }
  }
  InputFile file = read_from_disk(path, absolute, max_bytes, expected, binary);
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (s.freezes > 0) {
    // Another thread may have kept it meanwhile: the first kept wins.
    const auto [kept, inserted] = s.files.emplace(absolute, file);
    if (!inserted) {
      InputFile first = kept->second;
      first.path = path;
      return first;
    }
  }
  return file;
}

}  // namespace

InputFile read_input_text(const std::string& path, std::size_t max_bytes,
                          const std::string& expected) {
  return read_input(path, max_bytes, expected, false);
}

InputFile read_input_bytes(const std::string& path, std::size_t max_bytes,
                           const std::string& expected) {
  return read_input(path, max_bytes, expected, true);
}

InputFreeze::InputFreeze() {
  const std::lock_guard<std::mutex> lock(store().mutex);
  ++store().freezes;
}

InputFreeze::~InputFreeze() {
  Store& s = store();
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (--s.freezes == 0) s.files.clear();
}

bool input_kept(const std::string& path) {
  const std::string absolute = absolute_of(path);
  Store& s = store();
  const std::lock_guard<std::mutex> lock(s.mutex);
  return s.freezes > 0 && s.files.count(absolute) > 0;
}

std::optional<std::string> why_not_input_file(const std::string& path) {
  if (input_kept(path)) return std::nullopt;
  return why_not_regular_file(path);
}

void keep_input(const InputFile& file) {
  if (!file.text) return;
  Store& s = store();
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (s.freezes > 0) s.files.insert_or_assign(file.absolute, file);
}

void add_input(std::vector<InputFile>& inputs, const std::string& role, const std::string& path) {
  const std::string absolute = absolute_of(path);
  const bool listed = std::any_of(inputs.begin(), inputs.end(),
                                  [&](const InputFile& f) { return f.absolute == absolute; });
  if (listed) return;
  InputFile file =
      role == "URDF" ? read_input_text(path, kMaxUrdfBytes, "a URDF file")
      : role == "height map"
          ? read_input_bytes(path, kMaxHeightMapBytes, kHeightMapExpected)
          : read_input_text(path, kMaxConfigBytes, "a configuration file (a regular YAML file)");
  file.role = role;
  inputs.push_back(std::move(file));
}

const InputFile* find_input(const std::vector<InputFile>& inputs, std::uint64_t device,
                            std::uint64_t inode) {
  for (const InputFile& f : inputs)
    if ((f.device != 0 || f.inode != 0) && f.device == device && f.inode == inode) return &f;
  return nullptr;
}

std::vector<InputFile> without_texts(std::vector<InputFile> inputs) {
  for (InputFile& f : inputs) f.text.reset();
  return inputs;
}

std::string tree_urdf_path(const YAML::Node& tree) {
  if (!tree.IsMap()) return {};
  const YAML::Node robot = tree["robot"];
  if (!robot.IsDefined() || !robot.IsMap()) return {};
  const YAML::Node urdf = robot["urdf"];
  if (!urdf.IsDefined() || !urdf.IsScalar()) return {};
  return urdf.Scalar();
}

std::string tree_height_map_path(const YAML::Node& tree) {
  if (!tree.IsMap()) return {};
  const YAML::Node terrain = tree["terrain"];
  if (!terrain.IsDefined() || !terrain.IsMap()) return {};
  const YAML::Node type = terrain["type"];
  if (!type.IsDefined() || !type.IsScalar() || type.Scalar() != "height_map") return {};
  const YAML::Node map = terrain["height_map"];
  if (!map.IsDefined() || !map.IsMap()) return {};
  const YAML::Node file = map["file"];
  if (!file.IsDefined() || !file.IsScalar()) return {};
  return file.Scalar();
}

std::vector<InputFile> scene_inputs(const std::vector<std::string>& chain, const YAML::Node& tree) {
  std::vector<InputFile> inputs;
  for (std::size_t i = 0; i < chain.size(); ++i)
    add_input(inputs, i == 0 ? "scene" : "inherited scene", chain[i]);
  // A URDF that is no regular file is not read here: the scene's reader refuses it, naming
  // the key (config/config.cpp).
  const std::string urdf = tree_urdf_path(tree);
  if (!urdf.empty() && !why_not_input_file(urdf)) add_input(inputs, "URDF", urdf);
  const std::string map = tree_height_map_path(tree);
  if (!map.empty() && !why_not_input_file(map)) add_input(inputs, "height map", map);
  return inputs;
}

std::string input_sha256_text(const std::vector<InputFile>& inputs) {
  std::string text;
  for (const InputFile& f : inputs) text += f.sha256 + "  " + f.absolute + "\n";
  return text;
}

std::vector<InputFile> recorded_inputs(const std::string& input_sha256, const std::string& where) {
  std::vector<InputFile> out;
  std::size_t start = 0;
  while (start < input_sha256.size()) {
    std::size_t end = input_sha256.find('\n', start);
    if (end == std::string::npos) end = input_sha256.size();
    const std::string line = input_sha256.substr(start, end - start);
    start = end + 1;
    const std::size_t gap = line.find("  ");
    if (gap != 64 || line.size() <= gap + 2) continue;
    InputFile f;
    f.role = "input recorded in " + where;
    f.sha256 = line.substr(0, gap);
    f.path = f.absolute = line.substr(gap + 2);
    f.recorded = true;
    out.push_back(std::move(f));
  }
  return out;
}

std::size_t first_non_utf8(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      if (c == 0xE0) lo = 0xA0;  // no overlong form
      if (c == 0xED) hi = 0x9F;  // no surrogate
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      if (c == 0xF0) lo = 0x90;  // no overlong form
      if (c == 0xF4) hi = 0x8F;  // at most U+10FFFF
    } else {
      return i;
    }
    if (i + len > n) return i;
    if (s[i + 1] < lo || s[i + 1] > hi) return i;
    for (std::size_t k = 2; k < len; ++k)
      if (s[i + k] < 0x80 || s[i + k] > 0xBF) return i;
    i += len;
  }
  return std::string::npos;
}

void require_utf8(const std::string& text, const std::string& where) {
  const std::size_t at = first_non_utf8(text);
  if (at == std::string::npos) return;
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++column;
    }
  }
  char byte[8];
  std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[at]));
  throw ConfigError(where + ": not UTF-8 text: byte " + byte + " at line " + std::to_string(line) +
                    ", column " + std::to_string(column) +
                    "; hexdyn keeps its inputs' text in its files as UTF-8: save it as UTF-8");
}

}  // namespace hexdyn
