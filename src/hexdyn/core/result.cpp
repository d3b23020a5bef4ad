#include "hexdyn/core/result.hpp"

#include <ostream>

namespace hexdyn {

void KinematicsResult::resize(int T) {
  time_s.assign(T, 0.0);
  for (RowMatrix* m : {&base_position, &base_linear_velocity, &base_angular_velocity,
                       &base_linear_acceleration, &base_angular_acceleration, &com_position})
    m->setZero(T, 3);
  base_orientation_wxyz.setZero(T, 4);
  for (RowMatrix* m :
       {&joint_position, &joint_velocity, &joint_acceleration, &foot_position, &foot_velocity})
    m->setZero(T, kJoints);
  contact_phase.setZero(T, kLegs);
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
