#pragma once
/// \file balance.hpp
/// The balanced trunk (motion.trunk: balanced; docs/theory/balance.md): a horizontal offset
/// of the straight trunk path such that the zero-moment point (ZMP) of the whole robot's
/// required contact wrench stays in the support of the stance feet, shrunk by a stability
/// margin, on every instant outside touchdowns; on a line support (two feet: a trot, a pace) on
/// the line itself.
///
/// Method. The ZMP p(t) on a horizontal plane that moves with the trunk's height is taken from
/// the full inverse dynamics (dynamics/rnea.hpp, every leg's motion included). The offset e(t)
/// obeys the linear inverted pendulum e − ë/ω² = z(t) − s(t) (planning/trunk_offset.hpp): z is
/// the designed ZMP path, linear between waypoints at the breakpoints (every lift-off and
/// touchdown, each swing's lift and descent boundaries, the ends of the speed ramps, and
/// splits of long pieces), each waypoint inside the support the feet share on both sides of it;
/// s is what the pendulum leaves out, sampled at Chebyshev–Lobatto nodes of each piece and
/// interpolated. The waypoints nearest the straight path's ZMP that let the offset start and end
/// at rest are found by a projected semi-smooth Newton method on four multipliers. s is then
/// sampled again on the new path, until it changes by less than the tolerance: then p = z at
/// every node, and between nodes to the interpolation's accuracy.
///
/// The robot starts and ends at rest, its ZMP under its centre of mass: the plan of a balanced
/// scene stands on all its feet for at least kSettlePeriods / ω before its travel and first
/// swing and after its last while the trunk moves its weight (TrunkMotion's hold,
/// settle_time_s in planning/posture.hpp).
#include <string>

#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

struct BalanceOptions {
  double margin_m = 0.01;  ///< the stability margin: a waypoint's distance from the edges
  /// Largest |p − z| at the nodes of a piece whose support is a line or a point that ends the
  /// passes [m]: on a line the ZMP has no room, and the run's trunk rows then hold to 1e-9 of the
  /// weight (ctest dynamics.robots_against_dart).
  double tolerance_m = 1e-9;
  /// The same on pieces whose support is a polygon, where the margin leaves the ZMP room: a
  /// ten-thousandth of the default 0.01 m margin [m].
  double polygon_tolerance_m = 1e-6;
  int max_iterations = 60;  ///< iterations of s before PlanningError
  int nodes = 5;            ///< Chebyshev–Lobatto nodes per piece on a polygon support
  /// Nodes per piece on a segment or point support, where the ZMP has no room to miss its path
  /// between nodes: a miss of 4e-8 m under Solo-12's weight is a moment beyond the
  /// allocation's 1e-6 N m threshold (allocation/qp.hpp).
  int line_nodes = 17;
  double max_piece_s = 0.06;  ///< longest piece [s]
};

/// Passes that reach BalanceOptions::max_iterations without the tolerance still hold when the
/// ZMP's miss on a line support, times the largest force the feet supply, is at most this
/// moment [N m]: a quarter of the allocation's threshold of a violated trunk moment row
/// (kViolationThreshold, 1e-6 N m, allocation/qp.hpp), so that its trunk rows hold as on a
/// path within the tolerance; and when a polygon's miss is at most kStallPolygonShare of the
/// margin.
inline constexpr double kStallMoment_Nm = 2.5e-7;
inline constexpr double kStallPolygonShare = 0.01;

/// What balance_trunk found.
struct BalanceReport {
  int iterations = 0;              ///< evaluations of s on the whole path
  double zmp_error_m = 0.0;        ///< largest |p − z| at the nodes of the last path [m]
  double smallest_margin_m = 0.0;  ///< least depth of p in the support of its piece, at the nodes
  double omega_radps = 0.0;        ///< the pendulum's √(g / h)
  int pieces = 0;
  double largest_offset_m = 0.0;  ///< largest |e| at the nodes [m]
  /// Posture searches the plan took: 1, or more when an automatic posture was searched again
  /// with the offset because the legs could not follow the balanced path (pipeline.hpp).
  int posture_rounds = 1;
  /// True when the passes stopped at max_iterations short of the tolerance but within
  /// kStallMoment_Nm (zmp_error_m is then their last miss).
  bool stalled = false;
  double stall_moment_Nm = 0.0;  ///< the last pass's line miss times the largest foot force
};

/// Plans the offset of plan.trunk (which must have none) and sets it. Throws PlanningError in
/// one line when the robot does not stand statically balanced at the start or the end, when two
/// consecutive supports share no foot, or when the iteration does not settle (within its
/// tolerance, or at max_iterations within kStallMoment_Nm).
BalanceReport balance_trunk(const RobotModel& model, MotionPlan& plan,
                            const BalanceOptions& options);

}  // namespace hexdyn
