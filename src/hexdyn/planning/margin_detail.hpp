#pragma once
/// \file margin_detail.hpp
/// Internal to planning/: the kinematic margin of a motion (posture.hpp's file comment) as
/// the automatic posture evaluates it, and the lower bounds that let it skip samples without
/// changing a result (docs/theory/stages.md#posture).
///
/// Sample bounds. One evaluated sample of a paper-geometry leg (foot target p in its hip frame)
/// bounds the margins of every target p' with |p' − p| ≤ δ ≤ radius from below: each term
/// moves by at most a Lipschitz constant, taken over the whole ball of that radius, times δ:
///   reach     the wrist distance d = |(ρ − l1, z + d1)|, ρ = √(x² + y² − w²), moves by at
///             most k δ, k = r/ρ at the ball's smallest r = √(x² + y²) (ρ' = r'·r/ρ);
///   coxa      θ1 = atan2(y, x) − atan2(w, ρ) has |∇θ1| = 1/ρ;
///   tibia     β3 = −acos((d² − l2² − l3²)/(2 l2 l3)) moves by d/(l2 l3 sin β3) per metre
///             of d, sin β3 smallest at an end of the ball's range of d (√(1 − c²) is concave);
///   femur     β2 = atan2(v, u) − atan2(l3 sin β3, l2 + l3 cos β3): 1/d per metre of (u, v),
///             plus l3 (l2 + l3)/d² per radian of β3;
/// a joint's clearance (1-Lipschitz in its angle) by the angle's bound, and a joint margin by
/// clearance × the smallest lever arm in the ball (r, d, l3 for coxa, femur, tibia; the
/// Jacobian's column norms, with the 1e-6 relative and 1e-12 m allowance of the J-free bounds).
/// A bound exists only where every function is smooth and unwrapped in the ball (ρ > 0, no
/// crossing of an atan2 cut or of ±π, sin β3 > 0); a refused sample, a ball that reaches a
/// boundary, or another leg geometry gives none. The bounds are of the exact functions; the
/// evaluation rounds them by ~1e-15 m, so a sample is skipped only when its bound clears the
/// value it would have to lower by kSkipAllowance_m.
#include <array>
#include <limits>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/motion.hpp"
#include "hexdyn/planning/posture.hpp"

