#include "hexdyn/sweep/validate.hpp"

#include <yaml-cpp/yaml.h>

#include <sstream>

#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/sweep/scenario_factory.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

const char* validated_kind_name(ValidatedKind kind) {
  return kind == ValidatedKind::kSweep ? "sweep" : "scene";
}

namespace {

/// A sweep file's report: load_sweep's checks, then each scenario's scene.
ValidationReport validate_sweep_file(const std::string& path) {
  const SweepSpec spec = load_sweep(path);
  ValidationReport report;
  report.kind = ValidatedKind::kSweep;
  report.path = path;
  report.name = spec.name;
  const std::size_t n = spec.scenario_count();
  std::ostringstream line;
  line << path << ": valid sweep '" << spec.name << "', base scene " << spec.base_path << ", " << n
       << " scenario" << (n == 1 ? "" : "s") << " over";
  for (const auto& axis : spec.axes) line << " " << axis.key << " (" << axis.size() << ")";
  report.messages.push_back(line.str());
  // Every scenario's scene, as the sweep builds it (sweep/scenario_factory.hpp).
  const SweepScenarioCheck check = check_sweep_scenarios(spec);
  report.scenarios = check.scenarios;
  report.out_of_range = check.out_of_range;
  report.first_out_of_range = check.first;
  if (check.out_of_range > 0)
    report.messages.push_back(
        path + ": " + std::to_string(check.out_of_range) + " of " + std::to_string(n) +
        " scenarios have a value out of range and would be rows with status config; first: " +
        check.first);
  return report;
}

}  // namespace

ValidationReport validate_file(const std::string& path, const std::vector<Override>& overrides) {
  // A sweep file is recognised by its top-level axes: key (no scene has one).
  const YAML::Node root = parse_yaml_text(read_text_file(path), path);
  if (root["axes"].IsDefined()) {
    if (!overrides.empty())
      throw ConfigError("validate: --set applies to scene files; " + path +
                        " is a sweep file (it has axes:), fix keys with set: in it");
    return validate_sweep_file(path);
  }
  ValidationReport report;
  report.kind = ValidatedKind::kScene;
  report.path = path;
  report.scene = load_scene(path, overrides);
  report.name = report.scene->name;
  report.messages.push_back(path + ": valid scene '" + report.name + "'");
  return report;
}

}  // namespace hexdyn
