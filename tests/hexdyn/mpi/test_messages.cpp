// Messages between the ranks of a sweep (src/hexdyn/mpi/messages.*): the sweep, work
// batches, the stop, result batches and a worker's interruption notice round-trip every field,
// including empty and binary blocks, and a truncated message is an error rather than garbage.
#include <catch2/catch.hpp>
#include <cmath>
#include <csignal>
#include <memory>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/mpi/messages.hpp"
#include "hexdyn/sweep/record.hpp"

using namespace hexdyn;

TEST_CASE("mpi messages: work batches and stop round-trip", "[mpi]") {
  const std::vector<std::size_t> batch{123456789012ULL, 0, 7};
  const auto work = unpack_work(pack_work(batch));
  REQUIRE(work.has_value());
  CHECK(*work == batch);
  CHECK(unpack_work(pack_work({}))->empty());
  CHECK_FALSE(unpack_work(pack_stop()).has_value());
}

TEST_CASE("mpi messages: the sweep round-trips what a worker needs", "[mpi]") {
  SweepSpec spec;
  spec.name = "s";
  spec.base_path = "/x/base.yaml";
  spec.base_tree_yaml = "terrain:\n  riser_height: 0.04\n";
  SweepAxis a;
  a.key = "gait.duty_factor";
  a.values = {"0.5", "0.66666666666666663"};
  a.labels = {"1/2", "2/3"};
  spec.axes.push_back(a);
  SweepAxis cases;  // a cases axis: labels, and each case's keys
  cases.key = "robot";
  cases.values = cases.labels = {"mark4", "kraby"};
  cases.case_keys = {"robot.urdf", "robot.forward_axis"};
  cases.case_values = {{"/w/m.urdf", "+x"}, {"/w/k.urdf", "+y"}};
  spec.axes.push_back(cases);
  spec.inputs.resize(2);
  spec.inputs[0].role = "sweep file";
  spec.inputs[0].path = "s.yaml";
  spec.inputs[0].absolute = "/w/s.yaml";
  spec.inputs[0].sha256 = std::string(64, 'c');
  spec.inputs[1].role = "URDF";
  spec.inputs[1].path = "r.urdf";
  spec.inputs[1].absolute = "/w/r.urdf";
  spec.inputs[1].sha256 = std::string(64, 'd');
  // The bytes rank 0 read travel with it (every rank computes with them).
  spec.inputs[1].text = std::make_shared<const std::string>(std::string("<robot/>\0\xff", 10));
  const SweepIdentity id = make_identity(spec.inputs, "base: text", "hexdyn x", 7, true);
  SweepIdentity got;
  const SweepSpec back = unpack_spec(pack_spec(spec, id), got);
  CHECK(got.keep_runs);
  CHECK(got.difference(id).empty());
  CHECK(got.id == id.id);
  CHECK(back.name == "s");
  CHECK(back.base_path == spec.base_path);
  CHECK(back.base_tree_yaml == spec.base_tree_yaml);
  REQUIRE(back.inputs.size() == 2);
  CHECK(back.inputs[1].path == "r.urdf");
  CHECK(back.inputs[1].absolute == "/w/r.urdf");
  CHECK(back.inputs[1].sha256 == spec.inputs[1].sha256);
  CHECK(back.inputs[0].text == nullptr);
  REQUIRE(back.inputs[1].text != nullptr);
  CHECK(*back.inputs[1].text == *spec.inputs[1].text);
  REQUIRE(back.axes.size() == 2);
  CHECK(back.axes[0].key == a.key);
  CHECK(back.axes[0].values == a.values);
  CHECK(back.axes[0].labels == a.labels);
  CHECK_FALSE(back.axes[0].is_cases());
  CHECK(back.axes[1].key == "robot");
  CHECK(back.axes[1].labels == cases.labels);
  CHECK(back.axes[1].case_keys == cases.case_keys);
  CHECK(back.axes[1].case_values == cases.case_values);
}

