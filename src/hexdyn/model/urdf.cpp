#include "hexdyn/model/urdf.hpp"

#include <charconv>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace hexdyn {
namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Numbers with 17 significant digits (round-trip exact); −0 printed as 0.
std::string number(double x) {
  // As %.17g (what setprecision(17) gives), without a stream per number.
  char buf[32];
  const auto r =
      std::to_chars(buf, buf + sizeof buf, x == 0.0 ? 0.0 : x, std::chars_format::general, 17);
  return std::string(buf, r.ptr);
}

std::string triple(const Vec3& v) {
  return number(v.x()) + ' ' + number(v.y()) + ' ' + number(v.z());
}

/// Output document; numbers go through number() / triple().
class UrdfStream {
 public:
  std::ostringstream& os() { return os_; }
  std::string triple(const Vec3& v) { return hexdyn::triple(v); }
  std::string number(double x) { return hexdyn::number(x); }

 private:
  std::ostringstream os_;
};

void write_inertial(UrdfStream& u, const RigidInertia& in) {
  const Mat3& I = in.inertia_com;
  auto& os = u.os();
  os << "    <inertial>\n"
     << "      <origin xyz=\"" << u.triple(in.com_m) << "\" rpy=\"0 0 0\"/>\n"
     << "      <mass value=\"" << u.number(in.mass_kg) << "\"/>\n"
     << "      <inertia ixx=\"" << u.number(I(0, 0)) << "\" ixy=\"" << u.number(I(0, 1))
     << "\" ixz=\"" << u.number(I(0, 2)) << "\" iyy=\"" << u.number(I(1, 1)) << "\" iyz=\""
     << u.number(I(1, 2)) << "\" izz=\"" << u.number(I(2, 2)) << "\"/>\n"
     << "    </inertial>\n";
}

void write_link(UrdfStream& u, const std::string& name, const RigidInertia* inertia) {
  // A massless body (massless legs, no payload) has no <inertial>, as the URDF
  // specification says: an <inertial> with zero mass is not a valid body.
  if (inertia == nullptr || inertia->mass_kg == 0.0) {
    u.os() << "  <link name=\"" << name << "\"/>\n";
    return;
  }
  u.os() << "  <link name=\"" << name << "\">\n";
  write_inertial(u, *inertia);
  u.os() << "  </link>\n";
}

struct JointLimit {
  double lower_rad, upper_rad, effort_Nm, velocity_radps;
};

/// <dynamics damping friction> of a joint.
struct JointDynamics {
  double damping, friction;
};

void write_joint(UrdfStream& u, const std::string& name, const char* type,
                 const std::string& parent, const std::string& child, const Vec3& p, const Mat3& R,
                 const Vec3* axis, const JointLimit* limit,
                 const JointDynamics* dynamics = nullptr) {
  auto& os = u.os();
  os << "  <joint name=\"" << name << "\" type=\"" << type << "\">\n"
     << "    <parent link=\"" << parent << "\"/>\n"
     << "    <child link=\"" << child << "\"/>\n"
     << "    <origin xyz=\"" << u.triple(p) << "\" rpy=\"" << u.triple(rotation_to_rpy(R))
     << "\"/>\n";
  if (axis != nullptr) os << "    <axis xyz=\"" << u.triple(*axis) << "\"/>\n";
  if (limit != nullptr && std::string(type) == "continuous")
    os << "    <limit effort=\"" << u.number(limit->effort_Nm) << "\" velocity=\""
       << u.number(limit->velocity_radps) << "\"/>\n";
  else if (limit != nullptr)
    os << "    <limit lower=\"" << u.number(limit->lower_rad) << "\" upper=\""
       << u.number(limit->upper_rad) << "\" effort=\"" << u.number(limit->effort_Nm)
       << "\" velocity=\"" << u.number(limit->velocity_radps) << "\"/>\n";
  if (dynamics != nullptr)
    os << "    <dynamics damping=\"" << u.number(dynamics->damping) << "\" friction=\""
       << u.number(dynamics->friction) << "\"/>\n";
  os << "  </joint>\n";
}

}  // namespace

Vec3 rotation_to_rpy(const Mat3& R) {
  // R = Rz(y) Ry(p) Rx(r): R(2,0) = −sin p, R(2,1) = cos p sin r, R(2,2) = cos p cos r,
  // R(0,0) = cos y cos p, R(1,0) = sin y cos p.
  const double cos_pitch = std::hypot(R(0, 0), R(1, 0));
  const double pitch = std::atan2(-R(2, 0), cos_pitch);
  if (cos_pitch < 1e-12) {
    // Gimbal lock: only yaw ∓ roll is defined; take roll = 0.
    return Vec3(0.0, pitch, std::atan2(-R(0, 1), R(1, 1)));
  }
  return Vec3(std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0)));
}

