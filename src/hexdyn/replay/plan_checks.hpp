#pragma once
/// \file plan_checks.hpp
/// What the replay checks of its plan before any work (replay.hpp replay_plan): the plan's
/// sizes and times, the steps its span takes, and a mass matrix to integrate. Internal to the
/// replay stage; each throws ConfigError with one line naming what is wrong.
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/replay/replay.hpp"

namespace hexdyn {

/// At least 2 instants, strictly increasing, every series as long as the time, a terrain
/// profile of at least 2 vertices, and drive torques exactly when the robot has actuators.
void check_plan(const RobotModel& model, const ReplayPlan& p);

/// At most kMaxReplaySteps steps of replay.step over the plan's span
/// (docs/user/replay.md#bounded-work-and-progress), so that at most 64 times as many halved
/// steps can follow.
void check_replay_work(const ReplayPlan& p, const ReplayParams& replay);

/// The mass matrix at the plan's first state is positive definite: a robot with massless legs
/// (robot.leg_inertia: massless) has none to integrate. Fills data.M.
void check_mass_matrix(const RobotModel& model, RobotData& data, const ReplayPlan& p);

}  // namespace hexdyn
