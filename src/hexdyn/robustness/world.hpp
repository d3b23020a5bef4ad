#pragma once
/// \file world.hpp
/// A perturbed world (docs/theory/robustness.md#worlds): the robot, contact and terrain a plan
/// meets when the errors of one WorldDraw (perturbation.hpp) are applied to its scene's. The
/// plan itself is never changed: it keeps the torques and angles made for the nominal world.
#include <memory>
#include <vector>

#include "hexdyn/core/height_map.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/replay/replay.hpp"
#include "hexdyn/robustness/perturbation.hpp"

namespace hexdyn {

/// What the replay of one draw meets.
struct World {
  RobotModel model;
  ContactParams contact;
  TerrainParams terrain;
  /// The terrain's profile (ReplayPlan::terrain_y_m, terrain_z_m) and map the feet meet.
  std::vector<double> terrain_y_m, terrain_z_m;
  std::shared_ptr<const HeightMap> terrain_map;
};

/// The sizes of the draws on this robot and terrain: the staircase's risers (0 off stairs),
/// the leg links (bodies but the trunk) and the joints.
DrawSizes world_draw_sizes(const RobotModel& model, const TerrainParams& terrain);

/// The world of `draw` (sized by world_draw_sizes(model, terrain)):
/// - stairs: riser k + δh_k, tread k + δb_k, nosing k + δn_k (a step list);
/// - the terrain displaced by δy along +y (stairs: the first riser; a slope: its origin; a map:
///   its origin; flat ground: unchanged);
/// - μ_s, μ_d and μ + δμ; the contact stiffness × (1 + δK);
/// - the trunk structure's mass and inertia × (1 + δ), each link's × (1 + δ_link), and a point
///   mass δm at the trunk's centre of mass + δc (trunk frame);
/// - per joint with actuators: k_t and the peak and continuous torque ratings × (1 + δ), R ×
///   (1 + δ), τ_c and b × (1 + δ).
/// The profile is rebuilt over [plan.terrain_y_m.front(), back()] only when a terrain error is
/// not zero; otherwise the plan's own profile and map are kept, so that a draw of zeros is the
/// nominal world bit for bit. The draws must lie within the bounds the scene reader accepted
/// (config/robustness_keys.cpp: every drawable world physical).
World perturbed_world(const RobotModel& model, const ContactParams& contact,
                      const TerrainParams& terrain, const ReplayPlan& plan, const WorldDraw& draw);

}  // namespace hexdyn
