// hexdyn-result/5 writer: every dataset of the contract read back through the h5io
// readers with its shape, units and exact values; atomic replacement on failure.
//
// Setting HEXDYN_TEST_FIXTURE_DIR=<dir> keeps a copy of the synthetic result
// (kinematically consistent: feet and COM from the model's FK, URDF of the model) as
// <dir>/synthetic_result.h5, for exercising analysis/check_result.py.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/model/urdf.hpp"
#include "hexdyn/sample_models.hpp"
#include "hexdyn/version.hpp"

namespace {

namespace fs = std::filesystem;
using namespace hexdyn;

/// A fresh directory removed with its contents at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("hexdyn_test_output_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

RowMatrix random_matrix(std::mt19937& rng, int rows, int cols) {
  std::normal_distribution<double> n(0.0, 3.0);
  RowMatrix m(rows, cols);
  for (int i = 0; i < m.size(); ++i) m.data()[i] = n(rng);
  return m;
}

std::vector<double> random_vector(std::mt19937& rng, std::size_t size) {
  std::normal_distribution<double> n(0.0, 3.0);
  std::vector<double> v(size);
  for (double& x : v) x = n(rng);
  return v;
}

const char* kConfigYaml =
    "name: synthetic\n"
    "terrain:\n"
    "  type: stairs\n"
    "  ground_height: 0.0\n"
    "  riser_height: 0.05\n"
    "  tread_depth: 0.25\n"
    "  steps: 3\n"
    "  first_riser_y: 0.55\n";

/// Random but kinematically consistent result of T samples on the paper robot.
RunResult make_result(int T, bool dynamics, int impacts, int messages, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const RobotModel model = build_robot_model(test::paper_robot_params());
  RunResult r;
  r.config_yaml = kConfigYaml;
  r.urdf = robot_urdf(model, "hexapod");
  r.total_mass_kg = model.total_mass_kg;
  r.wall_time_s = 1.25;
  const int J = model.joints(), L = model.legs();
  KinematicsResult& k = r.kin;
  k.time_s.resize(T);
  k.base_position.resize(T, 3);
  k.base_orientation_wxyz.resize(T, 4);
  k.joint_position.resize(T, J);
  k.foot_position.resize(T, 3 * L);
  k.com_position.resize(T, 3);
  k.contact_phase.resize(T, L);
  for (int t = 0; t < T; ++t) {
    k.time_s[t] = 0.05 * t;
    const Vec3 p(0.01 * u(rng), 0.412 + 0.1 * t, 0.235 + 0.01 * u(rng));
    const Quat q = Quat(Eigen::AngleAxisd(0.2 + 0.05 * u(rng), Vec3::UnitX())) *
                   Quat(Eigen::AngleAxisd(0.1 * u(rng), Vec3::UnitY()));
    const Mat3 W_R_B = q.toRotationMatrix();
    JointVector joints(J);
    for (int leg = 0; leg < L; ++leg)
      joints.segment<3>(model.joint(leg, 0)) = test::random_leg_angles(rng);
    BodyPoses poses;
    forward_kinematics_tree(model, joints, poses);
    k.base_position.row(t) = p.transpose();
    k.base_orientation_wxyz.row(t) << q.w(), q.x(), q.y(), q.z();
    k.joint_position.row(t) = joints.transpose();
    for (int leg = 0; leg < L; ++leg)
      k.foot_position.block<1, 3>(t, 3 * leg) =
          (p + W_R_B * tree_foot_position_B(model, poses, leg)).transpose();
    k.com_position.row(t) = (p + W_R_B * center_of_mass_B(model, poses)).transpose();
    for (int leg = 0; leg < L; ++leg)
      k.contact_phase(t, leg) = static_cast<std::int8_t>((t + leg) % 3);
  }
  k.base_linear_velocity = random_matrix(rng, T, 3);
  k.base_angular_velocity = random_matrix(rng, T, 3);
  k.base_linear_acceleration = random_matrix(rng, T, 3);
  k.base_angular_acceleration = random_matrix(rng, T, 3);
  k.joint_velocity = random_matrix(rng, T, J);
  k.joint_acceleration = random_matrix(rng, T, J);
  k.foot_velocity = random_matrix(rng, T, 3 * L);
  k.sample_kind.assign(T, 0);
  for (int t = 1; t < T; t += 3) k.sample_kind[t] = 1;
  r.cycle_start_s = {0.0, 0.05 * T / 3.0, 0.1 * T / 3.0};  // kCycles
  r.terrain_y_m = {-0.25, 0.0, 0.0, 1.0};                  // kTerrainPoints
  r.terrain_z_m = {0.0, 0.0, 0.05, 0.05};
  r.terrain_type = "stairs";

  DynamicsResult& d = r.dyn;
  d.present = dynamics;
  if (!dynamics) return r;
  d.joint_torque = random_matrix(rng, T, J);
  d.contact_force = random_matrix(rng, T, 3 * L);
  d.penetration = random_matrix(rng, T, L);
  d.utilized_friction = random_matrix(rng, T, L);
  d.slip = RowMatrixI8::Zero(T, L);
  for (int t = 0; t < T; t += 2) d.slip(t, t % L) = 1;
  d.required_friction = random_vector(rng, T);
  for (int t = 0; t < T; ++t)
    d.required_friction_leg.push_back(static_cast<std::int8_t>(t % 7 - 1));
  for (int i = 0; i < impacts; ++i) {
    ImpactRecord im;
    im.leg = i % L;
    im.t_start_s = 0.1 * i + 0.01;
    im.duration_s = 0.003 + 1e-4 * i;
    im.peak_force_N = 20.0 + i;
    im.impulse_Ns = 0.05 * (i + 1);
    im.effective_mass_kg = 0.4 + 0.01 * i;
    im.approach_speed_mps = 0.05;
    d.impacts.push_back(im);
  }
  d.joint_power = random_matrix(rng, T, J);
  d.total_power_W = random_vector(rng, T);
  d.energy_total_J = 12.5;
  d.energy_joint_J = random_vector(rng, J);
  d.positive_work_joint_J = random_vector(rng, J);
  d.negative_work_joint_J = random_vector(rng, J);
  d.positive_work_J = 9.5;
  d.negative_work_J = -3.0;
  d.energy_cycle_J = random_vector(rng, 3);
  d.distance_m = 0.75;
  d.cost_of_transport = 0.253;
  for (int t = 0; t < T; ++t) d.solver_status.push_back(static_cast<SolverStatus>(t % 3));
  d.solver_iterations = random_vector(rng, T);
  d.solver_objective = random_vector(rng, T);
  d.solver_seconds = random_vector(rng, T);
  for (int m = 0; m < messages; ++m)
    d.solver_messages.push_back("t=" + std::to_string(0.05 * m) + " s: friction cone relaxed (µ)");
  return r;
}

std::vector<std::size_t> expected_dims(schema::Shape shape, std::size_t T, std::size_t n,
                                       std::size_t m) {
  using schema::Shape;
  switch (shape) {
    case Shape::kScalar:
    case Shape::kText:
      return {};
    case Shape::kTextList:
      return {m};
    case Shape::kJointNames:
    case Shape::kJ:
      return {18};
    case Shape::kLegNames:
    case Shape::kLegValues:
      return {6};
    case Shape::kT:
      return {T};
    case Shape::kT3:
      return {T, 3};
    case Shape::kT4:
      return {T, 4};
    case Shape::kTLeg:
      return {T, 6};
    case Shape::kTJoint:
      return {T, 18};
    case Shape::kTLegXyz:
      return {T, 6, 3};
    case Shape::kN:
      return {n};
    case Shape::kXyz:
    case Shape::kVector3:
      return {3};
    case Shape::kWxyz:
      return {4};
    case Shape::kAxes:
    case Shape::kCycles3:
    case Shape::kMapColumns:
    case Shape::kMapRows:
    case Shape::kMapGrid:
      break;  // not in this synthetic result (no height map)
    case Shape::kScenarios:
    case Shape::kScenarioAxes:
    case Shape::kScenarioJoints:
    case Shape::kAxisValues:
    case Shape::kCaseKeys:
    case Shape::kCaseValues:
      break;  // shapes of the sweep file, never of a result dataset
    case Shape::kEnvelopeTreads:
    case Shape::kEnvelopeDuties:
    case Shape::kEnvelopeSpeeds:
    case Shape::kEnvelopeCriteria:
    case Shape::kEnvelopeCells:
    case Shape::kEnvelopeGrid:
    case Shape::kEnvelopeProbes:
    case Shape::kEnvelopeCases:
    case Shape::kEnvelopeCaseKeys:
    case Shape::kEnvelopeCaseValues:
    case Shape::kEnvelopeCaseCells:
    case Shape::kEnvelopeCaseGrid:
    case Shape::kEnvelopeRisers:
    case Shape::kEnvelopeMuGrid:
    case Shape::kEnvelopeCaseMuGrid:
      break;  // shapes of the envelope file
    case Shape::kRobustReplays:
    case Shape::kRobustReplaySteps:
    case Shape::kRobustReplayLinks:
    case Shape::kRobustReplayJoints:
    case Shape::kRobustReplayXyz:
    case Shape::kRobustSteps:
    case Shape::kRobustLinks:
    case Shape::kRobustClasses:
    case Shape::kRobustPerturbations:
      break;  // shapes of the robustness file
    case Shape::kCycles:
      return {3};  // make_result's cycles
    case Shape::kTerrainPoints:
      return {4};  // make_result's terrain profile
  }
  return {};
}

const char* element_name(schema::Element e) {
  switch (e) {
    case schema::Element::kFloat64:
      return "float64";
    case schema::Element::kInt8:
      return "int8";
    case schema::Element::kInt32:
      return "int32";
    case schema::Element::kInt64:
      return "int64";
    case schema::Element::kString:
      return "string";
  }
  return "?";
}

template <std::size_t N>
void check_specs(const H5Reader& in, const std::array<schema::DatasetSpec, N>& specs, std::size_t T,
                 std::size_t n, std::size_t m) {
  for (const schema::DatasetSpec& spec : specs) {
    INFO(spec.path);
    REQUIRE(in.is_dataset(spec.path));
    CHECK(in.dims(spec.path) == expected_dims(spec.shape, T, n, m));
    CHECK(in.element_type(spec.path) == element_name(spec.element));
    if (*spec.units == '\0') {  // text and flags: no units
      CHECK_FALSE(in.has_attribute(spec.path, schema::kUnitsAttribute));
    } else {
      REQUIRE(in.has_attribute(spec.path, schema::kUnitsAttribute));
      CHECK(in.string_attribute(spec.path, schema::kUnitsAttribute) == spec.units);
    }
    REQUIRE(in.has_attribute(spec.path, schema::kLongNameAttribute));
    CHECK(in.string_attribute(spec.path, schema::kLongNameAttribute) == spec.long_name);
    // Every dataset with axes is labelled: a dimension scale, or one attached per axis.
    if (!expected_dims(spec.shape, T, n, m).empty())
      CHECK(
          (in.has_attribute(spec.path, "DIMENSION_LIST") || in.has_attribute(spec.path, "CLASS")));
  }
}

void check_values(const H5Reader& in, const std::string& path, const RowMatrix& m) {
  INFO(path);
  const H5DoubleArray a = in.read_doubles(path);
  REQUIRE(a.values.size() == static_cast<std::size_t>(m.size()));
  CHECK(std::equal(a.values.begin(), a.values.end(), m.data()));
}

void check_values(const H5Reader& in, const std::string& path, const std::vector<double>& v) {
  INFO(path);
  CHECK(in.read_doubles(path).values == v);
}

std::string file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

std::vector<std::string> directory_entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void check_kinematics(const H5Reader& in, const RunResult& r) {
  namespace s = schema;
  const KinematicsResult& k = r.kin;
  check_values(in, s::kTime.path, k.time_s);
  check_values(in, s::kBasePosition.path, k.base_position);
  check_values(in, s::kBaseOrientation.path, k.base_orientation_wxyz);
  check_values(in, s::kBaseLinearVelocity.path, k.base_linear_velocity);
  check_values(in, s::kBaseAngularVelocity.path, k.base_angular_velocity);
  check_values(in, s::kBaseLinearAcceleration.path, k.base_linear_acceleration);
  check_values(in, s::kBaseAngularAcceleration.path, k.base_angular_acceleration);
  check_values(in, s::kJointPosition.path, k.joint_position);
  check_values(in, s::kJointVelocity.path, k.joint_velocity);
  check_values(in, s::kJointAcceleration.path, k.joint_acceleration);
  check_values(in, s::kFeetPosition.path, k.foot_position);
  check_values(in, s::kFeetVelocity.path, k.foot_velocity);
  check_values(in, s::kComPosition.path, k.com_position);
  const std::vector<std::int64_t> phase = in.read_ints(s::kContactPhase.path);
  REQUIRE(phase.size() == static_cast<std::size_t>(k.contact_phase.size()));
  for (std::size_t i = 0; i < phase.size(); ++i) CHECK(phase[i] == k.contact_phase.data()[i]);
  const std::vector<std::int64_t> kind = in.read_ints(s::kSampleKind.path);
  CHECK(kind == std::vector<std::int64_t>(k.sample_kind.begin(), k.sample_kind.end()));
  check_values(in, s::kGaitCycleStart.path, r.cycle_start_s);
  check_values(in, s::kTerrainY.path, r.terrain_y_m);
  check_values(in, s::kTerrainZ.path, r.terrain_z_m);
  CHECK(in.string_attribute(s::kTerrainGroup, s::kTerrainType.name) == r.terrain_type);
  // (T,6,3) layout: [t][leg][axis] is column 3 leg + axis of the T×18 matrix.
  const H5DoubleArray feet = in.read_doubles(s::kFeetPosition.path);
  CHECK(feet.values[(1 * 6 + 4) * 3 + 2] == k.foot_position(1, 3 * 4 + 2));
}

}  // namespace

