// Temporary names (process/atomic_file.hpp): every output name the file systems take (up to
// 255 bytes, NAME_MAX) has a temporary name they take too, `.NAME.tmp.PID` while it fits and
// `.START~DIGEST.tmp.PID` beyond (cut on a whole UTF-8 character); an output of 255 bytes is
// published, and a stale temporary file of such a name is found and removed.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/temp_dir.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string name_of(const std::string& path) { return fs::path(path).filename().string(); }

}  // namespace

TEST_CASE("atomic file: the temporary name of every name up to 255 bytes has at most 255",
          "[atomic_file]") {
  const std::string pid = std::to_string(::getpid());
  for (std::size_t n = 1; n <= 255; ++n) {
    const std::string name(n, 'a');
    const std::string tmp = name_of(temporary_path_for("d/" + name));
    INFO(n);
    CHECK(tmp.size() <= 255);
    CHECK(tmp.substr(tmp.size() - pid.size() - 5) == ".tmp." + pid);
    if (n + 16 <= 255)  // room for '.', ".tmp." and 10 digits of any pid
      CHECK(tmp == "." + name + ".tmp." + pid);
    else
      CHECK(tmp.rfind("." + name.substr(0, 222) + "~", 0) == 0);
  }
  // Names alike in their first 250 bytes have temporary names of their own.
  const std::string a(250, 'a');
  CHECK(temporary_path_for(a + "1.h5") != temporary_path_for(a + "2.h5"));
  CHECK(temporary_path_for(a + "1.h5") == temporary_path_for(a + "1.h5"));
  // Cut on a whole character: 'a' and 125 two-byte characters, then ".h5" (254 bytes).
  std::string utf8 = "a";
  for (int i = 0; i < 125; ++i) utf8 += "\xc3\xa9";
  utf8 += ".h5";
  const std::string tmp = name_of(temporary_path_for(utf8));
  CHECK(tmp.size() <= 255);
  CHECK(first_non_utf8(tmp) == std::string::npos);
}

TEST_CASE("atomic file: an output of 255 bytes is published, its stale temporary removed",
          "[atomic_file]") {
  TempDir dir("atomic");
  const std::string out = (dir.path / (std::string(252, 'b') + ".h5")).string();
  write_bytes_atomically(out, "xyz", 3);
  std::ifstream in(out);
  std::string text;
  in >> text;
  CHECK(text == "xyz");
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 1);
  // A temporary file of a process that is gone, named as that process named it.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) ::_exit(0);
  REQUIRE(::waitpid(child, nullptr, 0) == child);
  std::string stale = temporary_path_for(out);
  stale = stale.substr(0, stale.rfind('.') + 1) + std::to_string(child);
  std::ofstream(stale) << "stale";
  REQUIRE(fs::exists(stale));
  const auto removed = remove_stale_temporaries(out);
  REQUIRE(removed.size() == 1);
  CHECK(removed[0].find(std::to_string(child) + ", which is gone") != std::string::npos);
  CHECK_FALSE(fs::exists(stale));
  CHECK(fs::exists(out));
}

}  // namespace hexdyn
