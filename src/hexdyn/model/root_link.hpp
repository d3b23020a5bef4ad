#pragma once
/// \file root_link.hpp
/// The trunk's state and that of the description's root link frame, which a result's
/// `/base/*` describe (docs/theory/conventions.md#robots-from-urdf): a frame fixed in the
/// trunk, at p_B_root with axes B_R_root (RobotModel). A YAML robot's root link is the trunk
/// frame itself, and both functions return their argument.
#include "hexdyn/core/base_state.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

/// The root link frame's state from the trunk's (frame B at P0, world axes): pose W_R_root =
/// W_R_B B_R_root and origin p_W + r with r = W_R_B p_B_root; velocity v_W + ω × r; classical
/// acceleration a_W + ω̇ × r + ω × (ω × r); ω and ω̇ unchanged (one rigid body).
BaseState root_link_state(const RobotModel& model, const BaseState& trunk);

/// The inverse: the trunk's state (what dynamics/rnea.hpp takes) from the root link frame's.
BaseState trunk_state_from_root_link(const RobotModel& model, const BaseState& root);

}  // namespace hexdyn
