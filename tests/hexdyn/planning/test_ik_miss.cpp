// A foot target out of a numerically solved leg's reach (model/leg_chain.cpp ik_numeric): the
// miss the IK reports, minus its margin, against the least distance from the target to the
// foot over the joint angles, found independently by a grid over the angles and a pattern
// search from its best points. The automatic posture ranks failing heights by that margin, and
// a run that fails names it.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/model/robot_model.hpp"

using namespace hexdyn;

namespace {

const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";

/// min over q of |FK(q) − p| [m]: a 36³ grid over [−π, π)³ (joint limits ignored, as the
/// iteration does), then a compass search from each of its five best points down to 1e-12 rad.
double least_distance(const RobotModel& m, int leg, const Vec3& p) {
  const auto dist = [&](const Vec3& q) { return (leg_foot_position_H(m, leg, q) - p).norm(); };
  constexpr int kGrid = 36;
  std::array<std::pair<double, Vec3>, 5> best;
  best.fill({std::numeric_limits<double>::infinity(), Vec3::Zero()});
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j)
      for (int k = 0; k < kGrid; ++k) {
        const Vec3 q = (Vec3(i, j, k) * (2.0 * M_PI / kGrid)).array() - M_PI;
        const double d = dist(q);
        if (d < best.back().first) {
          best.back() = {d, q};
          std::sort(best.begin(), best.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
        }
      }
  double least = std::numeric_limits<double>::infinity();
  for (auto [d, q] : best) {
    for (double step = 0.2; step > 1e-12;) {
      bool moved = false;
      for (int c = 0; c < 3; ++c)
        for (double s : {-step, step}) {
          Vec3 t = q;
          t[c] += s;
          const double dt = dist(t);
          if (dt < d) d = dt, q = t, moved = true;
        }
      if (!moved) step *= 0.5;
    }
    least = std::min(least, d);
  }
  return least;
}

}  // namespace

TEST_CASE("a target beyond a numeric leg's reach: the margin is minus the least miss",
          "[posture]") {
  // ANYmal C's legs (robots/anymal_c.urdf) solved by Levenberg–Marquardt instead of their closed
  // form; targets from 1.05 to 2 leg lengths from the hip in random directions.
  const Scene scene = load_scene(kConfigs + "/robots/anymal_c_flat.yaml");
  RobotModel model = build_robot_model(scene.robot);
  for (auto& d : model.leg_ik) d.method = LegIkMethod::kNumeric;
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), scale(1.05, 2.0);
  int compared = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const int leg = trial % model.legs();
    Vec3 u(unit(rng), unit(rng), unit(rng));
    u.normalize();
    const Vec3 p = scale(rng) * leg_reach_m(model, leg) * u;
    const LegIkResult ik = leg_inverse_kinematics(model, leg, p);
    const double least = least_distance(model, leg, p);
    INFO("leg " << leg << ", target " << p.transpose() << ": " << ik.reason << " (margin "
                << ik.margin_m << "), least distance " << least);
    REQUIRE_FALSE(ik.ok);
    CHECK(std::string(ik.margin_unit) == "m");
    CHECK(ik.reason.find("nearest foot position found is") != std::string::npos);
    // A miss is a distance some angles reach: never below the least one; and the iteration's
    // starts find the least one.
    CHECK(-ik.margin_m >= least - 1e-9);
    CHECK(-ik.margin_m <= least + 1e-6);
    ++compared;
  }
  CHECK(compared == 24);
}
