#include "hexdyn/core/result.hpp"

#include <ostream>
#include <utility>

namespace hexdyn {
namespace {

/// The rows `order` names, from the matrices m(part) of each part.
template <typename Matrix, typename Part, typename Get>
Matrix gather_rows(const std::vector<const Part*>& parts, const std::vector<SampleRef>& order,
                   Get m) {
  const Eigen::Index cols = parts.empty() ? 0 : m(*parts.front()).cols();
  Matrix out(static_cast<Eigen::Index>(order.size()), cols);
  for (std::size_t i = 0; i < order.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = m(*parts[order[i].part]).row(order[i].row);
  return out;
}

template <typename T, typename Part, typename Get>
std::vector<T> gather_entries(const std::vector<const Part*>& parts,
                              const std::vector<SampleRef>& order, Get v) {
  std::vector<T> out;
  out.reserve(order.size());
  for (const SampleRef& r : order) out.push_back(v(*parts[r.part])[r.row]);
  return out;
}

}  // namespace

KinematicsResult gather_samples(const std::vector<const KinematicsResult*>& parts,
                                const std::vector<SampleRef>& order) {
  using K = KinematicsResult;
  KinematicsResult out;
  out.time_s = gather_entries<double>(
      parts, order, [](const K& k) -> auto& { return k.time_s; });
  for (RowMatrix K::*m :
       {&K::base_position, &K::base_orientation_wxyz, &K::base_linear_velocity,
        &K::base_angular_velocity, &K::base_linear_acceleration, &K::base_angular_acceleration,
        &K::joint_position, &K::joint_velocity, &K::joint_acceleration, &K::foot_position,
        &K::foot_velocity, &K::foot_center, &K::com_position})
    out.*m = gather_rows<RowMatrix>(
        parts, order, [m](const K& k) -> auto& { return k.*m; });
  out.contact_phase = gather_rows<RowMatrixI8>(
      parts, order, [](const K& k) -> auto& { return k.contact_phase; });
  out.sample_kind.reserve(order.size());
  for (const SampleRef& r : order) {
    const K& k = *parts[r.part];
    out.sample_kind.push_back(k.sample_kind.empty() ? std::int8_t{0} : k.sample_kind[r.row]);
  }
  return out;
}

DynamicsResult gather_samples(const std::vector<const DynamicsResult*>& parts,
                              const std::vector<SampleRef>& order) {
  using D = DynamicsResult;
  DynamicsResult out;
  out.present = true;
  for (RowMatrix D::*m :
       {&D::joint_torque, &D::contact_force, &D::penetration, &D::utilized_friction})
    out.*m = gather_rows<RowMatrix>(
        parts, order, [m](const D& d) -> auto& { return d.*m; });
  out.solver_status = gather_entries<SolverStatus>(
      parts, order, [](const D& d) -> auto& { return d.solver_status; });
  for (std::vector<double> D::*v :
       {&D::solver_iterations, &D::solver_objective, &D::solver_seconds, &D::solver_max_violation})
    out.*v = gather_entries<double>(
        parts, order, [v](const D& d) -> auto& { return d.*v; });
  out.slip = gather_rows<RowMatrixI8>(
      parts, order, [](const D& d) -> auto& { return d.slip; });
  if (!parts.empty() && !parts.front()->required_friction.empty()) {
    out.required_friction = gather_entries<double>(
        parts, order, [](const D& d) -> auto& { return d.required_friction; });
    out.required_friction_leg = gather_entries<std::int8_t>(
        parts, order, [](const D& d) -> auto& { return d.required_friction_leg; });
  }
  out.solver_messages = gather_entries<std::string>(
      parts, order, [](const D& d) -> auto& { return d.solver_messages; });
  if (!parts.empty() && parts.front()->has_drive())
    for (RowMatrix D::*m : {&D::drive_torque, &D::drive_torque_limit, &D::drive_torque_lower_limit})
      out.*m = gather_rows<RowMatrix>(
          parts, order, [m](const D& d) -> auto& { return d.*m; });
  return out;
}

void KinematicsResult::resize(int T, int legs, int joints, bool zero) {
  time_s.assign(T, 0.0);
  const auto size = [&](auto& m, int columns) {
    m.resize(T, columns);
    if (zero) m.setZero();
  };
  for (RowMatrix* m : {&base_position, &base_linear_velocity, &base_angular_velocity,
                       &base_linear_acceleration, &base_angular_acceleration, &com_position})
    size(*m, 3);
  size(base_orientation_wxyz, 4);
  for (RowMatrix* m : {&joint_position, &joint_velocity, &joint_acceleration}) size(*m, joints);
  for (RowMatrix* m : {&foot_position, &foot_velocity, &foot_center}) size(*m, 3 * legs);
  size(contact_phase, legs);
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
