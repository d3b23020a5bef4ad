// The hexdyn-robustness/1 file (io/schema_robustness.hpp).
#include <cstdint>

#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/robustness/robustness.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace s = schema;

template <class T, class Get>
std::vector<T> per_replay(const RobustnessResult& r, Get get) {
  std::vector<T> out;
  out.reserve(r.outcomes.size());
  for (const ReplayOutcome& o : r.outcomes) out.push_back(static_cast<T>(get(o)));
  return out;
}

void add_replays(ResultLayout& b, const RobustnessResult& r) {
  const std::size_t n = r.outcomes.size();
  using O = const ReplayOutcome&;
  b.add(s::kRobustReachedTop, {n}, per_replay<std::int8_t>(r, [](O o) { return o.reached_top; }));
  b.add(s::kRobustFailure, {n}, per_replay<std::int8_t>(r, [](O o) { return o.failure; }));
  b.add(s::kRobustFailureTime, {n}, per_replay<double>(r, [](O o) { return o.failure_time_s; }));
  b.add(s::kRobustDrift, {n}, per_replay<double>(r, [](O o) { return o.drift_m; }));
  b.add(s::kRobustHeightError, {n}, per_replay<double>(r, [](O o) { return o.height_error_m; }));
  b.add(s::kRobustSlip, {n}, per_replay<double>(r, [](O o) { return o.slip_m; }));
  b.add(s::kRobustEnergy, {n}, per_replay<double>(r, [](O o) { return o.energy_J; }));
  b.add(s::kRobustElectricalEnergy, {n},
        per_replay<double>(r, [](O o) { return o.electrical_energy_J; }));
  b.add(s::kRobustSaturationTime, {n}, per_replay<double>(r, [](O o) { return o.saturation_s; }));
  b.add(s::kRobustMargin, {n}, per_replay<double>(r, [](O o) { return o.margin; }));
  b.add(s::kRobustMarginCriterion, {n},
        per_replay<std::int8_t>(r, [](O o) { return o.margin_criterion; }));
  b.add(s::kRobustSteps, {n}, per_replay<std::int32_t>(r, [](O o) { return o.steps; }));
  b.add(s::kRobustWallTime, {n}, per_replay<double>(r, [](O o) { return o.seconds; }));
  std::vector<std::int32_t> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<std::int32_t>(i);
  b.add(s::kReplayIndexCoordinate, {n}, index);
}

/// The drawn errors of every active perturbation, and the coordinates their dimensions need.
void add_perturbations(ResultLayout& b, const RobustnessParams& spec, const RobustnessResult& r) {
  bool steps = false, links = false, joints = false, xyz = false;
  for (Perturbation p : spec.perturbations.active()) {
    const auto k = static_cast<std::size_t>(p);
    const std::size_t width = static_cast<std::size_t>(draw_count(p, r.sizes));
    std::vector<double> values;
    values.reserve(r.draws.size() * width);
    for (const WorldDraw& d : r.draws) values.insert(values.end(), d[p].begin(), d[p].end());
    const PerturbationExtent e = perturbation_extent(p);
    std::vector<std::size_t> dims{r.draws.size()};
    if (e != PerturbationExtent::kOnce) dims.push_back(width);
    b.add(s::kRobustPerturbationDatasets[k], dims, std::move(values));
    steps |= e == PerturbationExtent::kPerStep;
    links |= e == PerturbationExtent::kPerLink;
    joints |= e == PerturbationExtent::kPerJoint;
    xyz |= e == PerturbationExtent::kXyz;
  }
  if (steps) {
    std::vector<std::int32_t> step(static_cast<std::size_t>(r.sizes.steps));
    for (std::size_t i = 0; i < step.size(); ++i) step[i] = static_cast<std::int32_t>(i + 1);
    b.add(s::kStepCoordinate, {step.size()}, step);
  }
  if (links) b.add(s::kLinkCoordinate, {r.joint_names.size()}, r.joint_names);
  if (joints) b.add(s::kJointCoordinate, {r.joint_names.size()}, r.joint_names);
  if (xyz) b.add(s::kXyzCoordinate, {3}, std::vector<std::string>{"x", "y", "z"});
}

