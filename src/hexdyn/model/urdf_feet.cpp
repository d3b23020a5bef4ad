// The feet of a URDF robot (docs/user/robots.md): where each chain's foot is, its collision
// shapes, the check that the foot point lies inside them, and the mapping of chains to legs.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/core/value_bounds.hpp"
#include "hexdyn/model/urdf_feet_detail.hpp"

namespace hexdyn::urdf_detail {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

/// The foot point p_foot_last [m] of a chain (named `chain` in messages) in its last link's
/// frame, from the links fixed to that link (`group`, with their placements in its frame):
/// a named foot link, else (robot.foot_offset is set per leg by finish_feet, once the legs
/// are mapped) a sphere <collision>, else the end of the links fixed to it.
void Reader::locate_foot(const std::vector<std::pair<std::string, Placement>>& group,
                         const std::string& chain, UrdfLeg& leg) {
  const std::string last = leg.last().link;
  leg.collisions = collision_shapes(group);
  bool found = false;
  for (const auto& f : opt_.foot_links) {
    for (const auto& [name, Xl] : group) {
      if (name != f) continue;
      leg.p_foot_last = Xl.p;
      leg.foot_source = f;
      ++foot_link_used_[f];
      found = true;
    }
  }
  if (!opt_.foot_links.empty() && !found)
    fail(chain + "none of robot.foot_links is fixed to its last link '" + last + "'");
  if (found || opt_.foot_offset) return;
  // The default sphere foot: of several spheres, the one farthest from the last joint.
  const CollisionShape* sphere = nullptr;
  for (const CollisionShape& s : leg.collisions)
    if (s.kind == CollisionShape::Kind::kSphere && s.size.x() > 0.0 &&
        (sphere == nullptr || s.p.norm() > sphere->p.norm()))
      sphere = &s;
  if (sphere != nullptr) {
    if (sphere->size.x() > kMaxFootRadius_m)
      fail("link '" + sphere->link + "': sphere <collision> of radius " + num(sphere->size.x()) +
           " m taken as the foot of chain '" + leg.joints.front().name + "', expected at most " +
           num(kMaxFootRadius_m) + " m; give robot.foot_offset or robot.foot_links");
    leg.p_foot_last = sphere->p;
    leg.foot_radius_m = sphere->size.x();
    leg.foot_kind = FootSource::kSphereCollision;
    leg.foot_source = sphere->link;
    return;
  }
  const auto [end, X_end] = fixed_chain_end(group, last, chain);
  leg.p_foot_last = X_end.p;
  leg.foot_source = end;
}

/// The <collision> geometries of the links of `group`, placed in the frame of its first link.
std::vector<CollisionShape> Reader::collision_shapes(
    const std::vector<std::pair<std::string, Placement>>& group) const {
  std::vector<CollisionShape> out;
  for (const auto& [name, X] : group) {
    for (const auto& col : model_->getLink(name)->collision_array) {
      if (!col || !col->geometry) continue;
      CollisionShape s;
      s.link = name;
      const Placement O = X * to_placement(col->origin);
      s.p = O.p;
      s.R = O.R;
      const urdf::Geometry& g = *col->geometry;
      switch (g.type) {
        case urdf::Geometry::SPHERE:
          s.kind = CollisionShape::Kind::kSphere;
          s.size.x() = static_cast<const urdf::Sphere&>(g).radius;
          break;
        case urdf::Geometry::BOX: {
          const urdf::Vector3& d = static_cast<const urdf::Box&>(g).dim;
          s.kind = CollisionShape::Kind::kBox;
          s.size = Vec3(d.x, d.y, d.z);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& c = static_cast<const urdf::Cylinder&>(g);
          s.kind = CollisionShape::Kind::kCylinder;
          s.size = Vec3(c.radius, c.length, 0.0);
          break;
        }
        default:
          s.kind = CollisionShape::Kind::kMesh;
      }
      out.push_back(s);
    }
  }
  return out;
}

/// The feet once the legs are mapped: robot.foot_offset per leg (with its foot check),
/// robot.foot_radius, and the refusal of a foot on its last joint's axis.
void Reader::finish_feet(UrdfRobot& robot) const {
  const int n = robot.n_legs();
  if (opt_.foot_offset && opt_.foot_links.empty() && opt_.foot_offset->size() != 1 &&
      static_cast<int>(opt_.foot_offset->size()) != n) {
    std::string points;
    for (const Vec3& p : *opt_.foot_offset)
      points += (points.empty() ? "[" : ", ") +
                ("[" + num(p.x()) + ", " + num(p.y()) + ", " + num(p.z()) + "]");
    fail("robot.foot_offset: got " + std::to_string(opt_.foot_offset->size()) + " points " +
         points + "], expected one [x, y, z] for every leg or one per leg (" + std::to_string(n) +
         " legs, " + leg_name(0) + " … " + leg_name(n - 1) + ")");
  }
  for (int leg = 0; leg < n; ++leg) {
    UrdfLeg& l = robot.legs[leg];
    const std::string chain = "leg " + leg_name(leg) + " (chain '" + l.joints.front().name + "'): ";
    if (opt_.foot_offset && opt_.foot_links.empty()) {
      l.p_foot_last = (*opt_.foot_offset)[opt_.foot_offset->size() == 1 ? 0 : leg];
      l.foot_kind = FootSource::kFootOffset;
      l.foot_source = "robot.foot_offset";
      check_foot_inside(leg, l);
    }
    if (opt_.foot_radius) l.foot_radius_m = *opt_.foot_radius;
    const UrdfJoint& last = l.last();
    const Vec3& a = last.axis;
    if (last.type != UrdfJointType::kPrismatic &&
        (l.p_foot_last - a.dot(l.p_foot_last) * a).norm() < 1e-6)
      fail(chain + "foot (" + l.foot_source + ") lies on the axis of its last joint '" + last.name +
           "' (link '" + last.link +
           "'): the description has no foot frame; name the foot links (robot.foot_links) or "
           "give robot.foot_offset");
  }
}

namespace {

/// How far the point x (last link frame) lies outside the primitive s [m]; 0 inside.
double distance_outside(const CollisionShape& s, const Vec3& x) {
  const Vec3 local = s.R.transpose() * (x - s.p);
  switch (s.kind) {
    case CollisionShape::Kind::kSphere:
      return std::max(0.0, local.norm() - s.size.x());
    case CollisionShape::Kind::kBox:
      return (local.cwiseAbs() - 0.5 * s.size).cwiseMax(0.0).norm();
    case CollisionShape::Kind::kCylinder:
      return std::hypot(std::max(0.0, local.head<2>().norm() - s.size.x()),
                        std::max(0.0, std::abs(local.z()) - 0.5 * s.size.y()));
    case CollisionShape::Kind::kMesh:
      break;
  }
  return kInf;
}

const char* kind_name(CollisionShape::Kind k) {
  switch (k) {
    case CollisionShape::Kind::kSphere:
      return "sphere";
    case CollisionShape::Kind::kBox:
      return "box";
    case CollisionShape::Kind::kCylinder:
      return "cylinder";
    case CollisionShape::Kind::kMesh:
      break;
  }
  return "mesh";
}

}  // namespace

/// The foot check of a robot.foot_offset point (urdf_reader.hpp): l.foot_check says what it
/// found; a point outside every primitive of a last link without meshes fails, naming the leg.
void Reader::check_foot_inside(int leg, UrdfLeg& l) const {
  const std::string last = l.last().link;
  double nearest = kInf;
  std::string kinds, meshes;
  for (const CollisionShape& s : l.collisions) {
    if (s.kind == CollisionShape::Kind::kMesh) {
      if (meshes.find("'" + s.link + "'") == std::string::npos)
        meshes += (meshes.empty() ? "'" : ", '") + s.link + "'";
      continue;
    }
    const double d = distance_outside(s, l.p_foot_last);
    if (d <= kFootCheckTolerance_m) {
      l.foot_check = std::string("inside the ") + kind_name(s.kind) + " <collision> of " + s.link;
      return;
    }
    nearest = std::min(nearest, d);
    kinds += (kinds.empty() ? "" : ", ") + std::string(kind_name(s.kind));
  }
  if (!meshes.empty()) {
    l.foot_check = "not checked: mesh <collision> geometry of " + meshes + " (files not read)";
    return;
  }
  if (kinds.empty()) {
    l.foot_check = "not checked: no <collision> on its last link '" + last + "'";
    return;
  }
  const Vec3& p = l.p_foot_last;
  fail("leg " + leg_name(leg) + " (chain '" + l.joints.front().name + "'): robot.foot_offset (" +
       num(p.x()) + ", " + num(p.y()) + ", " + num(p.z()) +
       ") m lies outside the <collision> geometry of its last link '" + last + "' (" + kinds +
       "; " + num(nearest) +
       " m from the nearest), expected a point inside it (robot.foot_offset may give each "
       "leg its own point: a list of one per leg or a map by leg name)");
}

/// The end of the chain of links fixed to link `last` (group: those links, placed in its
/// frame), and its placement; a link carrying two fixed links fails.
std::pair<std::string, Placement> Reader::fixed_chain_end(
    const std::vector<std::pair<std::string, Placement>>& group, const std::string& last,
    const std::string& chain) const {
  std::string end = last;
  Placement X_end;
  for (;;) {
    std::vector<std::pair<std::string, Placement>> kids;
    for (const auto& [name, Xl] : group) {
      const auto pj = parent_joint_.find(name);
      if (name != last && pj != parent_joint_.end() && pj->second->parent_link_name == end)
        kids.emplace_back(name, Xl);
    }
    if (kids.empty()) break;
    if (kids.size() > 1)
      fail(chain + "links '" + kids[0].first + "' and '" + kids[1].first + "' are both fixed to '" +
           end + "': name the foot links (robot.foot_links) or give robot.foot_offset");
    end = kids[0].first;
    X_end = kids[0].second;
  }
  return {end, X_end};
}

}  // namespace hexdyn::urdf_detail
