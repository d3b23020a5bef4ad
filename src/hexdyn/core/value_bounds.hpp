#pragma once
/// \file value_bounds.hpp
/// The plausibility bounds of a robot's values, one table for both ways of describing a
/// robot: the scene's robot.* keys (config/config.cpp) and a URDF's links and joints
/// (model/urdf_reader.cpp). Each is far beyond any legged robot and far inside what the
/// dynamics compute without overflow: a URDF <mass value="1e300"> used to run to NaN
/// torques and energy.
#include <numbers>

namespace hexdyn {

/// Largest mass of one body [kg] (robot.trunk.mass, robot.coxa.mass, …; a URDF link's
/// <mass>): 10 t.
inline constexpr double kMaxBodyMass_kg = 1e4;

/// Largest principal moment of inertia of one body about its COM [kg m²]
/// (robot.*.inertia; the eigenvalues of a URDF link's <inertia>).
inline constexpr double kMaxPrincipalInertia_kgm2 = 1e3;

/// Relative tolerance of the triangle inequality of principal moments (each at most the
/// sum of the other two, × (1 + this)): the rounding of tensors written to a few digits.
inline constexpr double kInertiaTriangleTolerance = 1e-9;

/// Largest coordinate of a point or offset within the robot [m] (robot.*.com,
/// robot.foot_offset; a URDF joint's <origin xyz> and a link's <inertial><origin xyz>), and
/// the longest link (robot.*.length).
inline constexpr double kMaxRobotCoordinate_m = 10.0;

/// Largest sphere foot radius [m] (robot.foot_radius; a URDF sphere <collision> taken as the
/// foot, model/urdf_reader.hpp).
inline constexpr double kMaxFootRadius_m = 1.0;

/// Widest joint limits [rad]: a URDF revolute joint's <limit lower upper> in [−4π, 4π], two
/// turns either way, since published descriptions write wide placeholders (Solo-12: ±10 rad;
/// ANYmal C: ±3π) while a limit in degrees read as radians (90) stays out (a scene's
/// robot.*.limits: [−π, π]; robot.nominal_pose: [−2π, 2π]).
inline constexpr double kMaxJointAngle_rad = 4.0 * std::numbers::pi;

/// Largest joint effort limit [N m] (allocation.torque_limit; a URDF joint's <limit effort>).
inline constexpr double kMaxJointEffort_Nm = 1e6;

/// Largest joint velocity limit [rad/s] (a URDF joint's <limit velocity>; a servo's is about
/// 6 rad/s).
inline constexpr double kMaxJointVelocity_radps = 1e4;

/// Largest joint friction [N m, or N m s/rad for viscous friction]: a URDF joint's
/// <dynamics damping friction> and an actuator's coulomb_friction and viscous_friction
/// (config/actuators.hpp); the effort bound, as no joint's friction exceeds its effort.
inline constexpr double kMaxJointFriction = kMaxJointEffort_Nm;

}  // namespace hexdyn
