// The keys of contact, replay, allocation, actuators, auto and output (scene_readers.hpp).
// Paths, ranges and defaults come from the table (scene_key_table.hpp); rules across keys
// from key_rules.hpp.
#include <algorithm>
#include <iterator>

#include "hexdyn/config/actuators.hpp"
#include "hexdyn/config/key_rules.hpp"
#include "hexdyn/config/scene_readers.hpp"
#include "hexdyn/config/table_keys.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn::scene_keys {

namespace {

/// The robot of the YAML keys (config/scene_read_robot.cpp): six legs of three joints.
constexpr int kYamlLegs = 6;
constexpr int kYamlLegJoints = 3;

/// The joints of a robot read from a URDF: each leg's, in flat joint order.
JointFacts urdf_joint_facts(const LoadedUrdfRobot& urdf) {
  JointFacts joints;
  const auto& legs = urdf.robot->legs;
  for (int l = 0; l < robot_leg_count(urdf); ++l) {
    const int m = legs[l].n_joints();
    for (int j = 0; j < m; ++j, ++joints.count) {
      const int k = joints.count;
      joints.names[k] = urdf.joint_names[k];
      joints.place[k] = j;
      joints.leg_joints[k] = m;
      joints.damping_Nmsprad[k] = urdf.damping_Nmsprad[k];
      joints.friction_Nm[k] = urdf.friction_Nm[k];
    }
  }
  return joints;
}

/// The joints of the robot of the YAML keys: positional names (core/common.hpp joint_name).
JointFacts yaml_joint_facts() {
  JointFacts joints;
  for (int l = 0; l < kYamlLegs; ++l)
    for (int j = 0; j < kYamlLegJoints; ++j, ++joints.count) {
      joints.names[joints.count] = joint_name(l, j, kYamlLegJoints);
      joints.place[joints.count] = j;
      joints.leg_joints[joints.count] = kYamlLegJoints;
    }
  return joints;
}

}  // namespace

int robot_leg_count(const LoadedUrdfRobot& urdf) {
  if (!urdf.robot) return kYamlLegs;
  return static_cast<int>(urdf.robot->legs.size());
}

void read_contact(Reader& r, Scene& s) {
  read_table_keys(r, s, "contact");
  ContactParams& c = s.contact;
  c.static_friction = number_key_or(r, "contact.static_friction", c.friction_coefficient);
  c.dynamic_friction =
      r.number_or("contact.dynamic_friction", c.static_friction, closed(0.0, c.static_friction));
  c.friction_velocity_mps = number_key_or(
      r, "contact.friction_velocity",
      std::max(default_scene().contact.friction_velocity_mps, 10.0 * c.stiction_velocity_mps));
  check_friction_velocity(r, c);
}

void read_replay(Reader& r, Scene& s) {
  read_table_keys(r, s, "replay");
  // The gains: numbers, or `auto` (the default), resolved for the robot when it is replayed
  // (replay/replay.hpp resolved_gains); the resolved configuration keeps the word.
  ReplayParams& p = s.replay;
  p.kp_auto = r.absent_or_word("replay.kp", "auto");
  if (!p.kp_auto) p.kp_Nmprad = number_key(r, "replay.kp");
  p.kd_auto = r.absent_or_word("replay.kd", "auto");
  if (!p.kd_auto) p.kd_Nmsprad = number_key(r, "replay.kd");
}

void read_allocation(Reader& r, Scene& s, const LoadedUrdfRobot& urdf) {
  read_table_keys(r, s, "allocation");
  AllocationParams& a = s.allocation;
  // auto = active-set: the dual active-set QP for the pyramids, and for the exact cone the
  // same QP under sequential outer approximation (allocation/cone_backend.hpp); ipopt: the NLP
  // reference for every friction model.
  const std::string solver = choice_key(r, "allocation.solver");
  a.solver = solver == "ipopt" ? AllocationSolver::kIpopt : AllocationSolver::kActiveSet;
  if (solver == "auto") {  // resolved as the back end used, the request beside it
    r.record("allocation.solver", "active-set");
    r.record("auto.allocation.solver", "auto");
  }
  // A URDF robot: its effort limits per joint unless the scene gives one limit for all
  // (allocation.torque_limit: effort names the default).
  if (urdf.robot && r.absent_or_word("allocation.torque_limit", "effort")) {
    JointValues<double> limits;
    limits.count = urdf_joint_facts(urdf).count;
    for (int k = 0; k < limits.count; ++k) limits[k] = urdf.effort_limit_Nm[k];
    a.joint_torque_limit_Nm = limits;
    a.torque_limit_Nm = 0.0;
    for (int k = 0; k < limits.count; ++k)
      a.torque_limit_Nm = std::max(a.torque_limit_Nm, limits[k]);
  } else {
    a.torque_limit_Nm = number_key(r, "allocation.torque_limit");
  }
  check_allocation_tolerance(r, a.tolerance);
  // Last, where read_drive_train records it when only actuators give it: a resolved
  // configuration read again resolves to the same text.
  if (r.given("allocation.objective"))
    a.objective = choice_key(r, "allocation.objective") == "copper_loss"
                      ? AllocationObjective::kCopperLoss
                      : AllocationObjective::kTorqueSquared;
}

/// actuators: (config/actuators.hpp) with the robot's joint names and URDF friction, and
/// allocation.objective's dependence on it: copper_loss needs actuators; with them, the
/// objective is recorded in the resolved configuration.
void read_drive_train(Reader& r, Scene& s, const LoadedUrdfRobot& urdf) {
  const JointFacts joints = urdf.robot ? urdf_joint_facts(urdf) : yaml_joint_facts();
  s.robot.drive = read_actuators(r, joints);
  if (s.robot.drive.present)
    r.record("allocation.objective", YAML::Node(objective_word(s.allocation.objective)));
  check_copper_loss(r, s);
}

/// `auto:`: what a scene asked hexdyn to choose, as the resolved configuration of an
/// earlier run records it beside the values chosen
/// (docs/user/configuration.md#automatic-choices-in-the-resolved-configuration). A record
/// only: carried into the resolved configuration unchanged, never read as a setting.
void read_auto_requests(Reader& r) {
  if (!r.has("auto")) return;
  const YAML::Node& requests = r.node("auto");
  if (!requests.IsMap())
    r.fail_value("auto", requests,
                 "a map of the keys hexdyn chose and what was asked (a resolved configuration's "
                 "record)");
  r.record("auto", YAML::Clone(requests));
}

void read_output(Reader& r, Scene& s) {
  read_table_keys(r, s, "output");
  check_event_step(r, s.output);
}

}  // namespace hexdyn::scene_keys
