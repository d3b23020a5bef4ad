// URDF robots of any leg count and chain length (urdf_reader.hpp, urdf_robot.hpp): the leg
// order of docs/theory/conventions.md#legs-and-joints, one-line refusals naming the leg and the
// link, and the two shipped quadrupeds (robots/solo12.urdf, robots/anymal_c.urdf) checked
// against a second reading of the same files: a small XML walk written here (no urdfdom, no
// merging code of the reader), which sums the link masses of each fixed group, composes the
// fixed joints to the feet and reads the limits as written.
#include <catch2/catch.hpp>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/leg_chain.hpp"
#include "hexdyn/model/stance.hpp"
#include "hexdyn/model/urdf.hpp"
#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {
namespace {

// ---- synthetic descriptions ----

/// One leg of a synthetic robot: hip in the URDF trunk frame (x forward, y left) [m], and its
/// count of moving joints (hip yaw, then pitch joints), each link 0.1 kg.
struct LegSpec {
  double x, y;
  int joints = 3;
};

std::string inertial(double mass) {
  std::ostringstream s;
  s << "<inertial><mass value=\"" << mass
    << "\"/><inertia ixx=\"1e-4\" iyy=\"1e-4\" izz=\"1e-4\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>"
    << "</inertial>";
  return s.str();
}

std::string joint_xml(const std::string& name, const std::string& parent, const std::string& child,
                      const std::string& xyz, const std::string& axis) {
  return "  <joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"" + xyz + "\"/><axis xyz=\"" + axis +
         "\"/><limit lower=\"-2\" upper=\"2\" effort=\"2\" velocity=\"5\"/></joint>\n";
}

std::string link_xml(const std::string& name, double mass) {
  return "  <link name=\"" + name + "\">" + (mass > 0.0 ? inertial(mass) : "") + "</link>\n";
}

/// A robot with these legs: leg i has links leg{i}_l1 … and joints leg{i}_j1 …, a massless
/// foot leg{i}_foot fixed 0.1 m along x of its last link; `extra` is added before </robot>.
std::string legged_urdf(const std::vector<LegSpec>& legs, const std::string& extra = "") {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<robot name=\"synthetic\">\n" << link_xml("trunk", 2.0);
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const std::string p = "leg" + std::to_string(i) + "_";
    std::string parent = "trunk";
    for (int j = 1; j <= legs[i].joints; ++j) {
      const std::string link = p + "l" + std::to_string(j);
      std::ostringstream xyz;
      if (j == 1)
        xyz << legs[i].x << " " << legs[i].y << " 0";
      else
        xyz << "0 " << (legs[i].y > 0 ? 0.05 : -0.05) << " 0";
      s << link_xml(link, 0.1)
        << joint_xml(p + "j" + std::to_string(j), parent, link, xyz.str(),
                     j == 1 ? "0 0 1" : "1 0 0");
      parent = link;
    }
    s << link_xml(p + "foot", 0.0) << "  <joint name=\"" << p
      << "foot_fixed\" type=\"fixed\"><parent link=\"" << parent << "\"/><child link=\"" << p
      << "foot\"/><origin xyz=\"0 " << (legs[i].y > 0 ? 0.1 : -0.1) << " -0.05\"/></joint>\n";
  }
  s << extra << "</robot>\n";
  return s.str();
}

std::vector<LegSpec> quadruped() { return {{0.2, 0.1}, {0.2, -0.1}, {-0.2, 0.1}, {-0.2, -0.1}}; }

