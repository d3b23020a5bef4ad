#include "dynamics.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "edge.hpp"
#include "forward_dynamics_args.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/core/spatial.hpp"
#include "hexdyn/dynamics/forward_dynamics.hpp"
#include "hexdyn/model/root_link.hpp"

namespace hexdyn_python {
namespace {

namespace py = pybind11;
using hexdyn::Vec3;
using OptionalArray = std::optional<DoubleArray>;

/// The arguments of one call, each one state or T of them; a Samples without data was not
/// given (the foot forces: none; the foot normals: +z; the arguments mass_matrix does not take:
/// zero).
struct StateArgs {
  const char* function = "";
  Samples p, quat, q, v, w, qd, a, dw, qdd, tau, forces, normals;
  py::ssize_t count = 1;
  bool batched = false;
  std::vector<Samples*> all() {
    return {&p, &quat, &q, &v, &w, &qd, &a, &dw, &qdd, &tau, &forces, &normals};
  }
};

/// Reads `array` into `to`: one sample of `shape` or (T, *shape); ValueError when it is None
/// unless it is optional.
void take(StateArgs& s, const OptionalArray& array, std::vector<py::ssize_t> shape,
          const char* name, Samples& to, bool optional = false) {
  if (array)
    to = samples_of(*array, shape, name, s.function);
  else if (!optional)
    throw py::value_error(std::string(s.function) + ": " + name + " is None, expected an array");
}

/// Reads the arguments forward_dynamics and inverse_dynamics share: the root link's pose and
/// twist, the joint angles and rates of the model's J joints.
void take_state(StateArgs& s, py::ssize_t J, const OptionalArray& base_position,
                const OptionalArray& base_orientation, const OptionalArray& joint_position,
                const OptionalArray& base_linear_velocity,
                const OptionalArray& base_angular_velocity, const OptionalArray& joint_velocity) {
  take(s, base_position, {3}, "base_position", s.p);
  take(s, base_orientation, {4}, "base_orientation", s.quat);
  take(s, joint_position, {J}, "joint_position", s.q);
  take(s, base_linear_velocity, {3}, "base_linear_velocity", s.v);
  take(s, base_angular_velocity, {3}, "base_angular_velocity", s.w);
  take(s, joint_velocity, {J}, "joint_velocity", s.qd);
}

/// Reads the foot forces and normals of the model's L legs, both optional.
void take_feet(StateArgs& s, py::ssize_t L, const OptionalArray& foot_forces,
               const OptionalArray& foot_normals) {
  take(s, foot_forces, {L, 3}, "foot_forces", s.forces, true);
  take(s, foot_normals, {L, 3}, "foot_normals", s.normals, true);
}

/// Checks the arguments together: one sample each or the same T, finite, unit quaternions,
/// foot normals under sphere feet (ValueError in one line naming the argument).
void check_args(StateArgs& s, const hexdyn::RobotModel& model) {
  const Samples& first = s.quat;
  s.batched = first.batched;
  s.count = first.count;
  for (const Samples* x : s.all())
    if (x->data != nullptr && (x->batched != s.batched || x->count != s.count))
      throw py::value_error(
          std::string(s.function) +
          ": the arguments hold different numbers of samples (base_orientation: " +
          std::to_string(s.batched ? s.count : 0) + " along its first axis, " + x->name + ": " +
          std::to_string(x->batched ? x->count : 0) + ")");
  for (const Samples* x : s.all()) check_finite(*x);
  check_unit_quaternions(s.quat);
  check_sphere_foot_normals(model, s.normals);
}

Vec3 vec3_or_zero(const Samples& s, py::ssize_t i) {
  return s.data != nullptr ? Vec3(s.at(i)) : Vec3::Zero();
}

hexdyn::JointVector joints_or_zero(const Samples& s, py::ssize_t i, int n) {
  if (s.data == nullptr) return hexdyn::JointVector::Zero(n);
  return Eigen::Map<const Eigen::VectorXd>(s.at(i), n);
}

/// Sample i's root link state (/base/*) as the trunk's (dynamics/rnea.hpp takes the trunk's).
hexdyn::BaseState trunk_state(const hexdyn::RobotModel& model, const StateArgs& s, py::ssize_t i) {
  const double* quat = s.quat.at(i);
  hexdyn::BaseState root;
  root.W_R_B =
      Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).normalized().toRotationMatrix();
  root.p_W = vec3_or_zero(s.p, i);
  root.v_W = vec3_or_zero(s.v, i);
  root.omega_W = vec3_or_zero(s.w, i);
  root.a_W = vec3_or_zero(s.a, i);
  root.omegadot_W = vec3_or_zero(s.dw, i);
  return hexdyn::trunk_state_from_root_link(model, root);
}

/// Sample i's foot forces and normals (forces: false when none were given).
struct FootInputs {
  hexdyn::LegArray<Vec3> forces, normals;
  bool has_forces = false;
};

FootInputs foot_inputs(const hexdyn::RobotModel& model, const StateArgs& s, py::ssize_t i) {
  FootInputs f;
  f.has_forces = s.forces.data != nullptr;
  for (int l = 0; l < model.legs(); ++l) {
    if (f.has_forces) f.forces[l] = Vec3(s.forces.at(i) + 3 * l);
    f.normals[l] =
        s.normals.data != nullptr ? Vec3(s.normals.at(i) + 3 * l).normalized() : Vec3::UnitZ();
  }
  return f;
}

/// T_root: the generalised velocity about the trunk origin P0, [v_P0; ω; q̇], of that about
/// the root link's origin, [v_root; ω; q̇]: v_P0 = v_root + r × ω, r = W_R_B p_B_root the root
/// origin seen from P0 (world axes). The root link's generalised forces are T_rootᵀ τ.
hexdyn::DofMatrix root_coordinates(const hexdyn::RobotModel& model,
                                   const hexdyn::BaseState& trunk) {
  hexdyn::DofMatrix T = hexdyn::DofMatrix::Identity(model.dofs(), model.dofs());
  T.block<3, 3>(0, 3) = hexdyn::skew(trunk.W_R_B * model.p_B_root);
  return T;
}

/// The shape of one output: (width...) for one state, (T, width...) for T.
std::vector<std::size_t> dims(const StateArgs& s, std::vector<std::size_t> one) {
  if (s.batched) one.insert(one.begin(), static_cast<std::size_t>(s.count));
  return one;
}

/// The model's names: "joint_names" (J, /model/joint_names) and "leg_names" (L).
void add_names(py::dict& out, const hexdyn::RobotModel& model) {
  std::vector<std::string> joints(model.joint_source_names.begin(),
                                  model.joint_source_names.begin() + model.joints());
  std::vector<std::string> legs;
  for (int l = 0; l < model.legs(); ++l) legs.push_back(model.leg(l).name);
  out["joint_names"] = joints;
  out["leg_names"] = legs;
}

/// The model of the scene, loaded with the GIL released.
hexdyn::RobotModel load_model(const std::string& scene, const std::vector<std::string>& sets) {
  const std::vector<hexdyn::Override> overrides = overrides_of(sets);
  py::gil_scoped_release no_gil;
  return guard_yaml(
      scene, [&] { return hexdyn::build_robot_model(hexdyn::load_scene(scene, overrides).robot); });
}

py::dict forward_dynamics_file(const std::string& scene, const std::vector<std::string>& sets,
                               const OptionalArray& base_position,
                               const OptionalArray& base_orientation,
                               const OptionalArray& joint_position,
                               const OptionalArray& base_linear_velocity,
                               const OptionalArray& base_angular_velocity,
                               const OptionalArray& joint_velocity,
                               const OptionalArray& joint_torque, const OptionalArray& foot_forces,
                               const OptionalArray& foot_normals) {
  const hexdyn::RobotModel model = load_model(scene, sets);
  const py::ssize_t J = model.joints(), L = model.legs();
  StateArgs s;
  s.function = "forward_dynamics";
  take_state(s, J, base_position, base_orientation, joint_position, base_linear_velocity,
             base_angular_velocity, joint_velocity);
  take(s, joint_torque, {J}, "joint_torque", s.tau);
  take_feet(s, L, foot_forces, foot_normals);
  check_args(s, model);
  const auto n = static_cast<std::size_t>(s.count), nj = static_cast<std::size_t>(J);
  std::vector<double> a(3 * n), dw(3 * n), qdd(nj * n);
  {
    py::gil_scoped_release no_gil;
    hexdyn::RobotData data(model);
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<py::ssize_t>(i);
      hexdyn::BaseState trunk = trunk_state(model, s, k);
      const FootInputs feet = foot_inputs(model, s, k);
      const hexdyn::DofVector& nu_dot = hexdyn::forward_dynamics_joints(
          model, data, trunk, joints_or_zero(s.q, k, model.joints()),
          joints_or_zero(s.qd, k, model.joints()), joints_or_zero(s.tau, k, model.joints()),
          feet.has_forces ? &feet.forces : nullptr, &feet.normals);
      trunk.a_W = nu_dot.head<3>();
      trunk.omegadot_W = nu_dot.segment<3>(3);
      const hexdyn::BaseState root = hexdyn::root_link_state(model, trunk);
      Vec3::Map(&a[3 * i]) = root.a_W;
      Vec3::Map(&dw[3 * i]) = root.omegadot_W;
      Eigen::VectorXd::Map(&qdd[nj * i], J) = nu_dot.tail(J);
    }
  }
  py::dict out;
  out["base_linear_acceleration"] = to_numpy(std::move(a), dims(s, {3}));
  out["base_angular_acceleration"] = to_numpy(std::move(dw), dims(s, {3}));
  out["joint_acceleration"] = to_numpy(std::move(qdd), dims(s, {nj}));
  add_names(out, model);
  return out;
}

