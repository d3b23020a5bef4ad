#pragma once
// The paper scene, run and replayed (replay/replay.hpp), for the replay's tests: the scene
// with the overrides given, its model, the plan of its run and the replay of that plan.
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/run.hpp"
#include "hexdyn/replay/replay.hpp"

namespace hexdyn::test {

struct Replayed {
  Scene scene;
  RobotModel model;
  ReplayPlan plan;
  ReplayResult result;
};

inline Replayed replay_paper(const std::vector<Override>& overrides) {
  Replayed r{load_scene(HEXDYN_SOURCE_DIR "/configs/paper.yaml", overrides), {}, {}, {}};
  r.model = build_robot_model(r.scene.robot);
  r.plan = plan_from_result(r.model, run_scene(r.scene));
  r.result = replay_plan(r.model, r.scene.contact, r.scene.replay, r.scene.terrain, r.plan);
  return r;
}

}  // namespace hexdyn::test
