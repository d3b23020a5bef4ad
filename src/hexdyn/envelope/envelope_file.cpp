// The hexdyn-envelope/2 file (io/schema.hpp).

#include "hexdyn/core/errors.hpp"
#include "hexdyn/envelope/envelope.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/labels.hpp"
#include "hexdyn/io/output.hpp"
#include "hexdyn/io/schema.hpp"
#include "hexdyn/process/atomic_file.hpp"
#include "hexdyn/version.hpp"

namespace hexdyn {
namespace {

namespace s = schema;

/// Writes datasets as declared in io/schema.hpp (path, units) and labels each for netCDF-4
/// readers (io/labels.hpp).
struct LabelledWriter {
  H5Writer& w;
  Labeller& labels;

  void doubles(const s::DatasetSpec& d, const std::vector<std::size_t>& dims,
               const std::vector<double>& v) {
    w.write_doubles(d.path, dims, v, d.units);
    labels.add(d);
  }
  void strings(const s::DatasetSpec& d, const std::vector<std::size_t>& dims,
               const std::vector<std::string>& v) {
    w.write_strings(d.path, dims, v, d.units);
    labels.add(d);
  }
};

/// /meta: the schema header, the envelope and base configurations, the search's settings
/// and the inputs' checksums.
void write_envelope_meta(H5Writer& w, const EnvelopeSpec& spec, const EnvelopeResult& r) {
  const std::string meta = s::kMetaGroup;
  write_meta_header(w, meta, s::kEnvelopeSchema, s::kEnvelopeSchemaVersion);
  w.set_string_attribute(meta, s::kAttrConfigYaml, spec.spec_yaml);
  w.set_double_attribute(meta, s::kAttrWallTime, r.wall_time_s);
  w.set_string_attribute(meta, s::kMetaEnvelopeBaseConfigYaml.name, spec.base_config_yaml);
  w.set_string_attribute(meta, s::kMetaEnvelopeName.name, spec.name);
  w.set_double_attribute(meta, s::kMetaEnvelopeTolerance.name, spec.tolerance_m);
  w.set_double_attribute(meta, s::kMetaEnvelopeStep.name, spec.riser_step_m);
  w.set_string_attribute(meta, s::kMetaEnvelopeDirection.name, spec.direction < 0 ? "down" : "up");
  w.set_string_attribute(meta, s::kAttrInputSha256, input_sha256_text(spec.inputs));
}

/// The grid's axes: tread depth [m], duty factor, peak speed [m/s] and criteria, as
/// coordinates and as /axes datasets, and the riser range searched [m].
void write_envelope_axes(LabelledWriter& out, const EnvelopeSpec& spec) {
  const std::size_t W = spec.tread_depth_m.size(), B = spec.duty_factor.size(),
                    S = spec.peak_speed_mps.size(), C = spec.criteria.size();
  out.doubles(s::kTreadDepthCoordinate, {W}, spec.tread_depth_m);
  out.doubles(s::kDutyFactorCoordinate, {B}, spec.duty_factor);
  out.doubles(s::kPeakSpeedCoordinate, {S}, spec.peak_speed_mps);
  out.doubles(s::kEnvelopeTreadDepth, {W}, spec.tread_depth_m);
  out.doubles(s::kEnvelopeDutyFactor, {B}, spec.duty_factor);
  out.doubles(s::kEnvelopePeakSpeed, {S}, spec.peak_speed_mps);
  std::vector<std::string> names;
  for (EnvelopeCriterion c : spec.criteria) names.push_back(criterion_name(c));
  out.strings(s::kCriterionCoordinate, {C}, names);
  out.strings(s::kEnvelopeCriteria, {C}, names);
  out.doubles(s::kEnvelopeRiserFrom, {}, {spec.riser_from_m});
  out.doubles(s::kEnvelopeRiserTo, {}, {spec.riser_to_m});
}

/// The boundary per cell and criterion and the posture per cell; with cases, the case
/// axis and table first and every grid with the leading dimension `case` (the
/// kEnvelopeCase* declarations).
void write_envelope_boundary(LabelledWriter& out, const EnvelopeSpec& spec,
                             const EnvelopeResult& r) {
  const std::size_t W = spec.tread_depth_m.size(), B = spec.duty_factor.size(),
                    S = spec.peak_speed_mps.size(), C = spec.criteria.size();
  std::vector<double> rmax, rfail, mu;
  std::vector<std::string> limit, message;
  for (const EnvelopeBoundary& b : r.boundary) {
    rmax.push_back(b.riser_max_m);
    mu.push_back(b.required_friction);
    rfail.push_back(b.riser_fail_m);
    limit.push_back(b.limit);
    message.push_back(b.message);
  }
  const std::size_t D = spec.cases.size();
  const bool cases = D > 0;
  const std::vector<std::size_t> grid =
      cases ? std::vector<std::size_t>{D, W, B, S, C} : std::vector<std::size_t>{W, B, S, C};
  const std::vector<std::size_t> cells =
      cases ? std::vector<std::size_t>{D, W, B, S} : std::vector<std::size_t>{W, B, S};
  if (cases) {
    const std::size_t K = spec.cases.keys.size();
    std::vector<std::string> table;
    for (const auto& row : spec.cases.values) table.insert(table.end(), row.begin(), row.end());
    out.strings(s::kCaseCoordinate, {D}, spec.cases.labels);
    out.strings(s::kEnvelopeCaseLabels, {D}, spec.cases.labels);
    out.strings(s::kCaseKeyCoordinateEnvelope, {K}, spec.cases.keys);
    out.strings(s::kEnvelopeCaseKeys, {K}, spec.cases.keys);
    out.strings(s::kEnvelopeCaseValues, {D, K}, table);
  }
  out.doubles(cases ? s::kEnvelopeCaseRiserMax : s::kEnvelopeRiserMax, grid, rmax);
  out.doubles(cases ? s::kEnvelopeCaseRiserFail : s::kEnvelopeRiserFail, grid, rfail);
  out.doubles(
      cases ? s::kEnvelopeCaseRiserMaxRequiredFriction : s::kEnvelopeRiserMaxRequiredFriction, grid,
      mu);
  out.strings(cases ? s::kEnvelopeCaseLimit : s::kEnvelopeLimit, grid, limit);
  out.strings(cases ? s::kEnvelopeCaseMessage : s::kEnvelopeMessage, grid, message);
  out.doubles(cases ? s::kEnvelopeCasePostureHeight : s::kEnvelopePostureHeight, cells,
              r.posture_height_m);
  out.doubles(cases ? s::kEnvelopeCasePostureFootLateral : s::kEnvelopePostureFootLateral, cells,
              r.posture_foot_lateral_m);
  out.doubles(cases ? s::kEnvelopeCasePostureMargin : s::kEnvelopePostureMargin, cells,
              r.posture_margin_m);
}

/// Every probe run, in the order run: cell, criterion (index into the criteria), riser [m],
/// whether it passed, and what failed.
void write_envelope_probes(LabelledWriter& out, const EnvelopeSpec& spec, const EnvelopeResult& r) {
  const std::size_t C = spec.criteria.size();
  std::vector<std::int32_t> cell, crit;
  std::vector<double> riser;
  std::vector<std::int8_t> passed;
  std::vector<std::string> plimit, pmessage;
  for (const EnvelopeProbe& p : r.probes) {
    cell.push_back(p.cell);
    std::int32_t ci = 0;
    for (std::size_t i = 0; i < C; ++i)
      if (spec.criteria[i] == p.criterion) ci = static_cast<std::int32_t>(i);
    crit.push_back(ci);
    riser.push_back(p.riser_m);
    passed.push_back(p.passed ? 1 : 0);
    plimit.push_back(p.limit);
    pmessage.push_back(p.message);
  }
  const std::size_t P = r.probes.size();
  out.w.write_int32(s::kProbeCell.path, {P}, cell, s::kProbeCell.units);
  out.labels.add(s::kProbeCell);
  out.w.write_int32(s::kProbeCriterion.path, {P}, crit, s::kProbeCriterion.units);
  out.labels.add(s::kProbeCriterion);
  out.doubles(s::kProbeRiser, {P}, riser);
  out.w.write_int8(s::kProbePassed.path, {P}, passed, s::kProbePassed.units);
  out.labels.add(s::kProbePassed);
  out.strings(s::kProbeLimit, {P}, plimit);
  out.strings(s::kProbeMessage, {P}, pmessage);
}

/// With search: friction, the risers and the least μ per cell and riser, its leg and time.
void write_envelope_friction(LabelledWriter& out, const EnvelopeSpec& spec,
                             const EnvelopeResult& r) {
  const std::vector<double> risers = spec.scan_risers();
  const std::size_t W = spec.tread_depth_m.size(), B = spec.duty_factor.size(),
                    S = spec.peak_speed_mps.size(), R = risers.size(), D = spec.cases.size();
  const bool cases = D > 0;
  const std::vector<std::size_t> grid =
      cases ? std::vector<std::size_t>{D, W, B, S, R} : std::vector<std::size_t>{W, B, S, R};
  out.doubles(s::kRiserCoordinate, {R}, risers);
  out.doubles(s::kEnvelopeRisers, {R}, risers);
  out.doubles(cases ? s::kEnvelopeCaseRequiredFriction : s::kEnvelopeRequiredFriction, grid,
              r.required_friction);
  const s::DatasetSpec& leg =
      cases ? s::kEnvelopeCaseRequiredFrictionLeg : s::kEnvelopeRequiredFrictionLeg;
  out.w.write_int32(
      leg.path, grid,
      std::vector<std::int32_t>(r.required_friction_leg.begin(), r.required_friction_leg.end()),
      leg.units);
  out.labels.add(leg);
  out.doubles(cases ? s::kEnvelopeCaseRequiredFrictionTime : s::kEnvelopeRequiredFrictionTime, grid,
              r.required_friction_time_s);
}

void write_file(H5Writer& w, const EnvelopeSpec& spec, const EnvelopeResult& r) {
  Labeller labels(w, "");
  LabelledWriter out{w, labels};
  write_envelope_meta(w, spec, r);
  write_envelope_axes(out, spec);
  write_envelope_boundary(out, spec, r);
  write_envelope_probes(out, spec, r);
  if (spec.search == EnvelopeSearch::kFriction) write_envelope_friction(out, spec, r);
  labels.finish();
}

}  // namespace

void write_envelope_file(const std::string& path, const EnvelopeSpec& spec,
                         const EnvelopeResult& result) {
  silence_hdf5_errors();
  check_output_target(path, spec.inputs);
  publish_atomically(path, [&](const std::string& tmp) {
    H5Writer w(tmp, compressed_output(spec.base_config_yaml));
    write_file(w, spec, result);
    w.close();
  });
}

}  // namespace hexdyn
