#include "hexdyn/io/result_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

using schema::DatasetSpec;

std::size_t to_size(int n) { return static_cast<std::size_t>(n); }

class Builder {
 public:
  explicit Builder(ResultLayout& layout) : layout_(layout) {}

  void add(const DatasetSpec& spec, std::vector<std::size_t> dims, LayoutValues values) {
    layout_.datasets.push_back({&spec, std::move(dims), std::move(values)});
  }

  /// A rows × cols matrix as a dataset of shape `dims`, checked.
  template <class Matrix>
  void matrix(const DatasetSpec& spec, const Matrix& m, int rows, int cols,
              std::vector<std::size_t> dims) {
    if (m.rows() != rows || m.cols() != cols)
      throw IoError(std::string(spec.path) + " is " + std::to_string(m.rows()) + "x" +
                    std::to_string(m.cols()) + ", expected " + std::to_string(rows) + "x" +
                    std::to_string(cols));
    using Scalar = typename Matrix::Scalar;
    add(spec, std::move(dims), std::vector<Scalar>(m.data(), m.data() + m.size()));
  }

  void vector(const DatasetSpec& spec, const std::vector<double>& v, std::size_t expected) {
    if (v.size() != expected)
      throw IoError(std::string(spec.path) + " has " + std::to_string(v.size()) +
                    " entries, expected " + std::to_string(expected));
    add(spec, {v.size()}, v);
  }

  void scalar(const DatasetSpec& spec, double value) { add(spec, {}, std::vector<double>{value}); }

 private:
  ResultLayout& layout_;
};

void add_meta(ResultLayout& layout, const RunResult& r) {
  namespace s = schema;
  layout.attributes = {
      {&s::kMetaSchema, std::string(s::kResultSchema)},
      {&s::kMetaSchemaVersion, s::kResultSchemaVersion},
      {&s::kMetaVersion, std::string(kVersion)},
      {&s::kMetaGitCommit, std::string(kGitCommit)},
      {&s::kMetaCreatedUtc, utc_timestamp_now()},
      {&s::kMetaConfigYaml,
       r.posture.automatic && !r.config_yaml.empty()
           ? with_chosen_posture(r.config_yaml, r.posture.height_m, r.posture.foot_lateral_m)
           : r.config_yaml},
      {&s::kMetaWallTime, r.wall_time_s},
      {&s::kMetaInputSha256, r.input_sha256},
      {&s::kMetaGridTolerance, r.grid.tolerance},
      {&s::kMetaGridEnergyError, r.grid.energy_error},
      {&s::kMetaGridPeakError, r.grid.peak_error},
      {&s::kMetaEnergyRule,
       std::string(r.grid.cubic_energy ? s::kEnergyRuleCubic : s::kEnergyRuleTrapezoid)}};
}

/// The robot's counts in a result: its legs (/feet/position has three columns a leg) and
/// joints (its joint names, or /joints/position's columns when it has none).
struct RobotCounts {
  int legs = 0, joints = 0;
};
RobotCounts robot_counts(const RunResult& r) {
  const auto joints = r.joint_names.empty() ? static_cast<std::size_t>(r.kin.joint_position.cols())
                                            : r.joint_names.size();
  return {static_cast<int>(r.kin.foot_position.cols() / 3), static_cast<int>(joints)};
}

void add_model(Builder& b, const RunResult& r, RobotCounts n) {
  namespace s = schema;
  std::vector<std::string> joints = r.joint_names, legs;
  // Without the description's counts: legs of equal joint counts; without its names,
  // positional names.
  std::vector<std::int32_t> counts(r.leg_joint_counts.begin(), r.leg_joint_counts.end());
  if (counts.empty()) counts.assign(to_size(n.legs), n.legs > 0 ? n.joints / n.legs : 0);
  if (counts.size() != to_size(n.legs))
    throw IoError(std::string(s::kModelLegJointCounts.path) + " has " +
                  std::to_string(counts.size()) + " legs, expected " + std::to_string(n.legs));
  for (int leg = 0; leg < n.legs; ++leg) {
    legs.push_back(leg_name(leg));
    const int m = counts[to_size(leg)];
    if (r.joint_names.empty())
      for (int j = 0; j < m; ++j) joints.push_back(joint_name(leg, j, m));
  }
  if (joints.size() != to_size(n.joints) ||
      std::accumulate(counts.begin(), counts.end(), 0) != n.joints)
    throw IoError(std::string(s::kModelJointNames.path) + " has " + std::to_string(joints.size()) +
                  " names and " + s::kModelLegJointCounts.path + " sums to " +
                  std::to_string(std::accumulate(counts.begin(), counts.end(), 0)) + ", expected " +
                  std::to_string(n.joints));
  if (!r.leg_mapping.empty()) b.add(s::kModelLegMapping, {r.leg_mapping.size()}, r.leg_mapping);
  b.add(s::kModelUrdf, {}, r.urdf);
  b.add(s::kModelJointNames, {joints.size()}, joints);
  b.add(s::kModelLegNames, {legs.size()}, legs);
  b.add(s::kModelLegJointCounts, {counts.size()}, counts);
  b.scalar(s::kModelTotalMass, r.total_mass_kg);
}

