// Messages between the ranks of a sweep (src/hexdyn/mpi/messages.*): work, stop and
// result messages round-trip every field, including empty and binary blocks, and a
// truncated message is an error rather than garbage.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/mpi/messages.hpp"

using namespace hexdyn;

TEST_CASE("mpi messages: work and stop round-trip", "[mpi]") {
  ScenarioInput in;
  in.index = 123456789012ULL;
  in.id = "123456789012";
  in.yaml = "terrain:\n  riser_height: 0.04\n";
  const auto work = unpack_work(pack_work(in, true));
  REQUIRE(work.has_value());
  CHECK(work->input.index == in.index);
  CHECK(work->input.id == in.id);
  CHECK(work->input.yaml == in.yaml);
  CHECK(work->keep_runs);
  CHECK_FALSE(unpack_work(pack_work(in, false))->keep_runs);
  CHECK_FALSE(unpack_work(pack_stop()).has_value());
}

TEST_CASE("mpi messages: a finished scenario round-trips, the sender from the envelope",
          "[mpi]") {
  Finished f;
  f.index = 7;
  f.status = ScenarioStatus::kReach;
  f.message = "scenario 000007: foothold out of reach";
  f.wall_time_s = 0.125;
  f.rank = 99;  // not sent: the receiver takes the rank from MPI's envelope
  f.checkpoint = {'\0', '\x89', 'H', 'D', 'F', '\0', '\xff'};
  const Finished g = unpack_result(pack_result(f), 3);
  CHECK(g.index == 7);
  CHECK(g.status == ScenarioStatus::kReach);
  CHECK(g.message == f.message);
  CHECK(g.wall_time_s == 0.125);
  CHECK(g.rank == 3);
  CHECK(g.checkpoint == f.checkpoint);

  Finished empty;
  const Finished h = unpack_result(pack_result(empty), 1);
  CHECK(h.message.empty());
  CHECK(h.checkpoint.empty());
}

TEST_CASE("mpi messages: a truncated message throws", "[mpi]") {
  ScenarioInput in;
  in.id = "000001";
  in.yaml = "a: 1\n";
  std::vector<char> work = pack_work(in, false);
  work.pop_back();
  CHECK_THROWS_AS(unpack_work(work), Error);
  Finished f;
  f.checkpoint.assign(100, 'x');
  std::vector<char> result = pack_result(f);
  result.resize(result.size() - 1);
  CHECK_THROWS_AS(unpack_result(result, 1), Error);
  CHECK_THROWS_AS(unpack_work({}), Error);
}
