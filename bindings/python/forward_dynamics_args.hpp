#pragma once
// The arguments of hexdyn.forward_dynamics, inverse_dynamics and mass_matrix as the compiled
// part takes them (dynamics.cpp): each one sample or T samples along a first axis, checked at
// the edge before any computing: the shape, every value finite, the base orientations unit
// quaternions, the foot normals under sphere feet directions. Each refusal is a ValueError in
// one line naming the function and the argument, as numpy indexes it (sample first), and what
// is allowed (docs/user/api.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "hexdyn/model/robot_model.hpp"

namespace hexdyn_python {

namespace py = pybind11;

/// A float64 array as numpy gives it, C order (converted when it is not).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Tolerance on the norm of a unit quaternion given to the dynamics functions: |‖q‖ − 1| at
/// most this.
inline constexpr double kUnitQuaternionTolerance = 1e-6;
/// Least norm of a foot normal under a sphere foot (normals are normalised): a shorter one
/// has no direction.
inline constexpr double kLeastNormalNorm = 1e-6;

/// The samples of one argument of a dynamics function: `count` of them, each `width` doubles from
/// `data`; `batched` when the array had a leading sample axis.
struct Samples {
  const double* data = nullptr;
  py::ssize_t count = 1;
  bool batched = false;
  py::ssize_t width = 0;
  std::vector<py::ssize_t> shape;  ///< of one sample
  const char* name = "";           ///< the argument's name
  const char* function = "";       ///< the function's name, which messages start with
  const double* at(py::ssize_t i) const { return data + (batched ? i * width : 0); }
};

/// `a` as one sample of shape `shape` or as T of them, (T, *shape), an argument of the function
/// `function`; ValueError naming both otherwise.
Samples samples_of(const DoubleArray& a, const std::vector<py::ssize_t>& shape, const char* name,
                   const char* function);

/// ValueError unless every value of `s` is finite, naming the first that is not
/// ("joint_torque[4, 7] is nan"). A Samples without data passes.
void check_finite(const Samples& s);

/// ValueError unless every quaternion of `s` (w, x, y, z) has norm 1 within
/// kUnitQuaternionTolerance, naming the first that has not.
void check_unit_quaternions(const Samples& s);

/// ValueError for a foot normal (L, 3 per sample) under a sphere foot (model.foot_radius_m >
/// 0) shorter than kLeastNormalNorm, naming it and its leg; the normals under point feet are
/// not used. A Samples without data passes.
void check_sphere_foot_normals(const hexdyn::RobotModel& model, const Samples& s);

}  // namespace hexdyn_python
