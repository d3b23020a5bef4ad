#include "hexdyn/core/common.hpp"

#include <cstdio>

namespace hexdyn {

std::string format_number(double x, int significant_digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant_digits, x);
  return buf;
}

std::string leg_name(int leg) { return "L" + std::to_string(leg + 1); }

std::string joint_name(int leg, int joint, int leg_joints) {
  static const char* kSuffix[3] = {"coxa", "femur", "tibia"};
  if (leg_joints == 3) return leg_name(leg) + "_" + kSuffix[joint];
  return leg_name(leg) + "_j" + std::to_string(joint + 1);
}

Mat3 bryant_to_rotation(const Vec3& eta) {
  return (Eigen::AngleAxisd(eta.x(), Vec3::UnitX()) * Eigen::AngleAxisd(eta.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(eta.z(), Vec3::UnitZ()))
      .toRotationMatrix();
}

}  // namespace hexdyn