namespace hexdyn {

struct MotionPlan;

namespace margin_detail {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A sample is skipped only when each bound clears the value it could lower by this much [m,
/// rad]: far above the evaluation's rounding (~1e-15), far below any decision.
constexpr double kSkipAllowance_m = 1e-9;

/// Largest radius of an evaluated sample's bound [m] (sample_bound may take less): two scan
/// steps of a typical height search, and more than the targets move between most instants a
/// bisection compares.
constexpr double kBoundRadius_m = 0.02;

/// What one evaluated sample tells about the targets within radius_m of its own (file comment).
struct SampleBound {
  double radius_m = 0.0;  ///< 0: no bound
  double reach_m = 0.0, reach_slope = 0.0;
  int n_joints = 0;  ///< the leg's joints: the first n_joints entries below are used
  std::array<double, kMaxLegJoints> clearance_rad{};  ///< joint_clearance_rad; +inf: continuous
  std::array<double, kMaxLegJoints> inside_rad{};     ///< distance inside [lo, hi] (no ±2π)
  std::array<double, kMaxLegJoints> slope{};          ///< rad per m
  std::array<double, kMaxLegJoints> lever_m{};        ///< smallest lever arm in the ball
  double min_margin_m = 0.0;                          ///< robot.ik_min_margin
};

/// Lower bounds of a target's margins at distance delta_m ≤ radius_m from the bound's sample;
/// -inf where none. admitted: the IK accepts every target within delta_m.
struct MarginBounds {
  double value_m = -kInf, reach_m = -kInf, joint_m = -kInf, joint_rad = -kInf;
  bool admitted = false;
};

/// The bounds of the sample at p_H with IK result ik, over the ball of radius_m.
SampleBound sample_bound(const RobotModel& model, int leg, const Vec3& p_H, const LegIkResult& ik,
                         double radius_m);

MarginBounds bounds_at(const SampleBound& b, double delta_m);

/// bounds_at(b, delta_m).value_m >= floor_m, and .admitted, computed alone.
bool value_clears(const SampleBound& b, double delta_m, double floor_m);
bool admits(const SampleBound& b, double delta_m);

/// The foot targets of a motion at its margin samples (margin_sample_times). They depend on
/// the foot spread and not on the trunk's height: the gait's timing follows the travel, its
/// footholds' x and y the trunk's x and y, their z the terrain (gait.hpp), so the automatic
/// posture plans the gait of a spread once and moves only the trunk for each height.
struct FootTrack {
  std::vector<double> t_s;
  int legs = 0;  ///< the robot's legs: sample s of a track is instant s / legs, leg s % legs
  /// per instant and leg [m, G0]: the foot points the IK places (a sphere foot's centre)
  std::vector<LegArray<Vec3>> p_W;
};

FootTrack foot_track(const RobotModel& model, const MotionPlan& plan, int uniform);

/// The samples evaluated so far on one FootTrack, at whatever trunk height: per sample
/// (i·legs + leg), its height and bound. Moving the trunk by Δh moves every foot target in its
/// hip frame by exactly |Δh|, so a sample's bound holds at another height within its radius,
/// less |Δh|; and the path of a leg's target between two instants is the same at every height.
struct SampleReferences {
  std::vector<double> path_m;  ///< per sample: its target's path from the first instant [m]
  std::vector<int> slot;       ///< per sample: its entry, -1: never evaluated
  struct Entry {
    double height_m = 0.0;  ///< where it was last evaluated
    int evaluation = 0;     ///< by which evaluation (generation)
    SampleBound bound;
  };
  std::vector<Entry> entries;
  int generation = 0;
};

/// A margin evaluation that may stop early: as soon as some sample's margin is below
/// `below_m` the motion's margin is known to be below it too, and value_m is that sample's
/// margin (an upper bound of the motion's), `complete` false.
struct MarginEvaluation {
  KinematicMargin margin;
  bool complete = true;
  int limiting_sample = -1;  ///< i·legs + leg of value_m
};

/// What a margin evaluation must find exactly.
enum class Evaluation {
  kCandidate,  ///< value_m (and leg, t_s) when complete: a candidate of the posture search
  kCheck,      ///< every field, as motion_kinematic_margin gives it
  kAdmission,  ///< `admitted` only (stops at the first sample the IK refuses)
};

struct MarginRequest {
  double below_m = -kInf;                 ///< stop at the first sample below it
  const std::vector<int>* hot = nullptr;  ///< evaluated first (limiting samples of earlier heights)
  int stride = 8;  ///< instants evaluated (or bounded) first: every stride-th
  Evaluation kind = Evaluation::kCandidate;
};

/// The margin of the motion with the trunk at height_m (any height of one posture search;
/// p_W of `feet` do not depend on it), evaluating only the samples whose bounds, from the
/// samples evaluated before at this or another height (refs, updated), cannot show harmless:
/// samples that could not lower the margin (for a check: any minimum, nor fail the IK; for an
/// admission: not fail the IK). Fields not asked for are NaN (constraint "").
/// Bounds exist for the paper geometry; other legs are evaluated at every sample.
MarginEvaluation bounded_margin(const RobotModel& model, const TrunkMotion& trunk,
                                const FootTrack& feet, double height_m, const MarginRequest& req,
                                SampleReferences& refs);

/// The margin at every sample, in time order (motion_kinematic_margin).
KinematicMargin full_margin(const RobotModel& model, const TrunkMotion& trunk,
                            const FootTrack& feet);

}  // namespace margin_detail
}  // namespace hexdyn
