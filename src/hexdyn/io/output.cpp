#include "hexdyn/io/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <span>
#include <system_error>
#include <variant>

#include "hexdyn/core/common.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/labels.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/process/launch.hpp"
#include "hexdyn/process/paths.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;
using schema::DatasetSpec;

[[noreturn]] void throw_output_error(const std::string& path, const std::string& reason) {
  throw IoError("cannot write output '" + path + "': " + reason);
}

/// Writes one dataset of a layout below `prefix`, in its element type.
void write_dataset(H5Writer& w, const std::string& prefix, const LayoutDataset& d) {
  const std::string path = prefix + d.spec->path;
  const std::string units = d.spec->units;
  if (const auto* v = std::get_if<std::vector<double>>(&d.values)) {
    if (d.dims.empty())
      w.write_scalar(path, v->at(0), units);
    else
      w.write_doubles(path, d.dims, *v, units);
  } else if (const auto* v8 = std::get_if<std::vector<std::int8_t>>(&d.values)) {
    w.write_int8(path, d.dims, *v8, units);
  } else if (const auto* v32 = std::get_if<std::vector<std::int32_t>>(&d.values)) {
    w.write_int32(path, d.dims, *v32, units);
  } else if (const auto* texts = std::get_if<std::vector<std::string>>(&d.values)) {
    w.write_strings(path, d.dims, *texts, units);
  } else {
    w.write_string(path, std::get<std::string>(d.values), units);
  }
}

void write_attribute(H5Writer& w, const std::string& prefix, const LayoutAttribute& a) {
  const std::string object = prefix + a.spec->object;
  if (const auto* text = std::get_if<std::string>(&a.value))
    w.set_string_attribute(object, a.spec->name, *text);
  else if (const auto* i = std::get_if<std::int64_t>(&a.value))
    w.set_int_attribute(object, a.spec->name, *i);
  else
    w.set_double_attribute(object, a.spec->name, std::get<double>(a.value));
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

namespace {

/// `path` absolute, its folders' links resolved, lexically normal: what two names of one
/// file, existing or not, have in common.
std::string resolved_path(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) p = fs::absolute(path, ec);
  return p.lexically_normal().string();
}

[[noreturn]] void refuse_input(const std::string& path, const InputFile& input, const char* how) {
  throw_output_error(path, "it is the " + input.role + " '" + input.path + "'" +
                               (input.recorded ? "" : " read by this command") + " (" + how +
                               "), which the output would destroy");
}

}  // namespace

void check_not_input(const std::string& path, const std::vector<InputFile>& inputs) {
  struct stat target {};
  if (::stat(path.c_str(), &target) != 0) {
    // No file there: a recorded input's path all the same (deleted since, it may come back:
    // the result names it). A file this command read and that is gone may be replaced.
    const std::string name = resolved_path(path);
    for (const InputFile& input : inputs)
      if (input.recorded && resolved_path(input.absolute) == name)
        refuse_input(path, input, "the same path");
    return;
  }
  // The file read, by the identity it had then; and whatever is at its path now.
  if (const InputFile* input = find_input(inputs, static_cast<std::uint64_t>(target.st_dev),
                                          static_cast<std::uint64_t>(target.st_ino)))
    refuse_input(path, *input, "same device and inode");
  for (const InputFile& input : inputs) {
    struct stat now {};
    if (::stat(input.absolute.c_str(), &now) == 0 && now.st_dev == target.st_dev &&
        now.st_ino == target.st_ino)
      refuse_input(path, input, "same device and inode");
  }
}

void check_output_target(const std::string& path, const std::vector<InputFile>& inputs) {
  if (path.empty()) throw IoError("cannot write output '': empty path");
  if (path.find('\0') != std::string::npos)
    throw IoError("cannot write output: the path contains a NUL character");
  struct stat target {};
  if (::lstat(path.c_str(), &target) == 0) {
    if (const auto why = why_not_replaceable(path)) throw_output_error(path, "it " + *why);
    check_not_input(path, inputs);
  } else if (errno != ENOENT) {
    const int err = errno;
    const std::string dir = directory_of(path);
    if (err == ENOTDIR) throw_output_error(path, "'" + dir + "' is not a directory");
    throw_output_error(path, std::strerror(err));
  } else {
    check_not_input(path, inputs);  // a recorded input's path, though nothing is there now
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
  // A signal between the creation and the removal removes it too (interrupt.hpp): the probe
  // is registered before it exists.
  const std::string tmp = temporary_path_for(path);
  register_temporary(tmp);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    unregister_temporary(tmp);
    if (err == EEXIST && !why_not_replaceable(tmp))
      return;  // a stale one of this pid: overwritten later
    if (err == EACCES || err == EPERM)
      throw_output_error(path,
                         "directory '" + dir + "' is not writable (" + std::strerror(err) + ")");
    throw_output_error(
        path, "cannot create a file in directory '" + dir + "' (" + std::strerror(err) + ")");
  }
  ::close(fd);
  ::unlink(tmp.c_str());
  unregister_temporary(tmp);
  // Temporary files of earlier runs killed before they could remove them (under MPI, rank
  // 0 alone looks).
  if (!launched_as_secondary_rank())
    for (const std::string& line : remove_stale_temporaries(path))
      std::cerr << "hexdyn: " << line << "\n";
}