/// The labelled coordinate variables (schema::kResultCoordinates): leg and joint names,
/// component labels.
void add_coordinates(Builder& b, const ResultLayout& layout) {
  namespace s = schema;
  std::vector<LayoutDataset> names;  // copied: adding to layout.datasets moves it
  for (const LayoutDataset& d : layout.datasets)
    if (d.spec == &s::kModelLegNames || d.spec == &s::kModelJointNames) names.push_back(d);
  for (LayoutDataset& d : names)
    b.add(d.spec == &s::kModelLegNames ? s::kLegCoordinate : s::kJointCoordinate, d.dims,
          std::move(d.values));
  b.add(s::kXyzCoordinate, {3}, std::vector<std::string>{"x", "y", "z"});
  b.add(s::kWxyzCoordinate, {4}, std::vector<std::string>{"w", "x", "y", "z"});
}

void add_kinematics(Builder& b, const KinematicsResult& k, bool sphere_feet, RobotCounts n) {
  namespace s = schema;
  const int T = k.samples();
  const std::size_t t = to_size(T);
  const int J = n.joints, L = n.legs;
  const std::size_t j = to_size(J), l = to_size(L);
  b.vector(s::kTime, k.time_s, t);
  b.matrix(s::kBasePosition, k.base_position, T, 3, {t, 3});
  b.matrix(s::kBaseOrientation, k.base_orientation_wxyz, T, 4, {t, 4});
  b.matrix(s::kBaseLinearVelocity, k.base_linear_velocity, T, 3, {t, 3});
  b.matrix(s::kBaseAngularVelocity, k.base_angular_velocity, T, 3, {t, 3});
  b.matrix(s::kBaseLinearAcceleration, k.base_linear_acceleration, T, 3, {t, 3});
  b.matrix(s::kBaseAngularAcceleration, k.base_angular_acceleration, T, 3, {t, 3});
  b.matrix(s::kJointPosition, k.joint_position, T, J, {t, j});
  b.matrix(s::kJointVelocity, k.joint_velocity, T, J, {t, j});
  b.matrix(s::kJointAcceleration, k.joint_acceleration, T, J, {t, j});
  b.matrix(s::kFeetPosition, k.foot_position, T, 3 * L, {t, l, 3});
  b.matrix(s::kFeetVelocity, k.foot_velocity, T, 3 * L, {t, l, 3});
  if (sphere_feet) b.matrix(s::kFeetCenter, k.foot_center, T, 3 * L, {t, l, 3});
  b.matrix(s::kComPosition, k.com_position, T, 3, {t, 3});
  b.matrix(s::kContactPhase, k.contact_phase, T, L, {t, l});
  if (!k.sample_kind.empty() && k.sample_kind.size() != t)
    throw IoError(std::string(s::kSampleKind.path) + " has " +
                  std::to_string(k.sample_kind.size()) + " entries, expected " + std::to_string(t));
  b.add(s::kSampleKind, {t},
        k.sample_kind.empty() ? std::vector<std::int8_t>(t, 0) : k.sample_kind);
}

