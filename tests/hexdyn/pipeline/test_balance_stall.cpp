// Balanced-trunk passes stopped short of their tolerance (balance/balance.hpp,
// kStallMoment_Nm; docs/theory/balance.md#the-passes): on Solo-12's balanced trot, whose line
// pieces converge to 1e-9 m in some N passes, the passes cut at fewer are kept exactly when the
// last miss on a line, times the largest foot force, is within the stall moment, and then the
// allocation (a second computation of the trunk's equations, with the feet's forces) holds
// every sample outside touchdowns on that path; cut earlier, they stop in one line naming the
// moment. Uncut, the passes do not stall and give the run's offset bit for bit.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "hexdyn/balance/balance.hpp"
#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/run.hpp"

namespace hexdyn {
namespace {

const std::string kTrot = HEXDYN_SOURCE_DIR "/configs/robots/solo12_trot_balanced.yaml";

int relaxed_outside_touchdowns(const RunResult& r) {
  int relaxed = 0;
  for (Eigen::Index i = 0; i < r.dyn.joint_torque.rows(); ++i) {
    bool impact = false;
    for (Eigen::Index l = 0; l < r.kin.contact_phase.cols(); ++l)
      impact =
          impact || r.kin.contact_phase(i, l) == static_cast<std::int8_t>(ContactPhase::kImpact);
    relaxed += !impact && r.dyn.solver_status[i] != SolverStatus::kOptimal;
  }
  return relaxed;
}

}  // namespace

TEST_CASE("balance: passes cut short hold only within the stall moment", "[pipeline][balance]") {
  const Scene scene = load_scene(kTrot);
  const PreparedScene prep = prepare_scene(scene);
  REQUIRE(prep.balance);
  REQUIRE(prep.balance->posture_rounds == 1);  // the offset is balance_trunk's own
  CHECK_FALSE(prep.balance->stalled);
  const int passes = prep.balance->iterations;
  REQUIRE(passes > 4);
  BalanceOptions options;
  options.margin_m = scene.motion.balance_margin_m;
  const auto balance = [&](int max_iterations, MotionPlan& plan) {
    plan = prep.plan;
    plan.trunk.set_offset(nullptr);
    options.max_iterations = max_iterations;
    return balance_trunk(prep.model, plan, options);
  };

  MotionPlan plan = prep.plan;
  const BalanceReport again = balance(passes, plan);
  CHECK_FALSE(again.stalled);
  CHECK(again.iterations == passes);
  for (double t = 0.0; t <= plan.trunk.duration_s(); t += 0.01)
    CHECK(plan.trunk.at(t).p_W == prep.plan.trunk.at(t).p_W);

  // Cut one pass at a time: kept while the last miss is within the stall moment, then refused.
  int kept = 0, refused_at = 0;
  for (int k = passes - 1; k >= 2 && refused_at == 0; --k) {
    try {
      const BalanceReport r = balance(k, plan);
      CHECK(r.stalled);
      CHECK(r.iterations == k);
      CHECK(r.zmp_error_m > options.tolerance_m);
      CHECK(r.stall_moment_Nm <= kStallMoment_Nm);
      ++kept;
      PreparedScene cut = prep;
      cut.plan = plan;
      const RunResult run = run_prepared_scene(scene, cut);
      INFO("cut at " << k << " passes of " << passes << ", miss " << r.zmp_error_m << " m, moment "
                     << r.stall_moment_Nm << " N m");
      CHECK(relaxed_outside_touchdowns(run) == 0);
    } catch (const PlanningError& e) {
      refused_at = k;
      const std::string m = e.what();
      INFO(m);
      CHECK(m.find("did not settle in " + std::to_string(k) + " passes") != std::string::npos);
      CHECK(m.find("a moment of") != std::string::npos);
    }
  }
  CHECK(kept >= 1);        // the last passes before the tolerance are within the moment
  CHECK(refused_at >= 2);  // and the early ones are not
}

}  // namespace hexdyn
