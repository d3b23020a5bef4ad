#pragma once
/// \file result_layout.hpp
/// A run's `hexdyn-result/5` layout in memory: every dataset the file holds (path, units,
/// dims and values, in the element type of io/schema.hpp) and every /meta attribute, in
/// the order the file is written. The one source of what a result file contains: the HDF5
/// writer (output.hpp, write_result_layout) writes this list, and the Python module
/// (bindings/python/) hands the same arrays to numpy, so both see the same bytes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "hexdyn/core/result.hpp"
#include "hexdyn/io/schema.hpp"

namespace hexdyn {

/// The values of one dataset, row-major, in the element type stored in the file
/// (schema::Element: kFloat64, kInt8, kInt32, kString for a list of strings); a scalar
/// text dataset (Shape::kText) is a single std::string.
using LayoutValues = std::variant<std::vector<double>, std::vector<std::int8_t>,
                                  std::vector<std::int32_t>, std::vector<std::string>, std::string>;

/// One dataset: its contract entry (path and units, schema.hpp), its shape `dims`
/// (outermost first; {} a scalar) and its values (product of dims entries; one string for
/// a scalar text).
struct LayoutDataset {
  const schema::DatasetSpec* spec = nullptr;
  std::vector<std::size_t> dims;
  LayoutValues values;
};

/// One attribute of the file (the /meta group's): its contract entry and its value.
struct LayoutAttribute {
  const schema::AttributeSpec* spec = nullptr;
  std::variant<std::string, std::int64_t, double> value;
};

/// A whole result file in memory.
struct ResultLayout {
  std::vector<LayoutAttribute> attributes;  ///< /meta, then /terrain's, in the order written
  std::vector<LayoutDataset> datasets;      ///< /model, kinematics, dynamics, in the order written
  /// Appends the dataset of `spec` of shape `dims` ({} a scalar) holding `values`.
  void add(const schema::DatasetSpec& spec, std::vector<std::size_t> dims, LayoutValues values) {
    datasets.push_back(LayoutDataset{&spec, std::move(dims), std::move(values)});
  }
  /// Appends a scalar float64 dataset.
  void scalar(const schema::DatasetSpec& spec, double v) { add(spec, {}, std::vector<double>{v}); }
};

/// The layout of `result`: /meta (created_utc = now), /model, the labelled coordinates
/// (kResultCoordinates: /leg, /joint, /xyz, /wxyz), the kinematic datasets and,
/// when result.dyn.present, the dynamic ones and the index coordinates /impact and
/// /message (schema.hpp's kModelDatasets, kUrdfRobotDatasets when the robot came from a
/// URDF, kResultCoordinates, kKinematicDatasets, kSphereFootDatasets when result.sphere_feet,
/// kDynamicsDatasets, kResultIndexCoordinates). Copies the arrays.
///
/// The robot's L legs are /feet/position's columns / 3 and its J joints result.joint_names'
/// count (none: /joints/position's columns, legs of J / L joints named L1_coxa … or
/// L1_j1 …, core/common.hpp joint_name); /model/leg_names are L1 … L{L}.
///
/// Preconditions (checked; a mismatch throws IoError "PATH is RxC, expected ..." naming the
/// dataset): every kinematic array has result.kin.samples() = T rows and its dataset's
/// column count (T×3, T×4, T×L, T×J or T×3L), kin.sample_kind T entries or none (all
/// ordinary), terrain_z_m as many as terrain_y_m; when result.dyn.present, the dynamics
/// arrays have T rows (or T entries), energy_joint_J J entries, energy_cycle_J one per
/// cycle_start_s, every impact a leg index 0..L−1 (written as is, 0-based).
ResultLayout result_layout(const RunResult& result);

}  // namespace hexdyn
