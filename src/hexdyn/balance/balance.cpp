#include "hexdyn/balance/balance.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "hexdyn/balance/anderson.hpp"
#include "hexdyn/balance/support_region.hpp"
#include "hexdyn/balance/waypoints.hpp"
#include "hexdyn/balance/zmp_probe.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"

namespace hexdyn {
namespace {

/// Breakpoints closer than this are one [s].
constexpr double kSameInstant_s = 1e-9;
/// A piece's first and last nodes are taken this far inside it, so that every event merged
/// into its breakpoints (within kSameInstant_s) lies outside: a leg touching down or lifting off
/// there is in the piece's own state at both nodes [s].
constexpr double kEndNudge_s = 2.0 * kSameInstant_s;
/// Feet closer than this, or this near a line through others, do not widen a support [m].
constexpr double kHullTolerance_m = 1e-9;

/// Whether `leg` stands at t (a swing holds [t_liftoff, t_touchdown)).
bool in_stance(const LegPlan& leg, double t) {
  for (const Swing& sw : leg.swings)
    if (t >= sw.t_liftoff_s && t < sw.t_touchdown_s) return false;
  return true;
}

/// Every instant where the ZMP's parts change smoothness (balance.hpp), sorted, on [0, T], with
/// pieces longer than max_piece split evenly.
std::vector<double> breakpoints(const MotionPlan& plan, double T, double max_piece) {
  std::vector<double> t = {0.0, T};
  const TrunkMotion& trunk = plan.trunk;
  const double h = trunk.hold_s(), r = trunk.ramp_duration_s();
  for (double b : {h, h + r, T - h - r, T - h})  // the travel's and its ramps' ends
    if (b > 0.0 && b < T) t.push_back(b);
  for (const LegPlan& leg : plan.gait.legs)
    for (const Swing& sw : leg.swings) {
      const double D = sw.t_touchdown_s - sw.t_liftoff_s;
      for (double b : {sw.t_liftoff_s, sw.t_touchdown_s, sw.t_liftoff_s + sw.lift_end_u * D,
                       sw.t_liftoff_s + sw.lower_start_u * D})
        if (b > 0.0 && b < T) t.push_back(b);
    }
  std::sort(t.begin(), t.end());
  std::vector<double> merged;
  for (double b : t)
    if (merged.empty() || b - merged.back() > kSameInstant_s) merged.push_back(b);
  merged.back() = T;
  std::vector<double> out;
  for (std::size_t k = 0; k + 1 < merged.size(); ++k) {
    const int parts =
        std::max(1, static_cast<int>(std::ceil((merged[k + 1] - merged[k]) / max_piece)));
    for (int j = 0; j < parts; ++j)
      out.push_back(merged[k] + (merged[k + 1] - merged[k]) * j / parts);
  }
  out.push_back(T);
  return out;
}

/// The stance feet of a waypoint's support, in the order of its hull's vertices [m, world]:
/// two for a segment, three or more for a polygon; where its exact lines are evaluated.
struct Edge {
  std::vector<Vec3> feet_W;
  /// A two-foot waypoint that must hold on both sides of its breakpoint (update_segment), the
  /// pieces before and after; otherwise -1 and the lines are taken at the node of piece `at`
  /// nearest the breakpoint (`at_end`: its last node).
  int before = -1, after = -1;
  int at = 0;
  bool at_end = true;
};

/// The pieces' geometry: breakpoints, each piece's support and each waypoint's region.
struct Layout {
  std::vector<double> t;                     ///< breakpoints t_0 … t_K
  std::vector<SupportRegion> piece_support;  ///< hull of the stance feet, per piece
  /// The waypoints, in time order: one per breakpoint, and two (just before and just after)
  /// at a breakpoint where a foot touches down and the feet shared are two, where the ZMP path
  /// jumps (docs/theory/balance.md#edges). Piece k runs from waypoint left[k] to right[k].
  std::vector<int> left, right;
  std::vector<SupportRegion> waypoint;  ///< per waypoint, its region (shrunk hull of its feet)
  /// Per waypoint, the feet of its support's hull, whose edges are taken on their exact lines
  /// (edge_line), when the hull is a segment or a polygon.
  std::vector<std::optional<Edge>> edge;
  /// Per pair of consecutive waypoints, the time its smoothness term divides by [s].
  std::vector<double> span_s;
  double margin_m = 0.0;
  /// Per piece, its Chebyshev–Lobatto nodes on [0, 1], decreasing: BalanceOptions::line_nodes
  /// on a piece whose support is a segment or a point, nodes on a polygon.
  std::vector<std::vector<double>> node_x;
  /// Nodes of piece k, n_k.
  int nodes(int k) const { return static_cast<int>(node_x[k].size()); }
  int pieces() const { return static_cast<int>(t.size()) - 1; }
};

std::string legs_text(const RobotModel& model, const std::vector<int>& legs) {
  std::string s;
  for (int l : legs) s += (s.empty() ? "" : ", ") + model.leg(l).name;
  return s.empty() ? "none" : s;
}

/// Appends a waypoint standing on feet_W: its region the hull of their projections shrunk by
/// the layout's margin, its edge the hull's feet in order (e: where its lines are taken).
/// Returns its index.
int add_waypoint(Layout& L, const std::vector<Vec3>& feet_W, Edge e) {
  std::vector<Vec2> feet;
  for (const Vec3& f : feet_W) feet.push_back(f.head<2>());
  const SupportRegion hull = convex_hull(feet, kHullTolerance_m);
  L.waypoint.push_back(shrink_to_fit(hull, L.margin_m, nullptr));
  std::optional<Edge> edge;
  if (hull.vertices.size() >= 2) {
    for (const Vec2& v : hull.vertices)
      for (std::size_t i = 0; i < feet.size(); ++i)
        if ((feet[i] - v).norm() <= kHullTolerance_m) {
          e.feet_W.push_back(feet_W[i]);
          break;
        }
    if (e.feet_W.size() == hull.vertices.size()) edge = std::move(e);
  }
  L.edge.push_back(std::move(edge));
  return static_cast<int>(L.waypoint.size()) - 1;
}

Layout make_layout(const RobotModel& model, const MotionPlan& plan, const BalanceOptions& o) {
  Layout L;
  const double T = plan.trunk.duration_s();
  L.t = breakpoints(plan, T, o.max_piece_s);
  const int K = L.pieces();
  std::vector<std::vector<int>> stance(K);
  for (int k = 0; k < K; ++k) {
    const double mid = 0.5 * (L.t[k] + L.t[k + 1]);
    std::vector<Vec2> feet;
    for (int l = 0; l < model.legs(); ++l) {
      if (!in_stance(plan.gait.legs[l], mid)) continue;
      stance[k].push_back(l);
      feet.push_back(leg_foot_motion(plan.gait.legs[l], mid).p_W.head<2>());
    }
    L.piece_support.push_back(convex_hull(feet, kHullTolerance_m));
  }
  L.margin_m = o.margin_m;
  const auto add = [&](const std::vector<Vec3>& feet_W, Edge e) {
    return add_waypoint(L, feet_W, std::move(e));
  };
  const auto feet_at = [&](const std::vector<int>& legs, double t) {
    std::vector<Vec3> f;
    for (int l : legs) f.push_back(leg_foot_motion(plan.gait.legs[l], t).p_W);
    return f;
  };
  L.left.assign(K, 0);
  L.right.assign(K, 0);
  L.left[0] = add(feet_at(stance[0], 0.0), Edge{});
  for (int k = 1; k < K; ++k) {
    std::vector<int> shared;
    bool touchdown = false;
    for (int l : stance[k]) {
      const bool before =
          std::find(stance[k - 1].begin(), stance[k - 1].end(), l) != stance[k - 1].end();
      if (before) shared.push_back(l);
      touchdown = touchdown || !before;
    }
    if (shared.empty()) {
      std::ostringstream m;
      m << "balanced trunk: at t = " << L.t[k] << " s the support changes from legs "
        << legs_text(model, stance[k - 1]) << " to legs " << legs_text(model, stance[k])
        << " with no foot in common, so the ZMP would have to jump; raise gait.duty_factor";
      throw PlanningError(m.str());
    }
    if (touchdown && shared.size() == 2) {
      L.right[k - 1] = add(feet_at(stance[k - 1], L.t[k]), Edge{{}, -1, -1, k - 1, true});
      L.span_s.push_back(L.t[k] - L.t[k - 1]);
      L.left[k] = add(feet_at(stance[k], L.t[k]), Edge{{}, -1, -1, k, false});
      L.span_s.push_back(o.max_piece_s);
    } else {
      L.right[k - 1] = L.left[k] = add(feet_at(shared, L.t[k]), Edge{{}, k - 1, k, k - 1, true});
      L.span_s.push_back(L.t[k] - L.t[k - 1]);
    }
  }
  L.right[K - 1] = add(feet_at(stance[K - 1], L.t[K]), Edge{});
  L.span_s.push_back(L.t[K] - L.t[K - 1]);
  L.edge.front().reset();  // the ends are pinned (at rest)
  L.edge.back().reset();
  for (int k = 0; k < K; ++k) {
    const int N = (L.piece_support[k].vertices.size() <= 2 ? o.line_nodes : o.nodes) - 1;
    std::vector<double> x;
    for (int j = 0; j <= N; ++j) x.push_back(0.5 * (1.0 + std::cos(M_PI * j / N)));
    L.node_x.push_back(std::move(x));
  }
  return L;
}

/// Chebyshev coefficients of the values f_j at y_j = cos(π j / N), j = 0 … N.
std::vector<Vec2> chebyshev_fit(const std::vector<Vec2>& f) {
  const int N = static_cast<int>(f.size()) - 1;
  std::vector<Vec2> c(N + 1, Vec2::Zero());
  for (int m = 0; m <= N; ++m) {
    for (int j = 0; j <= N; ++j) {
      const double half = (j == 0 || j == N) ? 0.5 : 1.0;
      c[m] += half * f[j] * std::cos(M_PI * m * j / N);
    }
    c[m] *= 2.0 / N;
  }
  c[0] *= 0.5;
  c[N] *= 0.5;
  return c;
}

/// The Chebyshev series of a piece's node values f (f[0] at its end, f[N] at its start, both
/// sampled kEndNudge_s inside it) with the two end values moved to the piece's ends along the
/// series' own slope: the one-sided limits there, to O(kEndNudge_s²).
std::vector<Vec2> end_corrected_fit(std::vector<Vec2> f, double span_s) {
  const int N = static_cast<int>(f.size()) - 1;
  const std::vector<Vec2> c = chebyshev_fit(f);
  Vec2 slope_end = Vec2::Zero(), slope_start = Vec2::Zero();  // d/dy at y = 1 and y = −1
  for (int m = 1; m <= N; ++m) {
    slope_end += c[m] * static_cast<double>(m * m);
    slope_start += c[m] * static_cast<double>(m % 2 ? m * m : -m * m);
  }
  const double dy_dt = 2.0 / span_s;
  f[0] += kEndNudge_s * dy_dt * slope_end;
  f[N] -= kEndNudge_s * dy_dt * slope_start;
  return chebyshev_fit(f);
}

Functionals functionals(const Layout& L, const std::vector<std::vector<Vec2>>& cheb, double w) {
  const int K = L.pieces();
  const double T = L.t[K];
  Functionals F;
  F.a.assign(L.waypoint.size(), Vec2::Zero());
  for (int k = 0; k < K; ++k) {
    const double t0 = L.t[k], t1 = L.t[k + 1];
    const double to_start = std::exp(-w * t0), to_end = std::exp(-w * (T - t1));
    OffsetPiece p{t0, t1, Vec2(1.0, 0.0), Vec2(0.0, 1.0), {}};  // x: left hat, y: right hat
    const Vec2 lo = decaying_integral(p, w, t0, t1, Decay::kFromLower) * to_start;
    const Vec2 hi = decaying_integral(p, w, t0, t1, Decay::kFromUpper) * to_end;
    F.a[L.left[k]] += Vec2(lo.x(), hi.x());
    F.a[L.right[k]] += Vec2(lo.y(), hi.y());
    OffsetPiece r{t0, t1, Vec2::Zero(), Vec2::Zero(), cheb[k]};  // forcing −s
    F.s_start -= decaying_integral(r, w, t0, t1, Decay::kFromLower) * to_start;
    F.s_end -= decaying_integral(r, w, t0, t1, Decay::kFromUpper) * to_end;
  }
  return F;
}

/// PlanningError unless the ZMP p of the robot at rest lies in its support.
void check_at_rest(const char* where, const Vec2& p, const SupportRegion& support) {
  if (depth(support, p) >= -1e-9) return;
  std::ostringstream m;
  m << "balanced trunk: at the " << where << " the robot stands with its ZMP (" << p.x() << ", "
    << p.y() << ") m outside its support by " << -depth(support, p)
    << " m, so it cannot stand still there";
  throw PlanningError(m.str());
}

/// Time of node j of piece k (balance.hpp): the last node just before the piece's end.
double node_time(const Layout& L, int k, int j) {
  const int N = L.nodes(k) - 1;
  const double nudge = j == 0 ? -kEndNudge_s : j == N ? kEndNudge_s : 0.0;
  return L.t[k] + L.node_x[k][j] * (L.t[k + 1] - L.t[k]) + nudge;
}

/// The pendulum fitted to the robot from its first offset e: per axis, the least-squares
/// ΔP ≈ κ e + γ ë over the nodes (ΔP the change of the ZMP it made), then κ and a common
/// ω² = mean of −κ/γ. Kept unchanged where the fit is not a pendulum (γ ≥ 0 or κ ≤ 0).
void fit_pendulum(const Layout& L, const TrunkOffset& offset,
                  const std::vector<std::vector<Vec2>>& before,
                  const std::vector<std::vector<Vec2>>& after, double& omega, Vec2& kappa) {
  Eigen::Matrix2d A[2] = {Eigen::Matrix2d::Zero(), Eigen::Matrix2d::Zero()};
  Eigen::Vector2d b[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  for (int k = 0; k < L.pieces(); ++k)
    for (int j = 0; j < L.nodes(k); ++j) {
      const OffsetState e = offset.at(node_time(L, k, j));
      const Vec2 dp = after[k][j] - before[k][j];
      for (int axis = 0; axis < 2; ++axis) {
        const Eigen::Vector2d x(e.e[axis], e.edd[axis]);
        A[axis] += x * x.transpose();
        b[axis] += x * dp[axis];
      }
    }
  double omega2 = 0.0;
  int fitted = 0;
  Vec2 k = kappa;
  for (int axis = 0; axis < 2; ++axis) {
    const Eigen::Vector2d f = A[axis].completeOrthogonalDecomposition().solve(b[axis]);
    if (!(f[0] > 0.0 && f[1] < 0.0)) continue;
    k[axis] = f[0];
    omega2 += -f[0] / f[1];
    ++fitted;
  }
  if (fitted == 0) return;
  kappa = k;
  omega = std::sqrt(omega2 / fitted);
}

}  // namespace

namespace {

/// Node values per piece and node (Layout::node_x order).
using NodeValues = std::vector<std::vector<Vec2>>;

/// The passes' state (balance.hpp): the pendulum (ω, κ), the ZMP P at the nodes, the path z
/// there, the waypoints' targets g and weights c, and the offset of the last pass.
struct Passes {
  Passes(const Layout& layout, double omega) : L(layout), w(omega) {
    const int K = L.pieces();
    P.resize(K);
    for (int k = 0; k < K; ++k) P[k].resize(L.nodes(k));
    W.resize(K);
    for (int k = 0; k < K; ++k) W[k].resize(L.nodes(k));
    s = z = P;
    g.resize(L.waypoint.size());
    c.assign(L.waypoint.size(), 0.0);
    for (int k = 0; k < K; ++k) {
      c[L.left[k]] += 0.5 * (L.t[k + 1] - L.t[k]);
      c[L.right[k]] += 0.5 * (L.t[k + 1] - L.t[k]);
    }
  }

