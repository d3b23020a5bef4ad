// Reading an envelope file (envelope.hpp, configs/envelope/paper.yaml) and building the
// scene of each probe from its base scene.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/envelope/envelope.hpp"
#include "hexdyn/io/config.hpp"
#include "hexdyn/io/paths.hpp"
#include "hexdyn/io/spec_reader.hpp"
#include "hexdyn/io/yaml_load.hpp"

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
                "criteria", "kinematic_margin"});
  spec.name =
      given(root["name"]) ? root["name"].Scalar() : std::filesystem::path(path).stem().string();
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
  std::vector<std::string> chain;
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
  const Scene base_scene = scene_from_yaml(tree, path + " (base " + spec.base_path + ")");
  spec.base_config_yaml = base_scene.resolved_yaml;
  add_input(spec.inputs, "envelope file", path);
  for (InputFile& f : scene_inputs(chain, tree))
    add_input(spec.inputs, f.role == "scene" ? "base scene" : f.role, f.path);
  // cases: the designs whose envelope is searched, each valid on the base scene.
  if (given(root["cases"])) {
    spec.cases = read_case_list(r, root["cases"], "cases", path);
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
  if (base_scene.terrain.type != TerrainType::kStairs)
    r.fail("base",
           "the base scene's terrain.type is not stairs, expected a staircase (its riser is "
           "searched)");

  const YAML::Node riser = root["riser"];
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

  spec.tread_depth_m = given(root["tread_depth"])
                           ? r.numbers(root["tread_depth"], "tread_depth", 1e-3, 10.0)
                           : std::vector<double>{base_scene.terrain.tread_depth_m};
  for (const char* k : {"duty_factor", "peak_speed"})
    if (!given(root[k])) r.fail(k, "missing, this key is required (a list of values)");
  spec.duty_factor = r.numbers(root["duty_factor"], "duty_factor", 0.5, 0.999999);
  spec.peak_speed_mps = r.numbers(root["peak_speed"], "peak_speed", 1e-6, 10.0);
  const YAML::Node crit = root["criteria"];
  if (given(crit)) {
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
  } else {
    spec.criteria = {EnvelopeCriterion::kKinematic, EnvelopeCriterion::kTorque,
                     EnvelopeCriterion::kFriction};
  }
  if (given(root["kinematic_margin"]))
    spec.kinematic_margin_m = r.number(root["kinematic_margin"], "kinematic_margin", 0.0, 0.1);
  // Every cell's scene at the lowest riser must be valid (speed against ramp, ...).
  const int cells = spec.cell_count();
  for (int cell = 0; cell < cells; ++cell)
    for (EnvelopeCriterion c : spec.criteria)
      (void)envelope_probe_scene(spec, cell, spec.riser_from_m, c);
  return spec;
}

int EnvelopeSpec::cell_count() const {
  return static_cast<int>(std::max<std::size_t>(1, cases.size()) * tread_depth_m.size() *
                          duty_factor.size() * peak_speed_mps.size());
}

Scene envelope_probe_scene(const EnvelopeSpec& spec, int cell, double riser_m,
                           EnvelopeCriterion c) {
  const std::size_t V = spec.peak_speed_mps.size(), B = spec.duty_factor.size(),
                    W = spec.tread_depth_m.size();
  const std::size_t n = static_cast<std::size_t>(cell);
  const std::size_t v = n % V, b = (n / V) % B, w = (n / (V * B)) % W, d = n / (V * B * W);
  YAML::Node tree = YAML::Load(spec.base_tree_yaml);
  auto text = [](double x) {
    std::ostringstream s;
    s.precision(17);
    s << x;
    return s.str();
  };
  std::vector<Override> ov;
  if (spec.cases.size() > 0) ov = spec.cases.overrides(d);
  const std::vector<Override> cell_keys = {{"terrain.riser_height", text(riser_m)},
                                           {"terrain.tread_depth", text(spec.tread_depth_m[w])},
                                           {"gait.duty_factor", text(spec.duty_factor[b])},
                                           {"motion.peak_speed", text(spec.peak_speed_mps[v])}};
  ov.insert(ov.end(), cell_keys.begin(), cell_keys.end());
  if (c == EnvelopeCriterion::kTorque) ov.push_back({"contact.friction_coefficient", "10"});
  if (c == EnvelopeCriterion::kFriction) ov.push_back({"allocation.torque_limit", "1e6"});
  if (c == EnvelopeCriterion::kKinematic && spec.kinematic_margin_m >= 0.0)
    ov.push_back({"robot.ik_min_margin", text(spec.kinematic_margin_m)});
  const std::string source =
      spec.name + " envelope cell " + std::to_string(cell) +
      (spec.cases.size() > 0 ? " (case " + spec.cases.labels[d] + ")" : std::string()) + " riser " +
      text(riser_m);
  for (const auto& o : ov) apply_override(tree, o, source);
  return scene_from_yaml(tree, source);
}

}  // namespace hexdyn
