#include "hexdyn/io/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <span>
#include <system_error>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/atomic_file.hpp"
#include "hexdyn/io/paths.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
using schema::DatasetSpec;

[[noreturn]] void throw_output_error(const std::string& path, const std::string& reason) {
  throw IoError("cannot write output '" + path + "': " + reason);
}

std::size_t to_size(int n) { return static_cast<std::size_t>(n); }

/// Writes the dataset `spec` below `prefix`, checking the matrix is rows × cols.
void write_matrix(H5Writer& w, const std::string& prefix, const DatasetSpec& spec,
                  const RowMatrix& m, int rows, int cols, std::vector<std::size_t> dims) {
  if (m.rows() != rows || m.cols() != cols)
    throw IoError("cannot write '" + w.file_path() + "': " + spec.path + " is " +
                  std::to_string(m.rows()) + "x" + std::to_string(m.cols()) + ", expected " +
                  std::to_string(rows) + "x" + std::to_string(cols));
  w.write_doubles(prefix + spec.path, dims, std::span<const double>(m.data(), to_size(m.size())),
                  spec.units);
}

void write_vector(H5Writer& w, const std::string& prefix, const DatasetSpec& spec,
                  const std::vector<double>& v, std::size_t expected) {
  if (v.size() != expected)
    throw IoError("cannot write '" + w.file_path() + "': " + spec.path + " has " +
                  std::to_string(v.size()) + " entries, expected " + std::to_string(expected));
  w.write_doubles(prefix + spec.path, {v.size()}, v, spec.units);
}

void write_meta(H5Writer& w, const std::string& prefix, const RunResult& r) {
  const std::string meta = prefix + schema::kMetaGroup;
  write_meta_header(w, meta, schema::kResultSchema, schema::kResultSchemaVersion);
  w.set_string_attribute(meta, schema::kAttrConfigYaml, r.config_yaml);
  w.set_double_attribute(meta, schema::kAttrWallTime, r.wall_time_s);
}

void write_model(H5Writer& w, const std::string& prefix, const RunResult& r) {
  std::vector<std::string> joints = r.joint_names, legs;
  for (int leg = 0; leg < kLegs; ++leg) {
    legs.push_back(leg_name(leg));
    if (r.joint_names.empty())
      for (int j = 0; j < kJointsPerLeg; ++j) joints.push_back(joint_name(leg, j));
  }
  if (joints.size() != static_cast<std::size_t>(kJoints))
    throw IoError("cannot write '" + w.file_path() + "': " + schema::kModelJointNames.path + " has " +
                  std::to_string(joints.size()) + " names, expected 18");
  if (!r.leg_mapping.empty())
    w.write_strings(prefix + schema::kModelLegMapping.path, r.leg_mapping, schema::kModelLegMapping.units);
  w.write_string(prefix + schema::kModelUrdf.path, r.urdf, schema::kModelUrdf.units);
  w.write_strings(prefix + schema::kModelJointNames.path, joints, schema::kModelJointNames.units);
  w.write_strings(prefix + schema::kModelLegNames.path, legs, schema::kModelLegNames.units);
  w.write_scalar(prefix + schema::kModelTotalMass.path, r.total_mass_kg,
                 schema::kModelTotalMass.units);
}

void write_kinematics(H5Writer& w, const std::string& prefix, const KinematicsResult& k) {
  namespace s = schema;
  const int T = k.samples();
  const std::size_t t = to_size(T);
  write_vector(w, prefix, s::kTime, k.time_s, t);
  write_matrix(w, prefix, s::kBasePosition, k.base_position, T, 3, {t, 3});
  write_matrix(w, prefix, s::kBaseOrientation, k.base_orientation_wxyz, T, 4, {t, 4});
  write_matrix(w, prefix, s::kBaseLinearVelocity, k.base_linear_velocity, T, 3, {t, 3});
  write_matrix(w, prefix, s::kBaseAngularVelocity, k.base_angular_velocity, T, 3, {t, 3});
  write_matrix(w, prefix, s::kBaseLinearAcceleration, k.base_linear_acceleration, T, 3, {t, 3});
  write_matrix(w, prefix, s::kBaseAngularAcceleration, k.base_angular_acceleration, T, 3, {t, 3});
  write_matrix(w, prefix, s::kJointPosition, k.joint_position, T, kJoints, {t, kJoints});
  write_matrix(w, prefix, s::kJointVelocity, k.joint_velocity, T, kJoints, {t, kJoints});
  write_matrix(w, prefix, s::kJointAcceleration, k.joint_acceleration, T, kJoints, {t, kJoints});
  write_matrix(w, prefix, s::kFeetPosition, k.foot_position, T, 3 * kLegs, {t, kLegs, 3});
  write_matrix(w, prefix, s::kFeetVelocity, k.foot_velocity, T, 3 * kLegs, {t, kLegs, 3});
  write_matrix(w, prefix, s::kComPosition, k.com_position, T, 3, {t, 3});
  const RowMatrixI8& phase = k.contact_phase;
  if (phase.rows() != T || phase.cols() != kLegs)
    throw IoError("cannot write '" + w.file_path() + "': " + s::kContactPhase.path + " is " +
                  std::to_string(phase.rows()) + "x" + std::to_string(phase.cols()) +
                  ", expected " + std::to_string(T) + "x" + std::to_string(kLegs));
  w.write_int8(prefix + s::kContactPhase.path, {t, kLegs},
               std::span<const std::int8_t>(phase.data(), to_size(phase.size())),
               s::kContactPhase.units);
}

