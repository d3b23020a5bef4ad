// terrain.steps as a list, terrain.nosing and the stairs' perturbations (stair_steps.hpp).
#include "hexdyn/config/stair_steps.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/table_keys.hpp"
#include "hexdyn/config/yaml_load.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/stairs.hpp"

namespace hexdyn::scene_keys {

namespace {

constexpr const char* kSteps = "terrain.steps";

/// The bounds of a list entry's fields (docs/user/configuration.md#terrain).
const Range kRiserRange = closed(-1.0, 1.0);
const Range kTreadRange = positive(10.0);
const Range kLandingRange = positive(100.0);

/// The problems of a step list, one line each.
class StepProblems {
 public:
  explicit StepProblems(const Reader& r) : file_(r.file()) {}
  void add(std::size_t k, const std::string& field, const YAML::Node& value,
           const std::string& expected) {
    std::string path = std::string(kSteps) + "[" + std::to_string(k + 1) + "]";
    if (!field.empty()) path += "." + field;
    lines_.push_back(file_ + ": " + path + ": " +
                     (value.IsDefined()
                          ? "got " + yaml_for_message(value) + ", expected " + expected
                          : "missing, expected " + expected));
  }
  /// An entry's key that is none of its fields.
  void unknown(std::size_t k, const std::string& key) {
    lines_.push_back(file_ + ": " + std::string(kSteps) + "[" + std::to_string(k + 1) + "]." + key +
                     ": unknown key, allowed here: landing, nosing, riser, tread");
  }
  void throw_if_any() const {
    if (lines_.size() == 1) throw ConfigError(lines_.front());
    if (!lines_.empty()) throw ConfigErrors(lines_);
  }

