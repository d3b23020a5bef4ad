// The checked YAML reader (yaml_load.hpp): duplicate keys with both lines, the nesting
// cap at its boundary, the top-level shape, regular files only (a FIFO is refused
// without blocking, in a child process with a time limit), the size cap at its
// boundary, inheritance cycles by canonical path, and p/q values.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

std::string parse_error(const std::string& text, const std::string& source = "f.yaml") {
  try {
    parse_yaml_text(text, source);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError for: " << text);
  return "";
}

/// `depth` maps nested in each other in block style: k:\n  k:\n ... with a value at the end.
std::string nested_maps(int depth) {
  std::string text;
  for (int i = 0; i < depth; ++i)
    text += std::string(2 * i, ' ') + "k:" + (i + 1 == depth ? " 1\n" : "\n");
  return text;
}

struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("hexdyn_yaml_load_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
};

std::string read_error(const std::string& path) {
  try {
    read_text_file(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError reading " << path);
  return "";
}

std::string tree_error(const std::string& path) {
  try {
    load_scene_tree(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError loading " << path);
  return "";
}

TEST_CASE("yaml load: duplicate keys name the path and both lines", "[config][yaml]") {
  CHECK(parse_error("a: 1\nb: 2\na: 3\n") ==
        "f.yaml: a: duplicate key, first at line 1, again at line 3");
  CHECK(parse_error("a:\n  b:\n    c: 1\n\n    c: 2\n") ==
        "f.yaml: a.b.c: duplicate key, first at line 3, again at line 5");
  CHECK(parse_error("l:\n  - {x: 1, y: 2}\n  - x: 1\n    x: 2\n") ==
        "f.yaml: l[1].x: duplicate key, first at line 3, again at line 4");
  // Quoted and plain spellings are the same key.
  CHECK(parse_error("a: 1\n\"a\": 2\n") ==
        "f.yaml: a: duplicate key, first at line 1, again at line 2");
  // Equal keys in different maps are not duplicates.
  const YAML::Node ok = parse_yaml_text("a: {k: 1}\nb: {k: 2}\n", "f.yaml");
  CHECK(ok["b"]["k"].as<int>() == 2);
  // An alias is not expanded by the check; as a value it is fine, as a key it is refused.
  CHECK(parse_yaml_text("a: &x {k: 1}\nb: *x\n", "f.yaml")["b"]["k"].as<int>() == 1);
  CHECK(parse_error("a: &x k\n*x : 2\n").find("as a key") != std::string::npos);
  CHECK(parse_error("[a, b]: 1\n").find("got a list as a key") != std::string::npos);
  // One document per file.
  CHECK(parse_error("a: 1\n---\nb: 2\n") ==
        "f.yaml:2: a second YAML document (after '---'), expected one document per file");
}

TEST_CASE("yaml load: nesting is capped at kMaxYamlDepth levels", "[config][yaml]") {
  REQUIRE(kMaxYamlDepth == 64);
  CHECK(parse_yaml_text(nested_maps(kMaxYamlDepth), "f.yaml").IsMap());
  const std::string msg = parse_error(nested_maps(kMaxYamlDepth + 1));
  INFO(msg);
  CHECK(msg.rfind("f.yaml:65: k.k.", 0) == 0);
  CHECK(msg.find("nested deeper than 64 levels") != std::string::npos);
  // Far deeper than yaml-cpp's own limit: the same one line, not "bad file".
  const std::string deep = parse_error("a: " + std::string(100000, '[') + std::string(100000, ']'));
  CHECK(deep.find("nested deeper than 64 levels") != std::string::npos);
  CHECK(deep.find("bad file") == std::string::npos);
  CHECK(deep.size() < 200);
}

TEST_CASE("yaml load: the top level must be a map", "[config][yaml]") {
  CHECK(parse_error("- 1\n- 2\n") == "f.yaml: top level: got a list, expected a map of sections");
  CHECK(parse_error("hello\n") ==
        "f.yaml: top level: got a single value 'hello', expected a map of sections");
  CHECK(parse_error("") == "f.yaml: top level: got an empty document, expected a map of sections");
  CHECK(parse_error("# only a comment\n") ==
        "f.yaml: top level: got an empty document, expected a map of sections");
  // A long multi-line scalar is shown short and on one line.
  const std::string msg = parse_error("|\n" + std::string(50, 'x') + "\n  y\n");
  CHECK(msg.find('\n') == std::string::npos);
}

TEST_CASE("yaml load: only regular files up to 1 MiB are read", "[config][yaml]") {
  TempDir d;
  CHECK(read_error(d.path.string()) ==
        d.path.string() + ": is a directory, expected a configuration file (a regular YAML file)");
  CHECK(read_error("/dev/zero").rfind("/dev/zero: is a device", 0) == 0);
  CHECK(read_error((d.path / "none.yaml").string()).find("does not exist") != std::string::npos);
  // The cap, at its boundary.
  const std::string at_cap = d.write("at_cap.yaml", std::string(kMaxConfigBytes, '#'));
  CHECK(read_text_file(at_cap).size() == kMaxConfigBytes);
  const std::string over = d.write("over.yaml", std::string(kMaxConfigBytes + 1, '#'));
  CHECK(read_error(over) == over +
                                ": larger than 1048576 bytes (1 MiB), expected a configuration "
                                "file (a regular YAML file) of at most that size");

  // A FIFO nobody writes to: refused at once. Run in a child so that a blocking open or
  // read fails the test after 10 s instead of hanging it.
  const std::string fifo = (d.path / "fifo.yaml").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    try {
      read_text_file(fifo);
    } catch (const ConfigError& e) {
      ::_exit(std::string(e.what()) == fifo +
                                           ": is a FIFO (named pipe), expected a configuration "
                                           "file (a regular YAML file)"
                  ? 0
                  : 1);
    }
    ::_exit(2);
  }
  int status = -1;
  bool ended = false;
  for (int i = 0; i < 1000 && !ended; ++i) {
    ended = ::waitpid(child, &status, WNOHANG) == child;
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!ended) {
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
  }
  CHECK(ended);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}

TEST_CASE("yaml load: inherit: cycles by canonical path, directories and duplicates",
          "[config][yaml]") {
  TempDir d;
  // A file inheriting itself, spelt differently.
  const std::string self = d.write("cfg.yaml", "inherit: ./cfg.yaml\n");
  const std::string self_msg = tree_error(self);
  INFO(self_msg);
  CHECK(self_msg.find("inherit: cycle ") != std::string::npos);
  CHECK(self_msg.find("cfg.yaml -> ") != std::string::npos);
  CHECK(self_msg.size() < 400);  // at once, not a growing path
  // Two files through ../dir.
  const std::string a = d.write("a/cfg.yaml", "inherit: ../b/cfg.yaml\n");
  d.write("b/cfg.yaml", "inherit: ../a/cfg.yaml\n");
  const std::string two = tree_error(a);
  INFO(two);
  CHECK(two.find("inherit: cycle ") != std::string::npos);
  CHECK(two.find("a/cfg.yaml -> ") != std::string::npos);
  CHECK(two.find("b/cfg.yaml -> ") != std::string::npos);
  // A chain of three files is not a cycle; maps merge key by key.
  d.write("base.yaml", "x: {p: 1, q: 2}\n");
  d.write("mid.yaml", "inherit: base.yaml\nx: {q: 3}\n");
  const std::string top = d.write("top.yaml", "inherit: mid.yaml\nx: {r: 4}\n");
  const YAML::Node merged = load_scene_tree(top);
  CHECK(merged["x"]["p"].as<int>() == 1);
  CHECK(merged["x"]["q"].as<int>() == 3);
  CHECK(merged["x"]["r"].as<int>() == 4);
  // inherit: of a directory names the inheriting file.
  fs::create_directories(d.path / "sub");
  const std::string of_dir = d.write("of_dir.yaml", "inherit: sub\n");
  CHECK(tree_error(of_dir).rfind(of_dir + ": inherit: got sub, which is a directory", 0) == 0);
  // A duplicate in an inherited file names that file.
  d.write("dup.yaml", "a: 1\na: 2\n");
  const std::string child = d.write("child.yaml", "inherit: dup.yaml\n");
  const std::string dup = tree_error(child);
  CHECK(dup.find("dup.yaml: a: duplicate key, first at line 1, again at line 2") !=
        std::string::npos);
}

TEST_CASE("yaml load: p/q values in --set and sweeps", "[config][yaml]") {
  CHECK(parse_fraction("3/4") == 0.75);
  CHECK(parse_fraction(" -2 / 3 ") == -2.0 / 3.0);
  CHECK_FALSE(parse_fraction("3/0"));
  CHECK_FALSE(parse_fraction("0.5"));
  CHECK_FALSE(parse_fraction("a/b"));
  CHECK_FALSE(parse_fraction("1.5/2"));
  CHECK_FALSE(parse_fraction(std::string(400, '9') + "/1"));  // no exception, no inf
  // The text reads back to the same double.
  CHECK(std::stod(fraction_to_number_text("2/3")) == 2.0 / 3.0);
  CHECK(fraction_to_number_text("fast") == "fast");
  CHECK(parse_override("gait.duty_factor=3/4").value == "0.75");
  CHECK(parse_override("gait.duty_factor=[1/2]").value == "[1/2]");  // lists are not values
  const Scene s = load_scene(std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml",
                             {parse_override("gait.duty_factor=2/3")});
  CHECK(s.gait.duty_factor == 2.0 / 3.0);
}

/// "a: &x [1, ..., 1]" (n items) "\nb: [*x, ...]" (k aliases) "\nc: [2, ..., 2]" (m items):
/// 1 + (1 + 1 + n) + (1 + 1 + k (1 + n)) + (1 + 1 + m) nodes once expanded, counted here.
struct AliasDocument {
  std::string text;
  std::uint64_t nodes = 0;
  AliasDocument(int n, int k, int m) {
    auto list = [](int count, const std::string& item) {
      std::string s = "[";
      for (int i = 0; i < count; ++i) s += (i ? "," : "") + item;
      return s + "]";
    };
    text = "a: &x " + list(n, "1") + "\nb: " + list(k, "*x") + "\nc: " + list(m, "2") + "\n";
    nodes = 1 + (2 + n) + (2 + std::uint64_t(k) * (1 + n)) + (2 + m);
  }
};

TEST_CASE("yaml load: aliases count as their anchor's node, capped before any tree is built",
          "[config][yaml][sizes]") {
  REQUIRE(kMaxYamlNodes == 1000000);
  // Just inside and just beyond the node limit, counted independently here.
  const AliasDocument inside(999, 998, 994), beyond(999, 998, 995);
  REQUIRE(inside.nodes == kMaxYamlNodes);
  REQUIRE(beyond.nodes == kMaxYamlNodes + 1);
  CHECK(parse_yaml_text(inside.text, "f.yaml")["b"][997][998].as<int>() == 1);
  std::string msg = parse_error(beyond.text);
  INFO(msg);
  CHECK(msg.rfind("f.yaml:3: c[994]: got more than 1000000 YAML nodes", 0) == 0);
  CHECK(msg.find("once aliases (*name) are expanded") != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
  // A billion laughs in 400 bytes: refused at once, in the `auto:` record as anywhere.
  std::string bomb = "name: x\nauto:\n a0: &0 [x,x,x,x,x,x,x,x,x,x]\n";
  for (int i = 1; i < 9; ++i) {
    bomb += " a" + std::to_string(i) + ": &" + std::to_string(i) + " [";
    for (int j = 0; j < 10; ++j) bomb += (j ? ",*" : "*") + std::to_string(i - 1);
    bomb += "]\n";
  }
  REQUIRE(bomb.size() < 400);
  const auto start = std::chrono::steady_clock::now();
  msg = parse_error(bomb);
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
  CHECK(msg.find(": auto.a5[") != std::string::npos);
  CHECK(msg.find("YAML nodes once aliases") != std::string::npos);
  // Bytes of values: one 100 kB scalar repeated, just inside and beyond 16 MiB.
  REQUIRE(kMaxYamlBytes == 16u << 20);
  const std::string big(100000, 'v');
  auto repeated = [&](int k) {
    std::string s = "a: &x " + big + "\nb: [";
    for (int i = 0; i < k; ++i) s += (i ? ",*x" : "*x");
    return s + "]\n";
  };
  // (1 + k) × 100,000 bytes plus the keys a, b: 166 aliases fit in 16,777,216 bytes.
  CHECK(parse_yaml_text(repeated(166), "f.yaml")["b"].size() == 166);
  msg = parse_error(repeated(167));
  CHECK(msg.find("b[166]: got more than 16777216 bytes of values") != std::string::npos);
  // An alias inside the node it names would expand for ever.
  CHECK(parse_error("a: &x [1, *x]\n") ==
        "f.yaml:1: a[1]: got an alias inside the node it names (a cycle), expected an alias of a "
        "complete node");
}

TEST_CASE("yaml load: a --set value is at most 1 MiB", "[config][yaml][sizes]") {
  const std::string inside(kMaxConfigBytes, 'x');
  CHECK(parse_yaml_checked(inside, "--set name=...").Scalar().size() == kMaxConfigBytes);
  try {
    parse_yaml_checked(inside + "x", "--set name=" + inside + "x");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    INFO(msg.substr(0, 300));
    CHECK(msg.size() < 300);
    CHECK(msg.find("got a value of 1048577 bytes, expected at most 1048576") != std::string::npos);
  }
}

}  // namespace
}  // namespace hexdyn