void check_run_size(std::size_t samples, int legs, int joints, bool allow_large) {
  if (samples <= kLargeResultSamples || allow_large) return;
  char size[64];
  std::snprintf(size, sizeof size, "%.2g GB",
                estimated_result_file_bytes(samples, static_cast<std::size_t>(legs),
                                            static_cast<std::size_t>(joints)) /
                    1e9);
  throw ConfigError("run: " + std::to_string(samples) + " output samples, a result file of about " +
                    size + "; more than " + std::to_string(kLargeResultSamples) +
                    " samples (about 0.29 GB) are refused as a likely typing error in output.* "
                    "(sample_step, impact_samples, event_step); pass --allow-large to run it");
}

double estimated_result_file_bytes(std::size_t samples, std::size_t legs, std::size_t joints) {
  namespace s = schema;
  double row = 0.0;  // bytes per sample
  for (const DatasetSpec* d : {&s::kTime,
                               &s::kBasePosition,
                               &s::kBaseOrientation,
                               &s::kBaseLinearVelocity,
                               &s::kBaseAngularVelocity,
                               &s::kBaseLinearAcceleration,
                               &s::kBaseAngularAcceleration,
                               &s::kJointPosition,
                               &s::kJointVelocity,
                               &s::kJointAcceleration,
                               &s::kFeetPosition,
                               &s::kFeetVelocity,
                               &s::kComPosition,
                               &s::kContactPhase,
                               &s::kJointTorque,
                               &s::kContactForce,
                               &s::kContactPenetration,
                               &s::kJointPower,
                               &s::kTotalPower,
                               &s::kSolverStatus,
                               &s::kSolverIterations,
                               &s::kSolverObjective,
                               &s::kSolverSeconds}) {
    double columns = 1.0;
    switch (d->shape) {
      case s::Shape::kT3:
        columns = 3;
        break;
      case s::Shape::kT4:
        columns = 4;
        break;
      case s::Shape::kTLeg:
        columns = static_cast<double>(legs);
        break;
      case s::Shape::kTJoint:
        columns = static_cast<double>(joints);
        break;
      case s::Shape::kTLegXyz:
        columns = 3.0 * static_cast<double>(legs);
        break;
      default:
        break;
    }
    row += columns * (d->element == s::Element::kInt8 ? 1.0 : 8.0);
  }
  constexpr double kMessageBytes = 32.0;  // a variable-length string's reference and heap entry
  constexpr double kFixedBytes = 64.0 * 1024.0;
  return static_cast<double>(samples) * (row + kMessageBytes) + kFixedBytes;
}

void write_layout(H5Writer& w, const ResultLayout& layout, const std::string& prefix,
                  bool dimension_scales) {
  for (const LayoutAttribute& a : layout.attributes) {
    w.create_group(prefix + a.spec->object);
    write_attribute(w, prefix, a);
  }
  Labeller labels(w, prefix, dimension_scales);
  for (const LayoutDataset& d : layout.datasets) {
    write_dataset(w, prefix, d);
    labels.add(*d.spec);
  }
  labels.finish();
}

void write_result_layout(H5Writer& w, const RunResult& result, const std::string& prefix,
                         bool dimension_scales) {
  if (result.summary_only)
    throw IoError(
        "result: computed for a sweep's summary row alone (output.summary_only: some "
        "required friction values are bounds), not written");
  ResultLayout layout;
  try {
    layout = result_layout(result);
  } catch (const IoError& e) {
    throw IoError("cannot write '" + w.file_path() + "': " + e.what());
  }
  write_layout(w, layout, prefix, dimension_scales);
}

bool compressed_output(const std::string& resolved_yaml) {
  const YAML::Node root = YAML::Load(resolved_yaml);
  if (!root.IsMap() || !root["output"].IsMap()) return true;
  const YAML::Node node = root["output"]["compression"];
  return !node.IsScalar() || node.as<std::string>() != "none";
}

void write_result_file(const std::string& path, const RunResult& result,
                       const std::vector<InputFile>& inputs) {
  check_output_target(path, inputs);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer writer(tmp, result.compress);
    write_result_layout(writer, result);
    writer.close();
  });
}

}  // namespace hexdyn