void write_dynamics(H5Writer& w, const std::string& prefix, const DynamicsResult& d, int T) {
  namespace s = schema;
  const std::size_t t = to_size(T);
  write_matrix(w, prefix, s::kJointTorque, d.joint_torque, T, kJoints, {t, kJoints});
  write_matrix(w, prefix, s::kContactForce, d.contact_force, T, 3 * kLegs, {t, kLegs, 3});
  write_matrix(w, prefix, s::kContactPenetration, d.penetration, T, kLegs, {t, kLegs});

  const std::size_t n = d.impacts.size();
  std::vector<std::int32_t> leg(n);
  std::vector<double> start(n), duration(n), peak(n), impulse(n), mass(n), speed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ImpactRecord& im = d.impacts[i];
    if (im.leg < 0 || im.leg >= kLegs)
      throw IoError("cannot write '" + w.file_path() + "': impact " + std::to_string(i) +
                    " has leg index " + std::to_string(im.leg) + ", expected 0..5");
    leg[i] = im.leg + 1;
    start[i] = im.t_start_s;
    duration[i] = im.duration_s;
    peak[i] = im.peak_force_N;
    impulse[i] = im.impulse_Ns;
    mass[i] = im.effective_mass_kg;
    speed[i] = im.approach_speed_mps;
  }
  w.write_int32(prefix + s::kImpactLeg.path, {n}, leg, s::kImpactLeg.units);
  write_vector(w, prefix, s::kImpactStart, start, n);
  write_vector(w, prefix, s::kImpactDuration, duration, n);
  write_vector(w, prefix, s::kImpactPeakForce, peak, n);
  write_vector(w, prefix, s::kImpactImpulse, impulse, n);
  write_vector(w, prefix, s::kImpactEffectiveMass, mass, n);
  write_vector(w, prefix, s::kImpactApproachSpeed, speed, n);

  write_matrix(w, prefix, s::kJointPower, d.joint_power, T, kJoints, {t, kJoints});
  write_vector(w, prefix, s::kTotalPower, d.total_power_W, t);
  w.write_scalar(prefix + s::kEnergyTotal.path, d.energy_total_J, s::kEnergyTotal.units);
  write_vector(w, prefix, s::kEnergyJoint, d.energy_joint_J, kJoints);
  w.write_scalar(prefix + s::kCostOfTransport.path, d.cost_of_transport, s::kCostOfTransport.units);
  w.write_scalar(prefix + s::kEnergyDistance.path, d.distance_m, s::kEnergyDistance.units);

  if (d.solver_status.size() != t)
    throw IoError("cannot write '" + w.file_path() + "': " + s::kSolverStatus.path + " has " +
                  std::to_string(d.solver_status.size()) + " entries, expected " +
                  std::to_string(t));
  w.write_int8(prefix + s::kSolverStatus.path, {t}, solver_status_codes(d.solver_status), s::kSolverStatus.units);
  write_vector(w, prefix, s::kSolverIterations, d.solver_iterations, t);
  write_vector(w, prefix, s::kSolverObjective, d.solver_objective, t);
  write_vector(w, prefix, s::kSolverSeconds, d.solver_seconds, t);
  w.write_strings(prefix + s::kSolverMessages.path, d.solver_messages, s::kSolverMessages.units);
}

}  // namespace

