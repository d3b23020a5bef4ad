// One robot shape per sweep (sweep/scenario_factory.hpp SweepShapeCheck): the shape of a
// model, and the refusal, naming the scenario, of a robot of other legs or joints.
#include <catch2/catch.hpp>
#include <string>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/sample_models.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"

using namespace hexdyn;

namespace {

RobotShape shape_of(std::initializer_list<int> leg_joints) {
  RobotShape s;
  for (int m : leg_joints) s.leg_joints[static_cast<std::size_t>(s.legs++)] = m;
  return s;
}

}  // namespace

TEST_CASE("sweep: a robot's shape is its legs' joint counts", "[sweep]") {
  const RobotShape paper = robot_shape(build_robot_model(test::paper_robot_params()));
  CHECK(paper == shape_of({3, 3, 3, 3, 3, 3}));
  CHECK(paper.joints() == 18);
  CHECK(paper.text() == "6 legs of 3 joints");
  CHECK(shape_of({3, 3, 4, 3}).text() == "4 legs of 3, 3, 4, 3 joints");
  CHECK(shape_of({3, 3, 4, 3}).joints() == 13);
  CHECK_FALSE(shape_of({3, 3, 3, 3}) == shape_of({3, 3, 3, 3, 3, 3}));
  CHECK_FALSE(shape_of({3, 3, 3, 3}) == shape_of({3, 3, 4, 3}));
}

TEST_CASE("sweep: scenarios of robots of another shape are refused, the scenario named",
          "[sweep]") {
  SweepShapeCheck check;
  check.add(shape_of({3, 3, 3, 3, 3, 3}), "000000");
  check.add(shape_of({3, 3, 3, 3, 3, 3}), "000001");
  CHECK(check.shape() == shape_of({3, 3, 3, 3, 3, 3}));
  CHECK_THROWS_WITH(check.add(shape_of({3, 3, 3, 3}), "000002"),
                    "scenario 000002: robot: a robot of 4 legs of 3 joints, the sweep's robot "
                    "(scenario 000000) has 6 legs of 3 joints; the scenarios of a sweep have "
                    "robots of one shape (legs and joints per leg)");
  CHECK_THROWS_AS(check.add(shape_of({3, 3, 3, 3, 3, 4}), "000003"), ConfigError);
  // The paper robot's scenes, one model built for all of them.
  SweepShapeCheck scenes;
  Scene scene;
  scene.robot = test::paper_robot_params();
  for (const char* id : {"000000", "000001"}) scenes.add(scene, id);
  CHECK(scenes.shape() == shape_of({3, 3, 3, 3, 3, 3}));
}
