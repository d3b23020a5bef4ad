#pragma once
/// Shared set-up of the benchmarks: the paper scene and the kinematic states of its run.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/allocation/problem.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/contact/touchdowns.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/pipeline/pipeline.hpp"

namespace hexdyn::bench {

/// configs/paper.yaml of the source tree (bench_common.hpp source_file).
inline std::string paper_scene_path() { return source_file("configs/paper.yaml"); }

/// The paper scene, its robot and plan, and its kinematics sampled on the run's own
/// output grid (events and touchdown transients included) with the impact phases
/// marked: everything a run has before allocation.
struct PaperSetup {
  Scene scene;
  RobotModel model;
  MotionPlan plan;
  std::vector<Touchdown> touchdowns;
  KinematicsResult kin;
};

inline PaperSetup make_paper_setup() {
  Scene scene = load_scene(paper_scene_path());
  PreparedScene prep = prepare_scene(scene);
  KinematicsResult kin = sample_kinematics(prep.model, prep.plan, prep.grid);
  return PaperSetup{std::move(scene), std::move(prep.model), std::move(prep.plan),
                    std::move(prep.touchdowns), std::move(kin)};
}

inline const PaperSetup& paper_setup() {
  static const PaperSetup setup = make_paper_setup();
  return setup;
}

/// Trunk and joint state of sample i.
struct SampleState {
  BaseState base;
  JointVector q, qd, qdd;
};

inline SampleState sample_state(const KinematicsResult& kin, int i) {
  return {base_state_at(kin, i), kin.joint_position.row(i).transpose(),
          kin.joint_velocity.row(i).transpose(), kin.joint_acceleration.row(i).transpose()};
}

/// Sample i's allocation problem, built as the run builds it: swing legs from the
/// kinematics, legs inside a touchdown transient carry its known normal force.
/// Returns the number of legs in their impact transient.
inline int sample_problem(const PaperSetup& p, RobotData& data, int i, QpProblem& qp) {
  const SampleState s = sample_state(p.kin, i);
  const ContactSplit& split = contact_split(p.model, data, s.base, s.q, s.qd, s.qdd);
  SampleContacts c;
  sample_contacts(p.kin, i, p.plan.terrain, p.touchdowns, c);
  build_allocation_problem(p.scene.allocation, p.scene.contact, split, c.phase, c.impact_force_N,
                           c.W_R_contact, qp);
  return c.impacting_legs;
}

/// Index of the first sample at or after t.
inline int sample_at(const KinematicsResult& kin, double t) {
  return static_cast<int>(std::lower_bound(kin.time_s.begin(), kin.time_s.end(), t) -
                          kin.time_s.begin());
}

}  // namespace hexdyn::bench