TEST_CASE("output: every dataset of the contract round-trips (dynamics present)", "[output]") {
  TempDir dir;
  const std::string path = dir.file("run.h5");
  const int T = 7;
  const RunResult r = make_result(T, true, 4, 2);
  write_result_file(path, r);
  CHECK(directory_entries(dir.path) == std::vector<std::string>{"run.h5"});
  if (const char* keep = std::getenv("HEXDYN_TEST_FIXTURE_DIR"))
    fs::copy_file(path, fs::path(keep) / "synthetic_result.h5",
                  fs::copy_options::overwrite_existing);

  const H5Reader in(path);
  check_specs(in, schema::kModelDatasets, T, 4, 2);
  check_specs(in, schema::kKinematicDatasets, T, 4, 2);
  check_specs(in, schema::kDynamicsDatasets, T, 4, 2);
  check_specs(in, schema::kResultCoordinates, T, 4, 2);

  namespace s = schema;
  const std::string meta = s::kMetaGroup;
  REQUIRE(in.is_group(meta));
  CHECK(in.string_attribute(meta, s::kAttrSchema) == "hexdyn-result/5");
  CHECK(in.int_attribute(meta, s::kAttrSchemaVersion) == 5);
  CHECK(in.string_attribute(meta, s::kAttrVersion) == kVersion);
  CHECK(in.string_attribute(meta, s::kAttrGitCommit) == kGitCommit);
  CHECK(in.string_attribute(meta, s::kAttrConfigYaml) == r.config_yaml);
  CHECK(in.double_attribute(meta, s::kAttrWallTime) == r.wall_time_s);
  const std::string created = in.string_attribute(meta, s::kAttrCreatedUtc);
  CHECK(created.size() == 20);
  CHECK(created[4] == '-');
  CHECK(created[10] == 'T');
  CHECK(created.back() == 'Z');

  CHECK(in.read_string(s::kModelUrdf.path) == r.urdf);
  const std::vector<std::string> joints = in.read_strings(s::kModelJointNames.path);
  REQUIRE(joints.size() == 18);
  CHECK(joints.front() == "L1_coxa");
  CHECK(joints[4] == "L2_femur");
  CHECK(joints.back() == "L6_tibia");
  CHECK(in.read_strings(s::kModelLegNames.path) ==
        std::vector<std::string>{"L1", "L2", "L3", "L4", "L5", "L6"});
  CHECK(in.read_ints(s::kModelLegJointCounts.path) == std::vector<std::int64_t>(6, 3));
  CHECK(in.read_doubles(s::kModelTotalMass.path).values == std::vector<double>{r.total_mass_kg});

  check_kinematics(in, r);
  const DynamicsResult& d = r.dyn;
  check_values(in, s::kJointTorque.path, d.joint_torque);
  check_values(in, s::kContactForce.path, d.contact_force);
  check_values(in, s::kContactPenetration.path, d.penetration);
  check_values(in, s::kContactUtilizedFriction.path, d.utilized_friction);
  check_values(in, s::kRequiredFriction.path, d.required_friction);
  CHECK(in.string_attribute(s::kContactSlip.path, "flag_meanings") == "holds slips");
  std::vector<std::int64_t> slip, binding;
  for (Eigen::Index i = 0; i < d.slip.size(); ++i) slip.push_back(d.slip.data()[i]);
  for (const std::int8_t leg : d.required_friction_leg) binding.push_back(leg);
  CHECK(in.read_ints(s::kContactSlip.path) == slip);
  CHECK(in.read_ints(s::kRequiredFrictionLeg.path) == binding);
  std::vector<std::int64_t> legs;  // 0-based, as the records
  for (const ImpactRecord& im : d.impacts) legs.push_back(im.leg);
  CHECK(in.read_ints(s::kImpactLeg.path) == legs);
  CHECK(legs == std::vector<std::int64_t>{0, 1, 2, 3});
  CHECK(in.string_attribute(s::kContactPhase.path, "flag_meanings") == "swing impact support");
  CHECK(in.read_strings(s::kJointCoordinate.path) == joints);
  std::vector<double> start, duration, peak, impulse, mass, speed;
  for (const ImpactRecord& im : d.impacts) {
    start.push_back(im.t_start_s);
    duration.push_back(im.duration_s);
    peak.push_back(im.peak_force_N);
    impulse.push_back(im.impulse_Ns);
    mass.push_back(im.effective_mass_kg);
    speed.push_back(im.approach_speed_mps);
  }
  check_values(in, s::kImpactStart.path, start);
  check_values(in, s::kImpactDuration.path, duration);
  check_values(in, s::kImpactPeakForce.path, peak);
  check_values(in, s::kImpactImpulse.path, impulse);
  check_values(in, s::kImpactEffectiveMass.path, mass);
  check_values(in, s::kImpactApproachSpeed.path, speed);
  check_values(in, s::kJointPower.path, d.joint_power);
  check_values(in, s::kTotalPower.path, d.total_power_W);
  check_values(in, s::kEnergyTotal.path, std::vector<double>{d.energy_total_J});
  check_values(in, s::kEnergyJoint.path, d.energy_joint_J);
  check_values(in, s::kEnergyPositiveWork.path, std::vector<double>{d.positive_work_J});
  check_values(in, s::kEnergyNegativeWork.path, std::vector<double>{d.negative_work_J});
  check_values(in, s::kEnergyPositiveWorkJoint.path, d.positive_work_joint_J);
  check_values(in, s::kEnergyNegativeWorkJoint.path, d.negative_work_joint_J);
  check_values(in, s::kCostOfTransport.path, std::vector<double>{d.cost_of_transport});
  check_values(in, s::kEnergyDistance.path, std::vector<double>{d.distance_m});
  const std::vector<std::int64_t> status = in.read_ints(s::kSolverStatus.path);
  const std::vector<std::int8_t> codes = solver_status_codes(d.solver_status);
  CHECK(status == std::vector<std::int64_t>(codes.begin(), codes.end()));
  check_values(in, s::kSolverIterations.path, d.solver_iterations);
  check_values(in, s::kSolverObjective.path, d.solver_objective);
  check_values(in, s::kSolverSeconds.path, d.solver_seconds);
  CHECK(in.read_strings(s::kSolverMessages.path) == d.solver_messages);
}

