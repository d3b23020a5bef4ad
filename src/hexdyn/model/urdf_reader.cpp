#include "hexdyn/model/urdf_reader.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/value_bounds.hpp"
#include "hexdyn/model/urdf_checks.hpp"
#include "hexdyn/model/urdf_feet_detail.hpp"

namespace hexdyn::urdf_detail {

std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

Placement to_placement(const urdf::Pose& pose) {
  Placement x;
  x.p = Vec3(pose.position.x, pose.position.y, pose.position.z);
  x.R = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
            .normalized()
            .toRotationMatrix();
  return x;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

/// Collects urdfdom's error messages (console_bridge) instead of printing them.
class CaptureErrors : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(one_line(text));
  }
  std::vector<std::string> errors;
};

/// A link's <inertial> in the link frame: COM = origin position, tensor rotated from the
/// inertial frame into the link axes.
RigidInertia link_inertia(const urdf::Link& link) {
  RigidInertia r;
  if (!link.inertial) return r;
  const urdf::Inertial& in = *link.inertial;
  const Placement o = to_placement(in.origin);
  Mat3 I;
  I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  r.mass_kg = in.mass;
  r.com_m = o.p;
  r.inertia_com = o.R * I * o.R.transpose();
  return r;
}

RigidInertia transformed(const RigidInertia& in, const Placement& X) {
  RigidInertia r = in;
  r.com_m = X.p + X.R * in.com_m;
  r.inertia_com = X.R * in.inertia_com * X.R.transpose();
  return r;
}

}  // namespace

/// Parses the description with urdfdom, its console messages captured: a description it
/// refuses fails with urdfdom's first (and last) reason.
void Reader::parse(const std::string& text) {
  static std::mutex console_mutex;  // console_bridge's output handler is global
  std::lock_guard<std::mutex> lock(console_mutex);
  CaptureErrors capture;
  console_bridge::useOutputHandler(&capture);
  try {
    model_ = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    capture.errors.push_back(one_line(e.what()));
    model_.reset();
  }
  console_bridge::restorePreviousOutputHandler();
  if (!model_) {
    std::string why = capture.errors.empty() ? "urdfdom gave no reason" : capture.errors.front();
    // urdfdom's missing-link message goes on with advice over several sentences.
    if (const auto cut = why.find(".  "); cut != std::string::npos) why.erase(cut + 1);
    if (capture.errors.size() > 1 && capture.errors.back() != why)
      why += "; " + capture.errors.back();
    fail("not a valid URDF (urdfdom: " + why + ")");
  }
}

/// The joints by parent link and by child link; a link that is the child of two joints
/// (a kinematic loop) fails.
void Reader::index_joints() {
  for (const auto& [name, joint] : model_->joints_) {
    child_joints_[joint->parent_link_name].push_back(joint);
    if (parent_joint_.count(joint->child_link_name))
      fail("link '" + joint->child_link_name + "': child of two joints, '" +
           parent_joint_[joint->child_link_name]->name + "' and '" + name +
           "' (a kinematic loop; a URDF must be a tree)");
    parent_joint_[joint->child_link_name] = joint;
  }
}

/// B_R_U, the trunk axes in the URDF trunk link's axes: forward (opt_.forward_axis) → +y,
/// up (+z) → +z, right = forward × up → +x.
Mat3 Reader::trunk_axes() const {
  Vec3 fwd;
  if (opt_.forward_axis == "+x")
    fwd = Vec3::UnitX();
  else if (opt_.forward_axis == "-x")
    fwd = -Vec3::UnitX();
  else if (opt_.forward_axis == "+y")
    fwd = Vec3::UnitY();
  else if (opt_.forward_axis == "-y")
    fwd = -Vec3::UnitY();
  else
    fail("forward axis '" + opt_.forward_axis + "', expected one of +x, -x, +y, -y");
  const Vec3 up = Vec3::UnitZ();
  Mat3 B_R_U;
  B_R_U.row(0) = fwd.cross(up).transpose();
  B_R_U.row(1) = fwd.transpose();
  B_R_U.row(2) = up.transpose();
  return B_R_U;
}