py::dict inverse_dynamics_file(
    const std::string& scene, const std::vector<std::string>& sets,
    const OptionalArray& base_position, const OptionalArray& base_orientation,
    const OptionalArray& joint_position, const OptionalArray& base_linear_velocity,
    const OptionalArray& base_angular_velocity, const OptionalArray& joint_velocity,
    const OptionalArray& base_linear_acceleration, const OptionalArray& base_angular_acceleration,
    const OptionalArray& joint_acceleration, const OptionalArray& foot_forces,
    const OptionalArray& foot_normals) {
  const hexdyn::RobotModel model = load_model(scene, sets);
  const py::ssize_t J = model.joints(), L = model.legs();
  StateArgs s;
  s.function = "inverse_dynamics";
  take_state(s, J, base_position, base_orientation, joint_position, base_linear_velocity,
             base_angular_velocity, joint_velocity);
  take(s, base_linear_acceleration, {3}, "base_linear_acceleration", s.a);
  take(s, base_angular_acceleration, {3}, "base_angular_acceleration", s.dw);
  take(s, joint_acceleration, {J}, "joint_acceleration", s.qdd);
  take_feet(s, L, foot_forces, foot_normals);
  check_args(s, model);
  const auto n = static_cast<std::size_t>(s.count), nj = static_cast<std::size_t>(J);
  std::vector<double> force(3 * n), moment(3 * n), torque(nj * n);
  {
    py::gil_scoped_release no_gil;
    hexdyn::RobotData data(model);
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<py::ssize_t>(i);
      const hexdyn::BaseState trunk = trunk_state(model, s, k);
      const FootInputs feet = foot_inputs(model, s, k);
      const hexdyn::DofVector& tau = hexdyn::rnea(
          model, data, trunk, joints_or_zero(s.q, k, model.joints()),
          joints_or_zero(s.qd, k, model.joints()), joints_or_zero(s.qdd, k, model.joints()),
          feet.has_forces ? &feet.forces : nullptr, &feet.normals);
      const hexdyn::DofVector tau_root = root_coordinates(model, trunk).transpose() * tau;
      Vec3::Map(&force[3 * i]) = tau_root.head<3>();
      Vec3::Map(&moment[3 * i]) = tau_root.segment<3>(3);
      Eigen::VectorXd::Map(&torque[nj * i], J) = tau_root.tail(J);
    }
  }
  py::dict out;
  out["base_force"] = to_numpy(std::move(force), dims(s, {3}));
  out["base_moment"] = to_numpy(std::move(moment), dims(s, {3}));
  out["joint_torque"] = to_numpy(std::move(torque), dims(s, {nj}));
  add_names(out, model);
  return out;
}