TEST_CASE("output: kinematics-only result has no dynamics datasets", "[output]") {
  TempDir dir;
  const std::string path = dir.file("kin.h5");
  const RunResult r = make_result(5, false, 0, 0);
  write_result_file(path, r);
  const H5Reader in(path);
  check_specs(in, schema::kModelDatasets, 5, 0, 0);
  check_specs(in, schema::kKinematicDatasets, 5, 0, 0);
  check_kinematics(in, r);
  for (const schema::DatasetSpec& spec : schema::kDynamicsDatasets) {
    INFO(spec.path);
    CHECK_FALSE(in.exists(spec.path));
  }
  CHECK_FALSE(in.exists("/impacts"));
  CHECK_FALSE(in.exists("/solver"));
}

TEST_CASE("output: zero impacts and zero messages give zero-length datasets", "[output]") {
  TempDir dir;
  const std::string path = dir.file("quiet.h5");
  write_result_file(path, make_result(3, true, 0, 0));
  const H5Reader in(path);
  check_specs(in, schema::kDynamicsDatasets, 3, 0, 0);
  CHECK(in.read_ints(schema::kImpactLeg.path).empty());
  CHECK(in.read_doubles(schema::kImpactPeakForce.path).values.empty());
  CHECK(in.read_strings(schema::kSolverMessages.path).empty());
}

