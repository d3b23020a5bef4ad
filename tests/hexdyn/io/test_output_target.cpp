// check_output_target and the last-moment check of publish_atomically: an
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

#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/process/atomic_file.hpp"

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
  std::vector<InputFile> inputs;
  add_input(inputs, "scene", d.file("cfg.yaml"));

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

TEST_CASE("output target: an input is known by the identity it had when read",
          "[output][target][inputs]") {
  Dir d;
  std::ofstream(d.file("robot.urdf")) << "<robot name='r'/>\n";
  std::vector<InputFile> inputs;
  add_input(inputs, "URDF", d.file("robot.urdf"));
  REQUIRE(inputs.size() == 1);
  struct stat st {};
  REQUIRE(::stat(d.file("robot.urdf").c_str(), &st) == 0);
  CHECK(inputs[0].device == static_cast<std::uint64_t>(st.st_dev));
  CHECK(inputs[0].inode == static_cast<std::uint64_t>(st.st_ino));
  // Renamed after it was read: its new name is still the input.
  fs::rename(d.file("robot.urdf"), d.file("moved.urdf"));
  CHECK_THROWS_WITH(check_output_target(d.file("moved.urdf"), inputs),
                    Catch::Contains("the URDF") && Catch::Contains("same device and inode"));
  // A new file at the input's path is refused as well (what is at an input's path now).
  std::ofstream(d.file("robot.urdf")) << "<robot name='s'/>\n";
  CHECK_THROWS_WITH(check_output_target(d.file("robot.urdf"), inputs),
                    Catch::Contains("same device and inode"));
  // Gone altogether: the output may take its name.
  fs::remove(d.file("robot.urdf"));
  CHECK_NOTHROW(check_output_target(d.file("robot.urdf"), inputs));
  CHECK_THROWS_WITH(check_output_target(std::string("a\0b", 3), inputs), Catch::Contains("NUL"));
  // An input a result records (/meta input_sha256) keeps its path even when gone, under any
  // name of its folder.
  const std::string digest(64, 'a');
  const auto recorded =
      recorded_inputs(digest + "  " + d.file("robot.urdf") + "\n", "the result's /meta");
  REQUIRE(recorded.size() == 1);
  CHECK(recorded[0].recorded);
  CHECK(recorded[0].sha256 == digest);
  CHECK_THROWS_WITH(check_output_target(d.file("robot.urdf"), recorded),
                    Catch::Contains("(the same path)"));
  fs::create_directory_symlink(d.file(""), d.file("alias"));
  CHECK_THROWS_WITH(check_output_target(d.file("alias/robot.urdf"), recorded),
                    Catch::Contains("the same path"));
  CHECK_NOTHROW(check_output_target(d.file("other.urdf"), recorded));
}

TEST_CASE("inputs: a file is read once while a freeze lives, and its digest is of those bytes",
          "[inputs]") {
  Dir d;
  const std::string path = d.file("scene.yaml");
  std::ofstream(path) << "name: first\n";
  std::string first_digest;
  {
    const InputFreeze freeze;
    const InputFile a = read_input_text(path, 1 << 20, "a scene");
    std::ofstream(path) << "name: second, longer\n";  // edited while the command runs
    const InputFile b = read_input_text(path, 1 << 20, "a scene");
    CHECK(*b.text == "name: first\n");
    CHECK(b.sha256 == a.sha256);
    first_digest = a.sha256;
    std::vector<InputFile> listed;
    add_input(listed, "scene", path);
    CHECK(listed.at(0).sha256 == first_digest);
    CHECK(input_kept(path));
  }
  // Outside a freeze, the file as it is now.
  const InputFile now = read_input_text(path, 1 << 20, "a scene");
  CHECK(*now.text == "name: second, longer\n");
  CHECK(now.sha256 != first_digest);
  CHECK_FALSE(input_kept(path));
}

TEST_CASE("inputs: text that is not UTF-8 is refused with its line and column", "[inputs]") {
  CHECK(first_non_utf8("plain ascii") == std::string::npos);
  CHECK(first_non_utf8("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80") == std::string::npos);
  CHECK(first_non_utf8("ab\xFF") == 2);            // not a lead byte
  CHECK(first_non_utf8("\xC0\xAF") == 0);          // overlong '/'
  CHECK(first_non_utf8("\xED\xA0\x80") == 0);      // a surrogate
  CHECK(first_non_utf8("\xF4\x90\x80\x80") == 0);  // beyond U+10FFFF
  CHECK(first_non_utf8("x\xE2\x82") == 1);         // cut short
  Dir d;
  const std::string path = d.file("latin1.yaml");
  std::ofstream(path) << "name: ok\nlabel: caf\xE9\n";
  CHECK_THROWS_WITH(
      read_input_text(path, 1 << 20, "a scene"),
      Catch::Contains("not UTF-8") && Catch::Contains("byte 0xE9 at line 2, column 11"));
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
