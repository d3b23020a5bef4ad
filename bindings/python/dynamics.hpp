#pragma once
// hexdyn.forward_dynamics, inverse_dynamics and mass_matrix: the rigid-body dynamics of a
// scene's robot (dynamics/rnea.hpp, dynamics/forward_dynamics.hpp) at states given from Python,
// in a result file's coordinates (the URDF root link's frame for the trunk, /base/*; the joints
// in /model/joint_names order). Sized by the robot's model: J joints, L legs.
#include <pybind11/pybind11.h>

namespace hexdyn_python {

/// Defines forward_dynamics, inverse_dynamics and mass_matrix on the module `m`.
void add_dynamics_functions(pybind11::module_& m);

}  // namespace hexdyn_python
