#include "dynamics_model.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/urdf_reader.hpp"
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn_python {
namespace {

using hexdyn::Vec3;

/// The scene's robot.* keys as the URDF reader takes them, from the tree `robot`.
class RobotKeys {
 public:
  RobotKeys(const YAML::Node& robot, const std::string& file) : robot_(robot), file_(file) {}

  [[noreturn]] void refuse(const std::string& key, const YAML::Node& v,
                           const std::string& expected) const {
    throw hexdyn::ConfigError(file_ + ": robot." + key + ": got " + hexdyn::yaml_for_message(v) +
                              ", expected " + expected);
  }

  /// robot.KEY as a non-empty string, `fallback` when absent.
  std::string text(const std::string& key, const std::string& fallback,
                   const char* expected) const {
    const YAML::Node v = robot_[key];
    if (!v.IsDefined() || v.IsNull()) return fallback;
    if (!v.IsScalar() || v.Scalar().empty()) refuse(key, v, expected);
    return v.Scalar();
  }

  /// A finite number of `v`, nullopt when it is none.
  static std::optional<double> number(const YAML::Node& v) {
    double x = 0.0;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, x) || !std::isfinite(x))
      return std::nullopt;
    return x;
  }

  /// [x, y, z] of `v`, nullopt when it is not three finite numbers.
  static std::optional<Vec3> point(const YAML::Node& v) {
    if (!v.IsSequence() || v.size() != 3) return std::nullopt;
    Vec3 p;
    for (std::size_t i = 0; i < 3; ++i) {
      const std::optional<double> x = number(v[i]);
      if (!x) return std::nullopt;
      p[static_cast<Eigen::Index>(i)] = *x;
    }
    return p;
  }

  std::vector<std::string> foot_links() const {
    const YAML::Node v = robot_["foot_links"];
    std::vector<std::string> out;
    if (!v.IsDefined() || v.IsNull()) return out;
    const char* expected = "a list of link names, one per leg";
    if (!v.IsSequence()) refuse("foot_links", v, expected);
    for (const YAML::Node& name : v) {
      if (!name.IsScalar() || name.Scalar().empty()) refuse("foot_links", v, expected);
      out.push_back(name.Scalar());
    }
    return out;
  }

  /// robot.foot_offset: one [x, y, z], one per leg in leg order, or a map {L1: …, L2: …}.
  std::optional<std::vector<Vec3>> foot_offset() const {
    const YAML::Node v = robot_["foot_offset"];
    if (!v.IsDefined() || v.IsNull()) return std::nullopt;
    const char* expected =
        "[x, y, z] [m], one [x, y, z] per leg in the order L1 … Ln, or a map "
        "{L1: [x, y, z], …} naming every leg";
    if (const std::optional<Vec3> one = point(v)) return std::vector<Vec3>{*one};
    std::vector<Vec3> out;
    if (v.IsSequence()) {
      for (const YAML::Node& p : v) out.push_back(point(p).value_or(Vec3::Constant(NAN)));
    } else if (v.IsMap()) {
      for (std::size_t l = 1; l <= v.size(); ++l)
        out.push_back(point(v["L" + std::to_string(l)]).value_or(Vec3::Constant(NAN)));
    }
    if (out.empty()) refuse("foot_offset", v, expected);
    for (const Vec3& p : out)
      if (!p.allFinite()) refuse("foot_offset", v, expected);
    return out;
  }

  std::optional<double> foot_radius() const {
    const YAML::Node v = robot_["foot_radius"];
    if (!v.IsDefined() || v.IsNull()) return std::nullopt;
    const std::optional<double> r = number(v);
    if (!r || *r < 0.0) refuse("foot_radius", v, "a radius >= 0 [m]");
    return r;
  }

  hexdyn::UrdfReadOptions options() const {
    hexdyn::UrdfReadOptions opt;
    opt.trunk_link = text("trunk_link", "", "a link name");
    opt.forward_axis = text("forward_axis", "+x", "one of +x, -x, +y, -y");
    opt.foot_links = foot_links();
    opt.foot_offset = foot_offset();
    opt.foot_radius = foot_radius();
    return opt;
  }

 private:
  const YAML::Node& robot_;
  const std::string& file_;
};

/// Whether the stages after the model (kinematics, the scene's stance keys) take `robot` in
/// this build: at most six legs, each of three revolute (or continuous) joints.
bool other_stages_take(const hexdyn::UrdfRobot& robot) {
  if (robot.n_legs() > hexdyn::kLegs) return false;
  for (const hexdyn::UrdfLeg& leg : robot.legs) {
    if (leg.n_joints() != hexdyn::kJointsPerLeg) return false;
    for (const hexdyn::UrdfJoint& j : leg.joints)
      if (j.type == hexdyn::UrdfJointType::kPrismatic) return false;
  }
  return true;
}

}  // namespace

hexdyn::RobotModel scene_dynamics_model(const std::string& scene_path,
                                        const std::vector<hexdyn::Override>& overrides) {
  YAML::Node tree = hexdyn::load_scene_tree(scene_path);
  for (const hexdyn::Override& ov : overrides) hexdyn::apply_override(tree, ov, scene_path);
  const YAML::Node robot = static_cast<const YAML::Node&>(tree)["robot"];
  if (robot.IsMap() && robot["urdf"].IsDefined()) {
    const RobotKeys keys(robot, scene_path);
    const std::string urdf = keys.text("urdf", "", "the path of a URDF file");
    if (!urdf.empty()) {
      const hexdyn::UrdfRobot description = hexdyn::read_urdf_robot(urdf, keys.options());
      if (!other_stages_take(description)) return hexdyn::build_dynamics_model(description);
    }
  }
  return hexdyn::build_robot_model(hexdyn::load_scene(scene_path, overrides).robot);
}

}  // namespace hexdyn_python