  /// Samples P on the current path; returns the largest |P − z| (0 on the straight path).
  double sample(ZmpProbe& probe) {
    double error = 0.0;
    worst_m = line_worst_m = polygon_worst_m = largest_force_N = 0.0;
    for (int k = 0; k < L.pieces(); ++k) {
      // A polygon piece's error is measured against its own tolerance (BalanceOptions).
      const bool line = L.piece_support[k].vertices.size() <= 2;
      const double scale = line ? 1.0 : polygon_scale;
      for (int j = 0; j < L.nodes(k); ++j) {
        W[k][j] = probe.wrench_at(node_time(L, k, j));
        P[k][j] = ZmpProbe::zmp(W[k][j]);
        largest_force_N = std::max(largest_force_N, W[k][j].F.norm());
        if (!offset) continue;
        const double e = (P[k][j] - z[k][j]).norm();
        worst_m = std::max(worst_m, e);
        (line ? line_worst_m : polygon_worst_m) =
            std::max(line ? line_worst_m : polygon_worst_m, e);
        error = std::max(error, scale * e);
      }
    }
    return error;
  }

  /// The region of waypoint k whose support is the two feet p1, p2 (update_edges). Before the
  /// breakpoint the ZMP must lie on the side of the exact line (edge_line) where the piece
  /// before has its other feet; after it, on the side where the piece after has them; both lines
  /// are taken where they hold, just before and just after the breakpoint, since the wrench
  /// jumps at a touchdown. The region is the strip between them over the feet, or, when the
  /// two sides leave none, the line midway. Returns how far P is outside either side there.
  double update_segment(int i, const Edge& e) {
    const Vec3 &p1 = e.feet_W[0], &p2 = e.feet_W[1];
    const int kb = e.before, ka = e.after;
    const auto [a0, b0] = ZmpProbe::edge_line(W[kb].front(), p1, p2);
    const auto [a1, b1] = ZmpProbe::edge_line(W[ka].back(), p1, p2);
    if (!(a0.squaredNorm() > 0.0 && a1.squaredNorm() > 0.0)) return 0.0;
    const auto other = [&](const SupportRegion& r) {
      Vec2 sum = Vec2::Zero();
      for (const Vec2& v : r.vertices) sum += v;
      return Vec2(sum / static_cast<double>(std::max<std::size_t>(1, r.vertices.size())));
    };
    // Unit normals pointing into each side's support, offsets along them.
    const double s0 = a0.dot(other(L.piece_support[kb])) >= b0 ? 1.0 : -1.0;
    const double s1 = a1.dot(other(L.piece_support[ka])) >= b1 ? 1.0 : -1.0;
    const Vec2 n0 = s0 * a0 / a0.norm(), n1 = s1 * a1 / a1.norm();
    const double c0 = s0 * b0 / a0.norm(), c1 = s1 * b1 / a1.norm();  // side: n · p ≥ c
    const auto onto = [](const Vec2& q, const Vec2& n, double c) -> Vec2 {
      return q - n * (n.dot(q) - c);
    };
    // The feet's ends moved toward each other by the margin; across, the strip is exact.
    const Vec2 along = p2.head<2>() - p1.head<2>();
    const double inset = std::min(L.margin_m, 0.25 * along.norm()) / along.norm();
    const Vec2 q1 = p1.head<2>() + inset * along, q2 = p2.head<2>() - inset * along;
    const bool strip = n0.dot(onto(q1, n1, c1)) >= c0 && n0.dot(onto(q2, n1, c1)) >= c0;
    const SupportRegion region = strip
                                     ? SupportRegion{{onto(q1, n0, c0), onto(q2, n0, c0),
                                                      onto(q2, n1, c1), onto(q1, n1, c1)}}
                                     : SupportRegion{{0.5 * (onto(q1, n0, c0) + onto(q1, n1, c1)),
                                                      0.5 * (onto(q2, n0, c0) + onto(q2, n1, c1))}};
    edge_region[i] = convex_hull(region.vertices, 0.0);
    ++(strip ? strips : gaps);
    if (!strip) return 0.0;  // no region holds both sides: the midway line is a compromise
    return std::max({0.0, c0 - n0.dot(P[kb].front()), c1 - n1.dot(P[ka].back())});
  }