void add_summary(ResultLayout& b, const RobustnessResult& r) {
  auto scalar = [&](const s::DatasetSpec& spec, double v) {
    b.add(spec, {}, std::vector<double>{v});
  };
  auto count = [&](const s::DatasetSpec& spec, long v) {
    b.add(spec, {}, std::vector<std::int32_t>{static_cast<std::int32_t>(v)});
  };
  count(s::kRobustReplayCount, static_cast<long>(r.outcomes.size()));
  count(s::kRobustSuccesses, r.successes);
  scalar(s::kRobustPSuccess, r.p_success);
  scalar(s::kRobustWilsonLow, r.interval.low);
  scalar(s::kRobustWilsonHigh, r.interval.high);
  std::vector<std::int32_t> counts;
  std::vector<std::string> names;
  for (int c = 0; c < kFailureClassCount; ++c) {
    counts.push_back(static_cast<std::int32_t>(r.counts[static_cast<std::size_t>(c)]));
    names.emplace_back(failure_class_name(static_cast<FailureClass>(c)));
  }
  b.add(s::kRobustFailureCount, {counts.size()}, counts);
  b.add(s::kFailureClassCoordinate, {names.size()}, names);
  scalar(s::kRobustDriftBound, r.bounds.drift_m);
  scalar(s::kRobustSlipBound, r.bounds.slip_m);
  scalar(s::kRobustSaturationBound, r.bounds.saturation_s);
  scalar(s::kRobustPlanWallTime, r.plan_seconds);
}

void add_tolerance(ResultLayout& b, const RobustnessParams& spec, const RobustnessResult& r) {
  if (!spec.search.enabled) return;
  const std::size_t n = r.tolerance.size();
  std::vector<double> scale, max_scale, magnitude, p;
  std::vector<std::string> unit, names;
  std::vector<std::int8_t> censored;
  std::vector<std::int32_t> probes;
  for (const ToleranceResult& t : r.tolerance) {
    scale.push_back(t.scale);
    max_scale.push_back(t.max_scale);
    magnitude.push_back(t.magnitude);
    p.push_back(t.p_success);
    unit.emplace_back(perturbation_unit(t.perturbation));
    names.emplace_back(perturbation_name(t.perturbation));
    censored.push_back(t.censored ? 1 : 0);
    probes.push_back(t.probes);
  }
  b.add(s::kRobustToleranceScale, {n}, scale);
  b.add(s::kRobustToleranceMaxScale, {n}, max_scale);
  b.add(s::kRobustToleranceMagnitude, {n}, magnitude);
  b.add(s::kRobustToleranceUnit, {n}, unit);
  b.add(s::kRobustTolerancePSuccess, {n}, p);
  b.add(s::kRobustToleranceCensored, {n}, censored);
  b.add(s::kRobustToleranceProbes, {n}, probes);
  b.add(s::kRobustToleranceReplays, {}, std::vector<std::int32_t>{spec.search.replays});
  b.add(s::kRobustToleranceTarget, {}, std::vector<double>{spec.search.target});
  b.add(s::kPerturbationCoordinate, {n}, names);
}

void add_meta(ResultLayout& b, const Scene& scene, const std::vector<InputFile>& inputs,
              const RobustnessResult& r) {
  b.attributes = {{&s::kMetaSchema, std::string(s::kRobustnessSchema)},
                  {&s::kMetaSchemaVersion, s::kRobustnessSchemaVersion},
                  {&s::kMetaVersion, std::string(kVersion)},
                  {&s::kMetaGitCommit, std::string(kGitCommit)},
                  {&s::kMetaCreatedUtc, utc_timestamp_now()},
                  {&s::kMetaConfigYaml, scene.resolved_yaml},
                  {&s::kMetaWallTime, r.seconds},
                  {&s::kMetaInputSha256, input_sha256_text(inputs)},
                  {&s::kMetaRobustnessName, scene.name},
                  {&s::kMetaRobustnessSeed, static_cast<std::int64_t>(scene.robustness.seed)}};
}

}  // namespace

ResultLayout robustness_layout(const Scene& scene, const std::vector<InputFile>& inputs,
                               const RobustnessResult& result) {
  ResultLayout b;
  add_meta(b, scene, inputs, result);
  add_replays(b, result);
  add_perturbations(b, scene.robustness, result);
  add_summary(b, result);
  add_tolerance(b, scene.robustness, result);
  return b;
}

void write_robustness_file(const std::string& path, const Scene& scene,
                           const std::vector<InputFile>& inputs, const RobustnessResult& result) {
  check_output_target(path, inputs);
  const ResultLayout b = robustness_layout(scene, inputs, result);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer writer(tmp, compressed_output(scene.resolved_yaml));
    write_layout(writer, b);
    writer.close();
  });
}

}  // namespace hexdyn