/// The one-line message of reading `text`, or "" when it loads.
std::string refusal(const std::string& text, const UrdfReadOptions& o = {}) {
  try {
    (void)read_urdf_robot_from_string(text, "robot.urdf", o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

/// The hip joints' names of `robot` in leg order.
std::vector<std::string> hip_names(const UrdfRobot& robot) {
  std::vector<std::string> out;
  for (const UrdfLeg& l : robot.legs) out.push_back(l.joints.front().name);
  return out;
}

TEST_CASE("urdf legs: 2 to 8 legs of 3 to 6 joints, in the documented leg order", "[urdf_legs]") {
  // Quadruped: L1 front left, L2 front right, L3 rear left, L4 rear right (URDF +y is left,
  // so the trunk frame's x < 0).
  const UrdfRobot four = read_urdf_robot_from_string(legged_urdf(quadruped()), "q.urdf");
  CHECK(hip_names(four) == std::vector<std::string>{"leg0_j1", "leg1_j1", "leg2_j1", "leg3_j1"});
  // Written in another order, numbered the same way: rank by rank, left before right.
  const UrdfRobot shuffled = read_urdf_robot_from_string(
      legged_urdf({{-0.2, -0.1}, {0.2, -0.1}, {-0.2, 0.1}, {0.2, 0.1}}), "q.urdf");
  CHECK(hip_names(shuffled) ==
        std::vector<std::string>{"leg3_j1", "leg1_j1", "leg2_j1", "leg0_j1"});
  // Three legs, two on the left: L1 left front, L2 the right one, L3 left rear.
  const UrdfRobot three =
      read_urdf_robot_from_string(legged_urdf({{-0.2, 0.1}, {0.0, -0.1}, {0.2, 0.1}}), "t.urdf");
  CHECK(hip_names(three) == std::vector<std::string>{"leg2_j1", "leg1_j1", "leg0_j1"});
  // Octopod 8 × 3, biped 2 × 6, a hexapod of 4-joint legs: every chain read whole.
  std::vector<LegSpec> eight;
  for (int r = 0; r < 4; ++r)
    for (double y : {0.1, -0.1}) eight.push_back({0.3 - 0.2 * r, y});
  const UrdfRobot octopod = read_urdf_robot_from_string(legged_urdf(eight), "o.urdf");
  REQUIRE(octopod.n_legs() == 8);
  CHECK(octopod.n_joints() == 24);
  for (int leg = 0; leg < 8; ++leg)
    CHECK(octopod.legs[leg].joints.front().name == "leg" + std::to_string(leg) + "_j1");
  const UrdfRobot biped =
      read_urdf_robot_from_string(legged_urdf({{0.0, 0.1, 6}, {0.0, -0.1, 6}}), "b.urdf");
  REQUIRE(biped.n_legs() == 2);
  for (const UrdfLeg& l : biped.legs) {
    REQUIRE(l.n_joints() == 6);
    CHECK(l.joints[5].link.substr(5) == "l6");
    CHECK(l.foot_source.substr(5) == "foot");
    CHECK(l.joints[5].merged_links == std::vector<std::string>{l.foot_source});
    for (const UrdfJoint& j : l.joints) {
      CHECK(j.inertia.mass_kg == 0.1);
      CHECK(j.lower_rad == -2.0);
      CHECK(j.effort_Nm == 2.0);
      CHECK(j.type == UrdfJointType::kRevolute);
    }
  }
  CHECK(biped.total_mass_kg == Approx(2.0 + 12 * 0.1).epsilon(1e-15));
  std::vector<LegSpec> six;
  for (int r = 0; r < 3; ++r)
    for (double y : {0.1, -0.1}) six.push_back({0.2 - 0.2 * r, y, 4});
  const UrdfRobot hexapod4 = read_urdf_robot_from_string(legged_urdf(six), "h.urdf");
  CHECK(hexapod4.n_joints() == 24);
  // The mapping lists every joint of a leg and its foot.
  const std::string text = leg_mapping_text(biped);
  CHECK(text.find("L1 <- leg0_j1 / leg0_j2 / leg0_j3 / leg0_j4 / leg0_j5 / leg0_j6, hip") !=
        std::string::npos);
  CHECK(text.find("  merged into leg1_l6: leg1_foot\n") != std::string::npos);
  CHECK(leg_mapping_entries(hexapod4)[5] == "L6: leg5_j1 leg5_j2 leg5_j3 leg5_j4 foot leg5_foot");
}

TEST_CASE("urdf legs: foot links and foot offsets per leg, of any count", "[urdf_legs]") {
  const std::string text = legged_urdf(quadruped());
  UrdfReadOptions o;
  o.foot_offset = std::vector<Vec3>{Vec3(0.0, 0.1, -0.05)};  // one point for every leg
  const UrdfRobot one = read_urdf_robot_from_string(text, "q.urdf", o);
  for (const UrdfLeg& l : one.legs) CHECK(l.p_foot_last == Vec3(0.0, 0.1, -0.05));
  o.foot_offset = std::vector<Vec3>{Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(0, 3, 0), Vec3(0, 4, 0)};
  const UrdfRobot each = read_urdf_robot_from_string(text, "q.urdf", o);
  for (int leg = 0; leg < 4; ++leg) CHECK(each.legs[leg].p_foot_last.y() == leg + 1.0);
  o.foot_offset->pop_back();
  CHECK(refusal(text, o) ==
        "robot.urdf: robot.foot_offset: got 3 points [[0, 1, 0], [0, 2, 0], [0, 3, 0]], expected "
        "one [x, y, z] for every leg or one per leg (4 legs, L1 … L4)");
  UrdfReadOptions links;
  links.foot_links = {"leg3_foot", "leg2_foot", "leg1_foot", "leg0_foot"};
  CHECK(refusal(text, links).empty());
  links.foot_links.pop_back();
  CHECK(refusal(text, links) == "robot.urdf: robot.foot_links: 3 names, expected 4 (one per leg)");
}

/// A message is one line naming the file first, and holds each of `parts`.
void check_message(const std::string& msg, const std::vector<std::string>& parts) {
  INFO(msg);
  CHECK(msg.rfind("robot.urdf: ", 0) == 0);
  CHECK(msg.find('\n') == std::string::npos);
  for (const std::string& p : parts) CHECK(msg.find(p) != std::string::npos);
}

std::string extra_joint(const std::string& name, const std::string& parent,
                        const std::string& child) {
  return link_xml(child, 0.1) + joint_xml(name, parent, child, "0 0.05 0", "1 0 0");
}

TEST_CASE("urdf legs: each broken leg layout is refused in one line naming the leg and link",
          "[urdf_legs]") {
  // A leg of two joints (L2: the front right leg).
  check_message(refusal(legged_urdf({{0.2, 0.1}, {0.2, -0.1, 2}, {-0.2, 0.1}, {-0.2, -0.1}})),
                {"leg L2 (chain 'leg1_j1'): 2 moving joints from the trunk to its last link "
                 "'leg1_l2', expected 3 to 6"});
  // A leg of seven joints.
  check_message(refusal(legged_urdf({{0.2, 0.1, 7}, {0.2, -0.1}, {-0.2, 0.1}, {-0.2, -0.1}})),
                {"leg L1 (chain 'leg0_j1'): joint 'leg0_j7' leaves link 'leg0_l6' after 6 moving "
                 "joints, expected 3 to 6 moving joints from the trunk to the foot"});
  // A chain that branches: a one-joint spur on the hip link of L3.
  check_message(refusal(legged_urdf(quadruped(), extra_joint("spur", "leg2_l1", "spur_link"))),
                {"leg L3 (chain 'leg2_j1'): the chain branches at link 'leg2_l1' (moving joints "
                 "'leg2_j2', 'spur' leave it)",
                 "expected one moving joint after another"});
  // Two legs sharing a link: a second two-joint chain from L4's hip link.
  check_message(refusal(legged_urdf(quadruped(), extra_joint("twin2", "leg3_l1", "twin_l2") +
                                                     extra_joint("twin3", "twin_l2", "twin_l3"))),
                {"leg L4 (chain 'leg3_j1'): two legs share link 'leg3_l1' (moving joints "
                 "'leg3_j2', 'twin2' leave it)",
                 "expected each leg its own chain"});
  // A foot that cannot be found: two links fixed to L1's last link.
  const std::string fork =
      link_xml("sensor", 0.0) +
      "  <joint name=\"sensor_fixed\" type=\"fixed\"><parent link=\"leg0_l3\"/><child "
      "link=\"sensor\"/><origin xyz=\"0 0 0.01\"/></joint>\n";
  check_message(
      refusal(legged_urdf(quadruped(), fork)),
      {"leg L1 (chain 'leg0_j1'): links ", "are both fixed to 'leg0_l3'", "robot.foot_links"});
  // More than eight legs, fewer than two.
  std::vector<LegSpec> nine;
  for (int i = 0; i < 9; ++i) nine.push_back({0.4 - 0.1 * i, i % 2 ? -0.1 : 0.1});
  check_message(refusal(legged_urdf(nine)),
                {"trunk 'trunk': 9 moving joints leave the trunk ('leg0_j1', ",
                 "'leg8_j1', the "
                 "first joint of each leg), expected at most 8 legs"});
  check_message(refusal(legged_urdf({{0.2, 0.1}})),
                {"trunk 'trunk': 1 moving joints leave the trunk ('leg0_j1', the first joint of "
                 "each leg), expected at least 2 legs"});
  // A hip on the centre line (|x| <= 1e-9 m in the trunk frame); 1e-8 m is a side.
  check_message(refusal(legged_urdf({{0.2, 0.1}, {0.2, -0.1}, {-0.2, 1e-10}})),
                {"chain 'leg2_j1' (link 'leg2_l1'): hip on the trunk's forward axis (-1e-10 m to "
                 "the side)",
                 "robot.forward_axis"});
  CHECK(refusal(legged_urdf({{0.2, 0.1}, {0.2, -0.1}, {-0.2, 1e-8}})).empty());
  // Sides whose counts differ by more than one: a mirror-symmetric robot read with the wrong
  // forward axis (three legs on the left, one on the right).
  check_message(refusal(legged_urdf({{0.2, 0.1}, {0.0, 0.1}, {-0.2, 0.1}, {0.0, -0.1}})),
                {"legs: 3 hips on the left and 1 on the right of the trunk (forward axis +x), "
                 "expected as many on each side",
                 "set robot.forward_axis"});
}

TEST_CASE("urdf legs: prismatic joints are read with their type and built into the model",
          "[urdf_legs]") {
  std::string text = legged_urdf(quadruped());
  const std::string knee = "<joint name=\"leg1_j3\" type=\"revolute\">";
  text.replace(text.find(knee), knee.size(), "<joint name=\"leg1_j3\" type=\"prismatic\">");
  const UrdfRobot robot = read_urdf_robot_from_string(text, "robot.urdf");
  CHECK(robot.legs[1].joints[2].type == UrdfJointType::kPrismatic);
  CHECK(robot.legs[1].joints[1].type == UrdfJointType::kRevolute);
  // The model takes it, typed, the other joints revolute; the tree is that of the same robot
  // with the joint revolute; the leg is solved on its chain.
  const RobotModel m = build_robot_model(robot);
  const RobotModel revolute =
      build_robot_model(read_urdf_robot_from_string(legged_urdf(quadruped()), "robot.urdf"));
  REQUIRE(m.joints() == revolute.joints());
  for (int k = 0; k < m.joints(); ++k) {
    CHECK(m.prismatic(k) == (m.joint_source_names[k] == "leg1_j3"));
    CHECK(m.joint_source_names[k] == revolute.joint_source_names[k]);
    CHECK(m.axis[1 + k] == revolute.axis[1 + k]);
    CHECK(m.p_parent_joint[1 + k] == revolute.p_parent_joint[1 + k]);
  }
  CHECK(m.total_mass_kg == revolute.total_mass_kg);
  CHECK(m.leg_on_chain[1]);
  CHECK_FALSE(m.leg_on_chain[0]);
}

TEST_CASE("urdf legs: a robot the model cannot hold is refused in one line when built",
          "[urdf_legs]") {
  // The model holds as many bodies as its storage; a leg layout it does not simulate (this
  // build: six legs of three joints) is refused naming the file and the robot's shape. A
  // robot that is built has the description's legs and joints.
  std::vector<LegSpec> eight;
  for (int r = 0; r < 4; ++r)
    for (double y : {0.1, -0.1}) eight.push_back({0.3 - 0.2 * r, y});
  for (const std::vector<LegSpec>& legs : {quadruped(), eight}) {
    const UrdfRobot robot = read_urdf_robot_from_string(legged_urdf(legs), "robot.urdf");
    try {
      const RobotModel m = build_robot_model(robot);
      REQUIRE(m.legs() == robot.n_legs());
      CHECK(m.joints() == robot.n_joints());
      for (int leg = 0; leg < m.legs(); ++leg)
        for (int j = 0; j < m.leg(leg).n_joints; ++j)
          CHECK(m.joint_source_names[m.joint(leg, j)] == robot.legs[leg].joints[j].name);
    } catch (const ConfigError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.rfind("robot.urdf: robot 'synthetic' (", 0) == 0);
      CHECK(msg.find('\n') == std::string::npos);
      const std::size_t bodies = static_cast<std::size_t>(1 + robot.n_joints());
      if (bodies > RobotModel{}.parent.size())
        CHECK(msg.find("): " + std::to_string(bodies) + " bodies, expected at most") !=
              std::string::npos);
      else
        CHECK(msg.find(std::to_string(robot.n_legs()) + " legs, this build holds") !=
              std::string::npos);
    }
  }
}

// ---- the shipped quadrupeds against a second reading ----

/// A minimal XML element: name, attributes, children (no text, comments skipped).
struct Element {
  std::string name;
  std::map<std::string, std::string> attr;
  std::vector<Element> children;
  const Element* child(const std::string& n) const {
    for (const Element& c : children)
      if (c.name == n) return &c;
    return nullptr;
  }
};

/// Parses the elements of `text` from `at` (no entities, which URDF numbers do not use).
class XmlWalk {
 public:
  explicit XmlWalk(std::string text) : t_(std::move(text)) {}
  Element document() {
    Element root;
    root.name = "#document";
    children(root);
    return root;
  }

 private:
  void children(Element& parent) {
    for (;;) {
      const std::size_t lt = t_.find('<', at_);
      if (lt == std::string::npos) return;
      at_ = lt;
      if (t_.compare(at_, 4, "<!--") == 0) {
        at_ = t_.find("-->", at_) + 3;
      } else if (t_.compare(at_, 2, "<?") == 0) {
        at_ = t_.find("?>", at_) + 2;
      } else if (t_.compare(at_, 2, "</") == 0) {
        at_ = t_.find('>', at_) + 1;
        return;
      } else {
        parent.children.push_back(element());
      }
    }
  }
  Element element() {
    Element e;
    ++at_;
    while (!std::isspace(static_cast<unsigned char>(t_[at_])) && t_[at_] != '>' && t_[at_] != '/')
      e.name += t_[at_++];
    for (;;) {
      while (std::isspace(static_cast<unsigned char>(t_[at_]))) ++at_;
      if (t_[at_] == '/') {
        at_ = t_.find('>', at_) + 1;
        return e;
      }
      if (t_[at_] == '>') {
        ++at_;
        children(e);
        return e;
      }
      const std::size_t eq = t_.find('=', at_);
      std::string key = t_.substr(at_, eq - at_);
      while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
      const std::size_t open = t_.find_first_of("\"'", eq);
      const std::size_t close = t_.find(t_[open], open + 1);
      e.attr[key] = t_.substr(open + 1, close - open - 1);
      at_ = close + 1;
    }
  }
  std::string t_;
  std::size_t at_ = 0;
};

Vec3 triple_of(const Element* e, const std::string& key) {
  Vec3 v = Vec3::Zero();
  if (e == nullptr || !e->attr.count(key)) return v;
  std::istringstream s(e->attr.at(key));
  s >> v.x() >> v.y() >> v.z();
  return v;
}

/// R = Rz(yaw) Ry(pitch) Rx(roll), URDF's fixed-axis rpy.
Mat3 rpy_matrix(const Vec3& rpy) {
  const double cr = std::cos(rpy.x()), sr = std::sin(rpy.x()), cp = std::cos(rpy.y()),
               sp = std::sin(rpy.y()), cy = std::cos(rpy.z()), sy = std::sin(rpy.z());
  Mat3 R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, sy * cp, sy * sp * sr + cy * cr,
      sy * sp * cr - cy * sr, -sp, cp * sr, cp * cr;
  return R;
}

/// The description as the XML says it: links' masses, joints by child link.
struct XmlRobot {
  struct Joint {
    std::string name, type, parent, child;
    Vec3 xyz, rpy;
    const Element* limit = nullptr;
  };
  std::map<std::string, double> mass;               ///< by link (0 without <inertial>)
  std::map<std::string, const Element*> link;       ///< by name
  std::map<std::string, Joint> joint_of_child;      ///< by child link
  std::map<std::string, std::vector<Joint>> below;  ///< joints by parent link
  Element doc;

  explicit XmlRobot(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    doc = XmlWalk(s.str()).document();
    const Element* robot = doc.child("robot");
    REQUIRE(robot != nullptr);
    for (const Element& e : robot->children) {
      if (e.name == "link") {
        link[e.attr.at("name")] = &e;
        const Element* in = e.child("inertial");
        const Element* m = in ? in->child("mass") : nullptr;
        mass[e.attr.at("name")] = m ? std::stod(m->attr.at("value")) : 0.0;
      } else if (e.name == "joint") {
        Joint j{e.attr.at("name"),
                e.attr.at("type"),
                e.child("parent")->attr.at("link"),
                e.child("child")->attr.at("link"),
                triple_of(e.child("origin"), "xyz"),
                triple_of(e.child("origin"), "rpy"),
                e.child("limit")};
        joint_of_child[j.child] = j;
        below[j.parent].push_back(j);
      }
    }
  }
  /// `link` and the links fixed below it.
  std::vector<std::string> fixed_group(const std::string& l) const {
    std::vector<std::string> out{l};
    for (std::size_t i = 0; i < out.size(); ++i)
      if (below.count(out[i]))
        for (const Joint& j : below.at(out[i]))
          if (j.type == "fixed") out.push_back(j.child);
    return out;
  }
  double group_mass(const std::string& l) const {
    double m = 0.0;
    for (const std::string& g : fixed_group(l)) m += mass.at(g);
    return m;
  }
  /// Origin of `frame` (a link below `ancestor` by fixed joints) in `ancestor`'s frame, and
  /// the rotation.
  std::pair<Vec3, Mat3> placement(const std::string& frame, const std::string& ancestor) const {
    Vec3 p = Vec3::Zero();
    Mat3 R = Mat3::Identity();
    for (std::string l = frame; l != ancestor;) {
      const Joint& j = joint_of_child.at(l);
      const Mat3 Rj = rpy_matrix(j.rpy);
      p = j.xyz + Rj * p;
      R = Rj * R;
      l = j.parent;
    }
    return {p, R};
  }
};

struct Quadruped {
  const char* file;
  const char* forward;
  std::vector<std::string> prefixes;  ///< the legs' joint prefixes in hexdyn's documented order
};

TEST_CASE("urdf legs: Solo-12 and ANYmal C read as four legs, checked against the XML",
          "[urdf_legs]") {
  const std::vector<Quadruped> robots = {{"solo12.urdf", "+x", {"FL", "FR", "HL", "HR"}},
                                         {"anymal_c.urdf", "+x", {"LF", "RF", "LH", "RH"}}};
  for (const Quadruped& q : robots) {
    const std::string path = std::string(HEXDYN_SOURCE_DIR) + "/robots/" + q.file;
    INFO(q.file);
    const UrdfRobot robot = read_urdf_robot(path);
    const XmlRobot xml(path);
    REQUIRE(robot.n_legs() == 4);
    double total = 0.0;
    for (const auto& [name, m] : xml.mass) total += m;
    CHECK(std::abs(robot.total_mass_kg - total) <= 1e-12);
    CHECK(std::abs(robot.trunk.mass_kg - xml.group_mass(robot.trunk_link)) <= 1e-12);
    double merged = robot.trunk.mass_kg;
    for (int leg = 0; leg < 4; ++leg) {
      const UrdfLeg& l = robot.legs[leg];
      INFO(leg_name(leg));
      REQUIRE(l.n_joints() == 3);
      const char* suffix[3] = {"_HAA", "_HFE", "_KFE"};
      // The hip in the URDF's own frame (+x forward, +y left): the order front left, front
      // right, rear left, rear right, from the XML's joint origins.
      const XmlRobot::Joint& hip = xml.joint_of_child.at(l.joints[0].link);
      const Vec3 hip_U = xml.placement(hip.parent, robot.trunk_link).first + hip.xyz;
      CHECK((hip_U.y() > 0.0) == (leg % 2 == 0));  // left first in each rank
      CHECK((hip_U.x() > 0.0) == (leg < 2));       // front rank first
      for (int j = 0; j < 3; ++j) {
        const UrdfJoint& joint = l.joints[j];
        CHECK(joint.name == q.prefixes[leg] + suffix[j]);
        const XmlRobot::Joint& x = xml.joint_of_child.at(joint.link);
        CHECK(x.name == joint.name);
        CHECK(x.type == "revolute");
        CHECK(std::abs(joint.inertia.mass_kg - xml.group_mass(joint.link)) <= 1e-12);
        merged += joint.inertia.mass_kg;
        REQUIRE(x.limit != nullptr);
        CHECK(joint.lower_rad == std::stod(x.limit->attr.at("lower")));
        CHECK(joint.upper_rad == std::stod(x.limit->attr.at("upper")));
        CHECK(joint.effort_Nm == std::stod(x.limit->attr.at("effort")));
        CHECK(joint.velocity_radps == std::stod(x.limit->attr.at("velocity")));
      }
      // The foot: Solo's *_FOOT link origin, ANYmal's sphere <collision> of *_FOOT, in the
      // shank's frame.
      const std::string foot = q.prefixes[leg] + "_FOOT";
      CHECK(l.foot_source == foot);
      auto [p, R] = xml.placement(foot, l.last().link);
      const Element* sphere = nullptr;  // the foot link's sphere <collision>, if any
      for (const Element& col : xml.link.at(foot)->children)
        if (col.name == "collision" && col.child("geometry")->child("sphere")) sphere = &col;
      if (sphere != nullptr) {
        p += R * triple_of(sphere->child("origin"), "xyz");
        CHECK(l.foot_radius_m ==
              std::stod(sphere->child("geometry")->child("sphere")->attr.at("radius")));
      } else {
        CHECK(l.foot_radius_m == 0.0);
      }
      CHECK((l.p_foot_last - p).norm() <= 1e-12);
    }
    CHECK(std::abs(merged - total) <= 1e-12);  // every link in some body
  }
}

TEST_CASE("urdf legs: a quadruped description written as URDF reads back the same", "[urdf_legs]") {
  for (const char* file : {"solo12.urdf", "anymal_c.urdf"}) {
    INFO(file);
    const UrdfRobot a = read_urdf_robot(std::string(HEXDYN_SOURCE_DIR) + "/robots/" + file);
    const UrdfRobot b = read_urdf_robot_from_string(description_urdf(a), "written");
    CHECK(b.name == a.name);
    CHECK(b.trunk_link == a.trunk_link);
    CHECK(b.B_R_U == a.B_R_U);
    CHECK(std::abs(b.total_mass_kg - a.total_mass_kg) <= 1e-12);
    CHECK(b.trunk.mass_kg == a.trunk.mass_kg);
    CHECK((b.trunk.com_m - a.trunk.com_m).norm() <= 1e-15);
    CHECK((b.trunk.inertia_com - a.trunk.inertia_com).norm() <= 1e-15);
    REQUIRE(b.n_legs() == a.n_legs());
    for (int leg = 0; leg < a.n_legs(); ++leg) {
      const UrdfLeg &x = a.legs[leg], &y = b.legs[leg];
      REQUIRE(y.n_joints() == x.n_joints());
      for (int j = 0; j < x.n_joints(); ++j) {
        const UrdfJoint &u = x.joints[j], &v = y.joints[j];
        CHECK(v.name == u.name);
        CHECK(v.link == u.link);
        CHECK(v.type == u.type);
        CHECK(v.p_parent_joint == u.p_parent_joint);
        CHECK((v.R_parent_joint - u.R_parent_joint).norm() <= 1e-15);
        CHECK((v.axis - u.axis).norm() <= 1e-15);
        CHECK(v.lower_rad == u.lower_rad);
        CHECK(v.upper_rad == u.upper_rad);
        CHECK(v.effort_Nm == u.effort_Nm);
        CHECK(v.velocity_radps == u.velocity_radps);
        CHECK(v.damping_Nmsprad == u.damping_Nmsprad);
        CHECK(v.friction_Nm == u.friction_Nm);
        CHECK(std::abs(v.inertia.mass_kg - u.inertia.mass_kg) <= 1e-15);
        CHECK((v.inertia.com_m - u.inertia.com_m).norm() <= 1e-15);
        CHECK((v.inertia.inertia_com - u.inertia.inertia_com).norm() <= 1e-15);
      }
      CHECK(y.p_foot_last == x.p_foot_last);
      CHECK(y.foot_radius_m == x.foot_radius_m);
    }
  }
}

TEST_CASE("urdf legs: Solo-12's and ANYmal C's legs take the yaw-pitch-pitch closed form",
          "[urdf_legs]") {
  // Built as six legs (their four, and the front pair again as a middle pair halfway back),
  // a shape every build holds: the IK method is chosen per leg from its chain alone.
  for (const char* file : {"solo12.urdf", "anymal_c.urdf"}) {
    INFO(file);
    UrdfRobot robot = read_urdf_robot(std::string(HEXDYN_SOURCE_DIR) + "/robots/" + file);
    REQUIRE(robot.n_legs() == 4);
    std::vector<UrdfLeg> six = {robot.legs[0], robot.legs[1], robot.legs[0],
                                robot.legs[1], robot.legs[2], robot.legs[3]};
    for (int leg : {2, 3}) six[leg].joints[0].p_parent_joint.y() = 0.0;
    robot.legs = six;
    const RobotModel m = build_robot_model(robot);
    REQUIRE(m.legs() == 6);
    for (int leg = 0; leg < 6; ++leg) CHECK(m.leg_ik[leg].method == LegIkMethod::kYawPitchPitch);
  }
}

TEST_CASE("urdf legs: Solo-12's and ANYmal C's legs hang below their rolling hips", "[urdf_legs]") {
  // A rolling hip (abduction) has two roots that put the foot on the femur plane: the leg
  // hanging below the hip, or folded over it. Around the default stance, every IK solution
  // must be the hanging one, checked on the chain's own geometry: the FK gives the target
  // back, the hip link stays upright (its image of the trunk normal has a positive component
  // along it; folded over, the link is turned by more than a quarter turn), the knee joint
  // lies below the femur joint along the trunk normal and the foot below the knee; and every
  // joint is inside its limits.
  for (const char* file : {"solo12.urdf", "anymal_c.urdf"}) {
    INFO(file);
    const RobotModel m =
        build_robot_model(read_urdf_robot(std::string(HEXDYN_SOURCE_DIR) + "/robots/" + file));
    REQUIRE(m.legs() == 4);
    for (int leg = 0; leg < m.legs(); ++leg) {
      INFO("leg " << leg);
      REQUIRE(rolling_hip(m.leg_ik[leg]));
      const NominalStance s = default_nominal_stance(m, leg);
      REQUIRE(s.from_pose);
      const Vec3 p0 = leg_foot_position_H(m, leg, s.q);
      const Vec3 up = m.leg_ik[leg].up_H;
      const double depth = s.depth_m;
      for (double dx : {-0.15, 0.0, 0.15})
        for (double dy : {-0.15, 0.0, 0.15})
          for (double dz : {-0.1, 0.0, 0.1}) {
            const Vec3 p = p0 + depth * (m.R_B_H[leg].transpose() * Vec3(dx, dy, dz));
            const LegIkResult r = leg_inverse_kinematics(m, leg, p);
            REQUIRE(r.ok);
            CHECK((leg_foot_position_H(m, leg, r.q) - p).norm() <= 1e-12);
            const LegChainPose c = chain_pose(m, leg, r.q);
            CHECK((c.R_H[0] * up).dot(up) > 0.0);
            CHECK(c.o_H[2].dot(up) < c.o_H[1].dot(up));
            CHECK(c.p_foot_H.dot(up) < c.o_H[2].dot(up));
            for (int j = 0; j < 3; ++j) {
              const int k = m.joint(leg, j);
              CHECK(r.q[j] >= m.joint_lower_rad[k]);
              CHECK(r.q[j] <= m.joint_upper_rad[k]);
            }
          }
    }
  }
}

}  // namespace
}  // namespace hexdyn
