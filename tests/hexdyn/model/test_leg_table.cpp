// The leg table of RobotModel (legs(), leg(l), joint(l, j), body(l, j), foot_body(l)) against
// a second reading of each robot: the paper robot from its parameters (hips, joint names of
// the flat order), and each shipped hexapod URDF (robots/, as configs/robots/*_stairs.yaml
// read them) from urdfdom's own tree: the moving joints from the trunk to each foot, in
// order, and each hip's side and rank from its position composed from the raw joint origins.
#include <urdf_parser/urdf_parser.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/sample_models.hpp"
#include "hexdyn/tree_models.hpp"

namespace hexdyn {
namespace {

/// The robots here: the paper robot and the shipped hexapods, six legs of three joints.
constexpr int kHexapodLegs = 6;
constexpr int kHexapodLegJoints = 3;

/// Following model.parent from leg l's foot body reaches the trunk in exactly n_joints steps,
/// through body(l, n_joints − 1), …, body(l, 0); joint(l, j) moves body(l, j).
void check_chain(const RobotModel& m, int l) {
  const LegInfo& leg = m.leg(l);
  REQUIRE(leg.n_joints == kHexapodLegJoints);
  int b = m.foot_body(l);
  for (int j = leg.n_joints - 1; j >= 0; --j) {
    CHECK(b == m.body(l, j));
    CHECK(m.joint(l, j) == b - 1);  // body b moves with joint b − 1 (robot_model.hpp)
    b = m.parent[b];
  }
  CHECK(b == 0);
  CHECK(leg.name == "L" + std::to_string(l + 1));
}

/// Side (x < 0 left) and front-to-rear rank (y descending within the side) of hips at p.
void check_sides_and_rows(const RobotModel& m, const std::vector<Vec3>& hips) {
  REQUIRE(static_cast<int>(hips.size()) == m.legs());
  for (int l = 0; l < m.legs(); ++l) {
    INFO("leg " << l);
    const bool left = hips[l].x() < 0.0;
    CHECK(m.leg(l).side == (left ? LegSide::kLeft : LegSide::kRight));
    int ahead = 0;
    for (int o = 0; o < m.legs(); ++o)
      if (o != l && (hips[o].x() < 0.0) == left && hips[o].y() > hips[l].y()) ++ahead;
    CHECK(m.leg(l).row == ahead);
    // docs/theory/conventions.md: L1 front left, L2 front right, L3 middle left, …
    CHECK(left == (l % 2 == 0));
    CHECK(m.leg(l).row == l / 2);
  }
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Mat3 rotation(const urdf::Rotation& r) {
  return Eigen::Quaterniond(r.w, r.x, r.y, r.z).toRotationMatrix();
}

/// The moving joints from the root link to `link`, root first, and the position of the
/// first one's origin in the root link frame at zero angles, composed from the raw origins.
struct RawChain {
  std::vector<std::string> joints;
  Vec3 p_hip_root = Vec3::Zero();
};

RawChain raw_chain(const urdf::ModelInterface& u, const std::string& link) {
  std::vector<urdf::JointConstSharedPtr> up;
  for (auto l = u.getLink(link); l->parent_joint; l = u.getLink(l->parent_joint->parent_link_name))
    up.push_back(l->parent_joint);
  RawChain c;
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  for (auto it = up.rbegin(); it != up.rend(); ++it) {
    const urdf::Pose& o = (*it)->parent_to_joint_origin_transform;
    p += R * Vec3(o.position.x, o.position.y, o.position.z);
    R = R * rotation(o.rotation);  // zero joint angles: no joint rotation
    if ((*it)->type == urdf::Joint::FIXED) continue;
    if (c.joints.empty()) c.p_hip_root = p;
    c.joints.push_back((*it)->name);
  }
  return c;
}

}  // namespace

TEST_CASE("the paper robot's leg table", "[leg_table]") {
  const RobotParams p = test::paper_robot_params();
  const RobotModel m = build_robot_model(p);
  REQUIRE(m.legs() == kHexapodLegs);
  std::vector<Vec3> hips;
  for (int l = 0; l < m.legs(); ++l) {
    check_chain(m, l);
    for (int j = 0; j < m.leg(l).n_joints; ++j)
      CHECK(m.joint_source_names[m.joint(l, j)] == joint_name(l, j));
    hips.push_back(p.hip_position_m[l]);
  }
  check_sides_and_rows(m, hips);
  // Counts from the table, against the tree walked directly: bodies whose parent chain
  // reaches the trunk.
  int moved = 0;
  for (int b = 1; b < kMaxBodies; ++b) {
    int a = b;
    while (a > 0) a = m.parent[a];
    moved += a == 0 ? 1 : 0;
  }
  CHECK(m.joints() == moved);
  CHECK(m.bodies() == moved + 1);
  CHECK(m.dofs() == moved + 6);
}

TEST_CASE("joint labels are positional: three joints by name, others numbered", "[leg_table]") {
  CHECK(joint_name(0, 0) == "L1_coxa");
  CHECK(joint_name(5, 2, 3) == "L6_tibia");
  CHECK(joint_name(3, 0, 4) == "L4_j1");
  CHECK(joint_name(7, 5, 6) == "L8_j6");
}

TEST_CASE("a tree of 2 to 8 legs of 3 to 6 joints, flat, is accepted", "[leg_table]") {
  RobotModel m = build_robot_model(test::paper_robot_params());
  m.parent[4] = 3;  // L2's coxa on L1's tibia: five legs, L1 of six joints
  fill_leg_table(m);
  CHECK(m.legs() == 5);
  CHECK(m.leg(0).n_joints == 6);
  CHECK(m.leg(0).foot_body == 6);
  CHECK(m.leg(1).first_body == 7);
  CHECK(m.leg(1).first_joint == 6);
  CHECK(m.joints() == 18);
  CHECK(m.bodies() == 19);
  std::mt19937 rng(7);
  for (const std::vector<int>& legs :
       {std::vector<int>{3, 3}, std::vector<int>(8, 6), std::vector<int>{5, 4, 3, 6}}) {
    const RobotModel t = test::tree_model(rng, legs);
    CHECK(t.legs() == static_cast<int>(legs.size()));
    CHECK(t.bodies() == 1 + std::accumulate(legs.begin(), legs.end(), 0));
  }
}

TEST_CASE("a tree the model cannot hold is refused in one line naming leg and body",
          "[leg_table]") {
  // The message of the std::logic_error f throws ("" when it throws none).
  const auto refusal = [](const auto& f) -> std::string {
    try {
      f();
    } catch (const std::logic_error& e) {
      return e.what();
    }
    return "";
  };
  const auto one_line = [](const std::string& message, const std::string& text) {
    INFO(message);
    CHECK(message.find(text) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  };
  RobotModel m = build_robot_model(test::paper_robot_params());
  m.parent[3] = 0;  // L1's tibia on the trunk: L1 of two joints
  one_line(refusal([&] { fill_leg_table(m); }),
           "robot model: leg L1 (hip body 1): 2 joints "
           "(bodies 1 to 2); a leg has 3 to 6");
  m = build_robot_model(test::paper_robot_params());
  m.parent[4] = 2;  // L2's coxa on L1's femur: L1 branches
  one_line(refusal([&] { fill_leg_table(m); }),
           "leg L1 (hip body 1): the chain branches at body 2 (2 children)");
  m = build_robot_model(test::paper_robot_params());
  m.p_parent_joint[4].x() = 0.0;  // L2's hip on the centre line
  one_line(refusal([&] { fill_leg_table(m); }),
           "leg L2 (hip body 4): hip on the trunk's centre line");
  m = build_robot_model(test::paper_robot_params());
  m.parent[2] = 5;  // a body whose parent comes after it
  one_line(refusal([&] { fill_leg_table(m); }), "robot model: body 2 has parent 5");
  std::mt19937 rng(8);
  one_line(refusal([&] {
             test::tree_model(rng, std::vector<int>{3, 7});
           }),
           "leg L2 (hip body 4): 7 joints");
  one_line(refusal([&] { test::tree_model(rng, std::vector<int>{4}); }),
           "robot model: 1 legs over bodies 1 to 4; a robot has 2 to 8 legs");
  one_line(refusal([&] { test::tree_model(rng, std::vector<int>(9, 3)); }),
           "leg L9 (hip body 25): more than 8 legs");
}

TEST_CASE("each shipped hexapod's leg table is its URDF's chains", "[leg_table]") {
  // forward_axis as configs/robots/<robot>_stairs.yaml sets it
  const std::pair<const char*, const char*> kRobots[] = {
      {"kraby", "+y"}, {"pexod", "+x"}, {"phantomx_mark4", "+x"}};
  for (const auto& [name, forward] : kRobots) {
    INFO(name);
    const std::string path = std::string(HEXDYN_SOURCE_DIR) + "/robots/" + name + ".urdf";
    UrdfReadOptions o;
    o.forward_axis = forward;
    const UrdfRobot robot = read_urdf_robot(path, o);
    const RobotModel m = build_robot_model(robot);
    const urdf::ModelInterfaceSharedPtr u = urdf::parseURDF(file_text(path));
    REQUIRE(u);
    REQUIRE(m.legs() == kHexapodLegs);
    int moving = 0;
    for (const auto& [jname, j] : u->joints_) moving += j->type != urdf::Joint::FIXED;
    int total = 0;
    std::vector<Vec3> hips;
    for (int l = 0; l < m.legs(); ++l) {
      INFO("leg " << l);
      check_chain(m, l);
      const LegInfo& leg = m.leg(l);
      // The URDF link of the leg's last joint; its moving joints up to the root, in order.
      const std::string last = m.joint_source_names[m.joint(l, leg.n_joints - 1)];
      REQUIRE(u->getJoint(last));
      const RawChain c = raw_chain(*u, u->getJoint(last)->child_link_name);
      REQUIRE(static_cast<int>(c.joints.size()) == leg.n_joints);
      for (int j = 0; j < leg.n_joints; ++j)
        CHECK(m.joint_source_names[m.joint(l, j)] == c.joints[j]);
      total += leg.n_joints;
      hips.push_back(robot.p_B_root + robot.B_R_root * c.p_hip_root);
      CHECK((hips.back() - m.p_hip_B[l]).norm() <= 1e-12);
    }
    CHECK(total == moving);  // every moving joint of the URDF belongs to one leg
    check_sides_and_rows(m, hips);
  }
}

}  // namespace hexdyn