  /// The waypoints' regions on the exact lines of their supports' edges for the path as it
  /// stands, from the wrenches the last sample() took at the nodes (ZmpProbe::edge_line;
  /// docs/theory/balance.md#edges): two feet by update_segment; a
  /// polygon's vertices where the lines of its two edges meet, just before the breakpoint,
  /// shrunk by the margin. Returns how far the ZMP lies outside a two-foot region's sides.
  double update_edges() {
    if (edge_region.empty()) edge_region = L.waypoint;
    strips = gaps = 0;
    double miss = 0.0;
    for (std::size_t slot = 0; slot < L.edge.size(); ++slot) {
      if (!L.edge[slot]) continue;
      const Edge& e = *L.edge[slot];
      const std::vector<Vec3>& f = e.feet_W;
      const int n = static_cast<int>(f.size());
      if (n == 2 && e.before >= 0) {
        miss = std::max(miss, update_segment(static_cast<int>(slot), e));
        continue;
      }
      // At the node nearest the breakpoint on the waypoint's side of it.
      const int j = e.at_end ? 0 : L.nodes(e.at) - 1;
      if (n == 2) {  // one side only: the segment on its line, its ends moved inward
        const auto [a, b] = ZmpProbe::edge_line(W[e.at][j], f[0], f[1]);
        if (!(a.squaredNorm() > 0.0)) continue;
        const Vec2 along = f[1].head<2>() - f[0].head<2>();
        const double inset = std::min(L.margin_m, 0.25 * along.norm()) / along.norm();
        const auto onto = [&](const Vec2& q) -> Vec2 {
          return q - a * ((a.dot(q) - b) / a.squaredNorm());
        };
        edge_region[slot] = SupportRegion{
            {onto(f[0].head<2>() + inset * along), onto(f[1].head<2>() - inset * along)}};
        miss = std::max(miss, std::abs(a.dot(P[e.at][j]) - b) / a.norm());
        continue;
      }
      // A polygon: each vertex where the exact lines of its two edges meet.
      std::vector<std::pair<Vec2, double>> line(n);
      for (int i = 0; i < n; ++i) line[i] = ZmpProbe::edge_line(W[e.at][j], f[i], f[(i + 1) % n]);
      SupportRegion poly;
      for (int i = 0; i < n; ++i) {
        const auto& [a1, b1] = line[(i + n - 1) % n];
        const auto& [a2, b2] = line[i];
        Mat2 A;
        A << a1.x(), a1.y(), a2.x(), a2.y();
        const double det = A.determinant();
        if (!(std::abs(det) > 1e-12 * a1.norm() * a2.norm())) {
          poly.vertices.clear();
          break;
        }
        poly.vertices.push_back(A.inverse() * Vec2(b1, b2));
      }
      if (poly.vertices.size() == f.size())
        edge_region[slot] =
            shrink_to_fit(convex_hull(poly.vertices, kHullTolerance_m), L.margin_m, nullptr);
    }
    return miss;
  }

