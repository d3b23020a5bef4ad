// A full disk under H5Writer (src/hexdyn/io/h5io.*; docs/user/faults.md#full-disk): the file
// is built in memory and written with write(2), so the error names the file and says the
// OS's reason; /dev/full, which refuses every write with ENOSPC, stands in for a full disk
// (tests/faults/full_disk.sh fills a real tmpfs, as root).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"

using namespace hexdyn;

TEST_CASE("io: H5Writer on a full disk says so and closes everything", "[io][faults]") {
  for (int attempt = 0; attempt < 2; ++attempt) {  // the second finds HDF5 clean
    H5Writer w("/dev/full");
    const std::vector<double> values(1000, 1.5);
    w.write_doubles("/a/b", {10, 100}, values, "m");
    w.set_string_attribute("/a", "note", "x");
    try {
      w.close();
      FAIL("close() on /dev/full succeeded");
    } catch (const IoError& e) {
      CHECK(std::string(e.what()) == "cannot write '/dev/full': No space left on device");
    }
    CHECK_NOTHROW(w.close());  // closed already: nothing left to do
  }
}

TEST_CASE("io: H5Writer never writes through a symbolic link", "[io][faults]") {
  const std::string link = "/tmp/hexdyn_h5writer_link_" + std::to_string(::getpid());
  REQUIRE(::symlink("/dev/null", link.c_str()) == 0);
  CHECK_THROWS_WITH(H5Writer(link), Catch::Contains("cannot create '" + link + "'"));
  ::unlink(link.c_str());
}
