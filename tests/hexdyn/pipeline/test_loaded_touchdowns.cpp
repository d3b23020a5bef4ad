// Loaded touchdowns on the paper scene (contact.touchdown: loaded,
// docs/theory/contact.md#loaded-touchdowns): every sample balanced, touchdowns included; the
// torques within the scene's limit; the required friction defined on every sample; each
// transient settled at its leg's load. The paper's transient on the same scene relaxes the
// trunk rows at every tripod switch, which is what the loaded one removes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "hexdyn/config/config.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/run.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

struct Counts {
  int relaxed = 0, relaxed_in_touchdowns = 0, impact_samples = 0, undefined_mu = 0;
  double peak_torque_Nm = 0.0;
};

Counts count(const RunResult& r) {
  Counts c;
  const DynamicsResult& d = r.dyn;
  for (Eigen::Index i = 0; i < d.joint_torque.rows(); ++i) {
    bool impact = false;
    for (Eigen::Index l = 0; l < r.kin.contact_phase.cols(); ++l)
      impact =
          impact || r.kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kImpact);
    const bool relaxed = d.solver_status[i] != SolverStatus::kOptimal;
    c.relaxed += relaxed;
    c.relaxed_in_touchdowns += relaxed && impact;
    c.impact_samples += impact;
    c.undefined_mu += !std::isfinite(d.required_friction[i]);
    c.peak_torque_Nm = std::max(c.peak_torque_Nm, d.joint_torque.row(i).cwiseAbs().maxCoeff());
  }
  return c;
}

}  // namespace

TEST_CASE("loaded touchdowns: the paper scene balanced on every sample, within its torques",
          "[pipeline][loaded]") {
  const Scene paper = load_scene(kPaper);
  REQUIRE(paper.contact.touchdown == TouchdownModel::kPaper);
  const Scene loaded = load_scene(kPaper, {parse_override("contact.touchdown=loaded")});
  const RunResult p = run_scene(paper), l = run_scene(loaded);
  const Counts cp = count(p), cl = count(l);
  INFO("paper: " << cp.relaxed << " relaxed (" << cp.relaxed_in_touchdowns << " in touchdowns), "
                 << "peak " << cp.peak_torque_Nm << " N m; loaded: " << cl.relaxed
                 << " relaxed, peak " << cl.peak_torque_Nm << " N m, " << cl.impact_samples
                 << " impact samples");
  // The paper's transient: the trunk rows relax at the tripod switches, beyond the limit.
  CHECK(cp.relaxed_in_touchdowns > 0);
  CHECK(cp.peak_torque_Nm > paper.allocation.torque_limit_Nm);
  // Loaded: none relaxed, touchdowns (densely sampled) included, within the limit, μ* defined.
  CHECK(cl.impact_samples > 50);
  CHECK(cl.relaxed == 0);
  CHECK(cl.peak_torque_Nm <= loaded.allocation.torque_limit_Nm);
  CHECK(cl.undefined_mu == 0);
  // Each transient settled at its leg's load, which the allocation's force at the end is near
  // (the load is the statics share, the force the torque-optimal one).
  REQUIRE(!l.dyn.impacts.empty());
  for (const ImpactRecord& imp : l.dyn.impacts) {
    INFO("leg " << imp.leg << " at t = " << imp.t_start_s);
    CHECK(imp.duration_s > 0.0);
    CHECK(imp.duration_s < 0.01);
    CHECK(imp.peak_force_N > 0.0);
    CHECK(imp.impulse_Ns > imp.effective_mass_kg * imp.approach_speed_mps);
  }
}

}  // namespace hexdyn
