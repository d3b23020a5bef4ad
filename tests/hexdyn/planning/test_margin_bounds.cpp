// The lower bounds that let the automatic posture skip samples (planning/margin_detail.hpp)
// against the margins themselves, computed here from the IK and the leg Jacobian
// (posture.hpp's definitions): for random foot targets of the paper robot's legs and random
// targets within a distance δ of them, every bound must lie below the true value at the
// second target, and a sample the bounds call admitted must be accepted by the IK. The bounds
// are also checked not to be vacuous: most of them exist and, for small δ, lie within a few δ
// of the value.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/margin_detail.hpp"
#include "hexdyn/planning/plan.hpp"
#include "hexdyn/planning/posture.hpp"

namespace hexdyn {
namespace {

const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The margins of one target, straight from their definitions.
struct TrueMargins {
  bool ok = false;
  double reach_m = kInf, joint_m = kInf, joint_rad = kInf;
  double value() const { return std::min(reach_m, joint_m); }
};

TrueMargins true_margins(const RobotModel& m, int leg, const Vec3& p) {
  TrueMargins t;
  const LegIkResult ik = leg_inverse_kinematics(m, leg, p);
  t.ok = ik.ok;
  if (!ik.ok) return t;
  t.reach_m = ik.margin_m;
  const Mat3 J = leg_jacobian_H(m, leg, ik.q);
  for (int j = 0; j < m.leg(leg).n_joints; ++j) {
    const int k = m.joint(leg, j);
    double c = -kInf;  // the angle to the nearer limit, the joint turned by 0 or ±2π
    for (double shift : {0.0, 2.0 * M_PI, -2.0 * M_PI})
      c = std::max(c, std::min(ik.q[j] + shift - m.joint_lower_rad[k],
                               m.joint_upper_rad[k] - ik.q[j] - shift));
    if (!std::isfinite(c)) continue;
    t.joint_rad = std::min(t.joint_rad, c);
    t.joint_m = std::min(t.joint_m, c * J.col(j).norm());
  }
  return t;
}

TEST_CASE("margin bounds: below the margins of every target within their distance", "[posture]") {
  const Scene scene = load_scene(kConfigs + "/paper.yaml");
  const RobotModel model = build_robot_model(scene.robot);
  REQUIRE(model.leg_geometry == LegGeometry::kPaperPlanar);
  std::mt19937 rng(20261126);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int pairs = 0, bounded = 0, admitted = 0, tight = 0, small = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    const int leg = trial % model.legs();
    // A target the IK accepts: random joint angles inside the limits.
    Vec3 q;
    for (int j = 0; j < model.leg(leg).n_joints; ++j) {
      const int k = model.joint(leg, j);
      const double lo = std::max(model.joint_lower_rad[k], -M_PI),
                   hi = std::min(model.joint_upper_rad[k], M_PI);
      q[j] = lo + (hi - lo) * unit(rng);
    }
    const Vec3 p = leg_foot_position_H(model, leg, q);
    const LegIkResult ik = leg_inverse_kinematics(model, leg, p);
    if (!ik.ok) continue;
    const TrueMargins at_p = true_margins(model, leg, p);
    const double radius = std::pow(10.0, -4.0 + 3.0 * unit(rng));  // 0.1 mm .. 10 cm
    const margin_detail::SampleBound b = margin_detail::sample_bound(model, leg, p, ik, radius);
    if (!(b.radius_m > 0.0)) continue;
    ++bounded;
    CHECK(b.radius_m <= radius);
    for (int k = 0; k < 4; ++k) {
      const double delta = b.radius_m * unit(rng);
      Vec3 dir(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
      const Vec3 p2 = p + delta * unit(rng) * dir.normalized();  // within delta of p
      const margin_detail::MarginBounds lb = margin_detail::bounds_at(b, delta);
      const TrueMargins at_p2 = true_margins(model, leg, p2);
      ++pairs;
      INFO("leg " << leg << " p " << p.transpose() << " delta " << delta);
      if (lb.admitted) {
        ++admitted;
        REQUIRE(at_p2.ok);
      }
      if (at_p2.ok) {
        CHECK(lb.reach_m <= at_p2.reach_m + 1e-12);
        CHECK(lb.joint_rad <= at_p2.joint_rad + 1e-12);
        CHECK(lb.joint_m <= at_p2.joint_m + 1e-12);
        CHECK(lb.value_m <= at_p2.value() + 1e-12);
      }
      // The value-only and admission-only forms agree with the full one.
      const double floor = at_p.value() - 0.5 * delta;
      CHECK(margin_detail::value_clears(b, delta, floor) == (lb.value_m >= floor));
      CHECK(margin_detail::admits(b, delta) == lb.admitted);
      // Not vacuous: at small distances the bound is within a few δ of the value.
      if (delta < 1e-3 && at_p.value() > 0.01) {
        ++small;
        tight += lb.value_m >= at_p.value() - 40.0 * delta;
      }
    }
  }
  INFO("pairs " << pairs << " bounded " << bounded << " admitted " << admitted << " tight " << tight
                << "/" << small);
  CHECK(pairs > 40000);
  CHECK(admitted > pairs / 2);
  CHECK(tight > small * 9 / 10);
}

TEST_CASE("margin bounds: none beyond the radius, for refused targets or other geometries",
          "[posture]") {
  const Scene scene = load_scene(kConfigs + "/paper.yaml");
  const RobotModel model = build_robot_model(scene.robot);
  const Vec3 p = leg_foot_position_H(model, 0, Vec3(0.1, 0.4, -1.6));
  const LegIkResult ik = leg_inverse_kinematics(model, 0, p);
  REQUIRE(ik.ok);
  const margin_detail::SampleBound b = margin_detail::sample_bound(model, 0, p, ik, 0.01);
  REQUIRE(b.radius_m > 0.0);
  CHECK(margin_detail::bounds_at(b, 0.5 * b.radius_m).value_m > -kInf);
  CHECK(margin_detail::bounds_at(b, 2.0 * b.radius_m).value_m == -kInf);
  CHECK_FALSE(margin_detail::bounds_at(b, 2.0 * b.radius_m).admitted);
  LegIkResult refused = ik;
  refused.ok = false;
  CHECK(margin_detail::sample_bound(model, 0, p, refused, 0.01).radius_m == 0.0);
  RobotModel chain = model;
  chain.leg_geometry = LegGeometry::kChain;
  CHECK(margin_detail::sample_bound(chain, 0, p, ik, 0.01).radius_m == 0.0);
}

TEST_CASE("foot track: leg_foot_motion's positions to the bit, on a dense grid", "[posture]") {
  const Scene scene = load_scene(kConfigs + "/sweeps/stairs_base.yaml");
  const RobotModel model = build_robot_model(scene.robot);
  const MotionPlan plan = plan_motion(scene, model);
  const margin_detail::FootTrack track = margin_detail::foot_track(model, plan, 3001);
  REQUIRE(track.t_s.size() > 3001);
  int swinging = 0;
  for (std::size_t i = 0; i < track.t_s.size(); ++i)
    for (int leg = 0; leg < model.legs(); ++leg) {
      const FootMotion f = leg_foot_motion(plan.gait.legs[leg], track.t_s[i]);
      swinging += f.in_swing;
      CHECK(track.p_W[i][leg] == f.p_W);
    }
  CHECK(swinging > 1000);
}

}  // namespace
}  // namespace hexdyn
