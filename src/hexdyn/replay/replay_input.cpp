// A result file read as the plan of a replay (replay_file.hpp read_replay_source): the robot
// and scene the run used, from the file itself, and every series checked before any work.
#include <sys/stat.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/model/robot_model.hpp"
#include "hexdyn/process/paths.hpp"
#include "hexdyn/process/sha256.hpp"
#include "hexdyn/replay/replay_file.hpp"

namespace hexdyn {
namespace {

namespace s = schema;

/// A dataset of the result as a rows×cols matrix (row-major values) of finite numbers;
/// throws IoError naming the file, the dataset, the sample and the value.
std::vector<double> read_matrix(const H5Reader& in, const std::string& file, const char* path,
                                std::size_t rows, std::size_t cols) {
  if (!in.is_dataset(path))
    throw IoError("replay: '" + file + "' has no " + path +
                  " (a hexdyn-result file with the dynamics is needed)");
  H5DoubleArray a = in.read_doubles(path);
  std::size_t n = 1;
  for (std::size_t d : a.dims) n *= d;
  if (a.dims.empty() || a.dims[0] != rows || n != rows * cols)
    throw IoError("replay: '" + file + "': " + path + " has " + std::to_string(n) +
                  " values, expected " + std::to_string(rows) + " samples of " +
                  std::to_string(cols));
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(a.values[i]))
      throw IoError("replay: '" + file + "': " + path + " at sample " + std::to_string(i / cols) +
                    " holds " + format_number(a.values[i], 6) + ", expected a finite number" +
                    (std::string(path) == s::kJointTorque.path
                         ? " (a failed sample cannot be replayed)"
                         : ""));
  return std::move(a.values);
}

Vec3 row3(const std::vector<double>& v, std::size_t i) {
  return Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
}

/// Row i of a samples × n matrix (row-major values) as a joint vector.
JointVector row_joints(const std::vector<double>& v, std::size_t i, Eigen::Index n) {
  return Eigen::Map<const Eigen::VectorXd>(v.data() + static_cast<std::size_t>(n) * i, n);
}

/// The result file as an input of the replay: its identity and checksum.
InputFile result_input(const std::string& path) {
  if (const auto why = why_not_regular_file(path))
    throw IoError("replay: '" + path + "' " + *why + ", expected a hexdyn-result file");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw IoError("replay: '" + path + "' cannot be read: " + std::strerror(errno));
  InputFile f;
  f.role = "result file";
  f.path = path;
  f.absolute = std::filesystem::absolute(path).lexically_normal().string();
  f.sha256 = sha256_file(path);
  f.device = static_cast<std::uint64_t>(st.st_dev);
  f.inode = static_cast<std::uint64_t>(st.st_ino);
  return f;
}

/// The unit quaternions of /base/orientation: a norm off 1 by more than kReplayQuaternionTolerance
/// is refused, naming the sample.
void check_quaternions(const std::vector<double>& wxyz, const std::string& file) {
  for (std::size_t i = 0; 4 * i < wxyz.size(); ++i) {
    const double norm = Eigen::Map<const Eigen::Vector4d>(wxyz.data() + 4 * i).norm();
    if (!(std::abs(norm - 1.0) <= kReplayQuaternionTolerance))
      throw IoError("replay: '" + file + "': " + s::kBaseOrientation.path + " at sample " +
                    std::to_string(i) + " has norm " + format_number(norm, 6) +
                    ", expected a unit quaternion (w, x, y, z) within " +
                    format_number(kReplayQuaternionTolerance, 6));
  }
}

/// The height map of a run on one (/terrain/map_x, map_y, map_z): its nodes evenly spaced.
std::shared_ptr<const HeightMap> read_height_map(const H5Reader& in, const std::string& file) {
  namespace s = schema;
  const auto dims = in.dims(s::kTerrainMapZ.path);
  if (dims.size() != 2 || dims[0] < 2 || dims[1] < 2)
    throw IoError("replay: '" + file + "': " + s::kTerrainMapZ.path +
                  " is not a grid of at least 2 x 2 heights");
  const std::vector<double> x = read_matrix(in, file, s::kTerrainMapX.path, dims[1], 1);
  const std::vector<double> y = read_matrix(in, file, s::kTerrainMapY.path, dims[0], 1);
  auto m = std::make_shared<HeightMap>();
  m->nx = static_cast<int>(dims[1]);
  m->ny = static_cast<int>(dims[0]);
  m->x0_m = x.front();
  m->y0_m = y.front();
  m->resolution_m = (x.back() - x.front()) / (m->nx - 1);
  m->z_m = read_matrix(in, file, s::kTerrainMapZ.path, dims[0], dims[1]);
  return m;
}

void read_plan(const H5Reader& in, const std::string& file, const RobotModel& model,
               ReplayPlan& p) {
  if (!in.is_dataset(s::kTime.path)) throw IoError("replay: '" + file + "' has no /time");
  const std::size_t T = in.dims(s::kTime.path).empty() ? 0 : in.dims(s::kTime.path)[0];
  p.t_s = read_matrix(in, file, s::kTime.path, T, 1);
  const auto pos = read_matrix(in, file, s::kBasePosition.path, T, 3);
  const auto quat = read_matrix(in, file, s::kBaseOrientation.path, T, 4);
  check_quaternions(quat, file);
  const auto vel = read_matrix(in, file, s::kBaseLinearVelocity.path, T, 3);
  const auto omega = read_matrix(in, file, s::kBaseAngularVelocity.path, T, 3);
  const auto J = static_cast<std::size_t>(model.joints());
  const auto q = read_matrix(in, file, s::kJointPosition.path, T, J);
  const auto qd = read_matrix(in, file, s::kJointVelocity.path, T, J);
  const auto tau = read_matrix(in, file, s::kJointTorque.path, T, J);
  // With actuators the drive torques are the feedforward (replay.hpp ReplayPlan).
  const std::vector<double> drive = model.drive.present
                                        ? read_matrix(in, file, s::kDriveTorque.path, T, J)
                                        : std::vector<double>{};
  for (std::size_t i = 0; i < T; ++i) {
    const Eigen::Vector4d wxyz(quat[4 * i], quat[4 * i + 1], quat[4 * i + 2], quat[4 * i + 3]);
    p.base.push_back(trunk_state_from_row(model, row3(pos, i), wxyz, row3(vel, i), row3(omega, i)));
    p.q_rad.push_back(row_joints(q, i, model.joints()));
    p.qd_radps.push_back(row_joints(qd, i, model.joints()));
    p.tau_Nm.push_back(row_joints(tau, i, model.joints()));
    if (!drive.empty()) p.tau_drive_Nm.push_back(row_joints(drive, i, model.joints()));
  }
  for (std::size_t k = 1; k < T; ++k)
    if (!(p.t_s[k] > p.t_s[k - 1]))
      throw IoError("replay: '" + file + "': /time at sample " + std::to_string(k) + " holds " +
                    format_number(p.t_s[k], 6) + ", expected more than the sample before (" +
                    format_number(p.t_s[k - 1], 6) + " s)");
  if (in.is_dataset(s::kGaitCycleStart.path)) {
    const auto dims = in.dims(s::kGaitCycleStart.path);
    p.cycle_start_s = read_matrix(in, file, s::kGaitCycleStart.path, dims.empty() ? 0 : dims[0], 1);
  }
  const std::size_t V = in.dims(s::kTerrainY.path).empty() ? 0 : in.dims(s::kTerrainY.path)[0];
  p.terrain_y_m = read_matrix(in, file, s::kTerrainY.path, V, 1);
  p.terrain_z_m = read_matrix(in, file, s::kTerrainZ.path, V, 1);
  if (in.is_dataset(s::kTerrainMapZ.path)) p.terrain_map = read_height_map(in, file);
}

/// The stored motion against the model: the feet placed by forward kinematics of the stored
/// joints and trunk, against the stored feet (a sphere foot's centre), within
/// kReplayFootTolerance_m. A mismatch means the scene or model is not the run's.
void check_feet(const H5Reader& in, const std::string& file, const RobotModel& model,
                const ReplayPlan& p) {
  const bool centre = in.is_dataset(s::kFeetCenter.path);
  const char* path = centre ? s::kFeetCenter.path : s::kFeetPosition.path;
  const int legs = model.legs();
  const auto feet = read_matrix(in, file, path, p.t_s.size(), 3 * static_cast<std::size_t>(legs));
  BodyPoses poses;
  for (std::size_t i = 0; i < p.t_s.size(); ++i) {
    forward_kinematics_tree(model, p.q_rad[i], poses);
    const BaseState& b = p.base[i];
    for (int leg = 0; leg < legs; ++leg) {
      const Vec3 fk_W = b.p_W + b.W_R_B * tree_foot_position_B(model, poses, leg);
      const Vec3 stored = row3(feet, static_cast<std::size_t>(legs) * i + leg);
      const double error = (fk_W - stored).norm();
      if (!(error <= kReplayFootTolerance_m))
        throw IoError("replay: '" + file + "': " + path + " of leg " + model.leg(leg).name +
                      " at sample " + std::to_string(i) + " (t = " + format_number(p.t_s[i], 6) +
                      " s) is " + format_number(error, 6) +
                      " m from where the stored joints and trunk put it, expected " + "at most " +
                      format_number(kReplayFootTolerance_m, 6) +
                      " m: the scene (/meta config_yaml, --set) or the robot is not the run's");
    }
  }
}

/// Each leg's joints: the model's leg table, which /model/leg_joint_counts (when the result has
/// it) must equal.
std::vector<std::int32_t> leg_joint_counts(const H5Reader& in, const std::string& file,
                                           const RobotModel& model) {
  std::vector<std::int32_t> counts;
  for (int l = 0; l < model.legs(); ++l) counts.push_back(model.leg(l).n_joints);
  if (!in.is_dataset(s::kModelLegJointCounts.path)) return counts;
  const std::vector<std::int64_t> stored = in.read_ints(s::kModelLegJointCounts.path);
  if (!std::equal(stored.begin(), stored.end(), counts.begin(), counts.end()))
    throw IoError("replay: '" + file + "': " + s::kModelLegJointCounts.path +
                  " does not match the legs of its own /model/urdf (" +
                  std::to_string(counts.size()) +
                  " legs): the file was edited or is not a hexdyn result");
  return counts;
}

/// The keys --set may change in a replay: those of its integrator and its contact law.
void check_replay_override(const Override& ov, bool robustness) {
  for (const char* prefix : {"replay.", "contact."})
    if (ov.key_path.rfind(prefix, 0) == 0) return;
  if (robustness && ov.key_path.rfind("robustness.", 0) == 0) return;
  throw ConfigError("--set " + ov.key_path +
                    ": a replay follows the stored plan, which this key does not change; "
                    "expected a key of replay.* or contact.* (the integrator, the contact and "
                    "friction laws)" +
                    (robustness ? std::string(" or robustness.*") : std::string()));
}

/// /contacts/phase (T × L, ContactPhase codes) of the result: which feet the plan has in swing.
RowMatrixI8 read_phases(const H5Reader& in, const std::string& file, std::size_t T,
                        Eigen::Index legs) {
  if (!in.is_dataset(s::kContactPhase.path))
    throw IoError("replay: '" + file + "' has no " + s::kContactPhase.path);
  const std::vector<std::int64_t> v = in.read_ints(s::kContactPhase.path);
  if (v.size() != T * static_cast<std::size_t>(legs))
    throw IoError("replay: '" + file + "': " + s::kContactPhase.path + " has " +
                  std::to_string(v.size()) + " values, expected " + std::to_string(T) +
                  " samples of " + std::to_string(legs));
  RowMatrixI8 phase(static_cast<Eigen::Index>(T), legs);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] < 0 || v[i] > static_cast<std::int64_t>(ContactPhase::kSupport))
      throw IoError("replay: '" + file + "': " + s::kContactPhase.path + " holds " +
                    std::to_string(v[i]) + ", expected 0 (swing), 1 (impact) or 2 (support)");
    phase.data()[i] = static_cast<std::int8_t>(v[i]);
  }
  return phase;
}