/// The leg chains leaving the trunk (links `trunk`, named trunk_link in messages), in leg order
/// (leg_order), placed in the trunk frame by B_X_U: 2 to 8 (kMinLegs … kMaxLegs); each named
/// foot link (robot.foot_links) must end exactly one chain.
std::vector<UrdfLeg> Reader::read_legs(const std::vector<std::pair<std::string, Placement>>& trunk,
                                       const Placement& B_X_U, const std::string& trunk_link) {
  const auto legs = moving_children(trunk);
  const int n = static_cast<int>(legs.size());
  if (n < kMinLegs || n > kMaxLegs) {
    std::string list;
    for (const auto& j : legs) list += (list.empty() ? "'" : ", '") + j->name + "'";
    fail("trunk '" + trunk_link + "': " + std::to_string(n) + " moving joints leave the trunk (" +
         (list.empty() ? "none" : list + ", the first joint of each leg") + "), expected " +
         (n < kMinLegs ? "at least " + std::to_string(kMinLegs)
                       : "at most " + std::to_string(kMaxLegs)) +
         " legs");
  }
  if (!opt_.foot_links.empty() && static_cast<int>(opt_.foot_links.size()) != n)
    fail("robot.foot_links: " + std::to_string(opt_.foot_links.size()) + " names, expected " +
         std::to_string(n) + " (one per leg)");
  for (const auto& f : opt_.foot_links) {
    if (!model_->getLink(f)) fail("robot.foot_links: no link '" + f + "' in the description");
    foot_link_used_[f] = 0;
  }
  std::vector<Placement> B_X_parent;
  std::vector<Vec3> hips;
  for (const auto& j : legs) {
    B_X_parent.push_back(B_X_U * trunk_group_.at(j->parent_link_name));
    hips.push_back((B_X_parent.back() * to_placement(j->parent_to_joint_origin_transform)).p);
  }
  std::vector<UrdfLeg> chains;
  for (const int i : leg_order(legs, hips))
    chains.push_back(read_chain(legs[i], B_X_parent[i], static_cast<int>(chains.size())));
  for (const auto& [f, count] : foot_link_used_)
    if (count != 1)
      fail("robot.foot_links: link '" + f +
           "' is not fixed to the last link of exactly one leg chain");
  return chains;
}

/// The legs' order (docs/theory/conventions.md#legs-and-joints): the side of each hip (its x in
/// the trunk frame: x < 0 left; |x| <= 1e-9 m refused; the two sides' counts may differ by one
/// at most), then the rank front to rear within a side (y descending), numbered rank by rank,
/// left before right. Returns the indices of
/// `legs` in that order.
std::vector<int> Reader::leg_order(const std::vector<urdf::JointConstSharedPtr>& legs,
                                   const std::vector<Vec3>& hips) const {
  std::vector<int> left, right;
  for (int i = 0; i < static_cast<int>(hips.size()); ++i) {
    const Vec3& h = hips[i];
    if (std::abs(h.x()) <= kCentreHip_m)
      fail("chain '" + legs[i]->name + "' (link '" + legs[i]->child_link_name +
           "'): hip on the trunk's forward axis (" + num(h.x()) +
           " m to the side), expected a hip left or right of it: cannot tell left from right; "
           "set robot.forward_axis (now " +
           opt_.forward_axis + ")");
    (h.x() < 0.0 ? left : right).push_back(i);
  }
  const int l = static_cast<int>(left.size()), r = static_cast<int>(right.size());
  if (std::abs(l - r) > 1)  // a mirror-symmetric robot: a wrong forward axis shows here
    fail("legs: " + std::to_string(l) + " hips on the left and " + std::to_string(r) +
         " on the right of the trunk (forward axis " + opt_.forward_axis +
         "), expected as many on each side (one more on one side for an odd count); set "
         "robot.forward_axis");
  auto by_y = [&](int a, int b) { return hips[a].y() > hips[b].y(); };
  std::stable_sort(left.begin(), left.end(), by_y);
  std::stable_sort(right.begin(), right.end(), by_y);
  std::vector<int> order;
  for (std::size_t rank = 0; rank < std::max(left.size(), right.size()); ++rank) {
    if (rank < left.size()) order.push_back(left[rank]);
    if (rank < right.size()) order.push_back(right[rank]);
  }
  return order;
}

