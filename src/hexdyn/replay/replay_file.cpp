// The hexdyn-replay/1 file (io/schema_replay.hpp) and the `hexdyn replay` command.
#include "hexdyn/replay/replay_file.hpp"

#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <iostream>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/model/root_link.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/process/sha256.hpp"

namespace hexdyn {
namespace {

namespace s = schema;

constexpr const char* kUsage =
    R"(usage: hexdyn replay RESULT -o FILE [--set key.path=value ...] [--progress SECONDS]
  Replays a result's joint torques through the forward dynamics of the robot on its terrain,
  with compliant contact and friction, and writes a hexdyn-replay/1 file to FILE
  (docs/user/replay.md).

Each joint is driven by its stored torque plus a PD on the planned angle and rate (gains
replay.kp [N m/rad] and replay.kd [N m s/rad]; 0 and 0 is open loop). The integrator's
largest step is replay.step [s]. The contact's friction law reads contact.static_friction,
contact.dynamic_friction, contact.stiction_velocity and contact.friction_velocity. --set
changes a key of replay.* or contact.* for the replay (--set contact.static_friction=0.2);
any other key would not change the stored plan and is refused. The robot and the scene are
the result's own (/meta config_yaml, /model/urdf): files edited since the run are not read.
A progress line comes at most every --progress seconds (default 5). The report (trunk drift per gait cycle, tracking error, slip and touchdown energy, whether
the robot reached the plan's end) is in /replay of FILE and printed on stderr.
)";

/// Collects the datasets of the replay file in the order written.
struct Layout {
  ResultLayout layout;
  void add(const s::DatasetSpec& spec, std::vector<std::size_t> dims, LayoutValues values) {
    layout.datasets.push_back(LayoutDataset{&spec, std::move(dims), std::move(values)});
  }
  void scalar(const s::DatasetSpec& spec, double v) { add(spec, {}, std::vector<double>{v}); }
};

/// Rows of 3-vectors, 18-vectors or per-leg arrays flattened row-major.
template <class Row, class Get>
std::vector<double> flatten(const std::vector<Row>& rows, std::size_t width, Get get) {
  std::vector<double> out;
  out.reserve(rows.size() * width);
  for (const Row& r : rows)
    for (std::size_t j = 0; j < width; ++j) out.push_back(get(r, j));
  return out;
}

std::vector<double> legs3(const std::vector<std::array<Vec3, kLegs>>& rows) {
  return flatten(rows, 3 * kLegs, [](const auto& r, std::size_t j) { return r[j / 3][j % 3]; });
}
std::vector<double> legs1(const std::vector<std::array<double, kLegs>>& rows) {
  return flatten(rows, kLegs, [](const auto& r, std::size_t j) { return r[j]; });
}
std::vector<double> joints(const std::vector<VecJ>& rows) {
  return flatten(rows, kJoints,
                 [](const VecJ& r, std::size_t j) { return r[static_cast<Eigen::Index>(j)]; });
}
std::vector<double> vec3s(const std::vector<Vec3>& rows) {
  return flatten(rows, 3,
                 [](const Vec3& r, std::size_t j) { return r[static_cast<Eigen::Index>(j)]; });
}

/// /base/*: the trunk frame's state moved to the root link frame (model/root_link.hpp).
void add_base(Layout& b, const RobotModel& m, const std::vector<BaseState>& base) {
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

void add_series(Layout& b, const RobotModel& m, const ReplayResult& r) {
  const std::size_t T = r.t_s.size(), J = kJoints, L = kLegs;
  b.add(s::kTime, {T}, r.t_s);
  add_base(b, m, r.base);
  b.add(s::kJointPosition, {T, J}, joints(r.q));
  b.add(s::kJointVelocity, {T, J}, joints(r.qd));
  b.add(s::kJointAcceleration, {T, J}, joints(r.qdd));
  b.add(s::kJointTorque, {T, J}, joints(r.tau));
  b.add(s::kContactForce, {T, L, 3}, legs3(r.force_W));
  b.add(s::kFeetPosition, {T, L, 3}, legs3(r.foot_W));
  b.add(s::kReplayTrackingError, {T, J}, joints(r.tracking_error));
  b.add(s::kReplayFeedforward, {T, J}, joints(r.tau_ff));
  b.add(s::kReplayNormalForce, {T, L}, legs1(r.normal_N));
  b.add(s::kContactPenetration, {T, L}, legs1(r.penetration_m));
  b.add(s::kReplaySlipVelocity, {T, L, 3}, legs3(r.slip_velocity_W));
  b.add(s::kReplaySlipDisplacement, {T, L, 3}, legs3(r.slip_displacement_W));
  b.add(s::kReplaySlipDistance, {T, L}, legs1(r.slip_distance_m));
  b.add(s::kReplayEnergyActuator, {T}, r.actuator_energy_J);
  b.add(s::kReplayEnergyDamping, {T, L}, legs1(r.damping_energy_J));
  b.add(s::kReplayEnergySlip, {T, L}, legs1(r.slip_energy_J));
  b.add(s::kReplayEnergyKinetic, {T}, r.kinetic_J);
  b.add(s::kReplayEnergyPotential, {T}, r.potential_J);
}

void add_report(Layout& b, const ReplayResult& r) {
  const std::size_t Y = r.cycle_end_s.size();
  auto legs = [](const std::array<double, kLegs>& a) {
    return std::vector<double>(a.begin(), a.end());
  };
  b.add(s::kReplayCycleEnd, {Y}, r.cycle_end_s);
  b.add(s::kReplayPositionDrift, {Y, 3}, vec3s(r.position_drift_m));
  b.add(s::kReplayOrientationDrift, {Y, 3}, vec3s(r.orientation_drift_rad));
  b.scalar(s::kReplayMaxTrackingError, r.max_tracking_error_rad);
  b.add(s::kReplayMaxTrackingErrorJoint, {}, std::vector<std::int32_t>{r.max_tracking_error_joint});
  b.scalar(s::kReplayMaxTrackingErrorTime, r.max_tracking_error_time_s);
  b.add(s::kReplaySlipDistanceTotal, {kLegs}, legs(r.slip_distance_total_m));
  b.add(s::kReplaySlipEnergyTotal, {kLegs}, legs(r.slip_energy_total_J));
  b.add(s::kReplayTouchdownEnergy, {kLegs}, legs(r.damping_total_J));
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

void add_model(Layout& b, const ReplaySource& src) {
  b.add(s::kModelUrdf, {}, src.urdf);
  b.add(s::kModelJointNames, {src.joint_names.size()}, src.joint_names);
  b.add(s::kModelLegNames, {src.leg_names.size()}, src.leg_names);
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
  Layout b;
  add_model(b, source);
  add_series(b, model, result);
  add_report(b, result);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer writer(tmp, compressed_output(source.scene.resolved_yaml));
    write_meta(writer, source, result);
    write_layout(writer, b.layout);
    writer.close();
  });
}

namespace {

/// The report on stderr, one line per item.
void print_report(const ReplayResult& r, std::ostream& os) {
  os << "hexdyn: replay: " << (r.reached_top ? "reached" : "did not reach")
     << " the plan's end; final trunk position error " << r.final_position_error_m.norm() << " m\n";
  if (!r.message.empty()) os << "hexdyn: replay: ended early: " << r.message << "\n";
  for (std::size_t y = 0; y < r.cycle_end_s.size(); ++y)
    os << "hexdyn: replay: cycle end t = " << r.cycle_end_s[y] << " s: drift "
       << r.position_drift_m[y].transpose() << " m, " << r.orientation_drift_rad[y].transpose()
       << " rad\n";
  double slip = 0.0, slip_e = 0.0, damp = 0.0;
  for (int l = 0; l < kLegs; ++l) {
    slip += r.slip_distance_total_m[l];
    slip_e += r.slip_energy_total_J[l];
    damp += r.damping_total_J[l];
  }
  os << "hexdyn: replay: largest tracking error " << r.max_tracking_error_rad << " rad (joint "
     << r.max_tracking_error_joint << ", t = " << r.max_tracking_error_time_s << " s)\n"
     << "hexdyn: replay: slip " << slip << " m and " << slip_e << " J, contact damping " << damp
     << " J, joint energy " << r.energy_J << " J (inverse dynamics " << r.energy_plan_J << " J)\n"
     << "hexdyn: replay: balance of energy: joint work " << r.actuator_work_J << " J, residual "
     << r.energy_residual_J << " J; " << r.steps << " steps (" << r.forced_steps
     << " beyond the tolerance at the smallest step)\n";
}

}  // namespace

int replay_command(int argc, char** argv) {
  std::string result_path, output;
  std::vector<Override> overrides;
  double progress_s = 5.0;
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::cout << kUsage;
      return 0;
    }
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "-o" || arg == "--output" || arg == "--set" || arg == "--progress") {
        if (i + 1 >= argc) throw ConfigError(arg + ": missing value");
        if (arg == "--set")
          overrides.push_back(parse_override(argv[++i]));
        else if (arg == "--progress")
          progress_s = parse_progress_interval(argv[++i]);
        else
          output = argv[++i];
      } else if (arg.rfind("--set=", 0) == 0) {
        overrides.push_back(parse_override(arg.substr(6)));
      } else if (!arg.empty() && arg[0] == '-') {
        throw ConfigError("unknown option " + arg + "; run 'hexdyn replay --help'");
      } else if (result_path.empty()) {
        result_path = arg;
      } else {
        throw ConfigError("unexpected argument " + arg + "; run 'hexdyn replay --help'");
      }
    }
    if (result_path.empty()) throw ConfigError("replay: missing RESULT file");
    if (output.empty()) throw ConfigError("replay: missing -o FILE");
    install_interrupt_handlers(InterruptMode::kExitInHandler,
                               "hexdyn: replay interrupted by {signal}: nothing written to " +
                                   output +
                                   " (an existing file there is kept, no temporary file left); "
                                   "run the command again to compute it");
    const InputFreeze freeze;
    const ReplaySource src = read_replay_source(result_path, overrides);
    check_output_target(output, src.inputs);
    for (const std::string& w : src.warnings) std::cerr << "hexdyn: warning: replay: " << w << "\n";
    const RobotModel model = build_robot_model(src.scene.robot);
    const ProgressScope progress(std::cerr, "replay", progress_s);
    const ReplayResult r =
        replay_plan(model, src.scene.contact, src.scene.replay, src.scene.terrain, src.plan);
    write_replay_file(output, src, model, r);
    print_report(r, std::cerr);
    std::cerr << "hexdyn: wrote " << output << " (" << r.t_s.size() << " samples, " << r.steps
              << " steps, " << r.seconds << " s)\n";
    return 0;
  } catch (const Error& e) {
    std::cerr << "hexdyn: error: " << one_line(e.what()) << "\n";
    return e.exit_status();
  } catch (const std::exception& e) {
    std::cerr << "hexdyn: internal error: " << one_line(e.what()) << "\n";
    return 4;
  }
}

}  // namespace hexdyn
