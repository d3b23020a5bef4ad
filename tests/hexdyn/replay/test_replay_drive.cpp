// The replay driven through the actuators (replay/replay.hpp,
// docs/theory/replay.md#driven-by-the-actuators) on the paper scene with Dynamixel MX-64 drives:
// each sample's accelerations are those that the inverse dynamics (RNEA, a second algorithm: the
// forward dynamics solve the composite-rigid-body mass matrix) turn back into the drive torque less
// the armature's and the friction's shares; the check fails with either share left out. Weak drives
// saturate and the robot falls; the MX-64 climbs, its electrical energy the inverse dynamics'.
#include <catch2/catch.hpp>
#include <cmath>

#include "hexdyn/config/config.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/pipeline/run.hpp"
#include "hexdyn/replay/replay.hpp"
#include "paper_replay.hpp"

namespace {

using namespace hexdyn;

using test::Replayed;

/// The paper scene with every joint driven by `drive` (a YAML map of actuators.default).
Replayed replay_driven(const std::string& drive, std::vector<Override> extra = {}) {
  extra.push_back(parse_override("actuators.default=" + drive));
  return test::replay_paper(extra);
}

/// The documented joint friction of the replay: τ_c tanh(q̇ / 1e-3 rad/s) + b q̇.
double friction_law(const ActuatorParams& a, double qd) {
  return a.coulomb_friction_Nm * std::tanh(qd / 1e-3) + a.viscous_friction_Nmsprad * qd;
}

double total(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

const char* const kMx64 = "{model: dynamixel_mx64}";

}  // namespace

TEST_CASE("a driven replay's samples carry the armature and the joints' friction", "[replay]") {
  const Replayed r = replay_driven(kMx64);
  const ReplayResult& res = r.result;
  const RobotModel& m = r.model;
  REQUIRE(m.drive.present);
  REQUIRE(res.message.empty());
  REQUIRE(res.tau_drive.size() == res.t_s.size());
  // The MX-64's armature and friction are not zero: the check below can tell them apart.
  REQUIRE(m.drive.joints[0].armature_kgm2 > 0.0);
  REQUIRE(m.drive.joints[0].coulomb_friction_Nm + m.drive.joints[0].viscous_friction_Nmsprad > 0.0);
  RobotData data(m);
  double worst = 0.0, without_armature = 0.0, without_friction = 0.0, scale = 0.0, trunk = 0.0;
  for (std::size_t i = 0; i < res.t_s.size(); ++i) {
    const DofVector& gen =
        rnea(m, data, res.base[i], res.q[i], res.qd[i], res.qdd[i], &res.force_W[i], nullptr);
    trunk = std::max(trunk, gen.head<6>().cwiseAbs().maxCoeff());
    for (Eigen::Index j = 0; j < m.joints(); ++j) {
      const ActuatorParams& a = m.drive.joints[j];
      const double armature = a.armature_kgm2 * res.qdd[i][j];
      const double friction = friction_law(a, res.qd[i][j]);
      const double u = res.tau_drive[i][j];
      scale = std::max(scale, std::abs(u));
      worst = std::max(worst, std::abs(gen[6 + j] - (u - armature - friction)));
      without_armature = std::max(without_armature, std::abs(gen[6 + j] - (u - friction)));
      without_friction = std::max(without_friction, std::abs(gen[6 + j] - (u - armature)));
      // The link torque written is the same share of the drive torque.
      CHECK(std::abs(res.tau[i][j] - (u - armature - friction)) <= 1e-9 * (1.0 + std::abs(u)));
    }
  }
  INFO("worst " << worst << " without armature " << without_armature << " without friction "
                << without_friction << " trunk rows " << trunk << " scale " << scale);
  CHECK(worst <= 1e-8 * scale);
  CHECK(trunk <= 1e-8 * scale);
  CHECK(without_armature > 1e-4 * scale);
  CHECK(without_friction > 1e-3 * scale);
}

TEST_CASE("MX-64 drives climb, and drives too weak for the plan saturate and the robot falls",
          "[replay]") {
  const Replayed strong = replay_driven(kMx64);
  const ReplayResult& s = strong.result;
  INFO(s.message);
  CHECK(s.reached_top);
  REQUIRE(s.saturation_time_s.size() == static_cast<std::size_t>(strong.model.joints()));
  // Only touchdown transients reach the envelope, for well under a millisecond in all.
  CHECK(total(s.saturation_time_s) < 1e-2);
  // The electrical energy drawn is the inverse dynamics' to a few per cent, the copper loss
  // and the joints' friction are parts of it, and the balance of energy closes with the
  // friction's loss and the armature's kinetic energy in it.
  CHECK(s.electrical_energy_J == Approx(s.electrical_energy_plan_J).epsilon(0.02));
  CHECK(s.copper_loss_J.back() > 0.0);
  CHECK(s.copper_loss_J.back() < s.electrical_energy_J);
  CHECK(s.joint_friction_J.back() > 0.0);
  CHECK(std::abs(s.energy_residual_J) < 5e-3 * s.actuator_work_J);

  // Drives whose peak torque (1.5 N m) is below the gait's support torques.
  const std::string weak = "{model: dynamixel_mx64, peak_torque: 1.5}";
  const Replayed w = replay_driven(weak);
  CHECK_FALSE(w.result.reached_top);
  CHECK(total(w.result.saturation_time_s) > 0.5);
  for (const JointVector& u : w.result.tau_drive) CHECK(u.cwiseAbs().maxCoeff() <= 1.5 + 1e-12);
  // Unbounded, the same plan asks more of them than they have.
  const Replayed unbounded = replay_driven(weak, {parse_override("replay.saturate=false")});
  CHECK(total(unbounded.result.saturation_time_s) == 0.0);
  double largest = 0.0;
  for (const JointVector& u : unbounded.result.tau_drive)
    largest = std::max(largest, u.cwiseAbs().maxCoeff());
  CHECK(largest > 1.5);
}

TEST_CASE("a driven replay needs the plan's drive torques", "[replay]") {
  Replayed r = replay_driven(kMx64);
  r.plan.tau_drive_Nm.clear();
  CHECK_THROWS_WITH(replay_plan(r.model, r.scene.contact, r.scene.replay, r.scene.terrain, r.plan),
                    Catch::Contains("the robot has actuators but the plan has no drive torques"));
}
