// gait.phases through a whole run (planning/gait.hpp): the wave gait's own phases given as
// the key give the run without it bit for bit, and other phases give the contact schedule
// that the phases predict, counted from the phases alone.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/gait_cases.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/planning/gait.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

/// The paper scene at β = 2/3 (phases with every bit of 1/3 in them) on a coarse uniform grid.
std::vector<Override> small_scene() {
  return {{"gait.duty_factor", "2/3"},
          {"output.grid", "uniform"},
          {"output.sample_step", "0.1"},
          {"output.impact_samples", "4"}};
}

TEST_CASE("gait phases: the wave gait's phases as gait.phases give the same run, bit for bit",
          "[gait][phases]") {
  const std::vector<double> wave = wave_gait_phases(test::hexapod_legs(), 2.0 / 3.0);
  std::vector<Override> given = small_scene();
  given.push_back({"gait.phases", test::phases_text(wave)});
  const Scene with_key = load_scene(kPaper, given);
  REQUIRE(with_key.gait.liftoff_phases == wave);
  const RunResult a = run_scene(load_scene(kPaper, small_scene()));
  const RunResult b = run_scene(with_key);
  REQUIRE(a.kin.samples() > 50);
  REQUIRE(a.kin.samples() == b.kin.samples());
  CHECK(a.kin.time_s == b.kin.time_s);
  CHECK(a.kin.base_position == b.kin.base_position);
  CHECK(a.kin.joint_position == b.kin.joint_position);
  CHECK(a.kin.joint_acceleration == b.kin.joint_acceleration);
  CHECK(a.kin.foot_position == b.kin.foot_position);
  CHECK(a.kin.contact_phase == b.kin.contact_phase);
  CHECK(a.dyn.joint_torque == b.dyn.joint_torque);
  CHECK(a.dyn.contact_force == b.dyn.contact_force);
  CHECK(a.dyn.penetration == b.dyn.penetration);
  CHECK(a.dyn.solver_objective == b.dyn.solver_objective);
  CHECK(a.dyn.energy_joint_J == b.dyn.energy_joint_J);
  CHECK(a.dyn.energy_total_J == b.dyn.energy_total_J);
  CHECK(a.dyn.required_friction == b.dyn.required_friction);
}

TEST_CASE("gait phases: other phases give the contact schedule they predict", "[gait][phases]") {
  // β = 3/4, swings of a quarter cycle: L1 with L4, then L2, then L3 with L6, then L5.
  const std::vector<double> phi{0.0, 0.25, 0.5, 0.0, 0.75, 0.5};
  const double beta = 0.75;
  std::vector<Override> o = small_scene();
  o[0].value = "3/4";
  o.push_back({"gait.phases", test::phases_text(phi)});
  const Scene scene = load_scene(kPaper, o);
  const PreparedScene prep = prepare_scene(scene);
  const RunResult r = run_prepared_scene(scene, prep, nullptr);
  const TrunkMotion& trunk = prep.plan.trunk;
  int checked = 0;
  for (int i = 0; i < r.kin.samples(); ++i) {
    const double tau = trunk.phase(r.kin.time_s[i]);
    if (tau < 0.02 || tau > trunk.cycles() - 0.02) continue;  // swings cut at the run's ends
    double u_min = 1.0;  // the sample's distance in phase from the nearest lift-off/touchdown
    const int legs = prep.model.legs();
    for (int leg = 0; leg < legs; ++leg) {
      const double u = tau - phi[leg] - std::floor(tau - phi[leg]);
      u_min = std::min({u_min, u, std::abs(u - (1.0 - beta)), 1.0 - u});
    }
    if (u_min < 1e-3) continue;  // event samples sit on a lift-off or a touchdown
    for (int leg = 0; leg < legs; ++leg) {
      const double u = tau - phi[leg] - std::floor(tau - phi[leg]);
      const bool swing = u < 1.0 - beta;
      INFO("t " << r.kin.time_s[i] << " phase " << tau << " leg " << leg_name(leg));
      CHECK((r.kin.contact_phase(i, leg) == static_cast<std::int8_t>(ContactPhase::kSwing)) ==
            swing);
      ++checked;
    }
  }
  CHECK(checked > 6 * 30);
}

}  // namespace
}  // namespace hexdyn
