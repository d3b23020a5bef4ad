// Progress lines (src/hexdyn/sweep/progress.*): throttled, with rate and time left.
#include <catch2/catch.hpp>
#include <string>

#include "hexdyn/sweep/progress.hpp"
#include "sweep_test_support.hpp"

using namespace hexdyn;
using namespace sweep_test;
namespace fs = std::filesystem;

TEST_CASE("sweep: progress lines are throttled and give rate and time left", "[sweep]") {
  using Clock = ProgressMeter::Clock;
  const Clock::time_point t0{};
  ProgressMeter m(100, 20, 5.0, t0);
  CHECK_FALSE(m.update(25, 0, t0 + std::chrono::seconds(2)).has_value());  // too soon
  const auto line = m.update(30, 1, t0 + std::chrono::seconds(5));
  REQUIRE(line.has_value());
  // 10 computed in 5 s: 2 per second, 70 left: 35 s.
  CHECK(*line == "hexdyn: sweep: 30/100 done, 1 failed, 2 scenarios/s, 35 s left, 5 s elapsed");
  CHECK_FALSE(m.update(30, 1, t0 + std::chrono::seconds(20)).has_value());  // nothing new
  CHECK_FALSE(m.update(31, 1, t0 + std::chrono::seconds(9)).has_value());   // too soon again
  CHECK(m.update(100, 1, t0 + std::chrono::seconds(40)).value() ==
        "hexdyn: sweep: 100/100 done, 1 failed, 2 scenarios/s, 40 s elapsed");
  CHECK(format_duration(125) == "2 min 05 s");
  CHECK(format_duration(7300) == "2 h 01 min");
}
