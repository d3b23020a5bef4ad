#include "hexdyn/sweep/checkpoint.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <span>
#include <system_error>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/atomic_file.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCheckpointSchema = "hexdyn-sweep-checkpoint/1";

[[noreturn]] void io_fail(const std::string& path, const std::string& what) {
  throw IoError("cannot write '" + path + "': " + what);
}

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read '" + path + "'");
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::span<const double> span_of(const std::array<double, kJoints>& a) {
  return {a.data(), a.size()};
}

/// Summary datasets of one row below `prefix` (checkpoint files).
void write_summary(H5Writer& w, const std::string& prefix, const ScenarioSummary& s) {
  const std::int8_t status = static_cast<std::int8_t>(s.status);
  w.write_int8(prefix + "/status", {}, std::span<const std::int8_t>(&status, 1), "1");
  w.write_string(prefix + "/message", s.message, "1");
  const std::int32_t counts[3] = {s.samples, s.relaxed_samples, s.failed_samples};
  w.write_int32(prefix + "/samples", {}, std::span<const std::int32_t>(&counts[0], 1), "1");
  w.write_int32(prefix + "/relaxed_samples", {}, std::span<const std::int32_t>(&counts[1], 1), "1");
  w.write_int32(prefix + "/failed_samples", {}, std::span<const std::int32_t>(&counts[2], 1), "1");
  w.write_scalar(prefix + "/duration", s.duration_s, "s");
  w.write_scalar(prefix + "/distance", s.distance_m, "m");
  w.write_scalar(prefix + "/energy", s.energy_J, "J");
  w.write_scalar(prefix + "/cost_of_transport", s.cost_of_transport, "1");
  w.write_scalar(prefix + "/peak_impact_force", s.peak_impact_force_N, "N");
  w.write_doubles(prefix + "/peak_torque", {kJoints}, span_of(s.peak_torque_Nm), "N m");
  w.write_doubles(prefix + "/rms_torque", {kJoints}, span_of(s.rms_torque_Nm), "N m");
  w.write_scalar(prefix + "/wall_time_s", s.wall_time_s, "s");
}

double read_scalar(const H5Reader& r, const std::string& path) {
  const H5DoubleArray a = r.read_doubles(path);
  if (a.values.size() != 1) throw IoError("'" + path + "' is not a scalar");
  return a.values[0];
}

void read_joint_array(const H5Reader& r, const std::string& path,
                      std::array<double, kJoints>& out) {
  const H5DoubleArray a = r.read_doubles(path);
  if (a.values.size() != kJoints) throw IoError("'" + path + "' does not hold 18 values");
  std::copy(a.values.begin(), a.values.end(), out.begin());
}

std::atomic<unsigned> scratch_counter{0};

}  // namespace

