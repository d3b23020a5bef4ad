// Reading an envelope file (envelope.hpp, configs/envelope/paper.yaml) and building the
// scene of each probe from its base scene.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/spec_reader.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/envelope/envelope.hpp"
#include "hexdyn/process/paths.hpp"

namespace hexdyn {
namespace {

/// The envelope file's reader: the study-file errors plus its lists of numbers.
class EnvelopeReader : public SpecReader {
 public:
  using SpecReader::SpecReader;
  /// A number (p/q allowed) inside [lo, hi].
  double number(const YAML::Node& n, const std::string& path, double lo, double hi) const {
    const std::string expected = "a number in [" + fmt(lo) + ", " + fmt(hi) + "]";
    if (!n.IsScalar()) fail_value(path, n, expected);
    refuse_quoted_number(path, n, expected);
    double v = 0.0;
    if (const auto f = parse_fraction(n.Scalar()))
      v = *f;
    else if (!YAML::convert<double>::decode(n, v))
      fail_value(path, n, expected);
    if (!std::isfinite(v) || v < lo || v > hi) fail_value(path, n, expected);
    return v;
  }
  std::vector<double> numbers(const YAML::Node& n, const std::string& path, double lo,
                              double hi) const {
    if (!n.IsSequence() || n.size() == 0)
      fail_value(path, n, "a non-empty list of numbers in [" + fmt(lo) + ", " + fmt(hi) + "]");
    if (n.size() > kMaxEnvelopeCells)  // before the values are compared with each other
      fail(path, "got " + std::to_string(n.size()) + " values, expected at most " +
                     std::to_string(kMaxEnvelopeCells) + " (an envelope has at most " +
                     std::to_string(kMaxEnvelopeCells) + " cells)");
    std::vector<double> v;
    for (std::size_t i = 0; i < n.size(); ++i)
      v.push_back(number(n[i], path + "[" + std::to_string(i) + "]", lo, hi));
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (v[i] == v[j]) fail_value(path, n, "distinct values");
    return v;
  }
  static std::string fmt(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }
};

bool given(const YAML::Node& n) { return n.IsDefined() && !n.IsNull(); }

/// x > 0 rounded up to 3 significant digits (for "at least x"), as printed.
double rounded_up(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  return std::stod(EnvelopeReader::fmt(std::ceil(x / unit * (1.0 - 1e-12)) * unit));
}

/// a × b, or nothing when it overflows 64 bits.
std::optional<std::uint64_t> times(std::uint64_t a, std::uint64_t b) {
  std::uint64_t p = 0;
  if (__builtin_mul_overflow(a, b, &p)) return std::nullopt;
  return p;
}

/// The cells (D × W × B × V) and the probes they plan, against kMaxEnvelopeCells and
/// kMaxEnvelopeProbes, before anything is allocated per cell. Names the list that adds most.
void check_envelope_size(const EnvelopeReader& r, const EnvelopeSpec& spec) {
  const std::pair<const char*, std::uint64_t> lists[] = {
      {"cases", std::max<std::uint64_t>(1, spec.cases.size())},
      {"tread_depth", spec.tread_depth_m.size()},
      {"duty_factor", spec.duty_factor.size()},
      {"peak_speed", spec.peak_speed_mps.size()}};
  std::optional<std::uint64_t> cells = 1;
  std::string product;
  const std::pair<const char*, std::uint64_t>* longest = &lists[0];
  for (const auto& list : lists) {
    if (cells) cells = times(*cells, list.second);
    product += (product.empty() ? "" : " x ") + std::string(list.first) + " " +
               std::to_string(list.second);
    if (list.second > longest->second) longest = &list;
  }
  if (!cells || *cells > kMaxEnvelopeCells)
    r.fail(longest->first, "got " + std::to_string(longest->second) + " values, " +
                               (cells ? std::to_string(*cells) : std::string("more than 2^64")) +
                               " cells (" + product + "), expected at most " +
                               std::to_string(kMaxEnvelopeCells) + " cells");
  // Per cell and criterion: the scan's probes, then the bisection's.
  const double span = spec.riser_to_m - spec.riser_from_m;
  const double lanes = static_cast<double>(*cells) * static_cast<double>(spec.criteria.size());
  auto scan = [&](double step) { return std::ceil(span / step - 1e-9) + 1.0; };
  auto halvings = [&](double step) { return std::ceil(std::log2(step / spec.tolerance_m)) + 1.0; };
  auto planned = [&](double step) { return lanes * (scan(step) + halvings(step)); };
  const double probes = planned(spec.riser_step_m);
  if (probes <= static_cast<double>(kMaxEnvelopeProbes)) return;
  const std::string what = " planned probes (" + std::to_string(*cells) + " cells x " +
                           std::to_string(spec.criteria.size()) + " criteria x (" +
                           EnvelopeReader::fmt(scan(spec.riser_step_m)) + " scan steps + " +
                           EnvelopeReader::fmt(halvings(spec.riser_step_m)) +
                           " halvings)), expected at most " + std::to_string(kMaxEnvelopeProbes);
  // A coarser riser.step, when one up to the whole span brings it within the limit: the
  // finest such step of 3 significant digits.
  for (double n = std::floor(span / spec.riser_step_m); n >= 1.0; n = std::floor(n * 0.999)) {
    const double step = rounded_up(span / n);
    if (step > span || planned(step) > static_cast<double>(kMaxEnvelopeProbes)) continue;
    r.fail("riser.step", "got " + EnvelopeReader::fmt(spec.riser_step_m) + " m, up to " +
                             EnvelopeReader::fmt(probes) + what + ": a step of at least " +
                             EnvelopeReader::fmt(step) + " m");
  }
  r.fail(longest->first, "got " + std::to_string(longest->second) + " values, up to " +
                             EnvelopeReader::fmt(probes) + what);
}

/// The base scene's tree: `base` (a scene file beside the envelope file, with what it
/// inherits, listed in chain) with the envelope's `set:` overrides applied; its YAML kept
/// in spec.base_tree_yaml.
YAML::Node read_base_tree(const EnvelopeReader& r, const YAML::Node& root, const std::string& path,
                          EnvelopeSpec& spec, std::vector<std::string>& chain) {
  const YAML::Node base = root["base"];
  if (!given(base))
    r.fail("base", "missing, this key is required (the scene file whose riser is searched)");
  if (!base.IsScalar() || base.Scalar().empty())
    r.fail_value("base", base, "the path of a scene file");
  spec.base_path = path_beside(path, base.Scalar());
  if (const auto why = why_not_regular_file(spec.base_path))
    r.fail_value("base", base,
                 "the path of a scene file, relative to the envelope file (" + spec.base_path +
                     " " + *why + ")");
  YAML::Node tree = load_scene_tree(spec.base_path, &chain);
  const YAML::Node set = root["set"];
  if (given(set)) {
    if (!set.IsMap()) r.fail_value("set", set, "a mapping of dotted key paths to values");
    for (const auto& kv : set) {
      if (kv.second.IsMap())
        r.fail_value("set." + kv.first.Scalar(), kv.second,
                     "a value or a list (write nested keys as dotted paths)");
      apply_override(tree, {kv.first.Scalar(), yaml_inline(kv.second)},
                     path + " (base " + spec.base_path + ")");
    }
  }
  YAML::Emitter emit;
  emit << tree;
  spec.base_tree_yaml = emit.c_str();
  return tree;
}

/// `cases:`: the designs whose envelope is searched, each valid on the base tree, none
/// setting a key the envelope sets itself; their files join spec.inputs.
void read_envelope_cases(const EnvelopeReader& r, const YAML::Node& node, const YAML::Node& tree,
                         const std::string& path, EnvelopeSpec& spec) {
  spec.cases = read_case_list(r, node, "cases", path);
  if (spec.cases.size() > kMaxEnvelopeCells)  // before each case is validated
    r.fail("cases", "got " + std::to_string(spec.cases.size()) + " cases, expected at most " +
                        std::to_string(kMaxEnvelopeCells) + " (an envelope has at most " +
                        std::to_string(kMaxEnvelopeCells) + " cells)");
  for (const std::string& key : spec.cases.keys)
    for (const char* own :
         {"terrain.riser_height", "terrain.tread_depth", "gait.duty_factor", "motion.peak_speed"})
      if (key == own)
        r.fail("cases", "got key " + key +
                            ", expected a key the envelope does not set itself (it searches "
                            "the riser and takes tread_depth, duty_factor and peak_speed)");
  check_cases_on(r, spec.cases, tree, "cases");
  add_case_inputs(spec.inputs, spec.cases);
}

/// `riser:` {from, to, step, tolerance} [m]: the range searched, the scan's step (0.01 m or
/// the span) and the bisection's tolerance (1 mm or the step).
void read_riser(const EnvelopeReader& r, const YAML::Node& riser, EnvelopeSpec& spec) {
  if (!given(riser))
    r.fail("riser", "missing, this key is required ({from, to, step, tolerance} in m)");
  r.check_keys(riser, "riser", {"from", "to", "step", "tolerance"});
  for (const char* k : {"from", "to"})
    if (!given(riser[k])) r.fail(std::string("riser.") + k, "missing, this key is required");
  spec.riser_from_m = r.number(riser["from"], "riser.from", 0.0, 1.0);
  spec.riser_to_m = r.number(riser["to"], "riser.to", 0.0, 1.0);
  if (!(spec.riser_from_m < spec.riser_to_m))
    r.fail("riser.to", "got " + EnvelopeReader::fmt(spec.riser_to_m) +
                           ", expected more than riser.from (" +
                           EnvelopeReader::fmt(spec.riser_from_m) + ")");
  const double span = spec.riser_to_m - spec.riser_from_m;
  spec.riser_step_m = given(riser["step"]) ? r.number(riser["step"], "riser.step", 1e-5, span)
                                           : std::min(0.01, span);
  spec.tolerance_m = given(riser["tolerance"])
                         ? r.number(riser["tolerance"], "riser.tolerance", 1e-6, spec.riser_step_m)
                         : std::min(1e-3, spec.riser_step_m);
}

/// `criteria:` each of kinematic, torque, friction at most once; all three when not given.
void read_criteria(const EnvelopeReader& r, const YAML::Node& crit, EnvelopeSpec& spec) {
  if (!given(crit)) {
    spec.criteria = {EnvelopeCriterion::kKinematic, EnvelopeCriterion::kTorque,
                     EnvelopeCriterion::kFriction};
    return;
  }
  if (!crit.IsSequence() || crit.size() == 0)
    r.fail_value("criteria", crit, "a non-empty list of kinematic, torque, friction");
  for (const auto& c : crit) {
    const std::string name = c.IsScalar() ? c.Scalar() : "";
    if (name == "kinematic")
      spec.criteria.push_back(EnvelopeCriterion::kKinematic);
    else if (name == "torque")
      spec.criteria.push_back(EnvelopeCriterion::kTorque);
    else if (name == "friction")
      spec.criteria.push_back(EnvelopeCriterion::kFriction);
    else
      r.fail_value("criteria", crit, "a list of kinematic, torque, friction");
  }
  if (std::set<EnvelopeCriterion>(spec.criteria.begin(), spec.criteria.end()).size() !=
      spec.criteria.size())
    r.fail_value("criteria", crit, "each criterion at most once");
}

/// `search:` riser (default) or friction; a friction search has the one criterion friction
/// (`criteria`, when given, must say so).
void read_search(const EnvelopeReader& r, const YAML::Node& root, EnvelopeSpec& spec) {
  if (!given(root["search"])) return;
  const YAML::Node search = root["search"];
  const std::string word = search.IsScalar() ? search.Scalar() : std::string();
  if (word == "riser") return;
  if (word != "friction") r.fail_value("search", search, "riser or friction");
  spec.search = EnvelopeSearch::kFriction;
  if (given(root["criteria"]) &&
      (spec.criteria.size() != 1 || spec.criteria.front() != EnvelopeCriterion::kFriction))
    r.fail_value("criteria", root["criteria"],
                 "[friction] or no criteria with search: friction (it searches the least mu)");
  spec.criteria = {EnvelopeCriterion::kFriction};
}

/// `direction:` up (default) or down: the way the stairs are walked, the sign of every probe's
/// riser.
void read_direction(const EnvelopeReader& r, const YAML::Node& root, EnvelopeSpec& spec) {
  if (!given(root["direction"])) return;
  const YAML::Node d = root["direction"];
  const std::string word = d.IsScalar() ? d.Scalar() : std::string();
  if (word != "up" && word != "down") r.fail_value("direction", d, "up or down");
  spec.direction = word == "down" ? -1 : 1;
}

/// Every cell's scene at the lowest riser must be valid (speed against ramp, ...): the
/// probe's keys set on the base's SceneTree (no YAML per cell), as envelope_probe_scene
/// sets them on the YAML tree, which it falls back to when a key runs through a non-map.
void check_every_cell(const EnvelopeSpec& spec, const YAML::Node& tree) {
  const SceneTree base_tree(tree);
  const int cells = spec.cell_count();
  for (int cell = 0; cell < cells; ++cell)
    for (EnvelopeCriterion c : spec.criteria) {
      SceneTree one = base_tree;
      bool set = true;
      for (const Override& o : probe_overrides(spec, cell, spec.riser_from_m, c))
        set = set && one.set(split_key_path(o.key_path),
                             SceneTree::convert(parse_yaml_checked(
                                 o.value, "--set " + o.key_path + "=" + o.value)));
      if (set)
        (void)scene_from_tree(one, probe_source(spec, cell, spec.riser_from_m), false);
      else
        (void)envelope_probe_scene(spec, cell, spec.riser_from_m, c);
    }
}

}  // namespace

const char* criterion_name(EnvelopeCriterion c) {
  switch (c) {
    case EnvelopeCriterion::kKinematic:
      return "kinematic";
    case EnvelopeCriterion::kTorque:
      return "torque";
    case EnvelopeCriterion::kFriction:
      return "friction";
  }
  return "kinematic";
}

EnvelopeSpec load_envelope_spec(const std::string& path) {
  EnvelopeSpec spec;
  spec.spec_yaml = read_text_file(path);
  const YAML::Node root = parse_yaml_text(spec.spec_yaml, path);
  const EnvelopeReader r(path);
  r.check_keys(root, "",
               {"name", "base", "set", "cases", "riser", "tread_depth", "duty_factor", "peak_speed",
                "criteria", "kinematic_margin", "search", "direction"});
  spec.name =
      given(root["name"]) ? root["name"].Scalar() : std::filesystem::path(path).stem().string();
  std::vector<std::string> chain;
  const YAML::Node tree = read_base_tree(r, root, path, spec, chain);
  const Scene base_scene = scene_from_yaml(tree, path + " (base " + spec.base_path + ")");
  spec.base_config_yaml = base_scene.resolved_yaml;
  add_input(spec.inputs, "envelope file", path);
  for (InputFile& f : scene_inputs(chain, tree))
    add_input(spec.inputs, f.role == "scene" ? "base scene" : f.role, f.path);
  if (given(root["cases"])) read_envelope_cases(r, root["cases"], tree, path, spec);
  if (base_scene.terrain.type != TerrainType::kStairs)
    r.fail("base",
           "the base scene's terrain.type is not stairs, expected a staircase (its riser is "
           "searched)");
  read_riser(r, root["riser"], spec);
  // The grid: tread depths [m] (the base scene's when not given), duty factors, peak speeds [m/s].
  spec.tread_depth_m = given(root["tread_depth"])
                           ? r.numbers(root["tread_depth"], "tread_depth", 1e-3, 10.0)
                           : std::vector<double>{base_scene.terrain.tread_depth_m};
  for (const char* k : {"duty_factor", "peak_speed"})
    if (!given(root[k])) r.fail(k, "missing, this key is required (a list of values)");
  spec.duty_factor = r.numbers(root["duty_factor"], "duty_factor", 0.5, 0.999999);
  spec.peak_speed_mps = r.numbers(root["peak_speed"], "peak_speed", 1e-6, 10.0);
  read_criteria(r, root["criteria"], spec);
  read_search(r, root, spec);
  read_direction(r, root, spec);
  if (given(root["kinematic_margin"]))
    spec.kinematic_margin_m = r.number(root["kinematic_margin"], "kinematic_margin", 0.0, 0.1);
  check_envelope_size(r, spec);
  check_every_cell(spec, tree);
  return spec;
}

int EnvelopeSpec::cell_count() const {
  // At most kMaxEnvelopeCells once load_envelope_spec has checked it (check_envelope_size).
  const std::uint64_t n = std::max<std::uint64_t>(1, cases.size()) * tread_depth_m.size() *
                          duty_factor.size() * peak_speed_mps.size();
  return static_cast<int>(std::min<std::uint64_t>(n, kMaxEnvelopeCells));
}

std::vector<double> EnvelopeSpec::scan_risers() const {
  const int steps = static_cast<int>(std::ceil((riser_to_m - riser_from_m) / riser_step_m - 1e-9));
  std::vector<double> r;
  for (int k = 0; k <= steps; ++k)
    r.push_back(std::min(riser_from_m + k * riser_step_m, riser_to_m));
  return r;
}

namespace {

std::string exact_text(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

/// The cell's (D, W, B, V) indices, row-major.
struct CellIndex {
  std::size_t d, w, b, v;
};

CellIndex cell_index(const EnvelopeSpec& spec, int cell) {
  const std::size_t V = spec.peak_speed_mps.size(), B = spec.duty_factor.size(),
                    W = spec.tread_depth_m.size();
  const std::size_t n = static_cast<std::size_t>(cell);
  return {n / (V * B * W), (n / (V * B)) % W, (n / V) % B, n % V};
}

}  // namespace

std::string probe_source(const EnvelopeSpec& spec, int cell, double riser_m) {
  const CellIndex i = cell_index(spec, cell);
  return spec.name + " envelope cell " + std::to_string(cell) +
         (spec.cases.size() > 0 ? " (case " + spec.cases.labels[i.d] + ")" : std::string()) +
         " riser " + exact_text(riser_m);
}

std::vector<Override> probe_overrides(const EnvelopeSpec& spec, int cell, double riser_m,
                                      EnvelopeCriterion c) {
  const CellIndex i = cell_index(spec, cell);
  const std::size_t v = i.v, b = i.b, w = i.w, d = i.d;
  const auto text = exact_text;
  std::vector<Override> ov;
  if (spec.cases.size() > 0) ov = spec.cases.overrides(d);
  const std::vector<Override> cell_keys = {{"terrain.riser_height", text(spec.direction * riser_m)},
                                           {"terrain.tread_depth", text(spec.tread_depth_m[w])},
                                           {"gait.duty_factor", text(spec.duty_factor[b])},
                                           {"motion.peak_speed", text(spec.peak_speed_mps[v])}};
  ov.insert(ov.end(), cell_keys.begin(), cell_keys.end());
  if (c == EnvelopeCriterion::kTorque) ov.push_back({"contact.friction_coefficient", "10"});
  if (c == EnvelopeCriterion::kFriction) ov.push_back({"allocation.torque_limit", "1e6"});
  if (spec.search == EnvelopeSearch::kFriction) ov.push_back({"output.required_friction", "true"});
  if (c == EnvelopeCriterion::kKinematic && spec.kinematic_margin_m >= 0.0)
    ov.push_back({"robot.ik_min_margin", text(spec.kinematic_margin_m)});
  return ov;
}

Scene envelope_probe_scene(const EnvelopeSpec& spec, int cell, double riser_m,
                           EnvelopeCriterion c) {
  YAML::Node tree = YAML::Load(spec.base_tree_yaml);
  const std::string source = probe_source(spec, cell, riser_m);
  for (const auto& o : probe_overrides(spec, cell, riser_m, c)) apply_override(tree, o, source);
  return scene_from_yaml(tree, source);
}

}  // namespace hexdyn