/// /gait/cycle_start and /terrain (docs/theory/output-grid.md#event-samples).
void add_gait_and_terrain(ResultLayout& layout, Builder& b, const RunResult& r) {
  namespace s = schema;
  b.vector(s::kGaitCycleStart, r.cycle_start_s, r.cycle_start_s.size());
  b.vector(s::kTerrainY, r.terrain_y_m, r.terrain_y_m.size());
  b.vector(s::kTerrainZ, r.terrain_z_m, r.terrain_y_m.size());
  layout.attributes.push_back({&s::kTerrainType, r.terrain_type});
  if (const HeightMap* m = r.terrain_map.get()) {
    const auto nx = static_cast<std::size_t>(m->nx), ny = static_cast<std::size_t>(m->ny);
    std::vector<double> x(nx), y(ny);
    for (std::size_t j = 0; j < nx; ++j) x[j] = m->x(static_cast<int>(j));
    for (std::size_t i = 0; i < ny; ++i) y[i] = m->y(static_cast<int>(i));
    b.add(s::kTerrainMapX, {nx}, std::move(x));
    b.add(s::kTerrainMapY, {ny}, std::move(y));
    b.add(s::kTerrainMapZ, {ny, nx}, m->z_m);
    for (const auto& [coordinate, size] :
         {std::pair{&s::kMapXCoordinate, nx}, std::pair{&s::kMapYCoordinate, ny}}) {
      std::vector<std::int32_t> index(size);
      for (std::size_t i = 0; i < size; ++i) index[i] = static_cast<std::int32_t>(i);
      b.add(*coordinate, {size}, std::move(index));
    }
  }
  // The index coordinates of the dimensions `gait_cycle` and `terrain_point` (io/labels.hpp).
  for (const auto& [coordinate, size] :
       {std::pair{&s::kCycleCoordinate, r.cycle_start_s.size()},
        std::pair{&s::kTerrainPointCoordinate, r.terrain_y_m.size()}}) {
    std::vector<std::int32_t> index(size);
    for (std::size_t i = 0; i < size; ++i) index[i] = static_cast<std::int32_t>(i);
    b.add(*coordinate, {size}, std::move(index));
  }
}

/// The thermal model's datasets (schema.hpp kThermalDatasets).
void add_thermal(Builder& b, const ElectricalResult& e, int T, int J) {
  namespace s = schema;
  const std::size_t t = to_size(T), j = to_size(J);
  b.matrix(s::kWindingTemperature, e.winding_temperature_degC, T, J, {t, j});
  b.matrix(s::kHousingTemperature, e.housing_temperature_degC, T, J, {t, j});
  b.vector(s::kPeakWindingTemperature, e.peak_winding_temperature_degC, j);
  b.vector(s::kTimeToWindingLimit, e.time_to_limit_s, j);
  if (e.limit_reached.size() != j)
    throw IoError(std::string(s::kWindingLimitReached.path) + " has " +
                  std::to_string(e.limit_reached.size()) + " entries, expected " +
                  std::to_string(j));
  b.add(s::kWindingLimitReached, {j}, e.limit_reached);
  double peak = -kInfinity, first = kInfinity;
  for (std::size_t k = 0; k < j; ++k) {
    if (!std::isnan(e.peak_winding_temperature_degC[k]))
      peak = std::max(peak, e.peak_winding_temperature_degC[k]);
    if (!std::isnan(e.time_to_limit_s[k])) first = std::min(first, e.time_to_limit_s[k]);
  }
  b.scalar(s::kThermalPeak, peak);
  b.scalar(s::kThermalFirstLimit, first);
}

/// The drive train's datasets (schema.hpp kDriveTrainDatasets), for a scene with actuators.
void add_drive_train(Builder& b, const DynamicsResult& d, int T, int J) {
  namespace s = schema;
  const std::size_t t = to_size(T), j = to_size(J);
  const ElectricalResult& e = d.electrical;
  b.matrix(s::kDriveTorque, d.drive_torque, T, J, {t, j});
  b.matrix(s::kDriveTorqueLimit, d.drive_torque_limit, T, J, {t, j});
  b.matrix(s::kDriveTorqueLowerLimit, d.drive_torque_lower_limit, T, J, {t, j});
  b.matrix(s::kMotorCurrent, e.current_A, T, J, {t, j});
  b.vector(s::kDriveTorqueRms, e.rms_torque_Nm, j);
  b.vector(s::kDriveTorqueWindowRms, e.window_rms_torque_Nm, j);
  b.matrix(s::kElectricalPower, e.power_W, T, J, {t, j});
  b.vector(s::kElectricalTotalPower, e.total_power_W, t);
  b.scalar(s::kEnergyElectrical, e.energy_J);
  b.vector(s::kEnergyElectricalJoint, e.energy_joint_J, j);
  b.scalar(s::kEnergyCopperLoss, e.copper_loss_J);
  b.scalar(s::kEnergyFrictionLoss, e.friction_loss_J);
  b.scalar(s::kEnergyRegenerated, e.regenerated_J);
  b.scalar(s::kCostOfTransportElectrical, e.cost_of_transport);
  if (e.has_thermal()) add_thermal(b, e, T, J);
}

