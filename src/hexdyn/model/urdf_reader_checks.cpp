// The URDF reader's checks of a parsed description (model/urdf_feet_detail.hpp Reader):
// a tree, finite and bounded inertials, bodies the dynamics can use, supported joints with
// finite, bounded axes, limits and dynamics. The bounds are those of a scene's robot keys
// (core/value_bounds.hpp, model/urdf_checks.hpp).
#include <urdf_model/model.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "hexdyn/core/value_bounds.hpp"
#include "hexdyn/model/urdf_checks.hpp"
#include "hexdyn/model/urdf_feet_detail.hpp"

namespace hexdyn::urdf_detail {
namespace {

/// The largest |coordinate| of a pose's position [m].
double largest_coordinate(const urdf::Pose& p) {
  return std::max({std::abs(p.position.x), std::abs(p.position.y), std::abs(p.position.z)});
}

std::string position_text(const urdf::Pose& p) {
  return num(p.position.x) + " " + num(p.position.y) + " " + num(p.position.z);
}

bool finite_pose(const urdf::Pose& p) {
  return std::isfinite(p.position.x) && std::isfinite(p.position.y) &&
         std::isfinite(p.position.z) && std::isfinite(p.rotation.x) &&
         std::isfinite(p.rotation.y) && std::isfinite(p.rotation.z) && std::isfinite(p.rotation.w);
}

const char* type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

/// A symmetric inertia tensor's principal moments, ascending [kg m2].
Vec3 principal_moments(const Mat3& I) {
  return Eigen::SelfAdjointEigenSolver<Mat3>(I, Eigen::EigenvaluesOnly).eigenvalues();
}

std::string moments_text(const Vec3& m) {
  return "principal moments (" + num(m[0]) + ", " + num(m[1]) + ", " + num(m[2]) + ") kg m2";
}

}  // namespace

void Reader::check_tree() {
  // Every link reachable from the root: links on a cycle of joints are not.
  const std::string root = model_->getRoot()->name;
  std::set<std::string> seen{root};
  std::vector<std::string> todo{root};
  while (!todo.empty()) {
    const std::string l = todo.back();
    todo.pop_back();
    for (const auto& j : child_joints_[l])
      if (seen.insert(j->child_link_name).second) todo.push_back(j->child_link_name);
  }
  for (const auto& [name, link] : model_->links_)
    if (!seen.count(name))
      fail("link '" + name + "': not connected to the root link '" + root +
           "' (a cycle of joints; a URDF must be a tree)");
}

void Reader::check_links() {
  for (const auto& [name, link] : model_->links_) {
    if (!link->inertial) continue;
    const urdf::Inertial& in = *link->inertial;
    const std::string who = "link '" + name + "': ";
    const double v[] = {in.mass, in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz};
    for (double x : v)
      if (!std::isfinite(x)) fail(who + "<inertial> holds " + num(x) + ", expected finite numbers");
    if (!finite_pose(in.origin)) fail(who + "<inertial><origin> is not finite");
    Mat3 I;
    I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    // A massless <inertial> (a sensor or tool frame) is a link without one; rotational inertia
    // without mass is no body.
    if (in.mass < 0.0 || (in.mass == 0.0 && !I.isZero(0.0)))
      fail(who + "mass " + num(in.mass) + " kg" +
           (in.mass == 0.0 ? " with a nonzero inertia" : "") +
           ", expected > 0 (or 0 with a zero inertia: a massless link)");
    if (in.mass > kMaxBodyMass_kg)
      fail(who + "mass " + num(in.mass) + " kg, expected at most " + num(kMaxBodyMass_kg) +
           " kg (the bound of a scene's robot.*.mass)");
    if (largest_coordinate(in.origin) > kMaxRobotCoordinate_m)
      fail(who + "<inertial><origin xyz=\"" + position_text(in.origin) +
           "\">, expected coordinates within +-" + num(kMaxRobotCoordinate_m) +
           " m (the bound of a scene's robot.*.com)");
    if (I.isZero(0.0)) continue;  // a point mass, or massless
    const Vec3 m = principal_moments(I);
    const std::string moments = moments_text(m);
    // A moment below zero beyond the rounding of the others (a zero moment comes out ±1e-19).
    if (m[0] < -kInertiaTriangleTolerance * m[2])
      fail(who + "inertia not positive definite (a negative moment): " + moments);
    if (m[2] > kMaxPrincipalInertia_kgm2)
      fail(who + "inertia too large: " + moments + ", expected each at most " +
           num(kMaxPrincipalInertia_kgm2) + " kg m2 (the bound of a scene's robot.*.inertia)");
  }
}

/// Every body the dynamics uses: the trunk with the links fixed to it, and each link a moving
/// joint moves with the links fixed to it.
void Reader::check_bodies() const {
  const std::string trunk = opt_.trunk_link.empty() ? model_->getRoot()->name : opt_.trunk_link;
  const std::vector<std::pair<std::string, Placement>> trunk_links(trunk_group_.begin(),
                                                                   trunk_group_.end());
  check_body(trunk, trunk_links, group_inertia(trunk_links));
  for (const auto& [name, j] : model_->joints_) {
    if (!is_moving(*j)) continue;
    const auto group = fixed_group(j->child_link_name);
    check_body(j->child_link_name, group, group_inertia(group));
  }
}

/// A body the dynamics uses, `link` with the links fixed to it (`group`, merged into
/// `body`): its inertia about the COM zero (point masses on one point, or none) or positive
/// definite with the triangle inequality of principal moments. A link's own <inertial> may
/// be degenerate (a camera frame's, a thin hatch's) when the body it joins is not.
void Reader::check_body(const std::string& link,
                        const std::vector<std::pair<std::string, Placement>>& group,
                        const RigidInertia& body) const {
  const Mat3& I = body.inertia_com;
  if (I.isZero(1e-15 * std::max(1.0, I.cwiseAbs().maxCoeff()))) return;
  const std::string who = "link '" + link + "'";
  std::string merged;
  for (const auto& [name, X] : group)
    if (name != link) merged += (merged.empty() ? "'" : ", '") + name + "'";
  if (!merged.empty()) merged = ", of the body with the links fixed to it: " + merged;
  const Vec3 m = principal_moments(I);
  const std::string moments = moments_text(m);
  if (!(m[0] > 0.0)) fail(who + ": inertia not positive definite: " + moments + merged);
  // Sorted ascending: the largest must not exceed the sum of the other two.
  if (m[2] > (m[0] + m[1]) * (1.0 + kInertiaTriangleTolerance))
    fail(who +
         ": inertia breaks the triangle inequality of principal moments (each at most the sum of "
         "the other two): " +
         moments + merged);
}

/// A joint's limits: finite, ordered, within ±bound; `beyond` completes the message of limits
/// past the bound (their unit and the range allowed).
void Reader::check_limits(const std::string& who, const urdf::JointLimits& l, double bound,
                          const std::string& beyond) const {
  if (!std::isfinite(l.lower) || !std::isfinite(l.upper)) fail(who + "limits are not finite");
  if (l.lower > l.upper)
    fail(who + "lower limit " + num(l.lower) + " above upper limit " + num(l.upper));
  if (l.lower < -bound || l.upper > bound)
    fail(who + "limits [" + num(l.lower) + ", " + num(l.upper) + "] " + beyond);
}

void Reader::check_joints() {
  for (const auto& [name, j] : model_->joints_) {
    const std::string who = "joint '" + name + "': ";
    if (!finite_pose(j->parent_to_joint_origin_transform)) fail(who + "<origin> is not finite");
    if (largest_coordinate(j->parent_to_joint_origin_transform) > kMaxRobotCoordinate_m)
      fail(who + "<origin xyz=\"" + position_text(j->parent_to_joint_origin_transform) +
           "\">, expected coordinates within +-" + num(kMaxRobotCoordinate_m) +
           " m (the bound of a scene's robot.*.length and robot.hips)");
    if (j->type != urdf::Joint::FIXED && j->type != urdf::Joint::REVOLUTE &&
        j->type != urdf::Joint::CONTINUOUS && j->type != urdf::Joint::PRISMATIC)
      fail(who + "type " + type_name(j->type) +
           " not supported (hexdyn reads fixed, revolute, continuous and prismatic joints)");
    if (!is_moving(*j)) continue;
    const Vec3 a(j->axis.x, j->axis.y, j->axis.z);
    if (!a.allFinite() || a.norm() < 1e-12)
      fail(who + "axis (" + num(a.x()) + ", " + num(a.y()) + ", " + num(a.z()) +
           ") is not a direction");
    if (const auto& d = j->dynamics) {
      if (!std::isfinite(d->damping) || d->damping < 0.0 || d->damping > kMaxJointFriction)
        fail(who + "<dynamics damping=\"" + num(d->damping) + "\">, expected a number in [0, " +
             num(kMaxJointFriction) + "] N m s/rad");
      if (!std::isfinite(d->friction) || d->friction < 0.0 || d->friction > kMaxJointFriction)
        fail(who + "<dynamics friction=\"" + num(d->friction) + "\">, expected a number in [0, " +
             num(kMaxJointFriction) + "] N m");
    }
    if (j->limits) {
      const urdf::JointLimits& l = *j->limits;
      if (!std::isfinite(l.effort) || l.effort < 0.0 || l.effort > kMaxJointEffort_Nm)
        fail(who + "effort limit " + num(l.effort) + " N m, expected a number in [0, " +
             num(kMaxJointEffort_Nm) +
             "] (0: none; the bound of a scene's allocation.torque_limit)");
      if (!std::isfinite(l.velocity) || l.velocity < 0.0 || l.velocity > kMaxJointVelocity_radps)
        fail(who + "velocity limit " + num(l.velocity) + " rad/s, expected a number in [0, " +
             num(kMaxJointVelocity_radps) + "] (0: none)");
      if (j->type == urdf::Joint::REVOLUTE)
        check_limits(who, l, kMaxJointAngle_rad,
                     "rad, expected limits within [-4 pi, 4 pi] (" + num(-kMaxJointAngle_rad) +
                         ", " + num(kMaxJointAngle_rad) + ")");
      if (j->type == urdf::Joint::PRISMATIC)
        check_limits(who, l, kMaxRobotCoordinate_m,
                     "m, expected limits within +-" + num(kMaxRobotCoordinate_m) +
                         " m (the bound of a scene's robot.*.length)");
    }
  }
}

}  // namespace hexdyn::urdf_detail
