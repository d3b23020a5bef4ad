// The robot's keys (scene_readers.hpp): the robot described by YAML keys, or read from its
// URDF. Paths, ranges and defaults come from the table (scene_key_table.hpp).
#include <cmath>

#include "hexdyn/config/key_rules.hpp"
#include "hexdyn/config/leg_keys.hpp"
#include "hexdyn/config/scene_readers.hpp"
#include "hexdyn/config/stance_keys.hpp"
#include "hexdyn/config/table_keys.hpp"
#include "hexdyn/model/link_scaling.hpp"
#include "hexdyn/model/stance.hpp"

namespace hexdyn::scene_keys {

namespace {

BodyParams read_body(Reader& r, const std::string& path, const Vec3& com_default) {
  BodyParams b;
  b.mass_kg = number_key(r, path + ".mass");
  b.inertia_kgm2 = vec3_key(r, path + ".inertia");
  check_principal_moments(r, path + ".inertia", b.inertia_kgm2);
  b.com_m = vec3_key(r, path + ".com", &com_default);
  return b;
}

/// robot.foot_offset (config/robot_config.hpp): one [x, y, z] for every leg, or one per leg
/// (a list in leg order, a map naming every leg). It is read before the robot, whose legs the
/// URDF reader then counts against it.
std::vector<Vec3> read_foot_offsets(Reader& r) {
  const std::string key = "robot.foot_offset";
  const LegKeyValues feet =
      read_leg_vectors(r, {key, "m", scene_key(key).range, true}, point_legs());
  std::vector<Vec3> out(feet.count);
  for (int leg = 0; leg < feet.count; ++leg) out[leg] = *feet.by_leg[leg];
  return out;
}

/// robot: {urdf: ...}: the robot read from its URDF (config/robot_config.hpp). Returns the
/// nominal stance radius, gait.foot_lateral's default [m].
double read_urdf_robot_keys(Reader& r, RobotParams& p, LoadedUrdfRobot& loaded) {
  UrdfRobotKeys k;
  k.path = r.string_or("robot.urdf", "");
  check_urdf_path(r, k.path);
  k.trunk_link = r.string_or("robot.trunk_link", "");
  k.forward_axis = choice_key(r, "robot.forward_axis");
  // One name per leg; the URDF reader checks the count against the legs it finds.
  k.foot_links = r.strings_or_none("robot.foot_links", kMinLegs, kMaxLegs);
  if (r.has("robot.foot_offset")) k.foot_offset_m = read_foot_offsets(r);
  if (r.has("robot.foot_radius")) k.foot_radius_m = number_key(r, "robot.foot_radius");
  k.ik_min_margin_m = p.ik_min_margin_m = number_key(r, "robot.ik_min_margin");
  loaded = load_urdf_robot(k);
  p.urdf = loaded.robot;
  p.legs = loaded.model->legs();
  read_nominal_pose(r, loaded);
  p.stance = loaded.stance;
  record_stance(r, loaded.stance);
  check_stance_radius(r, loaded.stance_radius_m);
  return loaded.stance_radius_m;
}

/// The three links of a leg, coxa (i1) to tibia (i3). How each link's mass, COM and inertia
/// follow its length (model/link_scaling.hpp): with uniform_density they are stated for
/// robot.<link>.reference_length (required) and stretched to robot.<link>.length; the COM's
/// default is the reference's mid-length.
void read_links(Reader& r, RobotParams& p) {
  const bool follow = choice_key(r, "robot.links_follow_length") != "none";
  const char* names[kYamlRobotLegJoints] = {"coxa", "femur", "tibia"};
  p.leg_joints = kYamlRobotLegJoints;
  for (int j = 0; j < kYamlRobotLegJoints; ++j) {
    const std::string base = std::string("robot.") + names[j];
    p.link_length_m[j] = number_key(r, base + ".length");
    p.joint_offset_m[j] = number_key(r, base + ".offset");
    const std::string ref_key = base + ".reference_length";
    check_reference_length_given(r, base, follow);
    const double ref_length =
        r.has(ref_key) ? number_key_or(r, ref_key, p.link_length_m[j]) : p.link_length_m[j];
    p.link[j] = read_body(r, base, Vec3(0.5 * (follow ? ref_length : p.link_length_m[j]), 0, 0));
    if (follow) p.link[j] = stretch_link(p.link[j], p.link_length_m[j] / ref_length);
    const auto lim = numbers_key(r, base + ".limits");
    check_increasing(r, base + ".limits", lim);
    p.joint_min_rad[j] = lim[0];
    p.joint_max_rad[j] = lim[1];
  }
}

void read_hips(Reader& r, RobotParams& p) {
  const double hip_x = number_key(r, "robot.hips.x");
  const auto hip_y = numbers_key(r, "robot.hips.y");
  check_hips_decreasing(r, hip_y);
  const double hip_z = number_key_or(r, "robot.hips.z", 0.0);
  const std::vector<double> zero3{0.0, 0.0, 0.0};
  const auto yaw = numbers_key(r, "robot.hips.yaw", &zero3);
  p.legs = kYamlRobotLegs;
  for (int leg = 0; leg < kYamlRobotLegs; ++leg) {
    const int row = leg / 2;  // 0 front, 1 middle, 2 rear
    const bool left = is_left(leg);
    p.hip_position_m[leg] = Vec3(left ? -hip_x : hip_x, hip_y[row], hip_z);
    // Yaw offsets are given for the right legs (positive turns the leg forward);
    // left legs mirror them.
    p.hip_yaw_rad[leg] = left ? M_PI - yaw[row] : yaw[row];
  }
}

}  // namespace

void read_robot(Reader& r, RobotParams& p, LoadedUrdfRobot& loaded) {
  if (r.has("robot.urdf")) {
    read_urdf_robot_keys(r, p, loaded);
    return;
  }
  p.trunk = read_body(r, "robot.trunk", Vec3::Zero());
  p.payload = read_body(r, "robot.payload", Vec3::Zero());
  read_links(r, p);
  read_hips(r, p);
  p.ik_min_margin_m = number_key(r, "robot.ik_min_margin");
  p.foot_radius_m = number_key(r, "robot.foot_radius");
  p.leg_inertia =
      choice_key(r, "robot.leg_inertia") == "massless" ? LegInertia::kMassless : LegInertia::kFull;
}

}  // namespace hexdyn::scene_keys
