#pragma once
// The URDF reader's internals, shared by model/urdf_reader.cpp, urdf_reader_checks.cpp and
// urdf_feet.cpp: the Reader that turns a description into a UrdfRobot, and the small helpers
// the files share. Not installed (a *_detail.hpp header); include model/urdf_reader.hpp instead.

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/urdf_reader.hpp"

namespace hexdyn::urdf_detail {

/// Rigid placement of a frame in another: p [m], R (frame axes → other axes).
struct Placement {
  Vec3 p = Vec3::Zero();
  Mat3 R = Mat3::Identity();
  Placement operator*(const Placement& b) const { return {p + R * b.p, R * b.R}; }
  Placement inverse() const { return {-(R.transpose() * p), R.transpose()}; }
};

/// A hip at most this far from the trunk's forward axis (|x| in the trunk frame) is on it [m]:
/// neither left nor right, refused (docs/theory/conventions.md#legs-and-joints).
inline constexpr double kCentreHip_m = 1e-9;

/// x as a default-formatted stream writes it (6 significant digits: "0.05", "1e-09").
std::string num(double x);

/// A URDF pose as a placement: its position [m] and its rotation (frame axes → parent axes).
Placement to_placement(const urdf::Pose& pose);

/// Whether a joint moves (every type but fixed).
inline bool is_moving(const urdf::Joint& j) { return j.type != urdf::Joint::FIXED; }

/// Reads one description: parse, check, collect the trunk, read the legs' chains and feet.
class Reader {
 public:
  Reader(std::string source, const UrdfReadOptions& options)
      : source_(std::move(source)), opt_(options) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw ConfigError(source_ + ": " + what);
  }

  UrdfRobot read(const std::string& text);

 private:
  void parse(const std::string& text);
  void index_joints();
  Mat3 trunk_axes() const;
  std::vector<UrdfLeg> read_legs(const std::vector<std::pair<std::string, Placement>>& trunk,
                                 const Placement& B_X_U, const std::string& trunk_link);
  void check_links();
  void check_bodies() const;
  void check_body(const std::string& link,
                  const std::vector<std::pair<std::string, Placement>>& group,
                  const RigidInertia& body) const;
  void check_joints();
  void check_limits(const std::string& who, const urdf::JointLimits& l, double bound,
                    const std::string& beyond) const;
  void check_tree();
  void collect_trunk();
  /// Links fixed below `link` (itself included), with their placements in its frame.
  std::vector<std::pair<std::string, Placement>> fixed_group(const std::string& link) const;
  RigidInertia group_inertia(const std::vector<std::pair<std::string, Placement>>& group) const;
  std::vector<urdf::JointConstSharedPtr> moving_children(
      const std::vector<std::pair<std::string, Placement>>& group) const;
  std::vector<int> leg_order(const std::vector<urdf::JointConstSharedPtr>& legs,
                             const std::vector<Vec3>& hips) const;
  UrdfLeg read_chain(const urdf::JointConstSharedPtr& first, const Placement& B_X_parent,
                     int leg_index);
  UrdfJoint read_joint(const urdf::Joint& joint, const Placement& X_joint,
                       const std::vector<std::pair<std::string, Placement>>& group) const;
  int chain_depth(const urdf::JointConstSharedPtr& joint) const;
  [[noreturn]] void fail_branch(const std::string& who, const std::string& link, int so_far,
                                const std::vector<urdf::JointConstSharedPtr>& next) const;
  void locate_foot(const std::vector<std::pair<std::string, Placement>>& group,
                   const std::string& chain, UrdfLeg& leg);
  std::vector<CollisionShape> collision_shapes(
      const std::vector<std::pair<std::string, Placement>>& group) const;
  void finish_feet(UrdfRobot& robot) const;
  void check_foot_inside(int leg, UrdfLeg& l) const;
  std::pair<std::string, Placement> fixed_chain_end(
      const std::vector<std::pair<std::string, Placement>>& group, const std::string& last,
      const std::string& chain) const;

  std::string source_;
  UrdfReadOptions opt_;
  urdf::ModelInterfaceSharedPtr model_;
  std::map<std::string, std::vector<urdf::JointConstSharedPtr>> child_joints_;  ///< by parent link
  std::map<std::string, urdf::JointConstSharedPtr> parent_joint_;               ///< by child link
  std::map<std::string, Placement>
      trunk_group_;  ///< links of the trunk body, in the trunk link frame
  std::map<std::string, int> foot_link_used_;
};

}  // namespace hexdyn::urdf_detail
