// SHA-256 of input files (process/sha256.hpp) against the FIPS 180-4 examples (NIST's "abc", the
// empty message, the 448-bit message and one million 'a') and against coreutils'
// `sha256sum` on a file larger than the read block; a scene's /meta input_sha256 lists its
// file, every inherited file and its URDF with `sha256sum`'s digests (config/inputs.hpp).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/sha256.hpp"
#include "hexdyn/temp_dir.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

/// `sha256sum FILE`'s digest: coreutils, an implementation independent of OpenSSL.
std::string coreutils_sha256(const std::string& path) {
  FILE* p = ::popen(("sha256sum '" + path + "'").c_str(), "r");
  REQUIRE(p != nullptr);
  char buf[65] = {0};
  const std::size_t got = std::fread(buf, 1, 64, p);
  ::pclose(p);
  REQUIRE(got == 64);
  return std::string(buf, 64);
}

TEST_CASE("sha256: the FIPS 180-4 examples", "[io]") {
  const std::string abc = "abc";
  CHECK(sha256_hex(abc.data(), abc.size()) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("", 0) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  const std::string m448 = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  REQUIRE(m448.size() * 8 == 448);
  CHECK(sha256_hex(m448.data(), m448.size()) ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  TempDir dir("sha256");
  CHECK(sha256_file(dir.write("abc", abc)) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_file(dir.write("empty", "")) ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  // One million 'a': 15.3 read blocks of 64 KiB.
  CHECK(sha256_file(dir.write("million", std::string(1000000, 'a'))) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("sha256: a file's digest is sha256sum's, an unreadable file is named", "[io]") {
  TempDir dir("sha256");
  std::string text;
  for (int i = 0; i < 20000; ++i) text += std::to_string(i * 7919 % 10007) + (i % 13 ? " " : "\n");
  const std::string path = dir.write("numbers.txt", text);
  CHECK(sha256_file(path) == coreutils_sha256(path));
  const std::string urdf = std::string(HEXDYN_SOURCE_DIR) + "/robots/kraby.urdf";
  CHECK(sha256_file(urdf) == coreutils_sha256(urdf));
  const std::string missing = (dir.path / "missing.yaml").string();
  CHECK_THROWS_AS(sha256_file(missing), IoError);
  CHECK_THROWS_WITH(sha256_file(missing), Catch::Contains(missing));
  CHECK_THROWS_WITH(sha256_file(dir.path.string()),
                    Catch::Contains(dir.path.string()) && Catch::Contains("not a regular file"));
}

TEST_CASE("sha256: a scene's input files with their digests", "[io]") {
  TempDir dir("sha256");
  const std::string source = HEXDYN_SOURCE_DIR;
  const std::string urdf = source + "/robots/kraby.urdf";
  const std::string base = dir.write(
      "base.yaml", "inherit: " + source + "/configs/robots/kraby_stairs.yaml\nname: base\n");
  const std::string top = dir.write("top.yaml", "inherit: base.yaml\nname: top\n");
  const Scene s = load_scene(top);
  const std::string kraby =
      fs::path(source + "/configs/robots/kraby_stairs.yaml").lexically_normal().string();
  const std::string expected = coreutils_sha256(top) + "  " + top + "\n" + coreutils_sha256(base) +
                               "  " + base + "\n" + coreutils_sha256(kraby) + "  " + kraby + "\n" +
                               coreutils_sha256(urdf) + "  " +
                               fs::path(urdf).lexically_normal().string() + "\n";
  CHECK(s.input_sha256 == expected);
}

}  // namespace
}  // namespace hexdyn
