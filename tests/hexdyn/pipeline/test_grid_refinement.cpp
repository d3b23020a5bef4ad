// The output grid's error control (pipeline/grid_refinement.hpp) on one fast, high-duty-factor
// climb, the end of the stair sweep where the grid as built errs most: its refined energies
// and peaks against the same scene on a converged grid (a second computation: a fine grid of
// its own, 0.5 ms steps and 400 intervals per transient), the estimates it records, and that
// tolerance 0 and the uniform grid leave the grid as built.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/planning/grid.hpp"
#include "hexdyn/power/power.hpp"

namespace hexdyn {
namespace {

const std::string kStairs = HEXDYN_SOURCE_DIR "/configs/sweeps/stairs_base.yaml";

/// One gait cycle at β = 3/4 and 0.15 m/s on 0.02 m risers (the worst scenario of the check
/// grid on the grid as built: a swing of 0.1 s gets a few samples).
Scene fast_climb(std::vector<Override> extra) {
  std::vector<Override> ov{{"motion.cycles", "2"},
                           {"gait.duty_factor", "0.75"},
                           {"motion.peak_speed", "0.15"},
                           {"terrain.riser_height", "0.02"}};
  ov.insert(ov.end(), extra.begin(), extra.end());
  return load_scene(kStairs, ov);
}

double peak(const RowMatrix& m) { return m.cwiseAbs().maxCoeff(); }

double peak(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

TEST_CASE("grid refinement: energy and peaks within the tolerance of a converged grid",
          "[grid_refinement]") {
  const RunResult converged = run_scene(fast_climb({{"output.sample_step", "0.0005"},
                                                    {"output.event_step", "0.0001"},
                                                    {"output.impact_samples", "400"},
                                                    {"output.tolerance", "1e-6"}}));
  const RunResult as_built = run_scene(fast_climb({{"output.tolerance", "0"}}));
  const double E_ref = converged.dyn.energy_total_J;
  const double as_built_error = std::abs(as_built.dyn.energy_total_J - E_ref) / E_ref;
  INFO("converged " << E_ref << " J; grid as built " << as_built.dyn.energy_total_J << " J");
  // The scene is one the grid as built gets wrong: the test would pass trivially otherwise.
  CHECK(as_built_error > 1e-2);
  CHECK(as_built.grid.tolerance == 0.0);
  CHECK(as_built.grid.added_samples == 0);
  CHECK(as_built.grid.energy_error > 1e-3);  // its estimate says so too

  for (double tol : {1e-2, 1e-3, 1e-4}) {
    const RunResult r = run_scene(fast_climb({{"output.tolerance", std::to_string(tol)}}));
    INFO("tolerance " << tol << ": " << r.kin.samples() << " samples, energy "
                      << r.dyn.energy_total_J << " J");
    CHECK(r.grid.tolerance == tol);
    CHECK(r.grid.energy_error <= tol);
    CHECK(r.grid.peak_error <= tol);
    CHECK(r.grid.added_samples == r.kin.samples() - as_built.kin.samples());
    CHECK(std::abs(r.dyn.energy_total_J - E_ref) <= tol * E_ref);
    const int joints = static_cast<int>(r.kin.joint_velocity.cols());
    for (int j = 0; j < joints; ++j) {
      const double e = r.dyn.energy_joint_J[j], e_ref = converged.dyn.energy_joint_J[j];
      CHECK(std::abs(e - e_ref) <= tol * std::max(e_ref, E_ref / joints));
    }
    CHECK(std::abs(peak(r.dyn.joint_torque) - peak(converged.dyn.joint_torque)) <=
          std::max(tol, 1e-3) * peak(converged.dyn.joint_torque));
    CHECK(std::abs(peak(r.dyn.total_power_W) - peak(converged.dyn.total_power_W)) <=
          std::max(tol, 1e-3) * peak(converged.dyn.total_power_W));
    // The grid as built is kept; the refined samples are ordinary ones, in time order, and the
    // stored samples integrate to the stored total.
    CHECK(std::is_sorted(r.kin.time_s.begin(), r.kin.time_s.end()));
    CHECK(std::adjacent_find(r.kin.time_s.begin(), r.kin.time_s.end()) == r.kin.time_s.end());
    for (double t : as_built.kin.time_s)
      CHECK(std::binary_search(r.kin.time_s.begin(), r.kin.time_s.end(), t));
    CHECK(std::count(r.kin.sample_kind.begin(), r.kin.sample_kind.end(), kSampleLeftLimit) ==
          std::count(as_built.kin.sample_kind.begin(), as_built.kin.sample_kind.end(),
                     kSampleLeftLimit));
    const std::vector<char> jump = jump_intervals(r.kin);
    double sum = 0.0;
    for (int j = 0; j < joints; ++j)
      sum += cubic_abs_integral(r.kin.time_s, jump, {r.dyn.joint_power.data() + j, joints});
    CHECK(sum == Approx(r.dyn.energy_total_J).epsilon(1e-12));
  }
}

TEST_CASE("grid refinement: the uniform grid and tolerance 0 keep the grid as built",
          "[grid_refinement]") {
  for (const std::vector<Override>& ov :
       {std::vector<Override>{{"output.tolerance", "0"}},
        std::vector<Override>{{"output.grid", "uniform"}, {"output.tolerance", "1e-4"}}}) {
    const Scene scene = fast_climb(ov);
    const PreparedScene prep = prepare_scene(scene);
    const RunResult r = run_prepared_scene(scene, prep);
    CHECK(r.kin.time_s == prep.grid);
    CHECK(r.grid.tolerance == 0.0);
    CHECK(r.grid.added_samples == 0);
    CHECK(r.grid.refinement_passes == 0);
    CHECK(r.grid.energy_error > 0.0);  // assessed all the same
  }
}

}  // namespace hexdyn
