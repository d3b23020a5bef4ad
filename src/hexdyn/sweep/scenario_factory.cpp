#include "hexdyn/sweep/scenario_factory.hpp"

#include <yaml-cpp/yaml.h>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/config.hpp"
#include "hexdyn/io/yaml_load.hpp"

namespace hexdyn {

struct ScenarioFactory::Impl {
  SweepSpec spec;            ///< axes and id width
  std::string input_sha256;  ///< the sweep's inputs: a kept run's /meta input_sha256
  YAML::Node base;
  struct Axis {
    std::vector<std::string> keys;
    std::vector<YAML::Node> values;  ///< parsed once
  };
  std::vector<Axis> axes;

  YAML::Node tree(std::size_t index) const {
    YAML::Node root = YAML::Clone(base);
    const auto p = grid_point(spec, index);
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const Axis& ax = axes[a];
      // As apply_override: intermediate maps are created where absent (load_sweep has
      // checked that every axis key is a single value of the base scene).
      YAML::Node cur = root;
      for (std::size_t k = 0; k + 1 < ax.keys.size(); ++k) {
        YAML::Node next = cur[ax.keys[k]];
        if (!next.IsDefined() || next.IsNull()) {
          cur[ax.keys[k]] = YAML::Node(YAML::NodeType::Map);
          next.reset(cur[ax.keys[k]]);
        }
        cur.reset(next);
      }
      cur[ax.keys.back()] = YAML::Clone(ax.values[p[a]]);
    }
    return root;
  }
};

ScenarioFactory::ScenarioFactory(const SweepSpec& spec) : impl_(std::make_unique<Impl>()) {
  impl_->spec.axes = spec.axes;
  impl_->input_sha256 = input_sha256_text(spec.inputs);
  impl_->base = parse_yaml_text(spec.base_tree_yaml, spec.base_path);
  for (const SweepAxis& axis : spec.axes) {
    Impl::Axis ax;
    ax.keys = split_key_path(axis.key);
    for (const std::string& v : axis.values)
      ax.values.push_back(parse_yaml_checked(v, axis.key + "=" + v));
    impl_->axes.push_back(std::move(ax));
  }
  count_ = spec.scenario_count();
}

ScenarioFactory::~ScenarioFactory() = default;
ScenarioFactory::ScenarioFactory(ScenarioFactory&&) noexcept = default;
ScenarioFactory& ScenarioFactory::operator=(ScenarioFactory&&) noexcept = default;

Scene ScenarioFactory::scene(std::size_t index, bool resolved_yaml) const {
  Scene s = scene_from_yaml(impl_->tree(index), scenario_source_name(id(index)), resolved_yaml);
  if (resolved_yaml) s.input_sha256 = impl_->input_sha256;
  return s;
}

std::string ScenarioFactory::yaml(std::size_t index) const {
  YAML::Emitter out;
  out << impl_->tree(index);
  return std::string(out.c_str()) + "\n";
}

std::string ScenarioFactory::id(std::size_t index) const { return scenario_id(impl_->spec, index); }

}  // namespace hexdyn