std::string robot_urdf(const RobotModel& model, const std::string& robot_name) {
  UrdfStream u;
  auto& os = u.os();
  os << "<?xml version=\"1.0\"?>\n"
     << "<!-- Robot as simulated by hexdyn: link frames are the simulation's body frames;\n"
     << "     trunk = body frame L0 at P0 (x right, y forward, z up). SI units. -->\n"
     << "<robot name=\"" << xml_escape(robot_name) << "\">\n";
  // The root link is the description's root link frame (a YAML robot: the trunk frame).
  const bool root_moved = !(model.p_B_root.isZero(0.0) && model.B_R_root == Mat3::Identity());
  const Mat3 root_R_B = model.B_R_root.transpose();
  RigidInertia trunk = model.trunk_only;
  if (root_moved) {
    trunk.com_m = root_R_B * (trunk.com_m - model.p_B_root);
    trunk.inertia_com = root_R_B * trunk.inertia_com * model.B_R_root;
  }
  write_link(u, "trunk", &trunk);
  write_link(u, "payload", &model.payload);
  write_joint(u, "payload_mount", "fixed", "trunk", "payload", Vec3::Zero(), Mat3::Identity(),
              nullptr, nullptr);
  for (int leg = 0; leg < model.legs(); ++leg) {
    const std::string prefix = model.leg(leg).name + "_";
    std::string parent = "trunk";
    for (int j = 0; j < model.leg(leg).n_joints; ++j) {
      const int b = model.body(leg, j);
      // L{i}_coxa_link … for a leg of three joints, L{i}_j1_link … otherwise.
      const std::string child = joint_name(leg, j, model.leg(leg).n_joints) + "_link";
      const int k = model.joint(leg, j);
      const JointLimit limit{
          model.joint_lower_rad[k], model.joint_upper_rad[k],
          std::isfinite(model.effort_limit_Nm[k]) ? model.effort_limit_Nm[k] : kUrdfEffortLimitNm,
          std::isfinite(model.velocity_limit_radps[k]) ? model.velocity_limit_radps[k]
                                                       : kUrdfVelocityLimitRadps};
      const bool continuous = !std::isfinite(limit.lower_rad) && !std::isfinite(limit.upper_rad);
      write_link(u, child, &model.inertia[b]);
      Vec3 p = model.p_parent_joint[b];
      Mat3 R = model.R_parent_joint[b];
      if (j == 0 && root_moved) {
        p = root_R_B * (p - model.p_B_root);
        R = root_R_B * R;
      }
      write_joint(u, model.joint_source_names[k], continuous ? "continuous" : "revolute", parent,
                  child, p, R, &model.axis[b], &limit);
      parent = child;
    }
    if (model.foot_radius_m[leg] > 0.0)  // a sphere foot: its <collision>, centred on the link
      os << "  <link name=\"" << prefix << "foot\">\n    <collision>\n      <geometry><sphere "
         << "radius=\"" << u.number(model.foot_radius_m[leg])
         << "\"/></geometry>\n    </collision>\n  </link>\n";
    else
      write_link(u, prefix + "foot", nullptr);
    write_joint(u, prefix + "foot_fixed", "fixed", parent, prefix + "foot", model.p_foot_last[leg],
                Mat3::Identity(), nullptr, nullptr);
  }
  os << "</robot>\n";
  return os.str();
}

std::string description_urdf(const UrdfRobot& robot) {
  UrdfStream u;
  auto& os = u.os();
  os << "<?xml version=\"1.0\"?>\n"
     << "<!-- Robot description as hexdyn read it: links fixed to a moving body merged into it;\n"
     << "     the root link is the trunk link. SI units. -->\n"
     << "<robot name=\"" << xml_escape(robot.name) << "\">\n";
  // Everything in the trunk link's frame U: B_R_U is a signed permutation (exact both ways).
  const Mat3 U_R_B = robot.B_R_U.transpose();
  RigidInertia trunk = robot.trunk;
  trunk.com_m = U_R_B * trunk.com_m;
  trunk.inertia_com = U_R_B * trunk.inertia_com * robot.B_R_U;
  write_link(u, xml_escape(robot.trunk_link), &trunk);
  for (int leg = 0; leg < robot.n_legs(); ++leg) {
    const UrdfLeg& l = robot.legs[leg];
    std::string parent = xml_escape(robot.trunk_link);
    for (std::size_t j = 0; j < l.joints.size(); ++j) {
      const UrdfJoint& joint = l.joints[j];
      const std::string child = xml_escape(joint.link);
      // The description's "none" (+inf) is written as 0, which reads back as none.
      const JointLimit limit{joint.lower_rad, joint.upper_rad,
                             std::isfinite(joint.effort_Nm) ? joint.effort_Nm : 0.0,
                             std::isfinite(joint.velocity_radps) ? joint.velocity_radps : 0.0};
      const char* type = joint.type == UrdfJointType::kPrismatic    ? "prismatic"
                         : joint.type == UrdfJointType::kContinuous ? "continuous"
                                                                    : "revolute";
      write_link(u, child, &joint.inertia);
      Vec3 p = joint.p_parent_joint;
      Mat3 R = joint.R_parent_joint;
      if (j == 0) {
        p = U_R_B * p;
        R = U_R_B * R;
      }
      const JointDynamics dynamics{joint.damping_Nmsprad, joint.friction_Nm};
      const bool has_dynamics = dynamics.damping != 0.0 || dynamics.friction != 0.0;
      write_joint(u, xml_escape(joint.name), type, parent, child, p, R, &joint.axis, &limit,
                  has_dynamics ? &dynamics : nullptr);
      parent = child;
    }
    const std::string foot = leg_name(leg) + "_foot";
    if (l.foot_radius_m > 0.0)
      os << "  <link name=\"" << foot << "\">\n    <collision>\n      <geometry><sphere "
         << "radius=\"" << u.number(l.foot_radius_m)
         << "\"/></geometry>\n    </collision>\n  </link>\n";
    else
      write_link(u, foot, nullptr);
    write_joint(u, foot + "_fixed", "fixed", parent, foot, l.p_foot_last, Mat3::Identity(), nullptr,
                nullptr);
  }
  os << "</robot>\n";
  return os.str();
}

}  // namespace hexdyn