py::dict mass_matrix_file(const std::string& scene, const std::vector<std::string>& sets,
                          const OptionalArray& base_orientation,
                          const OptionalArray& joint_position) {
  const hexdyn::RobotModel model = load_model(scene, sets);
  const py::ssize_t J = model.joints();
  StateArgs s;
  s.function = "mass_matrix";
  take(s, base_orientation, {4}, "base_orientation", s.quat);
  take(s, joint_position, {J}, "joint_position", s.q);
  check_args(s, model);
  const auto n = static_cast<std::size_t>(s.count), d = static_cast<std::size_t>(model.dofs());
  std::vector<double> M(d * d * n);
  {
    py::gil_scoped_release no_gil;
    hexdyn::RobotData data(model);
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<py::ssize_t>(i);
      const hexdyn::BaseState trunk = trunk_state(model, s, k);
      const hexdyn::DofMatrix& M_trunk =
          hexdyn::crba(model, data, trunk, joints_or_zero(s.q, k, model.joints()));
      const hexdyn::DofMatrix T = root_coordinates(model, trunk);
      Eigen::Map<RowMajor>(&M[d * d * i], model.dofs(), model.dofs()) = T.transpose() * M_trunk * T;
    }
  }
  py::dict out;
  out["mass_matrix"] = to_numpy(std::move(M), dims(s, {d, d}));
  add_names(out, model);
  return out;
}

}  // namespace

