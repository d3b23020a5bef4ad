#pragma once
/// \file posture.hpp
/// The trunk's posture relative to the terrain, and the automatic posture
/// (docs/theory/stages.md#posture).
///
/// Reference line. The trunk travels parallel to the terrain's mean slope
/// (docs/theory/stages.md#motion-planning), so its height above a line of that slope is
/// constant. The reference line is, in the y-z plane of G0 (heights independent of x):
///   stairs  the mean slope line through the tread centres,
///           z_ref(y) = ground + h_s ((y − y_r)/b_s + 1/2), y_r the first riser
///           (it passes through the centre of the ground tread before y_r as well);
///   slope   the surface, z_ref(y) = ground + tan(angle) (y − origin_y);
///   flat    the ground, z_ref = height.
/// A riser of 0 gives the flat line, so stairs flatten continuously into flat ground.
///
/// Relative posture (motion.posture {height: h, start_y: s}): P0(0) = (0, y0, z_ref(y0) + h)
/// with y0 = y_origin + s, y_origin the first riser (stairs), the slope's origin_y (slope)
/// or 0 (flat). h is measured vertically (along z); the distance normal to the line is
/// h cos α. The paper's start (0, 0.412, 0.235) m on its stairs (h_s 0.05, b_s 0.25,
/// y_r 0) is h = 0.1276 m, s = 0.412 m, and the arithmetic gives back 0.412 and 0.235 to
/// the last bit (tests/hexdyn/planning/test_posture.cpp).
///
/// Kinematic margin of a planned motion (motion_kinematic_margin): over sample instants
/// (a uniform grid plus every swing's lift-off, end of lift, start of descent and
/// touchdown) and every leg, the IK of the foot target in the hip frame gives
///   reach margin  the IK's margin_m: distance of the leg's wrist point from full
///                 extension and from full fold (LegIkResult), [m];
///   joint margin  for each joint, the angle to its nearer limit times the foot's lever
///                 arm about that joint (|∂p_foot/∂q_k|, the Jacobian column): how far
///                 the foot may move before that joint stops, to first order [m].
/// The criterion is the smallest of the two over the whole motion, value_m. A sample is
/// admitted when the IK accepts it (reach margin ≥ robot.ik_min_margin, joints inside
/// their limits). Swing paths clear the terrain by gait.swing_clearance by construction
/// (gait.hpp) whatever the posture, so clearance is not a term of the criterion.
///
/// Hip plane. The trunk's body is taken to lie about the plane of its lowest hip joint,
/// z_hip = min over legs of p_hip_B.z along the trunk normal; that plane stands
/// e_hip = z_hip / cos α above P0 (vertically; α the trunk's pitch, the trunk parallel to
/// the line). The paper robot's hips lie in the trunk plane (e_hip = 0); a URDF robot's
/// trunk frame may be anywhere (Kraby's is at ground level, e_hip = 0.208 m).
///
/// Trunk clearance. The trunk travels parallel to the reference line at height h, and
/// the terrain rises at most h_s/2 above the line (at the back of each tread, just past
/// its riser), which the trunk passes over: its vertical clearance is h + e_hip − h_s/2
/// (the trunk's axis taken as a line in the hip plane at least one tread long). The
/// automatic posture keeps it at least motion.posture.trunk_clearance (ASSUMPTION,
/// default 0.05 m: half a trunk thickness the paper does not give and a gap). The legs'
/// links are not checked against the nosings.
///
/// Automatic posture (motion.posture.height: auto): the trunk height h maximising value_m,
/// searched on height_range (default: the hip plane from 0 to the legs' reach above the
/// line, [−e_hip, reach − e_hip]; the reach is the foot's distance at zero angles for the
/// paper robot, the sum of the segments of a URDF leg), raised to at least
/// h_s/2 + trunk_clearance − e_hip, by a scan of 25 heights
/// and a golden-section refinement (to 0.1 mm) around the best. When the best margin is
/// below target_margin and motion.posture.foot_lateral gives a range, gait.foot_lateral
/// is searched as well (9 values over the range, each with its best height) and the pair
/// with the largest margin wins; otherwise the scene's gait.foot_lateral is kept. Only h
/// and gait.foot_lateral change; start, attitude, speed, gait timing and footholds' y
/// are those of the scene. The search takes exactly the decisions of that scan and golden
/// section over complete margins while planning each spread's gait once, stopping a
/// candidate at the first sample below the margin it is compared with, and skipping samples
/// whose proven lower bounds cannot lower a margin (planning/margin_detail.hpp,
/// docs/theory/stages.md#posture). The chosen posture is checked on a dense grid (5 ms); when no
/// posture is admitted, plan_motion throws ReachError naming the limiting leg, instant,
/// constraint and margin at the best posture found.
#include <memory>
#include <string>
#include <vector>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

struct MotionPlan;
class TrunkOffset;

/// Height of the terrain's reference line at y [m] (file comment).
double reference_line_height(const TerrainParams& terrain, double y_m);

