#pragma once
/// \file paper_robot.hpp
/// The robot described by YAML keys (the paper's hexapod, core/scene.hpp RobotParams) as a
/// description of the same kind a URDF gives (model/urdf_robot.hpp UrdfRobot), built by the
/// one builder, build_robot_model(const UrdfRobot&) (docs/theory/model.md#one-description).
///
/// The YAML robot has legs of three revolute joints (six in the paper; coxa about the trunk
/// normal, femur and tibia about −y of the coxa link), legs L1, L3, L5, … on the left, their
/// lateral offsets mirrored; link frames as docs/theory/model.md says. Its planar closed forms (the
/// model's LegGeometry::kPaperPlanar) are a shortcut the model keeps after the build
/// (use_paper_closed_forms): the tree, the inertias, the limits and the foot points are the
/// description's; tests check the shortcut against the chain kinematics of the same model.
#include "hexdyn/model/urdf_robot.hpp"

namespace hexdyn {

/// The YAML robot as a description: trunk (with the payload, and with massless legs' link
/// masses as point masses at their hips), params.legs legs of three joints named as joint_name
/// gives, limits from the keys (no effort or velocity limit: +inf), point or sphere feet at
/// the tibia's end. `params.urdf` must be null.
UrdfRobot paper_description(const RobotParams& params);

/// Switches a model built from paper_description(params) to the paper's planar closed forms
/// (LegGeometry::kPaperPlanar): link lengths and offsets, the outward directions, the trunk
/// and payload kept apart for the URDF writer. Changes nothing the dynamics reads.
void use_paper_closed_forms(RobotModel& model, const RobotParams& params);

}  // namespace hexdyn
