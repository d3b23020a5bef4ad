// The hexdyn-replay/3 file (io/schema_replay.hpp).
#include "hexdyn/replay/replay_file.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/model/root_link.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/process/sha256.hpp"

namespace hexdyn {
namespace {

namespace s = schema;

/// Rows of 3-vectors, 18-vectors or per-leg arrays flattened row-major.
template <class Row, class Get>
std::vector<double> flatten(const std::vector<Row>& rows, std::size_t width, Get get) {
  std::vector<double> out;
  out.reserve(rows.size() * width);
  for (const Row& r : rows)
    for (std::size_t j = 0; j < width; ++j) out.push_back(get(r, j));
  return out;
}

/// The first `legs` legs' vectors of each row (per-leg storage of a capacity).
template <class Row>
std::vector<double> legs3(const std::vector<Row>& rows, std::size_t legs) {
  return flatten(rows, 3 * legs, [](const auto& r, std::size_t j) { return r[j / 3][j % 3]; });
}
template <class Row>
std::vector<double> legs1(const std::vector<Row>& rows, std::size_t legs) {
  return flatten(rows, legs, [](const auto& r, std::size_t j) { return r[j]; });
}
/// The first `joints` entries of each row.
template <class Row>
std::vector<double> joints(const std::vector<Row>& rows, std::size_t joints) {
  return flatten(rows, joints,
                 [](const Row& r, std::size_t j) { return r[static_cast<Eigen::Index>(j)]; });
}
std::vector<double> vec3s(const std::vector<Vec3>& rows) {
  return flatten(rows, 3,
                 [](const Vec3& r, std::size_t j) { return r[static_cast<Eigen::Index>(j)]; });
}

/// /base/*: the trunk frame's state moved to the root link frame (model/root_link.hpp).
void add_base(ResultLayout& b, const RobotModel& m, const std::vector<BaseState>& base) {
  std::vector<Vec3> p, v, w, a, alpha;
  std::vector<double> quat;
  for (const BaseState& trunk : base) {
    const BaseState x = root_link_state(m, trunk);
    p.push_back(x.p_W);
    v.push_back(x.v_W);
    w.push_back(x.omega_W);
    a.push_back(x.a_W);
    alpha.push_back(x.omegadot_W);
    Eigen::Quaterniond q(x.W_R_B);
    q.normalize();
    if (q.w() < 0.0) q.coeffs() *= -1.0;
    quat.insert(quat.end(), {q.w(), q.x(), q.y(), q.z()});
  }
  const std::size_t T = base.size();
  b.add(s::kBasePosition, {T, 3}, vec3s(p));
  b.add(s::kBaseOrientation, {T, 4}, quat);
  b.add(s::kBaseLinearVelocity, {T, 3}, vec3s(v));
  b.add(s::kBaseAngularVelocity, {T, 3}, vec3s(w));
  b.add(s::kBaseLinearAcceleration, {T, 3}, vec3s(a));
  b.add(s::kBaseAngularAcceleration, {T, 3}, vec3s(alpha));
}

void add_series(ResultLayout& b, const RobotModel& m, const ReplayResult& r) {
  const std::size_t T = r.t_s.size(), J = static_cast<std::size_t>(m.joints()),
                    L = static_cast<std::size_t>(m.legs());
  b.add(s::kTime, {T}, r.t_s);
  add_base(b, m, r.base);
  b.add(s::kJointPosition, {T, J}, joints(r.q, J));
  b.add(s::kJointVelocity, {T, J}, joints(r.qd, J));
  b.add(s::kJointAcceleration, {T, J}, joints(r.qdd, J));
  b.add(s::kJointTorque, {T, J}, joints(r.tau, J));
  b.add(s::kContactForce, {T, L, 3}, legs3(r.force_W, L));
  b.add(s::kFeetPosition, {T, L, 3}, legs3(r.foot_W, L));
  b.add(s::kReplayTrackingError, {T, J}, joints(r.tracking_error, J));
  b.add(s::kReplayFeedforward, {T, J}, joints(r.tau_ff, J));
  b.add(s::kReplayNormalForce, {T, L}, legs1(r.normal_N, L));
  b.add(s::kContactPenetration, {T, L}, legs1(r.penetration_m, L));
  b.add(s::kReplaySlipVelocity, {T, L, 3}, legs3(r.slip_velocity_W, L));
  b.add(s::kReplaySlipDisplacement, {T, L, 3}, legs3(r.slip_displacement_W, L));
  b.add(s::kReplaySlipDistance, {T, L}, legs1(r.slip_distance_m, L));
  b.add(s::kReplayEnergyActuator, {T}, r.actuator_energy_J);
  b.add(s::kReplayEnergyDamping, {T, L}, legs1(r.damping_energy_J, L));
  b.add(s::kReplayEnergySlip, {T, L}, legs1(r.slip_energy_J, L));
  b.add(s::kReplayEnergyKinetic, {T}, r.kinetic_J);
  b.add(s::kReplayEnergyPotential, {T}, r.potential_J);
}

void add_report(ResultLayout& b, const RobotModel& m, const ReplayResult& r) {
  const std::size_t Y = r.cycle_end_s.size(), L = static_cast<std::size_t>(m.legs());
  auto legs = [L](const auto& a) {
    return std::vector<double>(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(L));
  };
  b.add(s::kReplayCycleEnd, {Y}, r.cycle_end_s);
  b.add(s::kReplayPositionDrift, {Y, 3}, vec3s(r.position_drift_m));
  b.add(s::kReplayOrientationDrift, {Y, 3}, vec3s(r.orientation_drift_rad));
  b.scalar(s::kReplayMaxTrackingError, r.max_tracking_error_rad);
  b.add(s::kReplayMaxTrackingErrorJoint, {}, std::vector<std::int32_t>{r.max_tracking_error_joint});
  b.scalar(s::kReplayMaxTrackingErrorTime, r.max_tracking_error_time_s);
  b.add(s::kReplaySlipDistanceTotal, {L}, legs(r.slip_distance_total_m));
  b.add(s::kReplaySlipEnergyTotal, {L}, legs(r.slip_energy_total_J));
  b.add(s::kReplayTouchdownEnergy, {L}, legs(r.damping_total_J));
  b.scalar(s::kReplayEnergy, r.energy_J);
  b.scalar(s::kReplayEnergyPlan, r.energy_plan_J);
  b.scalar(s::kReplayActuatorWork, r.actuator_work_J);
  b.scalar(s::kReplayEnergyResidual, r.energy_residual_J);
  b.add(s::kReplayFinalError, {3}, vec3s({r.final_position_error_m}));
  b.add(s::kReplayReachedTop, {},
        std::vector<std::int8_t>{r.reached_top ? std::int8_t{1} : std::int8_t{0}});
  b.add(s::kReplayMessage, {}, r.message);
  b.scalar(s::kReplayStep, r.max_step_s);
  b.add(s::kReplaySteps, {}, std::vector<std::int32_t>{static_cast<std::int32_t>(r.steps)});
  b.add(s::kReplayForcedSteps, {},
        std::vector<std::int32_t>{static_cast<std::int32_t>(r.forced_steps)});
  b.scalar(s::kReplaySeconds, r.seconds);
}

/// The driven replay's datasets (schema_replay.hpp kReplayDriveDatasets), with actuators.
void add_drive(ResultLayout& b, const RobotModel& m, const ReplayResult& r) {
  if (!m.drive.present) return;
  const std::size_t T = r.t_s.size(), J = static_cast<std::size_t>(m.joints());
  b.add(s::kDriveTorque, {T, J}, joints(r.tau_drive, J));
  std::vector<std::int8_t> flags;
  for (const JointVector& row : r.saturated)
    for (std::size_t j = 0; j < J; ++j)
      flags.push_back(row[static_cast<Eigen::Index>(j)] != 0.0 ? std::int8_t{1} : std::int8_t{0});
  b.add(s::kReplaySaturated, {T, J}, flags);
  b.add(s::kReplayEnergyElectrical, {T}, r.electrical_J);
  b.add(s::kReplayEnergyCopper, {T}, r.copper_loss_J);
  b.add(s::kReplayEnergyJointFriction, {T}, r.joint_friction_J);
  b.add(s::kReplaySaturationTime, {J}, r.saturation_time_s);
  b.scalar(s::kReplayElectricalEnergy, r.electrical_energy_J);
  b.scalar(s::kReplayElectricalEnergyPlan, r.electrical_energy_plan_J);
}

void add_model(ResultLayout& b, const ReplaySource& src) {
  b.add(s::kModelUrdf, {}, src.urdf);
  b.add(s::kModelJointNames, {src.joint_names.size()}, src.joint_names);
  b.add(s::kModelLegNames, {src.leg_names.size()}, src.leg_names);
  b.add(s::kModelLegJointCounts, {src.leg_joint_counts.size()}, src.leg_joint_counts);
  b.add(s::kLegCoordinate, {src.leg_names.size()}, src.leg_names);
  b.add(s::kJointCoordinate, {src.joint_names.size()}, src.joint_names);
  b.add(s::kXyzCoordinate, {3}, std::vector<std::string>{"x", "y", "z"});
  b.add(s::kWxyzCoordinate, {4}, std::vector<std::string>{"w", "x", "y", "z"});
  b.add(s::kTerrainY, {src.plan.terrain_y_m.size()}, src.plan.terrain_y_m);
  b.add(s::kTerrainZ, {src.plan.terrain_z_m.size()}, src.plan.terrain_z_m);
}

void write_meta(H5Writer& w, const ReplaySource& src, const ReplayResult& r) {
  const std::string meta = s::kMetaGroup;
  write_meta_header(w, meta, s::kReplaySchema, s::kReplaySchemaVersion);
  w.set_string_attribute(meta, s::kAttrConfigYaml, src.scene.resolved_yaml);
  w.set_double_attribute(meta, s::kAttrWallTime, r.seconds);
  w.set_string_attribute(meta, s::kAttrInputSha256, input_sha256_text(src.inputs));
  w.set_string_attribute(meta, s::kMetaReplaySource.name, src.inputs.front().absolute);
  w.set_string_attribute(meta, s::kMetaReplaySourceCreated.name, src.created_utc);
}

}  // namespace

void write_replay_file(const std::string& path, const ReplaySource& source, const RobotModel& model,
                       const ReplayResult& result) {
  check_output_target(path, source.inputs);
  ResultLayout b;
  add_model(b, source);
  add_series(b, model, result);
  add_report(b, model, result);
  add_drive(b, model, result);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer writer(tmp, compressed_output(source.scene.resolved_yaml));
    write_meta(writer, source, result);
    write_layout(writer, b);
    writer.close();
  });
}

}  // namespace hexdyn