TEST_CASE("output: a failed write leaves the old file untouched and no temporary", "[output]") {
  TempDir dir;
  const std::string path = dir.file("run.h5");
  write_result_file(path, make_result(6, true, 2, 1, 11));
  const std::string before = file_bytes(path);
  REQUIRE(!before.empty());

  SECTION("inconsistent dynamics array: the write throws after the kinematics") {
    RunResult bad = make_result(6, true, 2, 1, 12);
    bad.dyn.solver_seconds.pop_back();
    CHECK_THROWS_AS(write_result_file(path, bad), IoError);
  }
  SECTION("inconsistent kinematics matrix") {
    RunResult bad = make_result(6, false, 0, 0, 13);
    bad.kin.joint_velocity.resize(6, 17);
    CHECK_THROWS_WITH(write_result_file(path, bad), Catch::Contains("/joints/velocity"));
  }
  SECTION("impact on a leg that does not exist") {
    RunResult bad = make_result(6, true, 2, 0, 14);
    bad.dyn.impacts[1].leg = 6;
    CHECK_THROWS_AS(write_result_file(path, bad), IoError);
  }
  CHECK(file_bytes(path) == before);
  CHECK(directory_entries(dir.path) == std::vector<std::string>{"run.h5"});
}

TEST_CASE("output: unwritable destinations are refused before any work", "[output]") {
  TempDir dir;
  const std::string missing_dir = dir.file("no/such/dir/run.h5");
  CHECK_THROWS_AS(check_output_target(missing_dir, {}), IoError);
  CHECK_THROWS_WITH(check_output_target(missing_dir, {}),
                    Catch::Contains(missing_dir) && Catch::Contains("does not exist"));
  CHECK_THROWS_AS(write_result_file(missing_dir, make_result(2, false, 0, 0)), IoError);
  CHECK_THROWS_WITH(check_output_target(dir.path.string(), {}), Catch::Contains("is a directory"));
  const std::string not_a_dir = dir.file("plain");
  std::ofstream(not_a_dir) << "x";
  CHECK_THROWS_WITH(check_output_target(not_a_dir + "/run.h5", {}),
                    Catch::Contains("not a directory"));
  CHECK_NOTHROW(check_output_target(dir.file("fresh.h5"), {}));
  CHECK(directory_entries(dir.path) == std::vector<std::string>{"plain"});
  if (::geteuid() != 0) {  // root bypasses permission bits
    const fs::path locked = dir.path / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    CHECK_THROWS_WITH(check_output_target((locked / "run.h5").string(), {}),
                      Catch::Contains("not writable"));
    fs::permissions(locked, fs::perms::owner_all);
  }
}

