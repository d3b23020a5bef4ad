#include "hexdyn/core/result.hpp"

#include <ostream>

namespace hexdyn {

void KinematicsResult::resize(int T, bool zero) {
  time_s.assign(T, 0.0);
  const auto size = [&](auto& m, int columns) {
    m.resize(T, columns);
    if (zero) m.setZero();
  };
  for (RowMatrix* m : {&base_position, &base_linear_velocity, &base_angular_velocity,
                       &base_linear_acceleration, &base_angular_acceleration, &com_position})
    size(*m, 3);
  size(base_orientation_wxyz, 4);
  for (RowMatrix* m :
       {&joint_position, &joint_velocity, &joint_acceleration, &foot_position, &foot_velocity})
    size(*m, kJoints);
  size(contact_phase, kLegs);
  sample_kind.assign(T, 0);
}

std::ostream& operator<<(std::ostream& os, SolverStatus status) {
  switch (status) {
    case SolverStatus::kOptimal:
      return os << "optimal";
    case SolverStatus::kRelaxed:
      return os << "relaxed";
    case SolverStatus::kFailed:
      return os << "failed";
  }
  return os << "unknown";
}

std::vector<std::int8_t> solver_status_codes(const std::vector<SolverStatus>& status) {
  std::vector<std::int8_t> codes(status.size());
  for (std::size_t i = 0; i < status.size(); ++i) codes[i] = static_cast<std::int8_t>(status[i]);
  return codes;
}

}  // namespace hexdyn