  /// s = P − κ (e − ë/ω²) at the nodes, mixed with the earlier passes.
  void residual(bool mix) {
    for (int k = 0; k < L.pieces(); ++k)
      for (int j = 0; j < L.nodes(k); ++j) {
        Vec2 lip = Vec2::Zero();
        if (offset) {
          const OffsetState e = offset->at(node_time(L, k, j));
          lip = e.e - e.edd / (w * w);
        }
        s[k][j] = P[k][j] - kappa.cwiseProduct(lip);
      }
    mixer.mix(s, mix);
  }

  /// The waypoints for s, and the offset whose forcing is (z − s) / κ.
  std::shared_ptr<const TrunkOffset> plan_offset() {
    const int K = L.pieces();
    std::vector<std::vector<Vec2>> cheb(K);
    for (int k = 0; k < K; ++k) cheb[k] = end_corrected_fit(s[k], L.t[k + 1] - L.t[k]);
    std::vector<SupportRegion> region = edge_region;
    region.front() = SupportRegion{{s[0].back()}};  // at rest: ë = 0 needs z = s at both ends
    region.back() = SupportRegion{{s[K - 1][0]}};
    double residual = 0.0;
    const std::vector<Vec2> wp =
        smooth_waypoints(region, g, c, L.span_s, functionals(L, cheb, w), w, &residual);
    const Vec2 inv = kappa.cwiseInverse();
    std::vector<OffsetPiece> pieces(K);
    for (int k = 0; k < K; ++k) {
      std::vector<Vec2> r = cheb[k];
      for (Vec2& x : r) x = x.cwiseProduct(inv);
      const Vec2 &a = wp[L.left[k]], &b = wp[L.right[k]];
      pieces[k] = {L.t[k], L.t[k + 1], a.cwiseProduct(inv), b.cwiseProduct(inv), r};
      for (int j = 0; j < L.nodes(k); ++j) {
        const double x = (node_time(L, k, j) - L.t[k]) / (L.t[k + 1] - L.t[k]);
        z[k][j] = a + (b - a) * x;
      }
    }
    offset = std::make_shared<const TrunkOffset>(w, std::move(pieces));
    return offset;
  }

