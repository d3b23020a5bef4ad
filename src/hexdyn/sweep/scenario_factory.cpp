#include "hexdyn/sweep/scenario_factory.hpp"

#include <yaml-cpp/yaml.h>

#include <exception>
#include <optional>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/scene_tree.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {

struct ScenarioFactory::Impl {
  SweepSpec spec;            ///< axes and id width
  std::string input_sha256;  ///< the sweep's inputs: a kept run's /meta input_sha256
  YAML::Node base;
  SceneTree base_tree;  ///< `base` as the scene reader walks it
  /// One key set by an axis value: its dotted path and its value, parsed once.
  struct Setting {
    std::vector<std::string> keys;
    YAML::Node value;
    SceneTree::NodePtr node;  ///< `value` converted
  };
  /// Per axis, per value: the keys it sets (one, or a case's keys).
  std::vector<std::vector<std::vector<Setting>>> axes;

  explicit Impl(const SweepSpec& s)
      : input_sha256(input_sha256_text(s.inputs)),
        base(parse_yaml_text(s.base_tree_yaml, s.base_path)),
        base_tree(base) {
    spec.axes = s.axes;
  }

  /// The scenario's tree for the scene reader: the base tree sharing all it can with
  /// `base_tree`, the same as SceneTree(tree(index)); nullopt when a value must be set on
  /// the YAML tree itself (a key path through a value that is not a map).
  std::optional<SceneTree> scene_tree(std::size_t index) const {
    SceneTree t = base_tree;
    const auto p = grid_point(spec, index);
    for (std::size_t a = 0; a < axes.size(); ++a)
      for (const Setting& set : axes[a][p[a]])
        if (!t.set(set.keys, set.node)) return std::nullopt;
    return t;
  }

  YAML::Node tree(std::size_t index) const {
    YAML::Node root = YAML::Clone(base);
    const auto p = grid_point(spec, index);
    for (std::size_t a = 0; a < axes.size(); ++a) {
      for (const Setting& set : axes[a][p[a]]) {
        // As apply_override: intermediate maps are created where absent (load_sweep has
        // checked every axis key and every case on the base scene).
        YAML::Node cur = root;
        for (std::size_t k = 0; k + 1 < set.keys.size(); ++k) {
          YAML::Node next = cur[set.keys[k]];
          if (!next.IsDefined() || next.IsNull()) {
            cur[set.keys[k]] = YAML::Node(YAML::NodeType::Map);
            next.reset(cur[set.keys[k]]);
          }
          cur.reset(next);
        }
        cur[set.keys.back()] = YAML::Clone(set.value);
      }
    }
    return root;
  }
};

ScenarioFactory::ScenarioFactory(const SweepSpec& spec) : impl_(std::make_unique<Impl>(spec)) {
  for (const SweepAxis& axis : spec.axes) {
    std::vector<std::vector<Impl::Setting>> values;
    for (std::size_t v = 0; v < axis.size(); ++v) {
      std::vector<Impl::Setting> sets;
      for (const Override& ov : axis.overrides(v)) {
        YAML::Node value = parse_yaml_checked(ov.value, ov.key_path + "=" + ov.value);
        sets.push_back({split_key_path(ov.key_path), value, SceneTree::convert(value)});
      }
      values.push_back(std::move(sets));
    }
    impl_->axes.push_back(std::move(values));
  }
  count_ = spec.scenario_count();
}

ScenarioFactory::~ScenarioFactory() = default;
ScenarioFactory::ScenarioFactory(ScenarioFactory&&) noexcept = default;
ScenarioFactory& ScenarioFactory::operator=(ScenarioFactory&&) noexcept = default;

Scene ScenarioFactory::scene(std::size_t index, bool resolved_yaml) const {
  const std::string source = scenario_source_name(id(index));
  const std::optional<SceneTree> tree = impl_->scene_tree(index);
  Scene s = tree ? scene_from_tree(*tree, source, resolved_yaml)
                 : scene_from_yaml(impl_->tree(index), source, resolved_yaml);
  if (resolved_yaml) s.input_sha256 = impl_->input_sha256;
  return s;
}

std::string ScenarioFactory::yaml(std::size_t index) const {
  YAML::Emitter out;
  out << impl_->tree(index);
  return std::string(out.c_str()) + "\n";
}

std::string ScenarioFactory::id(std::size_t index) const { return scenario_id(impl_->spec, index); }

void SweepShapeCheck::add(const Scene& scene, const std::string& id) {
  const void* robot = scene.robot.urdf.get();
  if (!built_ || robot != last_robot_) {
    try {
      last_ = robot_shape(build_robot_model(scene.robot));
    } catch (const std::exception&) {  // the scenario's own run reports it
      return;
    }
    built_ = true;
    last_robot_ = robot;
  }
  add(last_, id);
}

void SweepShapeCheck::add(const RobotShape& robot, const std::string& id) {
  if (shape_.legs == 0) {
    shape_ = robot;
    first_id_ = id;
  } else if (!(robot == shape_)) {
    throw ConfigError(scenario_source_name(id) + ": robot: a robot of " + robot.text() +
                      ", the sweep's robot (" + scenario_source_name(first_id_) + ") has " +
                      shape_.text() +
                      "; the scenarios of a sweep have robots of one shape (legs and joints "
                      "per leg)");
  }
}

RobotShape sweep_robot_shape(const ScenarioFactory& factory) {
  SweepShapeCheck shapes;
  for (std::size_t i = 0; i < factory.scenario_count(); ++i) {
    std::optional<Scene> scene;
    try {
      scene.emplace(factory.scene(i, false));
    } catch (const std::exception&) {  // a row with status config
      continue;
    }
    shapes.add(*scene, factory.id(i));
  }
  return shapes.shape();
}

SweepScenarioCheck check_sweep_scenarios(const SweepSpec& spec) {
  SweepScenarioCheck check;
  check.scenarios = spec.scenario_count();
  const ScenarioFactory factory(spec);
  SweepShapeCheck shapes;
  // Every scenario is read, also one holding a value that failed on the base scene alone:
  // a cross-key rule (a ramp against the cruise time) may hold with another axis's value.
  for (std::size_t i = 0; i < check.scenarios; ++i) {
    std::optional<Scene> scene;
    try {
      scene.emplace(factory.scene(i, false));
    } catch (const std::exception& e) {  // as check_scenario: any failure is the row's
      if (check.out_of_range++ == 0) check.first = e.what();
      continue;
    }
    shapes.add(*scene, factory.id(i));
  }
  check.robot = shapes.shape();
  return check;
}

}  // namespace hexdyn
