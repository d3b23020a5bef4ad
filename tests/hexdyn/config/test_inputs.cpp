// What the input reader (config/inputs.hpp) says of a file that is not text: an HDF5 file by
// its signature where HDF5 looks for a superblock (offset 0, 512, 1024, 2048, ...), also past
// the first 4 kB and in a file larger than the reader's limit; a binary file by its first NUL
// byte; other bytes as before (not UTF-8); a missing file "does not exist".
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/temp_dir.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

const std::string kSignature("\x89HDF\r\n\x1a\n", 8);

/// `size` bytes of YAML text ("a: 1\n" repeated) with `insert` at `at`, as the file `name`
/// of `dir`.
std::string write_yaml(const testing::TempDir& dir, const std::string& name, std::size_t size,
                       std::size_t at, const std::string& insert) {
  std::string text;
  while (text.size() < size) text += "a: 1\n";
  text.resize(size);
  text.replace(at, insert.size(), insert);
  return dir.write(name, text);
}

std::string refusal(const std::string& path) {
  try {
    (void)read_input_text(path, kMaxConfigBytes, "a configuration file (a regular YAML file)");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("inputs: an HDF5 or binary file is named as such, before its size", "[inputs][config]") {
  const testing::TempDir dir("inputs");
  const std::string hdf5 =
      ": is an HDF5 file (a result, sweep or envelope file?), not text, "
      "expected a configuration file (a regular YAML file)";
  const std::size_t big = kMaxConfigBytes + 4096;
  for (const auto& [size, at] : {std::pair<std::size_t, std::size_t>{100, 0},
                                 {2000, 512},
                                 {5000, 1024},
                                 {5000, 2048},
                                 {big, 0},
                                 {big, 8192},
                                 {big, 1 << 20}}) {
    const std::string path = write_yaml(dir, "h.yaml", size, at, kSignature);
    INFO(size << " bytes, signature at " << at);
    CHECK(refusal(path) == path + hdf5);
  }
  // Not where HDF5 looks: text that is not UTF-8 (the signature's first byte).
  const std::string elsewhere = write_yaml(dir, "e.yaml", 2000, 100, kSignature);
  CHECK(refusal(elsewhere).find(": not UTF-8 text: byte 0x89 at line 21, column 1") !=
        std::string::npos);
  // A NUL byte: in the first 4 kB of a file larger than the limit, and past them.
  const std::string large = write_yaml(dir, "b.yaml", big, 10, std::string(1, '\0'));
  CHECK(refusal(large) == large +
                              ": is a binary file (a NUL byte at offset 10), not text, "
                              "expected a configuration file (a regular YAML file)");
  const std::string late = write_yaml(dir, "l.yaml", 6000, 5000, std::string(1, '\0'));
  CHECK(refusal(late).find(": is a binary file (a NUL byte at offset 5000), not text") !=
        std::string::npos);
  // Without either, the size is refused as before; a missing file does not exist.
  const std::string text = write_yaml(dir, "t.yaml", big, 0, "a: 2\n");
  CHECK(refusal(text).find(": larger than 1048576 bytes") != std::string::npos);
  const std::string missing = (dir.path / "missing.yaml").string();
  CHECK(refusal(missing) == missing +
                                ": does not exist, expected a configuration file (a regular "
                                "YAML file)");
  CHECK(why_not_regular_file(missing) == std::optional<std::string>("does not exist"));
  CHECK(why_not_regular_file(text + "/below") == std::optional<std::string>("does not exist"));
  CHECK(why_not_regular_file(dir.path.string()) == std::optional<std::string>("is a directory"));
}

}  // namespace hexdyn