/// Highest rise of the terrain above its reference line [m]: |h_s|/2 on uniform stairs (at
/// the back of every tread going up, at its front going down), the highest tread corner above
/// the line on other stairs, 0 on slopes and flat ground.
double terrain_rise_above_reference(const TerrainParams& terrain);

/// The terrain's origin along y: first riser, slope origin or 0 [m].
double terrain_origin_y(const TerrainParams& terrain);

/// P0(0) of a relative posture: (0, y_origin + start_y, z_ref + height) [m, G0].
Vec3 relative_start_position(const TerrainParams& terrain, double height_m, double start_y_m);

/// The smallest kinematic margin of a planned motion and where it occurs.
struct KinematicMargin {
  double value_m = 0.0;    ///< the criterion: min(reach_m, joint_m) over the motion [m]
  double reach_m = 0.0;    ///< smallest reach margin over the samples the IK solved [m]
  double joint_m = 0.0;    ///< smallest joint margin [m] (angle to the limit × lever arm)
  double joint_rad = 0.0;  ///< smallest angle to a joint limit [rad]
  bool admitted = false;   ///< every sampled foot target accepted by the IK
  // The limiting sample: where value_m occurs.
  int leg = 0;  ///< 0-based
  double t_s = 0.0;
  std::string constraint;  ///< "reach: beyond full extension", "joint L3_tibia upper limit", ...
  int samples = 0;         ///< instants evaluated
  /// One line: "leg L3 at t = 1.2 s: reach: beyond full extension (margin -0.004 m)".
  std::string describe() const;
};

/// Sample instants of a plan [s], increasing: `uniform` points over [0, duration] (at
/// least 2) and every swing's lift-off, end of lift, start of descent and touchdown.
std::vector<double> margin_sample_times(const MotionPlan& plan, int uniform);

/// The kinematic margin of `plan` on margin_sample_times(plan, uniform) (file comment).
KinematicMargin motion_kinematic_margin(const RobotModel& model, const MotionPlan& plan,
                                        int uniform = 200);

/// What the dense check of an automatic posture reports: the chosen posture's whole margin,
/// or only whether the IK admits it (the margin's other fields NaN, ""), which needs far fewer
/// samples (docs/theory/stages.md#posture). A run needs only the latter; when the posture is
/// not admitted the margin is computed in full all the same, for the error.
enum class PostureCheck { kMargin, kAdmission };

/// The posture a scene is planned with.
struct PostureChoice {
  Vec3 p0_W = Vec3::Zero();     ///< P0 at t = 0 [m, G0]
  double height_m = 0.0;        ///< above the reference line (computed for kAbsolute) [m]
  double foot_lateral_m = 0.0;  ///< gait.foot_lateral used [m]
  PostureMode mode = PostureMode::kAbsolute;
  /// kAuto only: the margin of the chosen posture on the dense check grid (with
  /// PostureCheck::kAdmission, only `admitted`, `samples` and, when not admitted, all), and
  /// the number of candidate postures evaluated.
  KinematicMargin margin;
  int evaluations = 0;
};

/// Resolves the scene's posture (file comment). For kAbsolute and kRelative nothing is
/// searched and nothing is thrown; for kAuto, throws ReachError when no posture in the
/// searched range admits the motion, PlanningError from the gait planner. `offset`, when
/// given, is the balanced trunk's horizontal offset (trunk_offset.hpp), a function of time
/// alone: every candidate's trunk carries it, so that the height is chosen for the path the
/// trunk will follow (docs/theory/balance.md#reach).
PostureChoice choose_posture(const Scene& scene, const RobotModel& model,
                             PostureCheck check = PostureCheck::kMargin,
                             std::shared_ptr<const TrunkOffset> offset = nullptr);

/// As choose_posture, but for kAuto the best posture found is returned also when it does
/// not admit the motion (margin.admitted false) instead of throwing.
PostureChoice best_posture(const Scene& scene, const RobotModel& model,
                           PostureCheck check = PostureCheck::kMargin,
                           std::shared_ptr<const TrunkOffset> offset = nullptr);

/// The motion planned with an explicit start and foot spread (the scene's posture keys
/// ignored). A balanced scene's (motion.trunk: balanced) trunk stands still for
/// settle_time_s(scene, model) at the start and at the end, on all its feet, before its travel
/// and its first swing and after its last (TrunkMotion's hold). Throws PlanningError.
MotionPlan plan_motion_with(const Scene& scene, const RobotModel& model, const Vec3& p0_W,
                            double foot_lateral_m);

/// A balanced scene's plan stands on all its feet for this many pendulum time constants 1/ω
/// at the start and at the end, while the trunk shifts its weight (docs/theory/balance.md).
inline constexpr double kSettlePeriods = 2.0;

/// The hold of a balanced scene's trunk at each end [s]: kSettlePeriods / ω with ω = √(g / l),
/// l the longest leg's reach (leg_reach_m), which bounds the trunk's height above its feet
/// (the lowest ω, the longest settling) whatever posture is chosen; 0 for a straight trunk.
double settle_time_s(const Scene& scene, const RobotModel& model);

}  // namespace hexdyn