UrdfRobot Reader::read(const std::string& text) {
  check_finite_numbers(text, source_);
  parse(text);
  index_joints();
  check_tree();
  check_links();
  check_link_geometry(*model_, source_);
  check_joints();
  collect_trunk();
  check_bodies();

  UrdfRobot robot;
  robot.name = model_->getName();
  robot.source_path = source_;
  robot.trunk_link = opt_.trunk_link.empty() ? model_->getRoot()->name : opt_.trunk_link;
  robot.forward_axis = opt_.forward_axis;
  robot.B_R_U = trunk_axes();
  const Placement B_X_U{Vec3::Zero(), robot.B_R_U};

  std::vector<std::pair<std::string, Placement>> trunk(trunk_group_.begin(), trunk_group_.end());
  robot.trunk = transformed(group_inertia(trunk), B_X_U);
  for (const auto& [name, link] : model_->links_)
    robot.total_mass_kg += link_inertia(*link).mass_kg;
  robot.root_link = model_->getRoot()->name;
  const Placement B_X_root =
      B_X_U * trunk_group_.at(robot.root_link);  // the root is fixed to the trunk
  robot.p_B_root = B_X_root.p;
  robot.B_R_root = B_X_root.R;

  for (const auto& [name, X] : trunk)
    if (name != robot.trunk_link) robot.trunk_merged_links.push_back(name);
  robot.legs = read_legs(trunk, B_X_U, robot.trunk_link);
  finish_feet(robot);
  return robot;
}

void Reader::collect_trunk() {
  const std::string trunk = opt_.trunk_link.empty() ? model_->getRoot()->name : opt_.trunk_link;
  if (!model_->getLink(trunk)) fail("robot.trunk_link: no link '" + trunk + "' in the description");
  // The fixed-joint component of the trunk link, both up and down the tree.
  trunk_group_[trunk] = Placement{};
  std::vector<std::string> todo{trunk};
  while (!todo.empty()) {
    const std::string l = todo.back();
    todo.pop_back();
    const Placement T_X_l = trunk_group_.at(l);
    for (const auto& j : child_joints_[l]) {
      if (is_moving(*j) || trunk_group_.count(j->child_link_name)) continue;
      trunk_group_[j->child_link_name] = T_X_l * to_placement(j->parent_to_joint_origin_transform);
      todo.push_back(j->child_link_name);
    }
    const auto up = parent_joint_.find(l);
    if (up == parent_joint_.end() || trunk_group_.count(up->second->parent_link_name)) continue;
    if (is_moving(*up->second))
      fail("joint '" + up->second->name + "': a moving joint above the trunk link '" + trunk +
           "' (the trunk must be the root, or fixed to it)");
    trunk_group_[up->second->parent_link_name] =
        T_X_l * to_placement(up->second->parent_to_joint_origin_transform).inverse();
    todo.push_back(up->second->parent_link_name);
  }
}

std::vector<std::pair<std::string, Placement>> Reader::fixed_group(const std::string& link) const {
  std::vector<std::pair<std::string, Placement>> out{{link, Placement{}}};
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto it = child_joints_.find(out[i].first);
    if (it == child_joints_.end()) continue;
    for (const auto& j : it->second)
      if (!is_moving(*j))
        out.emplace_back(j->child_link_name,
                         out[i].second * to_placement(j->parent_to_joint_origin_transform));
  }
  return out;
}

RigidInertia Reader::group_inertia(
    const std::vector<std::pair<std::string, Placement>>& group) const {
  RigidInertia r;
  for (const auto& [name, X] : group)
    r = combine_inertias(r, transformed(link_inertia(*model_->getLink(name)), X));
  return r;
}

std::vector<urdf::JointConstSharedPtr> Reader::moving_children(
    const std::vector<std::pair<std::string, Placement>>& group) const {
  std::vector<urdf::JointConstSharedPtr> out;
  for (const auto& [name, X] : group) {
    const auto it = child_joints_.find(name);
    if (it == child_joints_.end()) continue;
    for (const auto& j : it->second)
      if (is_moving(*j)) out.push_back(j);
  }
  return out;
}

namespace {

UrdfJointType joint_type(const urdf::Joint& j) {
  if (j.type == urdf::Joint::CONTINUOUS) return UrdfJointType::kContinuous;
  if (j.type == urdf::Joint::PRISMATIC) return UrdfJointType::kPrismatic;
  return UrdfJointType::kRevolute;
}

}  // namespace

