#pragma once
/// \file scenario_factory.hpp
/// The scenes of a sweep's scenarios, made one at a time when a scenario starts: the
/// base scene tree (after `inherit:` and `set:`) is parsed once and each axis value
/// once; a scenario's scene is the tree with its values set, validated as by
/// scene_from_yaml (so cross-key constraints are checked per scenario, and a failure
/// is that scenario's row). The scenario's tree shares every map it does not change with
/// the base (config/scene_tree.hpp) instead of copying the base. Nothing is done per scenario
/// before the scenario runs.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "hexdyn/core/scene.hpp"
#include "hexdyn/sweep/scenario.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace hexdyn {

class ScenarioFactory {
 public:
  /// From a validated sweep (load_sweep) or one received from rank 0; throws
  /// ConfigError if its base tree or a value does not parse (cannot happen for a
  /// SweepSpec from load_sweep).
  explicit ScenarioFactory(const SweepSpec& spec);
  ~ScenarioFactory();
  ScenarioFactory(ScenarioFactory&&) noexcept;
  ScenarioFactory& operator=(ScenarioFactory&&) noexcept;

  std::size_t scenario_count() const { return count_; }
  /// The scene of scenario `index` < scenario_count(); its messages name
  /// "scenario <id>". Throws ConfigError (a value out of range, a cross-key constraint)
  /// like load_scene. With `resolved_yaml` false, Scene::resolved_yaml stays empty
  /// (needed only for a run that is kept: it becomes the run's /meta config_yaml).
  Scene scene(std::size_t index, bool resolved_yaml = true) const;
  /// The same scene as YAML text (unvalidated), as scenario_input gives it.
  std::string yaml(std::size_t index) const;
  /// Scenario id ("000012"), as scenario_id.
  std::string id(std::size_t index) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t count_ = 0;
};

/// The robots of a sweep's scenarios, checked to be of one shape (RobotShape): add each valid
/// scenario's scene in turn. A robot is built once for each URDF robot the scenes share (their
/// parsed description) and once for the robot of the YAML keys, whose keys do not change its
/// legs or joints.
class SweepShapeCheck {
 public:
  /// Throws ConfigError "scenario ID: a robot of 4 legs of 3 joints, the sweep's robot (of
  /// scenario ID0) has 6 legs of 3 joints; a sweep's robots have one shape ..." for a robot of
  /// another shape than the first scenario's. A robot that cannot be built is left to its
  /// scenario's row.
  void add(const Scene& scene, const std::string& id);
  /// The same for a robot of shape `robot` (built by the caller).
  void add(const RobotShape& robot, const std::string& id);
  /// The first scenario's robot shape (legs 0 when none was built).
  const RobotShape& shape() const { return shape_; }

 private:
  RobotShape shape_, last_;
  std::string first_id_;
  const void* last_robot_ = nullptr;  ///< the robot last built (its description; null: YAML)
  bool built_ = false;
};

/// What `hexdyn validate` (and Python's hexdyn.validate) reports of a sweep's scenarios.
struct SweepScenarioCheck {
  std::size_t scenarios = 0;     ///< the sweep's scenario count
  std::size_t out_of_range = 0;  ///< scenarios whose scene is not valid (rows with status config)
  std::string first;             ///< the first such scenario's message ("" when none)
  RobotShape robot;              ///< the scenarios' robot shape (SweepShapeCheck)
};

/// The robot shape of every valid scenario of `factory`'s sweep (SweepShapeCheck; throws its
/// ConfigError for a sweep of robots of other shapes).
RobotShape sweep_robot_shape(const ScenarioFactory& factory);

/// Validates every scenario's scene as the sweep will when the scenario starts
/// (ScenarioFactory::scene, without the resolved configuration): each axis value and
/// case is parsed once (the factory), and a scenario is the base tree with its values set,
/// sharing every map it does not change, so no YAML is parsed or written per scenario.
/// About 20–30 µs per scenario for the paper robot: a sweep of
/// kMaxScenarios answers in under 30 s on 2 cores (docs/user/faults.md#sizes). Also checks
/// the scenarios' robots are of one shape (SweepShapeCheck, whose ConfigError it throws).
SweepScenarioCheck check_sweep_scenarios(const SweepSpec& spec);

}  // namespace hexdyn
