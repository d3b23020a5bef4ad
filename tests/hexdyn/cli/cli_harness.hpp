#pragma once
// Running the hexdyn binary from tests: a scratch directory per test, the command run
// there with a time limit, stdout and stderr captured, and a snapshot of the directory
// to show that a refused command changed and created nothing.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace hexdyn::cli_test {

namespace fs = std::filesystem;

inline const std::string kBinary = HEXDYN_BINARY;
inline const std::string kSourceDir = HEXDYN_SOURCE_DIR;
inline const std::string kPaperConfig = kSourceDir + "/configs/paper.yaml";
/// A coarse uniform grid keeps a whole run short; everything else is the paper scene.
inline const std::vector<std::string> kCoarse = {"--set", "output.grid=uniform", "--set",
                                                 "output.sample_step=0.5"};

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_file(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

/// A scratch directory `work` for the runs and a sibling `capture` for their output.
struct Scratch {
  fs::path root, work, capture;
  Scratch() {
    static int counter = 0;
    root = fs::temp_directory_path() /
           ("hexdyn_cli_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(root);
    work = root / "work";
    capture = root / "capture";
    fs::create_directories(work);
    fs::create_directories(capture);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(work)) names.insert(e.path().filename().string());
    return names;
  }

  /// Every entry below `work` with its type and, for regular files, its bytes (special
  /// files are not opened: a FIFO would block).
  std::map<std::string, std::string> snapshot() const {
    std::map<std::string, std::string> entries;
    for (const auto& e : fs::recursive_directory_iterator(work)) {
      const auto type = e.symlink_status().type();
      const std::string rel = fs::relative(e.path(), work).string();
      if (type == fs::file_type::regular)
        entries[rel] = "file:" + read_file(e.path());
      else
        entries[rel] = "type:" + std::to_string(static_cast<int>(type));
    }
    return entries;
  }
};

struct Outcome {
  int status = -1;
  std::string out, err;
};

/// Runs `hexdyn args...` inside the scratch work directory, killed after `limit_s`
/// seconds (then the status is 124, which no test expects).
inline Outcome run_cli(const Scratch& s, const std::vector<std::string>& args, int limit_s = 600) {
  std::string cmd = "cd " + quote(s.work.string()) + " && timeout -s KILL " +
                    std::to_string(limit_s) + " " + quote(kBinary);
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " > " + quote((s.capture / "stdout").string()) + " 2> " +
         quote((s.capture / "stderr").string());
  const int raw = std::system(cmd.c_str());
  Outcome o;
  REQUIRE(raw != -1);
  REQUIRE(WIFEXITED(raw));
  o.status = WEXITSTATUS(raw);
  o.out = read_file(s.capture / "stdout");
  o.err = read_file(s.capture / "stderr");
  return o;
}

inline std::vector<std::string> concat(std::vector<std::string> a,
                                       const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace hexdyn::cli_test