 private:
  std::string file_;
  std::vector<std::string> lines_;
};

/// A list entry's number: nullopt (a problem recorded) unless a finite number in `range`.
std::optional<double> entry_number(StepProblems& bad, std::size_t k, const YAML::Node& entry,
                                   const std::string& field, const Range& range,
                                   std::optional<double> def, const std::string& default_word) {
  const YAML::Node v = entry[field];
  const std::string interval = range.describe().substr(std::string("a number in ").size());
  const std::string expected = "a number in " + interval + " m";
  if (!v.IsDefined() || v.IsNull()) {
    if (!def) bad.add(k, field, YAML::Node(), expected + " (or " + default_word + ")");
    return def;
  }
  double x = 0.0;
  bool ok = v.IsScalar() && !is_quoted_number(v);
  if (ok) {
    if (const auto q = parse_fraction(v.Scalar()))
      x = *q;
    else
      ok = YAML::convert<double>::decode(v, x);
  }
  if (!ok || !std::isfinite(x) || !range.contains(x)) {
    bad.add(k, field, v, "a finite number in " + interval + " m");
    return std::nullopt;
  }
  return x;
}

struct EntryDefaults {
  std::optional<double> riser_m, tread_m;
  double nosing_m = 0.0;
};

/// One entry of the list: {riser, tread, nosing} or {landing}; nullopt when bad.
std::optional<StairStep> read_entry(StepProblems& bad, std::size_t k, const YAML::Node& e,
                                    const EntryDefaults& d) {
  if (!e.IsMap()) {
    bad.add(k, "", e, "a map {riser: h, tread: b, nosing: n} or {landing: L}");
    return std::nullopt;
  }
  bool landing = false, fields_ok = true;
  for (const auto& kv : e) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
    if (key == "landing") {
      landing = true;
    } else if (key != "riser" && key != "tread" && key != "nosing") {
      bad.unknown(k, key);
      fields_ok = false;
    }
  }
  if (!fields_ok) return std::nullopt;
  if (landing) {
    if (e.size() != 1) {
      bad.add(k, "", e, "{landing: L} alone, without riser, tread or nosing");
      return std::nullopt;
    }
    const auto L = entry_number(bad, k, e, "landing", kLandingRange, std::nullopt, "");
    if (!L) return std::nullopt;
    return StairStep{0.0, *L, 0.0};
  }
  const auto h = entry_number(bad, k, e, "riser", kRiserRange, d.riser_m, "terrain.riser_height");
  const auto b = entry_number(bad, k, e, "tread", kTreadRange, d.tread_m, "terrain.tread_depth");
  const auto n = entry_number(bad, k, e, "nosing", nonnegative(10.0), d.nosing_m, "");
  if (!h || !b || !n) return std::nullopt;
  return StairStep{*h, *b, *n};
}

/// A nosing that overhangs the whole tread below it makes two edges cross: the step whose
/// nosing moved its edge past the other is named.
void check_overhangs(const TerrainParams& t, StepProblems& bad, const YAML::Node& list) {
  const StairEdges e = stair_edges(t);
  for (std::size_t k = 1; k < e.edge_y_m.size(); ++k) {
    if (e.edge_y_m[k] > e.edge_y_m[k - 1]) continue;
    const int step_back = e.edge_step[k], step_ahead = e.edge_step[k - 1];
    const StairStep& up = t.step_list[step_back - 1];
    const int step = up.riser_m > 0.0 && up.nosing_m > 0.0 ? step_back : step_ahead;
    const StairStep& s = t.step_list[step - 1];
    const double going = s.riser_m > 0.0 ? t.step_list[step_ahead - 1].tread_m : s.tread_m;
    bad.add(static_cast<std::size_t>(step - 1), "nosing", list[step - 1]["nosing"],
            "less than the tread it overhangs (" + fmt(going) + " m between the risers)");
  }
}

/// A uniform list as the uniform stairs it spells out; any other list as it is.
void read_as_uniform(TerrainParams& t) {
  const StairStep& f = t.step_list.front();
  for (const StairStep& s : t.step_list)
    if (s.riser_m != f.riser_m || s.tread_m != f.tread_m || s.nosing_m != f.nosing_m ||
        s.riser_m == 0.0)
      return;
  t.riser_height_m = f.riser_m;
  t.tread_depth_m = f.tread_m;
  t.nosing_m = f.nosing_m;
  t.steps = static_cast<int>(t.step_list.size());
  t.step_list.clear();
}

void read_step_list(Reader& r, TerrainParams& t, const YAML::Node& list) {
  if (list.size() == 0 || list.size() > 100000)
    r.fail_value(kSteps, list, "a count in [1, 100000] or a list of 1 to 100000 steps");
  EntryDefaults d;
  if (r.given("terrain.riser_height")) d.riser_m = number_key(r, "terrain.riser_height");
  if (r.given("terrain.tread_depth")) d.tread_m = number_key(r, "terrain.tread_depth");
  d.nosing_m = number_key(r, "terrain.nosing");
  StepProblems bad(r);
  for (std::size_t k = 0; k < list.size(); ++k)
    if (const auto s = read_entry(bad, k, list[k], d)) t.step_list.push_back(*s);
  bad.throw_if_any();
  check_overhangs(t, bad, list);
  bad.throw_if_any();
  const bool any_riser = std::any_of(t.step_list.begin(), t.step_list.end(),
                                     [](const StairStep& s) { return s.riser_m != 0.0; });
  if (!any_riser)
    r.fail_value(kSteps, list,
                 "at least one step with a riser (landings alone are flat ground: terrain.type "
                 "flat)");
  t.steps = static_cast<int>(t.step_list.size());
  if (d.riser_m) t.riser_height_m = *d.riser_m;
  if (d.tread_m) t.tread_depth_m = *d.tread_m;
  t.nosing_m = d.nosing_m;
  read_as_uniform(t);
}

/// Uniform stairs: the nosing must leave part of the tread it overhangs.
void check_uniform_nosing(Reader& r, const TerrainParams& t) {
  if (t.nosing_m >= t.tread_depth_m && t.riser_height_m != 0.0)
    r.fail("terrain.nosing", "got " + fmt(t.nosing_m) +
                                 ", expected less than terrain.tread_depth (" +
                                 fmt(t.tread_depth_m) + " m, the tread it overhangs)");
}

/// terrain.riser_scale and terrain.step_offset: the perturbations a sweep varies.
void read_perturbations(Reader& r, TerrainParams& t) {
  const double scale = number_key_or(r, "terrain.riser_scale", 1.0);
  const int none = 0;
  const int step = r.integer("terrain.step_offset.step", 0, 100000, &none);
  const double offset = number_key_or(r, "terrain.step_offset.riser", 0.0);
  if (step > t.steps)
    r.fail("terrain.step_offset.step", "got " + std::to_string(step) +
                                           ", expected a step of the stairs, 1 to " +
                                           std::to_string(t.steps) + " (0: none)");
  if (scale == 1.0 && (step == 0 || offset == 0.0)) return;
  if (t.step_list.empty()) {  // spelt out, as the list the perturbation changes
    if (scale != 1.0 && step == 0) {
      t.riser_height_m *= scale;
      return;
    }
    t.step_list = stair_step_list(t);
  }
  for (StairStep& s : t.step_list) s.riser_m *= scale;
  if (step > 0) t.step_list[step - 1].riser_m += offset;
  const StairEdges e = stair_edges(t);
  for (std::size_t k = 1; k < e.edge_y_m.size(); ++k)
    if (e.edge_y_m[k] <= e.edge_y_m[k - 1])
      r.fail("terrain.step_offset.riser",
             "got " + fmt(offset) + ", expected a riser whose nosing keeps part of its tread " +
                 "(step " + std::to_string(e.edge_step[k]) + " overhangs the whole tread)");
}

}  // namespace

void read_stairs(Reader& r, TerrainParams& t) {
  const YAML::Node steps = r.peek(kSteps);
  if (steps.IsSequence()) {
    (void)r.node(kSteps);  // read here, entry by entry
    read_step_list(r, t, steps);
    r.record(kSteps, steps);
  } else {
    t.riser_height_m = number_key(r, "terrain.riser_height");
    t.tread_depth_m = number_key(r, "terrain.tread_depth");
    t.steps = r.integer(kSteps, 1, 100000);
    t.nosing_m = number_key(r, "terrain.nosing");
    check_uniform_nosing(r, t);
  }
  read_perturbations(r, t);
}

}  // namespace hexdyn::scene_keys