  const Layout& L;
  double w;
  Vec2 kappa = Vec2::Ones();  ///< the pendulum's gain per axis, fitted after the first pass
  NodeValues P, s, z, P_first;
  std::vector<std::vector<ZmpWrench>> W;  ///< the wrench at the nodes of the last sample()
  std::vector<Vec2> g;
  std::vector<double> c;
  std::vector<SupportRegion> edge_region;  ///< the waypoints' regions, edges on their lines
  int strips = 0, gaps = 0;                ///< two-foot waypoints of the last update_edges
  std::shared_ptr<const TrunkOffset> offset;
  AndersonMixer mixer{6};
  double polygon_scale = 1.0;  ///< tolerance_m / polygon_tolerance_m
  double worst_m = 0.0;        ///< largest |P − z| of the last sample() [m]
  /// The same on the pieces whose support is a line or a point, and on the polygons [m].
  double line_worst_m = 0.0, polygon_worst_m = 0.0;
  double largest_force_N = 0.0;  ///< largest |F| the feet supply at the nodes of the last sample()
};

}  // namespace

BalanceReport balance_trunk(const RobotModel& model, MotionPlan& plan, const BalanceOptions& o) {
  ZmpProbe probe(model, plan);
  BalanceReport rep;
  rep.omega_radps = std::sqrt(model.gravity_W.norm() / probe.height_m());
  const Layout L = make_layout(model, plan, o);
  const int K = L.pieces();
  rep.pieces = K;
  Passes passes(L, rep.omega_radps);
  const double tolerance_m = o.tolerance_m;
  passes.polygon_scale = tolerance_m / std::max(o.polygon_tolerance_m, tolerance_m);
  for (rep.iterations = 1;; ++rep.iterations) {
    const double sampled = passes.sample(probe);  // update_edges reads its wrenches
    const double edge_miss_m = passes.update_edges();
    const double error = std::max(sampled, edge_miss_m);
    if (rep.iterations == 1) {
      for (int k = 0; k < K; ++k) {
        passes.g[L.left[k]] = passes.P[k].back();
        passes.g[L.right[k]] = passes.P[k].front();  // a jump's waypoint before; the end
      }
      for (int k = 1; k < K; ++k) passes.g[L.left[k]] = passes.P[k].back();
      check_at_rest("start", passes.g.front(), L.piece_support.front());
      check_at_rest("end", passes.g.back(), L.piece_support.back());
      passes.P_first = passes.P;
    }
    if (passes.offset && error < tolerance_m) {
      rep.zmp_error_m = passes.worst_m;
      break;
    }
    if (rep.iterations >= o.max_iterations) {
      // Stalled just short of the tolerance: kept when the miss is a moment the allocation
      // cannot see (balance.hpp, kStallMoment_Nm) and a polygon's is far inside its margin.
      const double line_miss_m = std::max(passes.line_worst_m, edge_miss_m);
      rep.stall_moment_Nm = line_miss_m * passes.largest_force_N;
      if (passes.offset && rep.stall_moment_Nm <= kStallMoment_Nm &&
          passes.polygon_worst_m <= kStallPolygonShare * o.margin_m) {
        rep.stalled = true;
        rep.zmp_error_m = passes.worst_m;
        break;
      }
      std::ostringstream m;
      m << "balanced trunk: the ZMP did not settle in " << o.max_iterations
        << " passes (its largest miss of its path at the nodes is " << error / tolerance_m
        << " times its tolerance, " << tolerance_m << " m on a line support and "
        << std::max(o.polygon_tolerance_m, tolerance_m) << " m on a polygon; a moment of "
        << rep.stall_moment_Nm << " N m on a line";
      if (rep.stall_moment_Nm > kStallMoment_Nm)
        m << ", above the " << kStallMoment_Nm << " N m a stall may leave)";
      else
        m << " and a miss of " << passes.polygon_worst_m << " m on a polygon, above the "
          << kStallPolygonShare * o.margin_m << " m a stall may leave)";
      throw PlanningError(m.str());
    }
    if (rep.iterations == 2)
      fit_pendulum(L, *passes.offset, passes.P_first, passes.P, passes.w, passes.kappa);
    // Anderson mixing from the third pass on: the pendulum is a model, and its error makes
    // plain passes contract slowly; the fit of the second pass changes the map, so it restarts.
    passes.residual(rep.iterations >= 3);
    plan.trunk.set_offset(passes.plan_offset());
  }
  rep.omega_radps = passes.w;
  // Margins and offsets on the path that holds: the last pass sampled the ZMP on it.
  rep.smallest_margin_m = std::numeric_limits<double>::infinity();
  for (int k = 0; k < K; ++k)
    for (int j = 0; j < L.nodes(k); ++j) {
      rep.smallest_margin_m =
          std::min(rep.smallest_margin_m, depth(L.piece_support[k], passes.P[k][j]));
      rep.largest_offset_m =
          std::max(rep.largest_offset_m, passes.offset->at(node_time(L, k, j)).e.norm());
    }
  return rep;
}

}  // namespace hexdyn
