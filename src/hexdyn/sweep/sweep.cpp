#include "hexdyn/sweep/sweep.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/file.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <span>
#include <sstream>
#include <system_error>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/io/result_schema.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kCheckpointSchema = "hexdyn-sweep-checkpoint/1";

// ------------------------------------------------------------------ sweep file parsing

std::string show(const YAML::Node& node) { return yaml_inline(node); }

std::string emit(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

/// Reports errors of one sweep file as "FILE: path: message".
class SweepReader {
 public:
  explicit SweepReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw ConfigError(file_ + ": " + path + ": " + what);
  }
  [[noreturn]] void fail_value(const std::string& path, const YAML::Node& node,
                               const std::string& expected) const {
    fail(path, "got " + show(node) + ", expected " + expected);
  }
  /// Every key of the map `node` at `path` must be one of `allowed`.
  void check_keys(const YAML::Node& node, const std::string& path,
                  const std::vector<std::string>& allowed) const {
    for (const auto& kv : node) {
      const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : show(kv.first);
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        const std::set<std::string> sorted(allowed.begin(), allowed.end());
        std::string list;
        for (const auto& a : sorted) list += (list.empty() ? "" : ", ") + a;
        fail(path.empty() ? key : path + "." + key, "unknown key, allowed here: " + list);
      }
    }
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

std::string format_number(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

bool parse_finite_number(const YAML::Node& node, double& out) {
  return node.IsScalar() && YAML::convert<double>::decode(node, out) && std::isfinite(out);
}

/// "p/q" with integers p and q ≠ 0 → p/q; nothing otherwise.
std::optional<double> parse_fraction(const std::string& text) {
  static const std::regex fraction(R"(^\s*([+-]?[0-9]+)\s*/\s*([0-9]+)\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, fraction)) return std::nullopt;
  const double q = std::stod(m[2].str());
  if (q == 0.0) return std::nullopt;
  return std::stod(m[1].str()) / q;
}

/// The node at a dotted path of a tree of maps; undefined if absent.
YAML::Node lookup(const YAML::Node& root, const std::vector<std::string>& keys) {
  YAML::Node cur = YAML::Clone(root);
  for (const auto& k : keys) {
    if (!cur.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    YAML::Node next = cur[k];
    if (!next.IsDefined()) return YAML::Node(YAML::NodeType::Undefined);
    cur.reset(next);
  }
  return cur;
}

/// Keys of the deepest existing map along `keys` (for "allowed here" hints).
std::string keys_near(const YAML::Node& root, const std::vector<std::string>& keys) {
  YAML::Node cur = YAML::Clone(root);
  std::string prefix;
  for (const auto& k : keys) {
    if (!cur.IsMap() || !cur[k].IsDefined() || !cur[k].IsMap()) break;
    YAML::Node next = cur[k];
    cur.reset(next);
    prefix += k + ".";
  }
  std::string list;
  if (cur.IsMap())
    for (const auto& kv : cur) list += (list.empty() ? "" : ", ") + prefix + kv.first.Scalar();
  return list;
}

/// Text of an override value: scalars as written, lists in flow style, null as "null".
std::string override_text(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "null";
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

void read_values(const SweepReader& r, const YAML::Node& values, const std::string& path,
                 SweepAxis& axis) {
  const std::string expected = "a non-empty list of single values (numbers, p/q or words)";
  if (!values.IsSequence() || values.size() == 0) r.fail_value(path, values, expected);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const YAML::Node v = values[k];
    if (!v.IsScalar()) r.fail_value(path + "[" + std::to_string(k) + "]", v, "a single value");
    const std::string text = v.Scalar();
    axis.labels.push_back(text);
    if (const auto q = parse_fraction(text)) {
      axis.values.push_back(format_number(*q, 17));
    } else {
      axis.values.push_back(text);
    }
  }
}

void read_range(const SweepReader& r, const YAML::Node& range, const std::string& path,
                SweepAxis& axis) {
  if (!range.IsMap()) r.fail_value(path, range, "a mapping {from: A, to: B, count: N}");
  r.check_keys(range, path, {"from", "to", "count"});
  double lo = 0.0, hi = 0.0;
  if (!parse_finite_number(range["from"], lo))
    r.fail_value(path + ".from", range["from"], "a finite number");
  if (!parse_finite_number(range["to"], hi))
    r.fail_value(path + ".to", range["to"], "a finite number");
  long long count = 0;
  const YAML::Node c = range["count"];
  if (!c.IsScalar() || !YAML::convert<long long>::decode(c, count) || count < 2 || count > 100000)
    r.fail_value(path + ".count", c, "an integer in [2, 100000]");
  if (lo == hi) r.fail(path, "got from = to = " + format_number(lo, 12) + ", expected from != to");
  for (long long k = 0; k < count; ++k) {
    // Rounded to 12 significant digits so that 0.05 + 3 × 0.05 is written 0.2.
    const double v = lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(count - 1);
    const std::string text = format_number(v, 12);
    axis.values.push_back(text);
    axis.labels.push_back(text);
  }
}

void finish_axis(const SweepReader& r, const std::string& path, SweepAxis& axis) {
  axis.numeric = true;
  for (const auto& v : axis.values) {
    double x = 0.0;
    if (!parse_finite_number(YAML::Node(v), x)) {
      axis.numeric = false;
      break;
    }
    axis.numbers.push_back(x);
  }
  if (!axis.numeric) axis.numbers.clear();
  std::map<double, std::size_t> seen_numbers;
  std::map<std::string, std::size_t> seen_words;
  for (std::size_t a = 0; a < axis.size(); ++a) {
    std::size_t first = a;
    if (axis.numeric)
      first = seen_numbers.emplace(axis.numbers[a], a).first->second;
    else
      first = seen_words.emplace(axis.values[a], a).first->second;
    if (first != a)
      r.fail(path, "got " + axis.labels[a] + " twice (values " + std::to_string(first) + " and " +
                       std::to_string(a) + "), expected distinct values");
  }
}

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

}  // namespace

std::size_t SweepSpec::scenario_count() const {
  std::size_t n = 1;
  for (const auto& a : axes) n *= a.size();
  return n;
}

SweepSpec load_sweep(const std::string& path) {
  SweepSpec spec;
  spec.sweep_yaml = read_text_file(path);
  const YAML::Node root = parse_yaml_text(spec.sweep_yaml, path);
  const SweepReader r(path);
  r.check_keys(root, "", {"name", "base", "set", "axes"});

  const YAML::Node name = root["name"];
  if (name.IsDefined() && !name.IsNull()) {
    if (!name.IsScalar()) r.fail_value("name", name, "a string");
    spec.name = name.Scalar();
  } else {
    spec.name = fs::path(path).stem().string();
  }

  const YAML::Node base = root["base"];
  if (!base.IsDefined() || base.IsNull())
    r.fail("base", "missing, this key is required (the scene file the axes vary)");
  if (!base.IsScalar() || base.Scalar().empty())
    r.fail_value("base", base, "the path of a scene file");
  spec.base_path =
      base.Scalar().front() == '/' ? base.Scalar() : directory_of(path) + "/" + base.Scalar();
  std::error_code ec;
  if (!fs::is_regular_file(spec.base_path, ec))
    r.fail_value("base", base,
                 "the path of a scene file, relative to the sweep file (" + spec.base_path +
                     " is not a file)");
  YAML::Node tree = load_scene_tree(spec.base_path);

  const YAML::Node set = root["set"];
  std::set<std::string> fixed_keys;
  if (set.IsDefined() && !set.IsNull()) {
    if (!set.IsMap()) r.fail_value("set", set, "a mapping of dotted key paths to values");
    for (const auto& kv : set) {
      const std::string key = kv.first.Scalar();
      for (const auto& k : split_key_path(key))
        if (k.empty()) r.fail("set." + key, "empty key in the dotted path");
      if (kv.second.IsMap())
        r.fail_value("set." + key, kv.second,
                     "a value or a list (write nested keys as dotted paths)");
      spec.fixed.push_back({key, override_text(kv.second)});
      fixed_keys.insert(key);
    }
  }
  const std::string base_source = path + " (base " + spec.base_path + ")";
  for (const auto& ov : spec.fixed) apply_override(tree, ov, base_source);
  spec.base_tree_yaml = emit(tree);
  const Scene base_scene = scene_from_yaml(tree, base_source);
  spec.base_config_yaml = base_scene.resolved_yaml;
  const YAML::Node resolved = YAML::Load(spec.base_config_yaml);

  const YAML::Node axes = root["axes"];
  if (!axes.IsDefined() || axes.IsNull())
    r.fail("axes", "missing, this key is required (a list of {key, values} or {key, range})");
  if (!axes.IsSequence() || axes.size() == 0)
    r.fail_value("axes", axes, "a non-empty list of {key, values} or {key, range}");
  std::set<std::string> axis_keys;
  std::size_t count = 1;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const std::string at = "axes[" + std::to_string(i) + "]";
    const YAML::Node a = axes[i];
    if (!a.IsMap())
      r.fail_value(at, a, "a mapping {key: K, values: [...]} or {key: K, range: {...}}");
    r.check_keys(a, at, {"key", "values", "range"});
    SweepAxis axis;
    const YAML::Node key = a["key"];
    if (!key.IsDefined() || key.IsNull()) r.fail(at + ".key", "missing, this key is required");
    if (!key.IsScalar() || key.Scalar().empty())
      r.fail_value(at + ".key", key, "a dotted key path");
    axis.key = key.Scalar();
    const auto keys = split_key_path(axis.key);
    for (const auto& k : keys)
      if (k.empty()) r.fail_value(at + ".key", key, "a dotted key path without empty parts");
    const YAML::Node target = lookup(resolved, keys);
    if (!target.IsDefined()) {
      const std::string near = keys_near(resolved, keys);
      r.fail_value(at + ".key", key,
                   "a key of the base scene " + spec.base_path +
                       (near.empty() ? std::string() : " (near: " + near + ")"));
    }
    if (!target.IsScalar())
      r.fail_value(at + ".key", key,
                   std::string("a key holding a single value (it holds a ") +
                       (target.IsMap() ? "group of keys" : "list") + ")");
    if (fixed_keys.count(axis.key)) r.fail_value(at + ".key", key, "a key not also fixed by set:");
    if (!axis_keys.insert(axis.key).second)
      r.fail_value(at + ".key", key, "each key on one axis only");

    const bool has_values = a["values"].IsDefined(), has_range = a["range"].IsDefined();
    if (has_values == has_range)
      r.fail(at, std::string("got ") +
                     (has_values ? "both values and range" : "neither values nor range") +
                     ", expected exactly one of them");
    if (has_values)
      read_values(r, a["values"], at + ".values", axis);
    else
      read_range(r, a["range"], at + ".range", axis);
    finish_axis(r, at + (has_values ? ".values" : ".range"), axis);
    count *= axis.size();
    if (count > kMaxScenarios)
      r.fail("axes", "got more than " + std::to_string(kMaxScenarios) +
                         " scenarios, expected at most that many");
    spec.axes.push_back(std::move(axis));
  }
  return spec;
}

std::vector<std::size_t> grid_point(const SweepSpec& spec, std::size_t index) {
  std::vector<std::size_t> p(spec.axes.size());
  for (std::size_t a = spec.axes.size(); a-- > 0;) {
    p[a] = index % spec.axes[a].size();
    index /= spec.axes[a].size();
  }
  return p;
}

std::string scenario_id(const SweepSpec& spec, std::size_t index) {
  const std::size_t n = spec.scenario_count();
  const std::size_t width = std::max<std::size_t>(6, std::to_string(n > 0 ? n - 1 : 0).size());
  std::string s = std::to_string(index);
  return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

std::string scenario_source_name(const std::string& id) { return "scenario " + id; }

ScenarioInput scenario_input(const SweepSpec& spec, std::size_t index) {
  ScenarioInput in;
  in.index = index;
  in.id = scenario_id(spec, index);
  const std::string source = scenario_source_name(in.id);
  YAML::Node tree = parse_yaml_text(spec.base_tree_yaml, source);
  const auto p = grid_point(spec, index);
  for (std::size_t a = 0; a < spec.axes.size(); ++a)
    apply_override(tree, {spec.axes[a].key, spec.axes[a].values[p[a]]}, source);
  in.yaml = emit(tree);
  return in;
}

// ------------------------------------------------------------------ scenarios

const char* status_name(ScenarioStatus status) {
  switch (status) {
    case ScenarioStatus::kOk:
      return "ok";
    case ScenarioStatus::kConfig:
      return "config";
    case ScenarioStatus::kReach:
      return "reach";
    case ScenarioStatus::kPlanning:
      return "planning";
    case ScenarioStatus::kSolver:
      return "solver";
    case ScenarioStatus::kError:
      return "error";
    case ScenarioStatus::kInternal:
      return "internal";
  }
  return "internal";
}

std::string status_codes_text() {
  std::string s;
  for (int c = 0; c <= static_cast<int>(ScenarioStatus::kInternal); ++c)
    s += (s.empty() ? "" : ", ") + std::to_string(c) + " " +
         status_name(static_cast<ScenarioStatus>(c));
  return s;
}

ScenarioStatus classify_exception(const std::exception& e) {
  if (dynamic_cast<const ConfigError*>(&e)) return ScenarioStatus::kConfig;
  if (dynamic_cast<const ReachError*>(&e)) return ScenarioStatus::kReach;
  if (dynamic_cast<const PlanningError*>(&e)) return ScenarioStatus::kPlanning;
  if (dynamic_cast<const SolverError*>(&e)) return ScenarioStatus::kSolver;
  if (dynamic_cast<const Error*>(&e)) return ScenarioStatus::kError;
  return ScenarioStatus::kInternal;
}

ScenarioSummary failed_summary(std::size_t index, ScenarioStatus status,
                               const std::string& message) {
  ScenarioSummary s;
  s.index = index;
  s.status = status;
  s.message = message;
  s.duration_s = s.distance_m = s.energy_J = s.cost_of_transport = s.peak_impact_force_N = kNaN;
  s.peak_torque_Nm.fill(kNaN);
  s.rms_torque_Nm.fill(kNaN);
  return s;
}

ScenarioSummary summarize_run(const RunResult& run, std::size_t index) {
  ScenarioSummary s;
  s.index = index;
  const auto& t = run.kin.time_s;
  const int T = run.kin.samples();
  s.samples = T;
  s.duration_s = T > 0 ? t.back() - t.front() : 0.0;
  const DynamicsResult& d = run.dyn;
  if (!d.present || d.joint_torque.rows() != T || d.joint_torque.cols() != kJoints) {
    ScenarioSummary f = failed_summary(index, ScenarioStatus::kOk, "");
    f.samples = T;
    f.duration_s = s.duration_s;
    return f;
  }
  s.distance_m = d.distance_m;
  s.energy_J = d.energy_total_J;
  s.cost_of_transport = d.cost_of_transport;
  for (const ImpactRecord& im : d.impacts)
    s.peak_impact_force_N = std::max(s.peak_impact_force_N, im.peak_force_N);
  for (int k = 0; k < kJoints; ++k) {
    double peak = 0.0, integral = 0.0;
    for (int i = 0; i < T; ++i) peak = std::max(peak, std::abs(d.joint_torque(i, k)));
    for (int i = 0; i + 1 < T; ++i) {
      const double a = d.joint_torque(i, k), b = d.joint_torque(i + 1, k);
      integral += 0.5 * (a * a + b * b) * (t[i + 1] - t[i]);
    }
    s.peak_torque_Nm[k] = peak;
    s.rms_torque_Nm[k] = (T >= 2 && s.duration_s > 0.0)
                             ? std::sqrt(integral / s.duration_s)
                             : (T > 0 ? std::abs(d.joint_torque(0, k)) : 0.0);
  }
  for (SolverStatus st : d.solver_status) {
    if (st == SolverStatus::kRelaxed) ++s.relaxed_samples;
    if (st == SolverStatus::kFailed) ++s.failed_samples;
  }
  return s;
}

std::optional<ScenarioSummary> check_scenario(const ScenarioInput& input) {
  const std::string source = scenario_source_name(input.id);
  try {
    (void)scene_from_yaml(parse_yaml_text(input.yaml, source), source);
    return std::nullopt;
  } catch (const std::exception& e) {
    return failed_summary(input.index, classify_exception(e), e.what());
  }
}

ScenarioOutcome run_scenario(const ScenarioInput& input, bool keep_run) {
  const auto start = std::chrono::steady_clock::now();
  const std::string source = scenario_source_name(input.id);
  ScenarioOutcome out;
  try {
    const Scene scene = scene_from_yaml(parse_yaml_text(input.yaml, source), source);
    RunResult run = run_scene(scene, nullptr);
    out.summary = summarize_run(run, input.index);
    if (keep_run) out.run = std::move(run);
  } catch (const std::exception& e) {
    out.summary = failed_summary(input.index, classify_exception(e), e.what());
    out.run.reset();
  }
  out.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// ------------------------------------------------------------------ files

namespace {

[[noreturn]] void io_fail(const std::string& path, const std::string& what) {
  throw IoError("cannot write '" + path + "': " + what);
}

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read '" + path + "'");
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Writes `bytes` to `path` through `<dir>/.<name>.tmp`, fsync and rename.
void write_bytes_atomically(const std::string& path, const char* data, std::size_t size) {
  const fs::path p(path);
  const std::string tmp = (p.parent_path() / ("." + p.filename().string() + ".tmp")).string();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) io_fail(tmp, std::strerror(errno));
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      io_fail(tmp, std::strerror(err));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    io_fail(tmp, std::string("fsync/close failed: ") + std::strerror(err));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    io_fail(path, "cannot rename '" + tmp + "' to it: " + std::strerror(err));
  }
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
      if (outcome.run) write_result_layout(w, *outcome.run, "/run");
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

// ------------------------------------------------------------------ sweep file

namespace {

/// Copies `/run` of each kept checkpoint file to `/runs/<id>` of the open file `dst_path`.
void copy_runs(const std::string& dst_path, const SweepSpec& spec,
               const std::vector<ScenarioSummary>& rows, const Checkpoint& cp) {
  silence_hdf5_errors();
  const hid_t dst = H5Fopen(dst_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (dst < 0) io_fail(dst_path, "cannot reopen it to copy the runs");
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  std::string error;
  for (const ScenarioSummary& row : rows) {
    if (row.status != ScenarioStatus::kOk) continue;
    const std::string src_path = cp.scenario_path(row.index);
    if (!fs::exists(src_path)) continue;
    const hid_t src = H5Fopen(src_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (src < 0) {
      error = "cannot open checkpoint '" + src_path + "'";
      break;
    }
    if (H5Lexists(src, "run", H5P_DEFAULT) > 0) {
      const std::string to = "/runs/" + scenario_id(spec, row.index);
      if (H5Ocopy(src, "run", dst, to.c_str(), H5P_DEFAULT, lcpl) < 0)
        error = "cannot copy the run of scenario " + scenario_id(spec, row.index);
    }
    H5Fclose(src);
    if (!error.empty()) break;
  }
  H5Pclose(lcpl);
  const herr_t closed = H5Fclose(dst);
  H5Eclear2(H5E_DEFAULT);
  if (!error.empty()) io_fail(dst_path, error);
  if (closed < 0) io_fail(dst_path, "cannot close it after copying the runs");
}

}  // namespace

void write_sweep_file(const std::string& path, const SweepSpec& spec,
                      const std::vector<ScenarioSummary>& rows, const Checkpoint* runs_from,
                      const SweepRunInfo& info) {
  const std::size_t n = spec.scenario_count();
  const std::size_t A = spec.axes.size();
  if (rows.size() != n)
    throw IoError("cannot write '" + path + "': " + std::to_string(rows.size()) + " rows for " +
                  std::to_string(n) + " scenarios");
  for (std::size_t i = 0; i < n; ++i)
    if (rows[i].index != i)
      throw IoError("cannot write '" + path + "': row " + std::to_string(i) + " holds scenario " +
                    std::to_string(rows[i].index));
  check_output_path_writable(path);
  publish_atomically(path, [&](const std::string& tmp) {
    {
      H5Writer w(tmp);
      w.create_group("/meta");
      w.set_string_attribute("/meta", schema::kAttrSchema, schema::kSweepSchema);
      w.set_int_attribute("/meta", schema::kAttrSchemaVersion, 1);
      w.set_string_attribute("/meta", schema::kAttrVersion, kVersion);
      w.set_string_attribute("/meta", schema::kAttrGitCommit, kGitCommit);
      w.set_string_attribute("/meta", schema::kAttrCreatedUtc, utc_timestamp_now());
      w.set_string_attribute("/meta", "name", spec.name);
      w.set_string_attribute("/meta", "sweep_yaml", spec.sweep_yaml);
      w.set_string_attribute("/meta", "base_config_yaml", spec.base_config_yaml);
      w.set_int_attribute("/meta", "scenarios", static_cast<std::int64_t>(n));
      w.set_int_attribute("/meta", "keep_runs", runs_from != nullptr ? 1 : 0);
      w.set_double_attribute("/meta", schema::kAttrWallTime, info.wall_time_s);
      w.set_int_attribute("/meta", "ranks", info.ranks);
      w.set_int_attribute("/meta", "resumed_scenarios",
                          static_cast<std::int64_t>(info.resumed_scenarios));

      w.create_group("/axes");
      for (std::size_t a = 0; a < A; ++a) {
        const SweepAxis& ax = spec.axes[a];
        const std::string g = "/axes/" + std::to_string(a);
        w.write_string(g + "/key", ax.key, "1");
        if (ax.numeric)
          w.write_doubles(g + "/values", {ax.size()}, ax.numbers, "SI");
        else
          w.write_strings(g + "/values", ax.values, "1");
        w.write_strings(g + "/labels", ax.labels, "1");
      }
      std::vector<std::string> joints;
      for (int leg = 0; leg < kLegs; ++leg)
        for (int j = 0; j < kJointsPerLeg; ++j) joints.push_back(joint_name(leg, j));
      w.write_strings("/joint_names", joints, "1");

      std::vector<std::string> ids(n), messages(n);
      std::vector<std::int32_t> axis_index(n * A), samples(n), relaxed(n), failed(n);
      std::vector<std::int8_t> status(n);
      std::vector<double> duration(n), distance(n), energy(n), cot(n), impact(n), wall(n);
      std::vector<double> peak(n * kJoints), rms(n * kJoints);
      for (std::size_t i = 0; i < n; ++i) {
        const ScenarioSummary& s = rows[i];
        ids[i] = scenario_id(spec, i);
        messages[i] = s.message;
        const auto gp = grid_point(spec, i);
        for (std::size_t a = 0; a < A; ++a)
          axis_index[i * A + a] = static_cast<std::int32_t>(gp[a]);
        status[i] = static_cast<std::int8_t>(s.status);
        samples[i] = s.samples;
        relaxed[i] = s.relaxed_samples;
        failed[i] = s.failed_samples;
        duration[i] = s.duration_s;
        distance[i] = s.distance_m;
        energy[i] = s.energy_J;
        cot[i] = s.cost_of_transport;
        impact[i] = s.peak_impact_force_N;
        wall[i] = s.wall_time_s;
        std::copy(s.peak_torque_Nm.begin(), s.peak_torque_Nm.end(),
                  peak.begin() + static_cast<std::ptrdiff_t>(i * kJoints));
        std::copy(s.rms_torque_Nm.begin(), s.rms_torque_Nm.end(),
                  rms.begin() + static_cast<std::ptrdiff_t>(i * kJoints));
      }
      w.write_strings("/scenarios/id", ids, "1");
      w.write_int32("/scenarios/axis_index", {n, A}, axis_index, "1");
      for (std::size_t a = 0; a < A; ++a) {
        const SweepAxis& ax = spec.axes[a];
        const std::string d = "/scenarios/axis_" + std::to_string(a);
        if (ax.numeric) {
          std::vector<double> v(n);
          for (std::size_t i = 0; i < n; ++i)
            v[i] = ax.numbers[static_cast<std::size_t>(axis_index[i * A + a])];
          w.write_doubles(d, {n}, v, "SI");
        } else {
          std::vector<std::string> v(n);
          for (std::size_t i = 0; i < n; ++i)
            v[i] = ax.values[static_cast<std::size_t>(axis_index[i * A + a])];
          w.write_strings(d, v, "1");
        }
        w.set_string_attribute(d, "key", ax.key);
      }
      w.write_int8("/scenarios/status", {n}, status, "1");
      w.set_string_attribute("/scenarios/status", "codes", status_codes_text());
      w.write_strings("/scenarios/message", messages, "1");
      w.write_int32("/scenarios/samples", {n}, samples, "1");
      w.write_doubles("/scenarios/duration", {n}, duration, "s");
      w.write_doubles("/scenarios/distance", {n}, distance, "m");
      w.write_doubles("/scenarios/energy", {n}, energy, "J");
      w.write_doubles("/scenarios/cost_of_transport", {n}, cot, "1");
      w.write_doubles("/scenarios/peak_impact_force", {n}, impact, "N");
      w.write_doubles("/scenarios/peak_torque", {n, kJoints}, peak, "N m");
      w.write_doubles("/scenarios/rms_torque", {n, kJoints}, rms, "N m");
      w.write_int32("/scenarios/relaxed_samples", {n}, relaxed, "1");
      w.write_int32("/scenarios/failed_samples", {n}, failed, "1");
      w.write_doubles("/scenarios/wall_time_s", {n}, wall, "s");
      w.set_string_attribute("/scenarios", "missing_values",
                             "metrics are NaN for scenarios whose status is not 0 (ok)");
      if (runs_from != nullptr) w.create_group("/runs");
      w.close();
    }
    if (runs_from != nullptr) copy_runs(tmp, spec, rows, *runs_from);
  });
}

// ------------------------------------------------------------------ progress

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "unknown";
  const long long s = std::llround(seconds);
  char buf[64];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%lld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%lld min %02lld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld h %02lld min", s / 3600, (s % 3600) / 60);
  return buf;
}

ProgressMeter::ProgressMeter(std::size_t total, std::size_t already_done, double interval_s,
                             Clock::time_point start)
    : total_(total),
      already_done_(already_done),
      done_(already_done),
      interval_s_(interval_s),
      start_(start),
      last_line_(start),
      done_at_last_line_(already_done) {}

std::optional<std::string> ProgressMeter::update(std::size_t done, std::size_t failed,
                                                 Clock::time_point now) {
  done_ = done;
  failed_ = failed;
  if (done_ == done_at_last_line_) return std::nullopt;
  if (std::chrono::duration<double>(now - last_line_).count() < interval_s_) return std::nullopt;
  last_line_ = now;
  done_at_last_line_ = done_;
  return line(now);
}

std::string ProgressMeter::line(Clock::time_point now) const {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::size_t computed = done_ - already_done_;
  std::ostringstream s;
  s << "hexdyn: sweep: " << done_ << "/" << total_ << " done";
  if (failed_ > 0) s << ", " << failed_ << " failed";
  if (computed > 0 && elapsed > 0.0) {
    const double rate = static_cast<double>(computed) / elapsed;
    char r[32];
    std::snprintf(r, sizeof r, "%.3g", rate);
    s << ", " << r << " scenarios/s";
    if (done_ < total_)
      s << ", " << format_duration(static_cast<double>(total_ - done_) / rate) << " left";
  }
  s << ", " << format_duration(elapsed) << " elapsed";
  return s.str();
}

}  // namespace hexdyn
