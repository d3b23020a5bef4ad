// The rows of the robot's keys (scene_key_table.hpp): the robot described by YAML keys and
// the robot read from a URDF file (docs/user/configuration.md#robot,
// docs/user/configuration.md#robot-from-a-urdf).
#include <cmath>

#include "hexdyn/config/scene_key_rows.hpp"
#include "hexdyn/core/value_bounds.hpp"

namespace hexdyn {

using namespace scene_keys;
namespace f = key_fields;

namespace {

const Range kCoordinate = closed(-kMaxRobotCoordinate_m, kMaxRobotCoordinate_m);

/// Mass, inertia and COM of the trunk, the payload and the three links of every leg.
void add_bodies(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robot"};
  const std::string_view bodies = "trunk payload coxa femur tibia";
  add({.path = "robot.*.mass",
       .instances = bodies,
       .range = positive(kMaxBodyMass_kg),
       .unit = "kg",
       .required = true,
       .meaning = "mass of the trunk structure, of the payload (a body rigidly fixed to "
                  "the trunk) and of each link"});
  add({.path = "robot.*.inertia",
       .instances = bodies,
       .kind = KeyKind::kNumbers,
       .range = positive(kMaxPrincipalInertia_kgm2),
       .min_count = 3,
       .max_count = 3,
       .unit = "kg m^2",
       .required = true,
       .allowed_text = "3 numbers in (0, 1e3] kg m², each at most the sum of the other two",
       .meaning = "principal moments Ixx, Iyy, Izz about the body's COM: trunk axes for "
                  "the trunk and the payload; a link's own frame (x along the link from "
                  "its joint, z the trunk normal at zero angles)"});
  add({.path = "robot.*.com",
       .instances = "trunk payload",
       .kind = KeyKind::kNumbers,
       .range = kCoordinate,
       .min_count = 3,
       .max_count = 3,
       .unit = "m",
       .default_text = "`[0, 0, 0]`",
       .meaning = "COM in the trunk frame"});
  add({.path = "robot.*.com",
       .instances = "coxa femur tibia",
       .kind = KeyKind::kNumbers,
       .range = kCoordinate,
       .min_count = 3,
       .max_count = 3,
       .unit = "m",
       .default_text = "`[length/2, 0, 0]` (`uniform_density`: "
                       "`[reference_length/2, 0, 0]`)",
       .meaning = "COM in the link frame"});
}

void add_links(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robot"};
  const std::string_view links = "coxa femur tibia";
  add({.path = "robot.*.length",
       .instances = links,
       .range = positive(kMaxRobotCoordinate_m),
       .unit = "m",
       .required = true,
       .meaning = "link lengths l1, l2, l3"});
  add({.path = "robot.*.offset",
       .instances = links,
       .range = nonnegative(1.0),
       .unit = "m",
       .required = true,
       .meaning = "joint offsets d1, d2, d3 (read as DH link offsets along the joint "
                  "axes; see the comments of `configs/paper.yaml`)"});
  add({.path = "robot.*.limits",
       .instances = links,
       .kind = KeyKind::kNumbers,
       .range = closed(-M_PI, M_PI),
       .min_count = 2,
       .max_count = 2,
       .unit = "rad",
       .required = true,
       .allowed_text = "`[lower, upper]` in [−π, π], lower < upper",
       .meaning = "joint-angle limits [rad], checked by the inverse kinematics"});
}

void add_hips(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robot"};
  add({.path = "robot.hips.x",
       .range = positive(5.0),
       .unit = "m",
       .required = true,
       .meaning = "distance of the coxa joints from the trunk's mid-plane (left legs at "
                  "−x, right at +x)"});
  add({.path = "robot.hips.y",
       .kind = KeyKind::kNumbers,
       .range = closed(-5.0, 5.0),
       .min_count = 3,
       .max_count = 3,
       .unit = "m",
       .required = true,
       .allowed_text = "`[front, middle, rear]` in [−5, 5] m, decreasing",
       .meaning = "y of the coxa joints in the trunk frame"});
  add({.path = "robot.hips.z",
       .range = closed(-5.0, 5.0),
       .unit = "m",
       .default_text = "`0`",
       .meaning = "height of the coxa joints in the trunk frame"});
  add({.path = "robot.hips.yaw",
       .kind = KeyKind::kNumbers,
       .range = open_interval(-M_PI / 2, M_PI / 2),
       .min_count = 3,
       .max_count = 3,
       .unit = "rad",
       .default_text = "`[0, 0, 0]`",
       .meaning = "front, middle, rear: turn of the right legs from straight out "
                  "(positive turns forward); left legs mirror it"});
}

void add_robot_options(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robot"};
  add({.path = "robot.ik_min_margin",
       .range = nonnegative(0.1),
       .unit = "m",
       .meaning = "smallest distance from full extension or full fold the inverse "
                  "kinematics accepts; a foothold closer is a `reach` error",
       .field = f::number<&Scene::robot, &RobotParams::ik_min_margin_m>()});
  add({.path = "robot.leg_inertia",
       .kind = KeyKind::kChoice,
       .choices = "full massless",
       .meaning = "`full`: the leg links in the dynamics (swing legs load the "
                  "trunk); `massless`: link masses lumped at the hips",
       .field = f::choice<&Scene::robot, &RobotParams::leg_inertia>()});
  add({.path = "robot.foot_radius",
       .range = closed(0.0, kMaxFootRadius_m),
       .unit = "m",
       .meaning = "a sphere foot of this radius centred at each tibia's end (l3, 0, 0): "
                  "it touches r below its centre along the surface normal, where the "
                  "terrain's forces act; 0 is the paper's point foot "
                  "([docs/theory/model.md](docs/theory/model.md#sphere-feet))",
       .field = f::number<&Scene::robot, &RobotParams::foot_radius_m>()});
  add({.path = "robot.links_follow_length",
       .kind = KeyKind::kChoice,
       .choices = "none uniform_density",
       .meaning =
           "how each link's mass, COM and inertia follow its length. `none`: as stated, "
           "whatever the length. `uniform_density`: stated for the link's "
           "`reference_length`; a link of length L is that link stretched along its axis "
           "by r = L / reference_length at the same density: mass × r, COM x × r, inertia "
           "about its axis × r, the other two moments r³ Σ_xx + r Σ_zz and r³ Σ_xx + r "
           "Σ_yy ([docs/theory/model.md](docs/theory/model.md#links-that-follow-their-length))"});
  add({.path = "robot.*.reference_length",
       .instances = "coxa femur tibia",
       .range = positive(10.0),
       .unit = "m",
       .default_text = "required with `uniform_density`, else unused",
       .meaning = "the length the link's stated mass, COM and inertia belong to; "
                  "changing `length` alone then rescales them "
                  "(`configs/designs/paper_base.yaml` states the paper's lengths)"});
}

void add_urdf_robot(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robot-from-a-urdf"};
  add({.path = "robot.urdf",
       .kind = KeyKind::kText,
       .required = true,
       .allowed_text = "path of a regular file",
       .meaning = "relative to the file that names the key; given by `--set` or a "
                  "sweep's `set:`, relative to the working directory"});
  add({.path = "robot.trunk_link",
       .kind = KeyKind::kText,
       .default_text = "the root link",
       .allowed_text = "a link name",
       .meaning = "the trunk; links fixed to it are merged into it"});
  add({.path = "robot.forward_axis",
       .kind = KeyKind::kChoice,
       .choices = "+x -x +y -y",
       .default_text = "`+x` (ROS REP-103)",
       .meaning = "the trunk link's axis that points forward"});
  add({.path = "robot.foot_links",
       .kind = KeyKind::kText,
       .default_text = "—",
       .allowed_text = "one link name per leg (2 to 8)",
       .meaning = "one link fixed to the last link of each leg chain, any order"});
  add({.path = "robot.foot_offset",
       .kind = KeyKind::kNumbers,
       .range = kCoordinate,
       .min_count = 3,
       .max_count = 3,
       .unit = "m",
       .default_text = "—",
       .allowed_text = "`[x, y, z]`; or one per leg of the robot's n legs: a list of n "
                       "`[x, y, z]` in the order L1 … Ln of `/model/leg_names`, or a map "
                       "`{L1: [x, y, z], …, Ln: [x, y, z]}` naming every leg (a missing leg or "
                       "another count is an error); numbers in [−10, 10] m",
       .meaning =
           "the foot point in each leg's last link frame: one for every leg, or each "
           "leg's own (feet mirrored between the sides). `validate` and `run` refuse a "
           "point outside the last link's primitive `<collision>` geometry, naming the leg"});
  add({.path = "robot.foot_radius",
       .range = closed(0.0, kMaxFootRadius_m),
       .unit = "m",
       .default_text = "the sphere `<collision>` foot's radius, else `0`",
       .meaning = "every foot a sphere of this radius centred at its foot point "
                  "([docs/theory/model.md](docs/theory/model.md#sphere-feet)); 0 a point "
                  "foot"});
  add({.path = "robot.nominal_pose",
       .kind = KeyKind::kNumbers,
       .range = closed(-2 * M_PI, 2 * M_PI),
       .min_count = 3,
       .max_count = kMaxLegJoints,
       .unit = "rad",
       .default_text = "\"femur level, tibia plumb\"; a rolling hip: \"hanging\"; a leg of "
                       "other than three revolute joints: the middle of its joint limits",
       .allowed_text = "one position per joint of a leg, hip to foot (`[coxa, femur, tibia]` "
                       "for three joints; m for a prismatic joint), numbers in [−2π, 2π] "
                       "inside the joint limits; or one per leg of the robot's n legs: a list "
                       "of n in leg order L1 … Ln, or a map by leg name (`{L3: [0, 0, 1.5]}`)",
       .meaning = "the standing pose that sets `gait.foot_lateral`'s default; a leg of other "
                  "than three revolute joints also resolves its redundancy toward it "
                  "([docs/theory/model.md](docs/theory/model.md#redundant-legs)); legs a map "
                  "does not name keep the default"});
  add({.path = "robot.ik_min_margin",
       .range = nonnegative(0.1),
       .unit = "m",
       .meaning = "as for the YAML robot",
       .field = f::number<&Scene::robot, &RobotParams::ik_min_margin_m>()});
}

}  // namespace

void add_robot_key_rows(std::deque<SceneKey>& table) {
  add_bodies(table);
  add_links(table);
  add_hips(table);
  add_robot_options(table);
  add_urdf_robot(table);
}

}  // namespace hexdyn