void write_meta_header(H5Writer& w, const std::string& meta, const char* schema_name,
                       std::int64_t schema_version) {
  w.create_group(meta);
  w.set_string_attribute(meta, schema::kAttrSchema, schema_name);
  w.set_int_attribute(meta, schema::kAttrSchemaVersion, schema_version);
  w.set_string_attribute(meta, schema::kAttrVersion, kVersion);
  w.set_string_attribute(meta, schema::kAttrGitCommit, kGitCommit);
  w.set_string_attribute(meta, schema::kAttrCreatedUtc, utc_timestamp_now());
}

std::string utc_timestamp_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

void check_output_target(const std::string& path, const std::vector<std::string>& inputs) {
  if (path.empty()) throw IoError("cannot write output '': empty path");
  struct stat target {};
  if (::lstat(path.c_str(), &target) == 0) {
    if (const auto why = why_not_replaceable(path)) throw_output_error(path, "it " + *why);
    for (const std::string& input : inputs) {
      struct stat in {};
      if (::stat(input.c_str(), &in) != 0) continue;
      if (in.st_dev == target.st_dev && in.st_ino == target.st_ino)
        throw_output_error(path, "it is the input file '" + input +
                                     "' of this run (same device and inode), which the output would destroy");
    }
  } else if (errno != ENOENT) {
    const int err = errno;
    const std::string dir = directory_of(path);
    if (err == ENOTDIR) throw_output_error(path, "'" + dir + "' is not a directory");
    throw_output_error(path, std::strerror(err));
  }
  const std::string dir = directory_of(path);
  struct stat d {};
  if (::stat(dir.c_str(), &d) != 0) {
    if (errno == ENOENT) throw_output_error(path, "directory '" + dir + "' does not exist");
    if (errno == ENOTDIR) throw_output_error(path, "'" + dir + "' is not a directory");
    throw_output_error(path, "directory '" + dir + "': " + std::strerror(errno));
  }
  if (!S_ISDIR(d.st_mode)) throw_output_error(path, "'" + dir + "' is not a directory");
  // The temporary file is where the output is built: creating it is the test.
  const std::string tmp = temporary_path_for(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    if (err == EEXIST && !why_not_replaceable(tmp)) return;  // a stale one of this pid: overwritten later
    if (err == EACCES || err == EPERM)
      throw_output_error(path, "directory '" + dir + "' is not writable (" + std::strerror(err) + ")");
    throw_output_error(path, "cannot create a file in directory '" + dir + "' (" + std::strerror(err) + ")");
  }
  ::close(fd);
  ::unlink(tmp.c_str());
}

void check_output_path_writable(const std::string& path) { check_output_target(path, {}); }

double estimated_result_file_bytes(std::size_t samples) {
  namespace s = schema;
  double row = 0.0;  // bytes per sample
  for (const DatasetSpec* d :
       {&s::kTime, &s::kBasePosition, &s::kBaseOrientation, &s::kBaseLinearVelocity,
        &s::kBaseAngularVelocity, &s::kBaseLinearAcceleration, &s::kBaseAngularAcceleration,
        &s::kJointPosition, &s::kJointVelocity, &s::kJointAcceleration, &s::kFeetPosition,
        &s::kFeetVelocity, &s::kComPosition, &s::kContactPhase, &s::kJointTorque, &s::kContactForce,
        &s::kContactPenetration, &s::kJointPower, &s::kTotalPower, &s::kSolverStatus,
        &s::kSolverIterations, &s::kSolverObjective, &s::kSolverSeconds}) {
    double columns = 1.0;
    switch (d->shape) {
      case s::Shape::kT3: columns = 3; break;
      case s::Shape::kT4: columns = 4; break;
      case s::Shape::kT6: columns = 6; break;
      case s::Shape::kT18: case s::Shape::kT6x3: columns = 18; break;
      default: break;
    }
    row += columns * (d->element == s::Element::kInt8 ? 1.0 : 8.0);
  }
  constexpr double kMessageBytes = 32.0;  // a variable-length string's reference and heap entry
  constexpr double kFixedBytes = 64.0 * 1024.0;
  return static_cast<double>(samples) * (row + kMessageBytes) + kFixedBytes;
}

void write_result_layout(H5Writer& w, const RunResult& result, const std::string& prefix) {
  write_meta(w, prefix, result);
  write_model(w, prefix, result);
  write_kinematics(w, prefix, result.kin);
  if (result.dyn.present) write_dynamics(w, prefix, result.dyn, result.kin.samples());
}

void write_result_file(const std::string& path, const RunResult& result) {
  check_output_path_writable(path);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer writer(tmp);
    write_result_layout(writer, result);
    writer.close();
  });
}

}  // namespace hexdyn
