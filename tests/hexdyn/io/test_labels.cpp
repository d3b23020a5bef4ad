// io/labels.hpp: each group holds a copy of the root coordinate of every dimension its
// datasets use (schema.hpp, group coordinates), read back through H5Reader; a group whose
// dataset of a dimension's name is not that coordinate is refused naming it.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/labels.hpp"
#include "hexdyn/io/schema.hpp"

namespace {

namespace fs = std::filesystem;
using namespace hexdyn;
namespace s = schema;

std::string temp_file(const std::string& name) {
  return (fs::temp_directory_path() /
          ("hexdyn_test_labels_" + std::to_string(::getpid()) + "_" + name + ".h5"))
      .string();
}

std::vector<std::string> joints() {
  std::vector<std::string> names;
  for (int k = 0; k < 18; ++k) names.push_back("j" + std::to_string(k));
  return names;
}

/// /time (3 samples), /joint and /joints/torque (3 × 18), labelled.
void write_torque(H5Writer& w, const std::vector<double>& time) {
  w.write_doubles(s::kTime.path, {time.size()}, time, s::kTime.units);
  w.write_strings(s::kJointCoordinate.path, joints(), s::kJointCoordinate.units);
  w.write_doubles(s::kJointTorque.path, {time.size(), 18},
                  std::vector<double>(time.size() * 18, 1.5), s::kJointTorque.units);
}

}  // namespace

TEST_CASE("labels: a group holds copies of the root coordinates of its dimensions",
          "[io][labels]") {
  const std::string path = temp_file("copies");
  const std::vector<double> time{0.0, 0.25, 1.0};
  {
    H5Writer w(path);
    write_torque(w, time);
    Labeller labels(w, "");
    for (const s::DatasetSpec* d : {&s::kTime, &s::kJointCoordinate, &s::kJointTorque})
      labels.add(*d);
    labels.finish();
    w.close();
  }
  const H5Reader in(path);
  CHECK(in.read_doubles("/joints/time").values == time);
  CHECK(in.read_strings("/joints/joint") == joints());
  CHECK(in.string_attribute("/joints/time", s::kUnitsAttribute) == "s");
  CHECK(in.string_attribute("/joints/joint", s::kLongNameAttribute) ==
        s::kJointCoordinate.long_name);
  CHECK(in.string_attribute("/joints/time", "CLASS") == "DIMENSION_SCALE");
  CHECK(in.has_attribute(s::kJointTorque.path, "DIMENSION_LIST"));
  fs::remove(path);
}

TEST_CASE("labels: a dataset of a dimension's name that is not its coordinate is refused",
          "[io][labels]") {
  const std::string path = temp_file("clash");
  {
    H5Writer w(path);
    write_torque(w, {0.0, 1.0});
    w.write_doubles("/joints/time", {2, 2}, std::vector<double>{0.0, 1.0, 2.0, 3.0}, "s");
    Labeller labels(w, "");
    for (const s::DatasetSpec* d : {&s::kTime, &s::kJointCoordinate, &s::kJointTorque})
      labels.add(*d);
    CHECK_THROWS_WITH(labels.finish(), Catch::Contains("/joints/time is not the coordinate "
                                                       "variable of dimension 'time'"));
  }
  fs::remove(path);
}