/// The scene the run used, from /meta config_yaml; a URDF robot built from the result's own
/// /model/urdf (its bodies as simulated: trunk "trunk", feet "<leg>_foot"), kept as the
/// input read at the name "RESULT#/model/urdf" (config/inputs.hpp keep_input), so that the
/// file the run read, edited or gone since, plays no part.
std::string scene_with_stored_robot(const H5Reader& in, const ReplaySource& src) {
  YAML::Node root = YAML::Load(in.string_attribute(s::kMetaGroup, s::kAttrConfigYaml));
  YAML::Node robot = root["robot"];
  if (!robot.IsMap() || !robot["urdf"].IsDefined()) return YAML::Dump(root) + "\n";
  InputFile urdf;
  urdf.role = "URDF";
  urdf.path = urdf.absolute = src.inputs.front().absolute + "#" + s::kModelUrdf.path;
  urdf.text = std::make_shared<const std::string>(src.urdf);
  urdf.sha256 = sha256_hex(src.urdf.data(), src.urdf.size());
  keep_input(urdf);
  robot["urdf"] = urdf.path;
  robot["trunk_link"] = "trunk";
  // The feet as model/urdf.cpp writes them: a link "<leg>_foot" fixed to each leg's last link,
  // with a sphere <collision> centred on it for a sphere foot. Found by the reader's default
  // (docs/user/robots.md#feet): the sphere, with its radius, else the end of the fixed links.
  // Named in robot.foot_links they would be point feet, and a sphere foot would sink by its
  // radius into the terrain.
  robot.remove("foot_links");
  robot.remove("foot_offset");
  return YAML::Dump(root) + "\n";
}

