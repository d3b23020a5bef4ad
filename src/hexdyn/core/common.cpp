#include "hexdyn/core/common.hpp"

#include <cstdio>

namespace hexdyn {

std::string format_number(double x, int significant_digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant_digits, x);
  return buf;
}

std::string leg_name(int leg) { return "L" + std::to_string(leg + 1); }

std::string joint_name(int leg, int joint) {
  static const char* kSuffix[kJointsPerLeg] = {"coxa", "femur", "tibia"};
  return leg_name(leg) + "_" + kSuffix[joint];
}

Mat3 bryant_to_rotation(const Vec3& eta) {
  return (Eigen::AngleAxisd(eta.x(), Vec3::UnitX()) * Eigen::AngleAxisd(eta.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(eta.z(), Vec3::UnitZ()))
      .toRotationMatrix();
}

}  // namespace hexdyn