void add_dynamics(Builder& b, const DynamicsResult& d, int T, std::size_t cycles, RobotCounts c) {
  namespace s = schema;
  const int J = c.joints, L = c.legs;
  const std::size_t t = to_size(T), j = to_size(J), l = to_size(L);
  b.matrix(s::kJointTorque, d.joint_torque, T, J, {t, j});
  b.matrix(s::kContactForce, d.contact_force, T, 3 * L, {t, l, 3});
  b.matrix(s::kContactPenetration, d.penetration, T, L, {t, l});
  b.matrix(s::kContactUtilizedFriction, d.utilized_friction, T, L, {t, l});
  b.matrix(s::kContactSlip, d.slip, T, L, {t, l});
  if (!d.required_friction.empty()) {
    b.vector(s::kRequiredFriction, d.required_friction, t);
    if (d.required_friction_leg.size() != t)
      throw IoError(std::string(s::kRequiredFrictionLeg.path) + " has " +
                    std::to_string(d.required_friction_leg.size()) + " entries, expected " +
                    std::to_string(t));
    b.add(s::kRequiredFrictionLeg, {t}, d.required_friction_leg);
  }

  const std::size_t n = d.impacts.size();
  std::vector<std::int32_t> leg(n);
  std::vector<double> start(n), duration(n), peak(n), impulse(n), mass(n), speed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ImpactRecord& im = d.impacts[i];
    if (im.leg < 0 || im.leg >= L)
      throw IoError("impact " + std::to_string(i) + " has leg index " + std::to_string(im.leg) +
                    ", expected 0.." + std::to_string(L - 1));
    leg[i] = im.leg;
    start[i] = im.t_start_s;
    duration[i] = im.duration_s;
    peak[i] = im.peak_force_N;
    impulse[i] = im.impulse_Ns;
    mass[i] = im.effective_mass_kg;
    speed[i] = im.approach_speed_mps;
  }
  b.add(s::kImpactLeg, {n}, std::move(leg));
  b.vector(s::kImpactStart, start, n);
  b.vector(s::kImpactDuration, duration, n);
  b.vector(s::kImpactPeakForce, peak, n);
  b.vector(s::kImpactImpulse, impulse, n);
  b.vector(s::kImpactEffectiveMass, mass, n);
  b.vector(s::kImpactApproachSpeed, speed, n);

  b.matrix(s::kJointPower, d.joint_power, T, J, {t, j});
  b.vector(s::kTotalPower, d.total_power_W, t);
  b.scalar(s::kEnergyTotal, d.energy_total_J);
  b.vector(s::kEnergyJoint, d.energy_joint_J, j);
  b.vector(s::kEnergyCycle, d.energy_cycle_J, cycles);
  b.scalar(s::kEnergyPositiveWork, d.positive_work_J);
  b.scalar(s::kEnergyNegativeWork, d.negative_work_J);
  b.vector(s::kEnergyPositiveWorkJoint, d.positive_work_joint_J, j);
  b.vector(s::kEnergyNegativeWorkJoint, d.negative_work_joint_J, j);
  b.scalar(s::kCostOfTransport, d.cost_of_transport);
  b.scalar(s::kEnergyDistance, d.distance_m);

  if (d.solver_status.size() != t)
    throw IoError(std::string(s::kSolverStatus.path) + " has " +
                  std::to_string(d.solver_status.size()) + " entries, expected " +
                  std::to_string(t));
  b.add(s::kSolverStatus, {t}, solver_status_codes(d.solver_status));
  b.vector(s::kSolverIterations, d.solver_iterations, t);
  b.vector(s::kSolverObjective, d.solver_objective, t);
  b.vector(s::kSolverSeconds, d.solver_seconds, t);
  b.add(s::kSolverMessages, {d.solver_messages.size()}, d.solver_messages);
  if (d.has_drive()) add_drive_train(b, d, T, J);
  // The index coordinates of the dimensions `impact` and `message` (io/labels.hpp).
  for (const auto& [coordinate, size] :
       {std::pair{&s::kImpactCoordinate, n},
        std::pair{&s::kMessageCoordinate, d.solver_messages.size()}}) {
    std::vector<std::int32_t> index(size);
    for (std::size_t i = 0; i < size; ++i) index[i] = static_cast<std::int32_t>(i);
    b.add(*coordinate, {size}, std::move(index));
  }
}

}  // namespace

ResultLayout result_layout(const RunResult& result) {
  ResultLayout layout;
  Builder b(layout);
  const RobotCounts counts = robot_counts(result);
  add_meta(layout, result);
  add_model(b, result, counts);
  add_coordinates(b, layout);
  add_kinematics(b, result.kin, result.sphere_feet, counts);
  add_gait_and_terrain(layout, b, result);
  if (result.dyn.present)
    add_dynamics(b, result.dyn, result.kin.samples(), result.cycle_start_s.size(), counts);
  return layout;
}

}  // namespace hexdyn
