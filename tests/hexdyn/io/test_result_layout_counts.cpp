// The result layout of robots other than the hexapod: every leg and joint dimension, and the
// names of /model, sized from the result's own counts (io/result_layout.hpp).
#include <catch2/catch.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/result_layout.hpp"

namespace {

using namespace hexdyn;

/// A result of T samples of a robot of `legs` legs of `leg_joints` joints each, its arrays
/// zero, with dynamics (no drive train) and one touchdown of the last leg.
RunResult result_of(int legs, int leg_joints, int T) {
  const int J = legs * leg_joints;
  RunResult r;
  KinematicsResult& k = r.kin;
  k.time_s.resize(static_cast<std::size_t>(T));
  for (int i = 0; i < T; ++i) k.time_s[static_cast<std::size_t>(i)] = 0.1 * i;
  for (RowMatrix* m : {&k.base_position, &k.base_linear_velocity, &k.base_angular_velocity,
                       &k.base_linear_acceleration, &k.base_angular_acceleration, &k.com_position})
    m->setZero(T, 3);
  k.base_orientation_wxyz.setZero(T, 4);
  for (RowMatrix* m : {&k.joint_position, &k.joint_velocity, &k.joint_acceleration})
    m->setZero(T, J);
  k.foot_position.setZero(T, 3 * legs);
  k.foot_velocity.setZero(T, 3 * legs);
  k.contact_phase.setZero(T, legs);
  DynamicsResult& d = r.dyn;
  d.present = true;
  d.joint_torque.setZero(T, J);
  d.joint_power.setZero(T, J);
  d.contact_force.setZero(T, 3 * legs);
  d.penetration.setZero(T, legs);
  d.utilized_friction.setZero(T, legs);
  d.slip.setZero(T, legs);
  d.total_power_W.assign(static_cast<std::size_t>(T), 0.0);
  d.energy_joint_J.assign(static_cast<std::size_t>(J), 0.0);
  d.positive_work_joint_J.assign(static_cast<std::size_t>(J), 0.0);
  d.negative_work_joint_J.assign(static_cast<std::size_t>(J), 0.0);
  d.solver_status.assign(static_cast<std::size_t>(T), SolverStatus::kOptimal);
  d.solver_iterations.assign(static_cast<std::size_t>(T), 0.0);
  d.solver_objective.assign(static_cast<std::size_t>(T), 0.0);
  d.solver_seconds.assign(static_cast<std::size_t>(T), 0.0);
  ImpactRecord im;
  im.leg = legs - 1;
  d.impacts.push_back(im);
  return r;
}

const LayoutDataset& dataset(const ResultLayout& layout, const schema::DatasetSpec& spec) {
  for (const LayoutDataset& d : layout.datasets)
    if (d.spec == &spec) return d;
  FAIL("no dataset " << spec.path);
  throw;
}

std::vector<std::size_t> dims(std::initializer_list<std::size_t> list) { return list; }

}  // namespace

TEST_CASE("result layout: leg and joint dimensions and names from the result's counts",
          "[output]") {
  // A quadruped of three joints a leg, a hexapod, and a biped of five joints a leg.
  const auto [legs, leg_joints] = GENERATE(std::pair{4, 3}, std::pair{6, 3}, std::pair{2, 5});
  CAPTURE(legs, leg_joints);
  const std::size_t T = 7, L = static_cast<std::size_t>(legs);
  const auto J = static_cast<std::size_t>(legs * leg_joints);
  const ResultLayout layout = result_layout(result_of(legs, leg_joints, static_cast<int>(T)));
  namespace s = schema;
  for (const s::DatasetSpec* d : {&s::kJointPosition, &s::kJointVelocity, &s::kJointAcceleration,
                                  &s::kJointTorque, &s::kJointPower})
    CHECK(dataset(layout, *d).dims == dims({T, J}));
  for (const s::DatasetSpec* d : {&s::kFeetPosition, &s::kFeetVelocity, &s::kContactForce})
    CHECK(dataset(layout, *d).dims == dims({T, L, 3}));
  for (const s::DatasetSpec* d :
       {&s::kContactPhase, &s::kContactPenetration, &s::kContactSlip, &s::kContactUtilizedFriction})
    CHECK(dataset(layout, *d).dims == dims({T, L}));
  CHECK(dataset(layout, s::kEnergyJoint).dims == dims({J}));
  // Names: L1 … Ln, and the joints by position (core/common.hpp: coxa, femur, tibia for legs
  // of three joints, j1 … otherwise), leg by leg.
  std::vector<std::string> leg_names, joint_names;
  for (int l = 1; l <= legs; ++l) {
    leg_names.push_back("L" + std::to_string(l));
    for (int j = 1; j <= leg_joints; ++j)
      joint_names.push_back(
          "L" + std::to_string(l) + "_" +
          (leg_joints == 3
               ? std::vector<std::string>{"coxa", "femur", "tibia"}[static_cast<std::size_t>(j - 1)]
               : "j" + std::to_string(j)));
  }
  CHECK(std::get<std::vector<std::string>>(dataset(layout, s::kModelLegNames).values) == leg_names);
  CHECK(std::get<std::vector<std::string>>(dataset(layout, s::kModelJointNames).values) ==
        joint_names);
  CHECK(std::get<std::vector<std::string>>(dataset(layout, s::kLegCoordinate).values) == leg_names);
}

TEST_CASE(
    "result layout: an impact of a leg the robot does not have, or names of another "
    "count, are refused",
    "[output]") {
  RunResult r = result_of(4, 3, 5);
  r.dyn.impacts.front().leg = 4;
  CHECK_THROWS_WITH(result_layout(r), "impact 0 has leg index 4, expected 0..3");
  r = result_of(4, 3, 5);
  r.joint_names.assign(13, "j");
  CHECK_THROWS_AS(result_layout(r), IoError);
}
