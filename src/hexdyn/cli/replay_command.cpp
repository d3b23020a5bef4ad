// `hexdyn replay RESULT -o FILE` (cli/command.hpp; replay/replay_file.hpp).
#include <yaml-cpp/yaml.h>

#include <iostream>
#include <string>

#include "hexdyn/cli/subcommands.hpp"
#include "hexdyn/core/progress.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/replay/replay_file.hpp"

namespace hexdyn::cli {
namespace {

/// "L3 tibia" for flat joint index 8 of the hexapod ("L3 j4" for a fourth joint:
/// docs/user/output.md#conventions), with the description's own name when it differs from
/// the positional one (a URDF robot's joint).
std::string joint_label(const RobotModel& model, int k, const std::vector<std::string>& names) {
  for (int leg = 0; leg < model.legs(); ++leg) {
    const int j = k - model.joint(leg, 0), m = model.leg(leg).n_joints;
    if (j < 0 || j >= m) continue;
    const std::string positional = joint_name(leg, j, m);  // "L3_tibia"
    std::string label = model.leg(leg).name + " " + positional.substr(positional.find('_') + 1);
    const auto at = static_cast<std::size_t>(k);
    if (at < names.size() && names[at] != positional) label += ", joint " + names[at];
    return label;
  }
  return "no joint";
}

/// After a fall, a note when the joint PD is weak against the robot's weight (weak_joint_pd).
void print_gain_note(const RobotModel& model, const ReplayResult& r, const ReplayParams& gains,
                     std::ostream& os) {
  const double moment_Nm = weight_moment_Nm(model);
  if (!r.fell || !weak_joint_pd(gains.kp_Nmprad, moment_Nm)) return;
  const double pd_Nm = 0.1 * gains.kp_Nmprad;
  os << "hexdyn: replay: note: the joint PD gives " << pd_Nm << " N m at 0.1 rad (replay.kp "
     << gains.kp_Nmprad << " N m/rad) against a weight moment m g l of " << moment_Nm << " N m ("
     << model.total_mass_kg << " kg): a robot this heavy may fall for want of feedback, whatever "
     << "its plan; try stiffer replay.kp and replay.kd, or auto (docs/user/replay.md#gains)\n";
}

/// The scene as replayed: its resolved configuration with the gains used in place of `auto`,
/// the request recorded beside them (auto.replay.kp: auto), as every automatic choice is.
std::string replayed_yaml(const std::string& resolved, const ReplayParams& gains) {
  YAML::Node root = YAML::Load(resolved);
  if (gains.kp_auto) {
    root["replay"]["kp"] = gains.kp_Nmprad;
    root["auto"]["replay"]["kp"] = "auto";
  }
  if (gains.kd_auto) {
    root["replay"]["kd"] = gains.kd_Nmsprad;
    root["auto"]["replay"]["kd"] = "auto";
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

/// The report on stderr, one line per item.
void print_report(const RobotModel& model, const ReplayResult& r, const ReplaySource& src,
                  const ReplayParams& gains, std::ostream& os) {
  os << "hexdyn: replay: " << (r.reached_top ? "reached" : "did not reach")
     << " the plan's end; final trunk position error " << r.final_position_error_m.norm() << " m\n";
  if (!r.message.empty()) os << "hexdyn: replay: ended early: " << r.message << "\n";
  print_gain_note(model, r, gains, os);
  for (std::size_t y = 0; y < r.cycle_end_s.size(); ++y)
    os << "hexdyn: replay: cycle end t = " << r.cycle_end_s[y] << " s: drift "
       << r.position_drift_m[y].transpose() << " m, " << r.orientation_drift_rad[y].transpose()
       << " rad\n";
  double slip = 0.0, slip_e = 0.0, damp = 0.0;
  for (int l = 0; l < model.legs(); ++l) {
    slip += r.slip_distance_total_m[l];
    slip_e += r.slip_energy_total_J[l];
    damp += r.damping_total_J[l];
  }
  os << "hexdyn: replay: largest tracking error " << r.max_tracking_error_rad << " rad ("
     << joint_label(model, r.max_tracking_error_joint, src.joint_names)
     << ", t = " << r.max_tracking_error_time_s << " s)\n"
     << "hexdyn: replay: slip " << slip << " m and " << slip_e << " J, contact damping " << damp
     << " J, joint energy " << r.energy_J << " J (inverse dynamics " << r.energy_plan_J << " J)\n"
     << "hexdyn: replay: balance of energy: joint work " << r.actuator_work_J << " J, residual "
     << r.energy_residual_J << " J; " << r.steps << " steps (" << r.forced_steps
     << " beyond the tolerance at the smallest step)\n";
  if (!model.drive.present) return;
  // The driven replay: electrical energy and saturation (docs/user/replay.md#actuators).
  std::size_t worst = 0;
  double saturated = 0.0;
  for (std::size_t j = 0; j < r.saturation_time_s.size(); ++j) {
    saturated += r.saturation_time_s[j];
    if (r.saturation_time_s[j] > r.saturation_time_s[worst]) worst = j;
  }
  os << "hexdyn: replay: drives: electrical energy " << r.electrical_energy_J
     << " J (inverse dynamics " << r.electrical_energy_plan_J << " J), copper loss "
     << r.copper_loss_J.back() << " J, joint friction " << r.joint_friction_J.back() << " J; ";
  if (saturated > 0.0)
    os << "saturated for " << saturated << " joint-s in all, longest "
       << joint_label(model, static_cast<int>(worst), src.joint_names) << " "
       << r.saturation_time_s[worst] << " s\n";
  else
    os << (src.scene.replay.saturate ? "never saturated\n"
                                     : "not bounded (replay.saturate: false)\n");
}

}  // namespace

int replay_command(const Args& args) {
  ReplaySource src = read_replay_source(args.input, args.overrides);
  check_output_target(args.output, src.inputs);
  for (const std::string& w : src.warnings) std::cerr << "hexdyn: warning: replay: " << w << "\n";
  const RobotModel model = build_robot_model(src.scene.robot);
  const ReplayParams gains = resolved_gains(src.scene.replay, model);
  if (gains.kp_auto || gains.kd_auto)
    std::cerr << "hexdyn: replay: joint PD kp " << gains.kp_Nmprad << " N m/rad, kd "
              << gains.kd_Nmsprad
              << " N m s/rad (replay.kp, replay.kd: " << (gains.kp_auto ? "auto" : "given") << ", "
              << (gains.kd_auto ? "auto" : "given") << "; weight moment " << weight_moment_Nm(model)
              << " N m)\n";
  const ProgressScope progress(std::cerr, "replay", args.progress_s);
  const ReplayResult r = replay_plan(model, src.scene.contact, gains, src.scene.terrain, src.plan);
  src.scene.replay = gains;  // the scene as replayed
  src.scene.resolved_yaml = replayed_yaml(src.scene.resolved_yaml, gains);
  write_replay_file(args.output, src, model, r);
  print_report(model, r, src, gains, std::cerr);
  std::cerr << "hexdyn: wrote " << args.output << " (" << r.t_s.size() << " samples, " << r.steps
            << " steps, " << r.seconds << " s)\n";
  return 0;
}

}  // namespace hexdyn::cli