TEST_CASE("output: h5io reports HDF5 failures as IoError with the object path", "[output]") {
  TempDir dir;
  const std::string path = dir.file("io.h5");
  {
    H5Writer w(path);
    const std::vector<double> v{1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
    w.write_doubles("/a/b/matrix", {2, 3}, v, "m");
    CHECK_THROWS_WITH(w.write_doubles("/a/b/matrix", {6}, v, "m"), Catch::Contains("/a/b/matrix"));
    CHECK_THROWS_WITH(w.write_doubles("/a/wrong", {4}, v, "m"), Catch::Contains("/a/wrong"));
    CHECK_THROWS_AS(w.set_string_attribute("/nowhere", "x", "y"), IoError);
    w.set_string_attribute("/a", "note", "first");
    w.set_string_attribute("/a", "note", "second");
    w.set_int_attribute("/", "answer", 42);
    w.write_scalar("/scalar", -0.5, "J");
    w.write_string("/text", "héxapod ✓", "1");
    w.close();
  }
  const H5Reader in(path);
  const H5DoubleArray m = in.read_doubles("/a/b/matrix");
  CHECK(m.dims == std::vector<std::size_t>{2, 3});
  CHECK(m.values[5] == 6.0);
  CHECK_FALSE(in.exists("/a/wrong"));
  CHECK_FALSE(in.exists("/x/y/z"));
  CHECK(in.is_group("/a/b"));
  CHECK(in.string_attribute("/a", "note") == "second");
  CHECK(in.int_attribute("/", "answer") == 42);
  CHECK(in.dims("/scalar").empty());
  CHECK(in.read_doubles("/scalar").values == std::vector<double>{-0.5});
  CHECK(in.read_string("/text") == "héxapod ✓");
  CHECK_THROWS_WITH(in.read_doubles("/text"), Catch::Contains("/text"));
  CHECK_THROWS_WITH(in.read_doubles("/missing"), Catch::Contains("/missing"));
  CHECK_THROWS_AS(in.string_attribute("/a", "absent"), IoError);
  CHECK_THROWS_AS(H5Reader(dir.file("absent.h5")), IoError);
  CHECK_THROWS_WITH(H5Writer(dir.file("no/dir/x.h5")), Catch::Contains("no/dir/x.h5"));
}
