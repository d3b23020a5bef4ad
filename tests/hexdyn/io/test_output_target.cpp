// check_output_target and the last-moment check of publish_atomically (issue 13): an
// output is a new path or a regular file that is none of the inputs (by device and inode),
// in a folder that takes a new file; nothing else is ever replaced, and the checks leave
// the folder as they found it.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/atomic_file.hpp"
#include "hexdyn/io/output.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

struct Dir {
  fs::path path;
  Dir() {
    path = fs::temp_directory_path() / ("hexdyn_target_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Dir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(path)) names.insert(e.path().filename().string());
    return names;
  }
};

std::string text_of(const std::string& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_CASE("output target: special files and inputs are refused, by type and identity",
          "[output][target]") {
  Dir d;
  std::ofstream(d.file("cfg.yaml")) << "name: x\n";
  std::ofstream(d.file("other.yaml")) << "name: y\n";
  fs::create_hard_link(d.file("cfg.yaml"), d.file("hard.h5"));
  fs::create_symlink("other.yaml", d.file("link.h5"));
  REQUIRE(::mkfifo(d.file("fifo.h5").c_str(), 0644) == 0);
  fs::create_directory(d.file("sub"));
  const std::set<std::string> before = d.entries();
  const std::vector<std::string> inputs = {d.file("cfg.yaml")};

  CHECK_THROWS_WITH(check_output_target(d.file("cfg.yaml"), inputs),
                    Catch::Contains("same device and inode"));
  CHECK_THROWS_WITH(check_output_target(d.file("hard.h5"), inputs),
                    Catch::Contains("same device and inode"));
  CHECK_THROWS_WITH(check_output_target(d.file("sub/../cfg.yaml"), inputs),
                    Catch::Contains("same device and inode"));
  CHECK_THROWS_WITH(check_output_target(d.file("link.h5"), inputs),
                    Catch::Contains("is a symbolic link"));
  CHECK_THROWS_WITH(check_output_target(d.file("fifo.h5"), inputs), Catch::Contains("is a FIFO"));
  CHECK_THROWS_WITH(check_output_target(d.file("sub"), inputs), Catch::Contains("is a directory"));
  CHECK_THROWS_WITH(check_output_target("/dev/null", inputs),
                    Catch::Contains("is a character device"));
  CHECK_THROWS_WITH(check_output_target(d.file(std::string(300, 'x')), inputs),
                    Catch::Contains("File name too long"));
  CHECK_THROWS_AS(check_output_target("", inputs), IoError);
  // Allowed: a new name, and a regular file that is no input (other.yaml is not listed).
  CHECK_NOTHROW(check_output_target(d.file("new.h5"), inputs));
  CHECK_NOTHROW(check_output_target(d.file("other.yaml"), inputs));
  CHECK(d.entries() == before);  // the probe's temporary file is gone
  CHECK(text_of(d.file("cfg.yaml")) == "name: x\n");
}

TEST_CASE("output target: publish_atomically never renames over what appeared meanwhile",
          "[output][target]") {
  Dir d;
  const std::string out = d.file("out.h5");
  // The output became a FIFO / a symbolic link while the file was written.
  REQUIRE(::mkfifo(out.c_str(), 0644) == 0);
  CHECK_THROWS_WITH(write_bytes_atomically(out, "abc", 3), Catch::Contains("is a FIFO"));
  struct stat st {};
  REQUIRE(::lstat(out.c_str(), &st) == 0);
  CHECK(S_ISFIFO(st.st_mode));
  fs::remove(out);
  std::ofstream(d.file("target")) << "keep";
  fs::create_symlink("target", out);
  CHECK_THROWS_WITH(write_bytes_atomically(out, "abc", 3), Catch::Contains("is a symbolic link"));
  CHECK(fs::is_symlink(out));
  CHECK(text_of(d.file("target")) == "keep");
  CHECK(d.entries() == std::set<std::string>{"out.h5", "target"});  // no temporary left
  // A regular file is replaced.
  fs::remove(out);
  std::ofstream(out) << "old";
  write_bytes_atomically(out, "abc", 3);
  CHECK(text_of(out) == "abc");
}

}  // namespace
}  // namespace hexdyn