/// One joint of a chain, its frame in the leg's parent body (X_joint), and the body it moves.
UrdfJoint Reader::read_joint(const urdf::Joint& joint, const Placement& X_joint,
                             const std::vector<std::pair<std::string, Placement>>& group) const {
  UrdfJoint out;
  out.name = joint.name;
  out.link = joint.child_link_name;
  out.type = joint_type(joint);
  out.p_parent_joint = X_joint.p;
  out.R_parent_joint = X_joint.R;
  out.axis = Vec3(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
  const bool continuous = out.type == UrdfJointType::kContinuous;
  const auto& lim = joint.limits;
  out.lower_rad = continuous || !lim ? -kInf : lim->lower;
  out.upper_rad = continuous || !lim ? kInf : lim->upper;
  out.effort_Nm = lim && lim->effort > 0.0 ? lim->effort : kInf;
  out.velocity_radps = lim && lim->velocity > 0.0 ? lim->velocity : kInf;
  if (const auto& dyn = joint.dynamics) {
    out.damping_Nmsprad = dyn->damping;
    out.friction_Nm = dyn->friction;
  }
  out.inertia = group_inertia(group);
  for (std::size_t i = 1; i < group.size(); ++i) out.merged_links.push_back(group[i].first);
  return out;
}

/// The most moving joints in a row below `joint` (itself included).
int Reader::chain_depth(const urdf::JointConstSharedPtr& joint) const {
  int most = 0;
  for (const auto& next : moving_children(fixed_group(joint->child_link_name)))
    most = std::max(most, chain_depth(next));
  return 1 + most;
}

/// Refuses a chain that branches at link `link` (leg `who`, `so_far` joints above it): two of
/// the branches long enough to be legs are two legs sharing the link; otherwise the chain
/// branches.
void Reader::fail_branch(const std::string& who, const std::string& link, int so_far,
                         const std::vector<urdf::JointConstSharedPtr>& next) const {
  std::string list;
  int legs = 0;
  for (const auto& n : next) {
    list += (list.empty() ? "'" : ", '") + n->name + "'";
    if (so_far + chain_depth(n) >= kMinLegJoints) ++legs;
  }
  if (legs >= 2)
    fail(who + "two legs share link '" + link + "' (moving joints " + list +
         " leave it), expected each leg its own chain of links from the trunk");
  fail(who + "the chain branches at link '" + link + "' (moving joints " + list +
       " leave it), expected one moving joint after another from the trunk to the foot");
}

/// Leg `leg_index` (in leg order) from its first joint `first`, whose parent link is placed in
/// the trunk frame by B_X_parent: 3 to 6 moving joints in a chain, then its foot.
UrdfLeg Reader::read_chain(const urdf::JointConstSharedPtr& first, const Placement& B_X_parent,
                           int leg_index) {
  UrdfLeg leg;
  const std::string chain = "leg " + leg_name(leg_index) + " (chain '" + first->name + "'): ";
  urdf::JointConstSharedPtr joint = first;
  Placement X_parent = B_X_parent;  // the joint's parent link in its body's frame
  std::vector<std::pair<std::string, Placement>> group;
  for (;;) {
    if (leg.n_joints() == kMaxLegJoints)
      fail(chain + "joint '" + joint->name + "' leaves link '" + joint->parent_link_name +
           "' after " + std::to_string(kMaxLegJoints) + " moving joints, expected " +
           std::to_string(kMinLegJoints) + " to " + std::to_string(kMaxLegJoints) +
           " moving joints from the trunk to the foot");
    group = fixed_group(joint->child_link_name);
    leg.joints.push_back(read_joint(
        *joint, X_parent * to_placement(joint->parent_to_joint_origin_transform), group));
    const auto next = moving_children(group);
    if (next.empty()) break;
    if (next.size() > 1) fail_branch(chain, joint->child_link_name, leg.n_joints(), next);
    joint = next.front();
    for (const auto& [name, Xl] : group)
      if (name == joint->parent_link_name) X_parent = Xl;
  }
  if (leg.n_joints() < kMinLegJoints)
    fail(chain + std::to_string(leg.n_joints()) + " moving joint" +
         (leg.n_joints() == 1 ? "" : "s") + " from the trunk to its last link '" + leg.last().link +
         "', expected " + std::to_string(kMinLegJoints) + " to " + std::to_string(kMaxLegJoints));
  locate_foot(group, chain, leg);
  return leg;
}

}  // namespace hexdyn::urdf_detail

namespace hexdyn {

using urdf_detail::Reader;

UrdfRobot read_urdf_robot_from_string(const std::string& urdf_text, const std::string& source_name,
                                      const UrdfReadOptions& options) {
  Reader reader(source_name, options);
  return reader.read(urdf_text);
}

std::string read_urdf_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in && !std::filesystem::exists(path, ec) && !ec)  // a link to nothing too
    throw ConfigError(path + ": does not exist, expected a URDF file");
  if (!in) throw ConfigError(path + ": cannot read the URDF file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw ConfigError(path + ": cannot read the URDF file");
  return s.str();
}

UrdfRobot read_urdf_robot(const std::string& path, const UrdfReadOptions& options) {
  return read_urdf_robot_from_string(read_urdf_text(path), path, options);
}

}  // namespace hexdyn