std::vector<char> encode_checkpoint(const ScenarioOutcome& outcome,
                                    const std::string& scratch_dir) {
  const std::string tmp =
      (fs::path(scratch_dir) / ("hexdyn-scenario-" + std::to_string(::getpid()) + "-" +
                                std::to_string(scratch_counter++) + ".h5"))
          .string();
  try {
    {
      H5Writer w(tmp);
      w.create_group("/meta");
      w.set_string_attribute("/meta", schema::kAttrSchema, kCheckpointSchema);
      w.set_int_attribute("/meta", "index", static_cast<std::int64_t>(outcome.summary.index));
      write_summary(w, "/summary", outcome.summary);
      if (outcome.run) write_result_layout(w, *outcome.run, kCheckpointRunGroup);
      w.close();
    }
    std::vector<char> bytes = read_bytes(tmp);
    fs::remove(tmp);
    return bytes;
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

ScenarioSummary read_checkpoint_summary(const std::string& path) {
  const H5Reader r(path);
  if (!r.has_attribute("/meta", schema::kAttrSchema) ||
      r.string_attribute("/meta", schema::kAttrSchema) != kCheckpointSchema)
    throw IoError("'" + path + "' is not a sweep checkpoint file");
  ScenarioSummary s;
  s.index = static_cast<std::size_t>(r.int_attribute("/meta", "index"));
  const auto status = r.read_ints("/summary/status");
  if (status.size() != 1 || status[0] < 0 ||
      status[0] > static_cast<int>(ScenarioStatus::kInternal))
    throw IoError("'" + path + "': bad /summary/status");
  s.status = static_cast<ScenarioStatus>(status[0]);
  s.message = r.read_string("/summary/message");
  s.samples = static_cast<int>(read_scalar(r, "/summary/samples"));
  s.relaxed_samples = static_cast<int>(read_scalar(r, "/summary/relaxed_samples"));
  s.failed_samples = static_cast<int>(read_scalar(r, "/summary/failed_samples"));
  s.duration_s = read_scalar(r, "/summary/duration");
  s.distance_m = read_scalar(r, "/summary/distance");
  s.energy_J = read_scalar(r, "/summary/energy");
  s.cost_of_transport = read_scalar(r, "/summary/cost_of_transport");
  s.peak_impact_force_N = read_scalar(r, "/summary/peak_impact_force");
  read_joint_array(r, "/summary/peak_torque", s.peak_torque_Nm);
  read_joint_array(r, "/summary/rms_torque", s.rms_torque_Nm);
  s.wall_time_s = read_scalar(r, "/summary/wall_time_s");
  return s;
}

// ------------------------------------------------------------------ Checkpoint

namespace {

const char* kManifest = "manifest.h5";

struct ManifestFields {
  std::string sweep_yaml, base_config_yaml, version, git_commit;
  std::int64_t keep_runs = 0, scenarios = 0;
};

ManifestFields manifest_of(const SweepSpec& spec, bool keep_runs) {
  return {spec.sweep_yaml, spec.base_config_yaml, kVersion,
          kGitCommit,      keep_runs ? 1 : 0,     static_cast<std::int64_t>(spec.scenario_count())};
}

void write_manifest(const std::string& dir, const ManifestFields& m) {
  publish_atomically(dir + "/" + kManifest, [&](const std::string& tmp) {
    H5Writer w(tmp);
    w.create_group("/meta");
    w.set_string_attribute("/meta", schema::kAttrSchema, kCheckpointSchema);
    w.set_string_attribute("/meta", "sweep_yaml", m.sweep_yaml);
    w.set_string_attribute("/meta", "base_config_yaml", m.base_config_yaml);
    w.set_string_attribute("/meta", schema::kAttrVersion, m.version);
    w.set_string_attribute("/meta", schema::kAttrGitCommit, m.git_commit);
    w.set_int_attribute("/meta", "keep_runs", m.keep_runs);
    w.set_int_attribute("/meta", "scenarios", m.scenarios);
    w.close();
  });
}

/// Empty when `found` matches `want`, else what differs.
std::string manifest_difference(const ManifestFields& found, const ManifestFields& want) {
  if (found.sweep_yaml != want.sweep_yaml) return "the sweep file's text differs";
  if (found.base_config_yaml != want.base_config_yaml) return "the resolved base scene differs";
  if (found.keep_runs != want.keep_runs)
    return std::string("it was made ") + (found.keep_runs ? "with" : "without") + " --keep-runs";
  if (found.version != want.version || found.git_commit != want.git_commit)
    return "it was made by hexdyn " + found.version + " (" + found.git_commit + "), this is " +
           want.version + " (" + want.git_commit + ")";
  if (found.scenarios != want.scenarios) return "the number of scenarios differs";
  return {};
}

ManifestFields read_manifest(const std::string& path) {
  const H5Reader r(path);
  if (!r.has_attribute("/meta", schema::kAttrSchema) ||
      r.string_attribute("/meta", schema::kAttrSchema) != kCheckpointSchema)
    throw IoError("'" + path + "' is not a sweep checkpoint manifest");
  return {r.string_attribute("/meta", "sweep_yaml"),
          r.string_attribute("/meta", "base_config_yaml"),
          r.string_attribute("/meta", schema::kAttrVersion),
          r.string_attribute("/meta", schema::kAttrGitCommit),
          r.int_attribute("/meta", "keep_runs"),
          r.int_attribute("/meta", "scenarios")};
}

bool is_scenario_file(const std::string& name, std::size_t& index) {
  static const std::regex pattern(R"(^([0-9]+)\.h5$)");
  std::smatch m;
  if (!std::regex_match(name, m, pattern)) return false;
  index = static_cast<std::size_t>(std::stoull(m[1].str()));
  return true;
}

}  // namespace

Checkpoint::Checkpoint(const std::string& output_path, const SweepSpec& spec, bool keep_runs,
                       bool resume)
    : dir_(output_path + ".checkpoint"), spec_(&spec) {
  std::error_code ec;
  const bool existed = fs::exists(dir_, ec);
  if (existed && !resume)
    throw ConfigError(dir_ +
                      ": the checkpoint of an interrupted sweep exists; continue it with "
                      "--resume, or remove the directory to start afresh");
  if (existed && !fs::is_directory(dir_, ec))
    throw IoError("cannot use checkpoint '" + dir_ + "': not a directory");
  if (!existed && !fs::create_directory(dir_, ec))
    throw IoError("cannot create checkpoint directory '" + dir_ + "': " + ec.message());

  const std::string lock_path = dir_ + "/lock";
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT, 0644);
  if (lock_fd_ < 0) io_fail(lock_path, std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0 && (errno == EWOULDBLOCK || errno == EINTR)) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw IoError("checkpoint '" + dir_ + "' is in use by another running sweep");
  }

  try {
    scan(spec, keep_runs);
  } catch (...) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw;
  }
}