void add_dynamics_functions(py::module_& m) {
  m.def("forward_dynamics", &forward_dynamics_file, py::arg("scene"), py::arg("overrides"),
        py::arg("base_position"), py::arg("base_orientation"), py::arg("joint_position"),
        py::arg("base_linear_velocity"), py::arg("base_angular_velocity"),
        py::arg("joint_velocity"), py::arg("joint_torque"), py::arg("foot_forces") = py::none(),
        py::arg("foot_normals") = py::none(),
        "The accelerations of the scene's robot at given states under joint torques and foot "
        "forces (C++ forward_dynamics_joints), in the result file's coordinates.");
  m.def("inverse_dynamics", &inverse_dynamics_file, py::arg("scene"), py::arg("overrides"),
        py::arg("base_position"), py::arg("base_orientation"), py::arg("joint_position"),
        py::arg("base_linear_velocity"), py::arg("base_angular_velocity"),
        py::arg("joint_velocity"), py::arg("base_linear_acceleration"),
        py::arg("base_angular_acceleration"), py::arg("joint_acceleration"),
        py::arg("foot_forces") = py::none(), py::arg("foot_normals") = py::none(),
        "The generalised forces (trunk wrench, joint torques) that give the scene's robot the "
        "accelerations given at given states under foot forces (C++ rnea), in the result "
        "file's coordinates.");
  m.def("mass_matrix", &mass_matrix_file, py::arg("scene"), py::arg("overrides"),
        py::arg("base_orientation"), py::arg("joint_position"),
        "The mass matrix of the scene's robot at given poses (C++ crba), in the result file's "
        "coordinates.");
}

}  // namespace hexdyn_python
