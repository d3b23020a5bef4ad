#include "hexdyn/sweep/spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <system_error>

#include "hexdyn/config/cases.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/spec_reader.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/paths.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

std::string emit(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

bool parse_finite_number(const YAML::Node& node, double& out) {
  return node.IsDefined() && node.IsScalar() && YAML::convert<double>::decode(node, out) &&
         std::isfinite(out);
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

void read_values(const SpecReader& r, const YAML::Node& values, const std::string& path,
                 SweepAxis& axis) {
  const std::string expected = "a non-empty list of single values (numbers, p/q or words)";
  if (!values.IsSequence() || values.size() == 0) r.fail_value(path, values, expected);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const YAML::Node v = values[k];
    if (!v.IsScalar()) r.fail_value(path + "[" + std::to_string(k) + "]", v, "a single value");
    const std::string text = v.Scalar();
    axis.labels.push_back(text);
    if (is_quoted_number(v)) {  // a string: the scene reader refuses it for a number key
      axis.values.push_back(yaml_inline(v));
    } else if (const auto q = parse_fraction(text)) {
      axis.values.push_back(format_number(*q, 17));
    } else {
      axis.values.push_back(text);
    }
  }
}

void read_range(const SpecReader& r, const YAML::Node& range, const std::string& path,
                SweepAxis& axis) {
  if (!range.IsMap()) r.fail_value(path, range, "a mapping {from: A, to: B, count: N}");
  r.check_keys(range, path, {"from", "to", "count"});
  double lo = 0.0, hi = 0.0;
  r.refuse_quoted_number(path + ".from", range["from"], "a finite number");
  r.refuse_quoted_number(path + ".to", range["to"], "a finite number");
  r.refuse_quoted_number(path + ".count", range["count"], "an integer in [2, 100000]");
  if (!parse_finite_number(range["from"], lo))
    r.fail_value(path + ".from", range["from"], "a finite number");
  if (!parse_finite_number(range["to"], hi))
    r.fail_value(path + ".to", range["to"], "a finite number");
  long long count = 0;
  const YAML::Node c = range["count"];
  if (!c.IsDefined() || !c.IsScalar() || !YAML::convert<long long>::decode(c, count) || count < 2 ||
      count > 100000)
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

void finish_axis(const SpecReader& r, const std::string& path, SweepAxis& axis) {
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

/// Names that a cases axis may not take: the sweep file's own groups and coordinates, and the
/// datasets of /axes/<i>, which holds the coordinate of the axis's dimension (io/labels.hpp).
bool reserved_axis_name(const std::string& name) {
  for (const char* r : {"meta", "axes", "scenarios", "runs", "joint_names", "scenario", "axis",
                        "joint", "key", "case_keys", "case_values"})
    if (name == r) return true;
  return false;
}

/// A cases axis {cases: [...], name: NAME} into `axis`: its name as key, the labels as its
/// values (config/cases.hpp reads the list). The validation on the base scene comes later.
void read_cases(const SpecReader& r, const YAML::Node& a, const std::string& at,
                const std::string& sweep_path, SweepAxis& axis) {
  const YAML::Node name = a["name"];
  axis.key = "case";
  if (name.IsDefined() && !name.IsNull()) {
    static const std::regex word("[A-Za-z_][A-Za-z0-9_]*");
    if (!name.IsScalar() || !std::regex_match(name.Scalar(), word) ||
        reserved_axis_name(name.Scalar()))
      r.fail_value(at + ".name", name,
                   "a word of letters, digits and _ (the axis's dimension), not one of meta, "
                   "axes, scenarios, runs, joint_names, scenario, axis, joint, key, case_keys, "
                   "case_values");
    axis.key = name.Scalar();
  }
  const CaseList cases = read_case_list(r, a["cases"], at + ".cases", sweep_path);
  axis.values = axis.labels = cases.labels;
  axis.case_keys = cases.keys;
  axis.case_values = cases.values;
  axis.numeric = false;
}

/// The cases of a cases axis, as config/cases.hpp holds them.
CaseList case_list(const SweepAxis& axis) {
  CaseList c;
  c.labels = axis.labels;
  c.keys = axis.case_keys;
  c.values = axis.case_values;
  return c;
}

}  // namespace

std::vector<Override> SweepAxis::overrides(std::size_t v) const {
  if (!is_cases()) return {{key, values[v]}};
  std::vector<Override> out;
  for (std::size_t k = 0; k < case_keys.size(); ++k)
    out.push_back({case_keys[k], case_values[v][k]});
  return out;
}

std::size_t SweepSpec::scenario_count() const {
  std::size_t n = 1;
  for (const auto& a : axes) n *= a.size();
  return n;
}

namespace {

/// `name:`, the sweep file's stem when not given.
std::string read_sweep_name(const SpecReader& r, const YAML::Node& root, const std::string& path) {
  const YAML::Node name = root["name"];
  if (name.IsDefined() && !name.IsNull()) {
    if (!name.IsScalar()) r.fail_value("name", name, "a string");
    return name.Scalar();
  }
  return fs::path(path).stem().string();
}

/// `base:` the scene file the axes vary (relative to the sweep file), into spec.base_path;
/// returns its tree, the files it inherits listed in chain.
YAML::Node read_sweep_base(const SpecReader& r, const YAML::Node& root, const std::string& path,
                           SweepSpec& spec, std::vector<std::string>& chain) {
  const YAML::Node base = root["base"];
  if (!base.IsDefined() || base.IsNull())
    r.fail("base", "missing, this key is required (the scene file the axes vary)");
  if (!base.IsScalar() || base.Scalar().empty())
    r.fail_value("base", base, "the path of a scene file");
  spec.base_path = path_beside(path, base.Scalar());
  if (const auto why = why_not_regular_file(spec.base_path))
    r.fail_value("base", base,
                 "the path of a scene file, relative to the sweep file (" + spec.base_path + " " +
                     *why + ")");
  return load_scene_tree(spec.base_path, &chain);
}

/// `set:` the keys every scenario fixes, into spec.fixed; returns their key paths.
std::set<std::string> read_fixed(const SpecReader& r, const YAML::Node& set, SweepSpec& spec) {
  std::set<std::string> fixed_keys;
  if (!set.IsDefined() || set.IsNull()) return fixed_keys;
  if (!set.IsMap()) r.fail_value("set", set, "a mapping of dotted key paths to values");
  for (const auto& kv : set) {
    const std::string key = kv.first.Scalar();
    for (const auto& k : split_key_path(key))
      if (k.empty()) r.fail("set." + key, "empty key in the dotted path");
    if (kv.second.IsMap())
      r.fail_value("set." + key, kv.second,
                   "a value or a list (write nested keys as dotted paths)");
    spec.fixed.push_back({key, yaml_inline(kv.second)});
    fixed_keys.insert(key);
  }
  return fixed_keys;
}

/// What the axes are read against: the resolved base scene, its file (for messages), the
/// keys fixed by set: and the keys of the axes read so far (each key on one axis only).
struct AxisContext {
  const SpecReader& r;
  const std::string& path;       ///< the sweep file
  const std::string& base_path;  ///< the base scene file
  const YAML::Node& resolved;    ///< the base scene, resolved
  const std::set<std::string>& fixed_keys;
  std::set<std::string> axis_keys;
};

/// A cases axis {cases: [...], name}, at `at`: its name and keys on no other axis and not
/// fixed by set:.
SweepAxis read_cases_axis(AxisContext& ctx, const YAML::Node& a, const std::string& at) {
  SweepAxis axis;
  ctx.r.check_keys(a, at, {"cases", "name"});
  read_cases(ctx.r, a, at, ctx.path, axis);
  if (!ctx.axis_keys.insert(axis.key).second)
    ctx.r.fail_value(at + ".name", YAML::Node(axis.key),
                     "a name no other axis has (name each cases axis)");
  for (const std::string& k : axis.case_keys) {
    if (ctx.fixed_keys.count(k))
      ctx.r.fail(at + ".cases", "got key " + k + ", expected a key not also fixed by set:");
    if (!ctx.axis_keys.insert(k).second)
      ctx.r.fail(at + ".cases", "got key " + k + ", expected each key on one axis only");
  }
  return axis;
}

/// A key axis {key, values} or {key, range}, at `at`: a key of the base scene holding a
/// single value, on no other axis and not fixed by set:, and exactly one of values, range.
SweepAxis read_key_axis(AxisContext& ctx, const YAML::Node& a, const std::string& at) {
  const SpecReader& r = ctx.r;
  SweepAxis axis;
  r.check_keys(a, at, {"key", "values", "range"});
  const YAML::Node key = a["key"];
  if (!key.IsDefined() || key.IsNull()) r.fail(at + ".key", "missing, this key is required");
  if (!key.IsScalar() || key.Scalar().empty()) r.fail_value(at + ".key", key, "a dotted key path");
  axis.key = key.Scalar();
  const auto keys = split_key_path(axis.key);
  for (const auto& k : keys)
    if (k.empty()) r.fail_value(at + ".key", key, "a dotted key path without empty parts");
  const YAML::Node target = lookup(ctx.resolved, keys);
  if (!target.IsDefined()) {
    const std::string near = keys_near(ctx.resolved, keys);
    r.fail_value(at + ".key", key,
                 "a key of the base scene " + ctx.base_path +
                     (near.empty() ? std::string() : " (near: " + near + ")"));
  }
  if (!target.IsScalar())
    r.fail_value(at + ".key", key,
                 std::string("a key holding a single value (it holds a ") +
                     (target.IsMap() ? "group of keys" : "list") + ")");
  if (ctx.fixed_keys.count(axis.key))
    r.fail_value(at + ".key", key, "a key not also fixed by set:");
  if (!ctx.axis_keys.insert(axis.key).second)
    r.fail_value(at + ".key", key, "each key on one axis only (and not also in cases)");

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
  return axis;
}

/// `axes:` a non-empty list of key and cases axes, into spec.axes, of at most
/// kMaxScenarios scenarios together.
void read_axes(AxisContext& ctx, const YAML::Node& axes, SweepSpec& spec) {
  const SpecReader& r = ctx.r;
  if (!axes.IsDefined() || axes.IsNull())
    r.fail("axes", "missing, this key is required (a list of {key, values} or {key, range})");
  if (!axes.IsSequence() || axes.size() == 0)
    r.fail_value("axes", axes, "a non-empty list of {key, values} or {key, range}");
  std::size_t count = 1;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const std::string at = "axes[" + std::to_string(i) + "]";
    const YAML::Node a = axes[i];
    if (!a.IsMap())
      r.fail_value(at, a,
                   "a mapping {key: K, values: [...]}, {key: K, range: {...}} or {cases: [...]}");
    SweepAxis axis =
        a["cases"].IsDefined() ? read_cases_axis(ctx, a, at) : read_key_axis(ctx, a, at);
    count *= axis.size();
    if (count > kMaxScenarios)
      r.fail("axes", "got more than " + std::to_string(kMaxScenarios) +
                         " scenarios, expected at most that many");
    spec.axes.push_back(std::move(axis));
  }
}

/// The sweep's input files: the sweep file, the base scene with what it inherits, the
/// URDFs of a robot.urdf axis and of the cases.
void add_sweep_inputs(SweepSpec& spec, const std::string& path,
                      const std::vector<std::string>& chain, const YAML::Node& tree) {
  add_input(spec.inputs, "sweep file", path);
  for (InputFile& f : scene_inputs(chain, tree))
    add_input(spec.inputs, f.role == "scene" ? "base scene" : f.role, f.path);
  // A robot.urdf axis names its URDFs as --set does (relative to the working directory).
  for (const SweepAxis& axis : spec.axes)
    if (axis.key == "robot.urdf")
      for (const std::string& v : axis.values)
        if (why_not_regular_file(v) == std::nullopt) add_input(spec.inputs, "URDF", v);
  // A case's URDF is resolved from the sweep file (read_cases).
  for (const SweepAxis& axis : spec.axes)
    if (axis.is_cases()) add_case_inputs(spec.inputs, case_list(axis));
}

/// Each value once against its key, on the base scene: a value out of range is found
/// here without looking at any combination of values (its message into axis.errors). The
/// value is set on the base's SceneTree, which shares every map it does not change (no
/// copy of the base per value).
void check_axis_values(const SpecReader& r, SweepSpec& spec, const YAML::Node& tree) {
  const SceneTree base_tree(tree);
  for (SweepAxis& axis : spec.axes) {
    axis.errors.assign(axis.size(), std::string());
    // A case is its keys together: one that is not valid on the base scene stops the sweep.
    if (axis.is_cases())
      check_cases_on(r, case_list(axis), tree,
                     "axes[" + std::to_string(&axis - spec.axes.data()) + "].cases");
    for (std::size_t v = 0; !axis.is_cases() && v < axis.size(); ++v) {
      const std::string source = axis.key + "=" + axis.labels[v];
      try {
        SceneTree one = base_tree;
        const YAML::Node value =
            parse_yaml_checked(axis.values[v], "--set " + axis.key + "=" + axis.values[v]);
        if (one.set(split_key_path(axis.key), SceneTree::convert(value))) {
          (void)scene_from_tree(one, source, false);
        } else {  // through a value that is not a map: the YAML tree's own rules
          YAML::Node copy = YAML::Clone(tree);
          apply_override(copy, {axis.key, axis.values[v]}, source);
          (void)scene_from_yaml(copy, source, false);
        }
      } catch (const Error& e) {
        axis.errors[v] = e.what();
      }
    }
  }
}

}  // namespace

SweepSpec load_sweep(const std::string& path) {
  SweepSpec spec;
  spec.sweep_yaml = read_text_file(path);
  const YAML::Node root = parse_yaml_text(spec.sweep_yaml, path);
  const SpecReader r(path);
  r.check_keys(root, "", {"name", "base", "set", "axes"});
  spec.name = read_sweep_name(r, root, path);
  std::vector<std::string> chain;
  YAML::Node tree = read_sweep_base(r, root, path, spec, chain);
  const std::set<std::string> fixed_keys = read_fixed(r, root["set"], spec);
  const std::string base_source = path + " (base " + spec.base_path + ")";
  for (const auto& ov : spec.fixed) apply_override(tree, ov, base_source);
  spec.base_tree_yaml = emit(tree);
  const Scene base_scene = scene_from_yaml(tree, base_source);
  spec.base_config_yaml = base_scene.resolved_yaml;
  const YAML::Node resolved = YAML::Load(spec.base_config_yaml);
  AxisContext ctx{r, path, spec.base_path, resolved, fixed_keys, {}};
  read_axes(ctx, root["axes"], spec);
  add_sweep_inputs(spec, path, chain, tree);
  check_axis_values(r, spec, tree);
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
    for (const Override& ov : spec.axes[a].overrides(p[a])) apply_override(tree, ov, source);
  in.yaml = emit(tree);
  return in;
}

}  // namespace hexdyn