void Checkpoint::scan(const SweepSpec& spec, bool keep_runs) {
  std::error_code ec;
  const ManifestFields want = manifest_of(spec, keep_runs);
  const std::string manifest_path = dir_ + "/" + kManifest;
  const std::size_t n = spec.scenario_count();
  if (fs::exists(manifest_path, ec)) {
    ManifestFields found;
    try {
      found = read_manifest(manifest_path);
    } catch (const IoError& e) {
      throw ConfigError(dir_ + ": unreadable checkpoint manifest (" + e.what() +
                        "); remove the directory to start afresh");
    }
    const std::string diff = manifest_difference(found, want);
    if (!diff.empty())
      throw ConfigError(dir_ + ": the checkpoint belongs to another sweep (" + diff +
                        "); remove the directory to start afresh");
  } else {
    write_manifest(dir_, want);
  }

  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    const std::string p = dir_ + "/" + name;
    std::size_t index = 0;
    if (!name.empty() && name[0] == '.') {
      fs::remove(p, ec);  // a temporary file of an interrupted write
    } else if (is_scenario_file(name, index)) {
      bool ok = index < n && name == scenario_id(spec, index) + ".h5";
      if (ok) {
        try {
          ok = read_checkpoint_summary(p).index == index;
        } catch (const Error&) {
          ok = false;
        }
      }
      if (ok)
        finished_.push_back(index);
      else
        fs::remove(p, ec);  // not of this sweep, or damaged: computed again
    }
  }
  std::sort(finished_.begin(), finished_.end());
}

Checkpoint::~Checkpoint() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

std::string Checkpoint::scenario_path(std::size_t index) const {
  return dir_ + "/" + scenario_id(*spec_, index) + ".h5";
}

void Checkpoint::store(std::size_t index, const std::vector<char>& bytes) {
  write_bytes_atomically(scenario_path(index), bytes.data(), bytes.size());
}

void Checkpoint::remove() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
  if (lock_fd_ >= 0) ::close(lock_fd_);
  lock_fd_ = -1;
  if (ec) throw IoError("cannot remove checkpoint '" + dir_ + "': " + ec.message());
}

}  // namespace hexdyn