TEST_CASE("mpi messages: finished scenarios round-trip in order", "[mpi]") {
  Finished f;
  f.index = 7;
  f.cost_s = 0.125;
  f.payload = {'\0', '\x89', 'H', 'D', 'F', '\0', '\xff'};
  Finished c;
  c.index = 9;
  c.crashed = true;
  c.reason = "its process was killed by signal 6 (SIGABRT)";
  std::vector<char> msg;
  append_result(msg, f);
  append_result(msg, c);
  const std::vector<Finished> got = unpack_results(msg);
  REQUIRE(got.size() == 2);
  CHECK(got[0].index == 7);
  CHECK(got[0].cost_s == 0.125);
  CHECK_FALSE(got[0].crashed);
  CHECK(got[0].payload == f.payload);
  CHECK(got[1].index == 9);
  CHECK(got[1].crashed);
  CHECK(got[1].reason == c.reason);
  CHECK(got[1].payload.empty());
  CHECK(unpack_results({}).empty());
}

TEST_CASE("mpi messages: a truncated message throws", "[mpi]") {
  std::vector<char> work = pack_work({1, 2});
  work.pop_back();
  CHECK_THROWS_AS(unpack_work(work), Error);
  Finished f;
  f.payload.assign(100, 'x');
  std::vector<char> result;
  append_result(result, f);
  result.resize(result.size() - 1);
  CHECK_THROWS_AS(unpack_results(result), Error);
  CHECK_THROWS_AS(unpack_work({}), Error);
  std::vector<char> notice = pack_interrupted(SIGTERM);
  notice.pop_back();
  CHECK_THROWS_AS(unpack_interrupted(notice), Error);
}

TEST_CASE("mpi messages: a worker's interruption notice names its signal", "[mpi]") {
  CHECK(unpack_interrupted(pack_interrupted(SIGTERM)) == SIGTERM);
  CHECK(unpack_interrupted(pack_interrupted(SIGINT)) == SIGINT);
}

TEST_CASE("mpi messages: a row carries its joint count, and one of another robot is refused",
          "[mpi]") {
  // A quadruped's row of 12 joints travels in a result message (its record, record.hpp).
  ScenarioSummary row = failed_summary(4, ScenarioStatus::kOk, "");
  row.joints = 12;
  for (int k = 0; k < row.joints; ++k) row.peak_torque_Nm[static_cast<std::size_t>(k)] = 0.5 * k;
  Finished f;
  f.index = 4;
  f.payload = encode_record({row, {}});
  std::vector<char> message;
  append_result(message, f);
  const std::vector<Finished> back = unpack_results(message);
  REQUIRE(back.size() == 1);
  const ScenarioSummary got = decode_record(back[0].payload.data(), back[0].payload.size()).summary;
  CHECK(got.joints == 12);
  for (int k = 0; k < 12; ++k) CHECK(got.peak_torque_Nm[static_cast<std::size_t>(k)] == 0.5 * k);
  CHECK(std::isnan(got.peak_torque_Nm[12]));  // beyond the robot's joints: nothing sent
  // The coordinator of a sweep of that robot takes it; one of an 18-joint robot refuses it.
  CHECK_NOTHROW(check_row_joints(got, 12, "000004", 2));
  CHECK_THROWS_WITH(check_row_joints(got, 18, "000004", 2),
                    "sweep: scenario 000004: the result from rank 2 has 12 joints, the sweep's "
                    "robot 18");
  // A row of no computed run has no per-joint values: nothing to refuse.
  CHECK_NOTHROW(check_row_joints(failed_summary(5, ScenarioStatus::kReach, "x"), 18, "000005", 1));
  // A record claiming more joints than any robot has is refused.
  row.joints = kMaxJoints + 1;
  CHECK_THROWS_AS(encode_record({row, {}}), IoError);
}