/// One warning per input the run read that is no longer on disk as it was (its digest in
/// /meta input_sha256): the replay does not read them.
std::vector<std::string> changed_inputs(const std::vector<InputFile>& recorded) {
  std::vector<std::string> out;
  for (const InputFile& f : recorded) {
    struct stat st {};
    std::string now;
    if (::stat(f.absolute.c_str(), &st) != 0)
      now = "is gone";
    else if (!S_ISREG(st.st_mode) || sha256_file(f.absolute) != f.sha256)
      now = "has changed";
    if (!now.empty())
      out.push_back("the run's input '" + f.absolute + "' " + now +
                    " since the run (/meta input_sha256); the replay uses the result's own "
                    "description (/meta config_yaml, /model/urdf)");
  }
  return out;
}

}  // namespace

ReplaySource read_replay_source(const std::string& result_path,
                                const std::vector<Override>& overrides, bool robustness) {
  for (const Override& ov : overrides) check_replay_override(ov, robustness);
  const InputFreeze freeze;  // keeps the stored URDF as an input while the scene is read
  ReplaySource src;
  src.path = result_path;
  src.inputs.push_back(result_input(result_path));
  const H5Reader in(result_path);
  const std::string meta = s::kMetaGroup;
  // Layout versions 2 to 4 have the same datasets the replay reads but
  // /model/leg_joint_counts (versions 2 and 3; version 2: its energies by the trapezoid).
  const std::string schema =
      in.has_attribute(meta, s::kAttrSchema) ? in.string_attribute(meta, s::kAttrSchema) : "";
  if (schema != s::kResultSchema && schema != "hexdyn-result/4" && schema != "hexdyn-result/3" &&
      schema != "hexdyn-result/2")
    throw IoError("replay: '" + result_path + "' is not a " + s::kResultSchema + " file");
  src.created_utc = in.string_attribute(meta, s::kAttrCreatedUtc);
  if (in.has_attribute(meta, s::kAttrInputSha256)) {
    const auto recorded = recorded_inputs(in.string_attribute(meta, s::kAttrInputSha256),
                                          "the result's /meta input_sha256");
    src.warnings = changed_inputs(recorded);
    src.inputs.insert(src.inputs.end(), recorded.begin(), recorded.end());
  }
  src.urdf = in.read_string(s::kModelUrdf.path);
  src.joint_names = in.read_strings(s::kModelJointNames.path);
  src.leg_names = in.read_strings(s::kModelLegNames.path);
  src.scene = load_scene_from_string(scene_with_stored_robot(in, src),
                                     result_path + " /meta config_yaml", overrides);
  const RobotModel model = build_robot_model(src.scene.robot);
  src.leg_joint_counts = leg_joint_counts(in, result_path, model);
  read_plan(in, result_path, model, src.plan);
  check_feet(in, result_path, model, src.plan);
  src.plan.contact_phase = read_phases(in, result_path, src.plan.t_s.size(), model.legs());
  return src;
}

}  // namespace hexdyn
