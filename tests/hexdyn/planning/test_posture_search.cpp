// The automatic posture search (planning/posture.cpp, PostureSearch) against a second
// computation: the plain search written out here, a scan of 25 heights and a golden-section
// refinement with every candidate's margin computed completely from a freshly planned motion
// (plan_motion_with, motion_kinematic_margin), and the spread search when the margin is below
// the target. The library's search plans a spread's gait once and stops losing candidates
// early; it must take the same decisions: the same height and spread to the last bit, the same
// number of candidates, the same margin on the dense check grid (every field, though the check
// skips the samples its bounds show harmless), and the same verdict when only admission is
// asked. And no height of the plain scan may have a larger margin than the chosen posture.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/planning/plan.hpp"
#include "hexdyn/planning/posture.hpp"

namespace hexdyn {
namespace {

const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The plain search of posture.hpp's file comment, for the paper robot (hips in the trunk
/// plane, so the default heights run from the trunk clearance to the legs' reach).
struct PlainSearch {
  const Scene& scene;
  const RobotModel& model;
  int evaluations = 0;
  std::vector<double> scan_margins;  ///< of the scene's own spread

  struct Point {
    double h = 0.0, w = 0.0, margin = -kInf;
  };

  double margin(double h, double w, int uniform) {
    ++evaluations;
    try {
      const Vec3 p0 = relative_start_position(scene.terrain, h, scene.motion.posture.start_y_m);
      return motion_kinematic_margin(model, plan_motion_with(scene, model, p0, w), uniform).value_m;
    } catch (const PlanningError&) {
      return -kInf;
    }
  }

  Point best_height(double w, double lo, double hi, bool record) {
    std::vector<Point> scan;
    int best = 0;
    for (int i = 0; i < 25; ++i) {
      const double h = lo + (hi - lo) * i / 24;
      scan.push_back({h, w, margin(h, w, 200)});
      if (record) scan_margins.push_back(scan.back().margin);
      if (scan[i].margin > scan[best].margin) best = i;
    }
    double a = scan[std::max(best - 1, 0)].h, b = scan[std::min(best + 1, 24)].h;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    Point x1{b - g * (b - a), w}, x2{a + g * (b - a), w};
    x1.margin = margin(x1.h, w, 200);
    x2.margin = margin(x2.h, w, 200);
    Point top = scan[best];
    while (b - a > 1e-4) {
      if (x1.margin >= x2.margin) {
        b = x2.h;
        x2 = x1;
        x1 = {b - g * (b - a), w};
        x1.margin = margin(x1.h, w, 200);
      } else {
        a = x1.h;
        x1 = x2;
        x2 = {a + g * (b - a), w};
        x2.margin = margin(x2.h, w, 200);
      }
      for (const Point* c : {&x1, &x2})
        if (c->margin > top.margin) top = *c;
    }
    return top;
  }

  Point run() {
    const PostureParams& p = scene.motion.posture;
    double reach = 0.0;
    for (int leg = 0; leg < model.legs(); ++leg)
      reach = std::max(reach, leg_foot_position_H(model, leg, Vec3::Zero()).norm());
    const double lo = std::max(0.0, scene.terrain.riser_height_m / 2 + p.trunk_clearance_m);
    Point best = best_height(scene.gait.foot_lateral_m, lo, reach, true);
    if (p.vary_foot_lateral && best.margin < p.target_margin_m)
      for (int i = 0; i < 9; ++i) {
        const double w =
            p.foot_lateral_min_m + (p.foot_lateral_max_m - p.foot_lateral_min_m) * i / 8;
        const Point c = best_height(w, lo, reach, false);
        if (c.margin > best.margin) best = c;
      }
    return best;
  }
};

std::string exact(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

TEST_CASE("posture search: the same decisions as the plain scan and golden section", "[posture]") {
  // Scenes of the 1,000-scenario grid (bench/sweep_1000.yaml): riser, peak speed, duty factor,
  // and a target margin; the grid's (0.01 m) is met at the scene's own foot spread, a larger
  // one makes the search try the spreads of motion.posture.foot_lateral as well.
  const double scenes[][4] = {{0.01, 0.05, 0.5, 0.01},
                              {0.05, 0.1, 2.0 / 3.0, 0.01},
                              {0.08, 0.2, 0.9, 0.01},
                              {0.10, 0.05, 5.0 / 6.0, 0.2}};
  int spread_searches = 0;
  for (const auto& s : scenes) {
    const Scene scene = load_scene(kConfigs + "/sweeps/stairs_base.yaml",
                                   {{"terrain.riser_height", exact(s[0])},
                                    {"motion.peak_speed", exact(s[1])},
                                    {"gait.duty_factor", exact(s[2])},
                                    {"motion.posture.target_margin", exact(s[3])}});
    INFO("riser " << s[0] << " speed " << s[1] << " duty factor " << s[2]);
    const RobotModel model = build_robot_model(scene.robot);
    REQUIRE(model.leg_geometry == LegGeometry::kPaperPlanar);
    const PostureChoice fast = best_posture(scene, model);
    PlainSearch plain{scene, model, 0, {}};
    const PlainSearch::Point ref = plain.run();
    CHECK(fast.height_m == ref.h);
    CHECK(fast.foot_lateral_m == ref.w);
    const double T =
        plan_motion_with(scene, model, fast.p0_W, fast.foot_lateral_m).trunk.duration_s();
    const double dense =
        plain.margin(ref.h, ref.w, static_cast<int>(std::ceil(T / 0.005)) + 1);  // as posture.cpp
    CHECK(fast.evaluations == plain.evaluations);
    CHECK(fast.margin.value_m == dense);
    // The dense check skips samples by their bounds; every field must be the complete one's.
    const int dense_uniform = static_cast<int>(std::ceil(T / 0.005)) + 1;
    const KinematicMargin full = motion_kinematic_margin(
        model, plan_motion_with(scene, model, fast.p0_W, fast.foot_lateral_m), dense_uniform);
    CHECK(fast.margin.value_m == full.value_m);
    CHECK(fast.margin.reach_m == full.reach_m);
    CHECK(fast.margin.joint_m == full.joint_m);
    CHECK(fast.margin.joint_rad == full.joint_rad);
    CHECK(fast.margin.admitted == full.admitted);
    CHECK(fast.margin.leg == full.leg);
    CHECK(fast.margin.t_s == full.t_s);
    CHECK(fast.margin.constraint == full.constraint);
    CHECK(fast.margin.samples == full.samples);
    // A run's check asks only whether the IK admits the posture: the same posture and verdict.
    const PostureChoice admission = best_posture(scene, model, PostureCheck::kAdmission);
    CHECK(admission.height_m == fast.height_m);
    CHECK(admission.foot_lateral_m == fast.foot_lateral_m);
    CHECK(admission.evaluations == fast.evaluations);
    CHECK(admission.margin.admitted == full.admitted);
    CHECK(std::isnan(admission.margin.value_m) == full.admitted);
    // Not worse than any height of the plain scan, on the scan's own sample grid.
    const Vec3 p0 =
        relative_start_position(scene.terrain, fast.height_m, scene.motion.posture.start_y_m);
    const double chosen =
        motion_kinematic_margin(model, plan_motion_with(scene, model, p0, fast.foot_lateral_m), 200)
            .value_m;
    for (double m : plain.scan_margins) CHECK(chosen >= m - 1e-9);
    spread_searches += fast.evaluations > 60;
  }
  CHECK(spread_searches >= 1);  // the spread search is among the checked decisions
}

}  // namespace
}  // namespace hexdyn
