#pragma once
/// \file gait.hpp
/// Gait planning: periodic gaits for any duty factor β ∈ [1/2, 1), footholds on the terrain,
/// and C² swing-foot paths.
///
/// Phases (fraction of a cycle at which a leg lifts off): those of gait.pattern, the wave gait
/// by default, or gait.phases (model/gait_pattern.hpp, which has the formulas: liftoff_phases,
/// gait_legs, wave_gait_phases). Each leg swings once per cycle, from its phase φ for 1 − β of
/// a cycle.
/// Swings that straddle the start or the end of the run are shortened to it, so the
/// robot starts and ends with all feet on the ground.
///
/// Footholds: a stance that (nominally) begins at phase τ* stands at the hip's
/// horizontal position at τ* moved `foot_lateral` along the hip's outward direction
/// (RobotModel::hip_outward_B, made horizontal in the world; the paper robot's legs stand
/// straight out, ±x) and s0/2 forward, moved along y to the nearest point at least
/// `foothold_margin` from every nosing and riser. A sphere foot of radius r keeps the margin
/// with the sphere (its horizontal extent [y − r, y + r]): its contact point keeps margin + r
/// (docs/theory/stages.md#gait-planning).
///
/// Swing path, u = (t − t_lo)/(t_td − t_lo): a vertical lift (smootherstep) to the apex
/// z_a = H_m + Δh, H_m the highest terrain under the horizontal segment (a sphere foot's:
/// under the sphere's shadow, the segment widened by r, so the sphere clears by Δh); a horizontal
/// transfer at z_a (smootherstep); a vertical descent reaching the foothold with the
/// downward touchdown speed. Position is C² inside the swing, velocity and acceleration
/// are zero at lift-off; the descent is shortened when needed so that it is monotone. With
/// gait.swing_profile blended the transfer spans the whole swing (σ = u) while the foot lifts
/// and descends over the same fractions, so its peak horizontal acceleration is
/// (ud − ul)² times the staged one; such a path is checked against the terrain under it
/// (plan_gait; docs/theory/stages.md#swing-profiles).
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/gait_pattern.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/motion.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {

struct Swing {
  double t_liftoff_s = 0.0, t_touchdown_s = 0.0;
  Vec3 p_liftoff_W = Vec3::Zero(), p_touchdown_W = Vec3::Zero();
  double apex_z_m = 0.0;       ///< z of the transfer segment
  double lift_end_u = 0.3;     ///< normalised time at which the lift ends
  double lower_start_u = 0.8;  ///< normalised time at which the descent starts
  /// Normalised times between which the foot moves horizontally: [lift_end_u, lower_start_u]
  /// for a staged swing, [0, 1] for a blended one.
  double transfer_start_u = 0.3, transfer_end_u = 0.8;
  double touchdown_speed_mps = 0.0;
};

/// Foot position, velocity and acceleration in the world frame.
struct FootMotion {
  Vec3 p_W = Vec3::Zero(), v_W = Vec3::Zero(), a_W = Vec3::Zero();
  bool in_swing = false;
};

struct LegPlan {
  Vec3 p_initial_W = Vec3::Zero();  ///< foothold at t = 0
  std::vector<Swing> swings;        ///< in time order, non-overlapping
};

struct GaitPlan {
  double duty_factor = 0.5;
  std::vector<double> liftoff_phase;  ///< per leg of the model, in [0, 1)
  std::vector<LegPlan> legs;          ///< per leg of the model (built once per plan)
};

/// Plans every swing of every leg over the whole run. Throws PlanningError when no
/// foothold satisfies the margin, in one line naming the leg, the stance's start time, the
/// step and the margin; or when a blended swing's foot (its sphere) would pass below the
/// terrain, naming the leg, the time and how deep.
GaitPlan plan_gait(const RobotModel& model, const GaitParams& gait, const TrunkMotion& trunk,
                   const Terrain& terrain);

/// The mean height of the legs' footholds at t = 0 (LegPlan::p_initial_W) [m]: the trunk's
/// height above its feet, as the balanced trunk's pendulum takes it, is measured from it.
/// Precondition: gait.legs is not empty.
double mean_initial_foot_z(const GaitPlan& gait);

/// Foot of one swing at time t ∈ [t_liftoff, t_touchdown].
FootMotion swing_foot_motion(const Swing& swing, double t_s);

/// swing_foot_motion(swing, t_s).p_W alone (the same arithmetic, the same bits).
Vec3 swing_foot_position(const Swing& swing, double t_s);

/// Foot of a leg at time t: on its path during a swing (t_lo ≤ t < t_td), fixed at its
/// foothold otherwise.
FootMotion leg_foot_motion(const LegPlan& leg, double t_s);

/// Unit normal n of the surface a foot stands on and its first two time derivatives
/// [1, 1/s, 1/s²], world frame: a sphere foot's centre is the planned foot point + r n
/// (docs/theory/model.md#sphere-feet).
struct FootNormal {
  Vec3 n_W = Vec3::UnitZ(), nd_W = Vec3::Zero(), ndd_W = Vec3::Zero();
};

/// The normal under a leg's foot at time t (the same swing or foothold as leg_foot_motion):
/// the terrain's normal at the foothold in support; in a swing the lift-off and touchdown
/// normals n0, n1 blended, n = m/|m| with m = (1 − S(σ)) n0 + S(σ) n1 and S(σ) the horizontal
/// transfer's smootherstep, so n turns while the foot moves across and stays n0 during the
/// lift, n1 during the descent and at touchdown.
FootNormal leg_foot_normal(const LegPlan& leg, const Terrain& terrain, double t_s);

/// The swing's part of leg_foot_normal: lift-off normal n0_W and touchdown normal n1_W (unit)
/// blended at t ∈ [t_liftoff, t_touchdown].
FootNormal swing_foot_normal(const Swing& swing, const Vec3& n0_W, const Vec3& n1_W, double t_s);

}  // namespace hexdyn
