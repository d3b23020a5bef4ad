// The keys of robustness: (scene_readers.hpp; core/robustness_params.hpp), and the bounds that
// keep every world a study can draw physical.
#include <cmath>
#include <sstream>

#include "hexdyn/config/robustness_bounds.hpp"
#include "hexdyn/config/scene_readers.hpp"

namespace hexdyn::scene_keys {
namespace {

using P = Perturbation;

/// The largest error a distribution may be given, in its unit.
constexpr double kLargestError = 1e6;

std::string text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// robustness.perturbations.NAME: {distribution: normal, sigma, bound (default 3 sigma)} or
/// {distribution: uniform, low, high}.
Distribution read_distribution(Reader& r, const std::string& path) {
  Distribution d;
  const std::string kind = r.choice(path + ".distribution", {"normal", "uniform"});
  if (kind == "normal") {
    d.kind = DistributionKind::kNormal;
    d.sigma = r.number(path + ".sigma", nonnegative(kLargestError));
    d.bound = r.number_or(path + ".bound", 3.0 * d.sigma, nonnegative(kLargestError));
    if (d.sigma > 0.0 && !(d.bound > 0.0))
      r.fail(path + ".bound", "got 0, expected a positive bound with a positive sigma");
    for (const char* k : {".low", ".high"})
      if (r.given(path + k)) r.fail(path + k, "a key of a uniform distribution, not of normal");
  } else {
    d.kind = DistributionKind::kUniform;
    d.low = r.number(path + ".low", closed(-kLargestError, kLargestError));
    d.high = r.number(path + ".high", closed(-kLargestError, kLargestError));
    if (d.high < d.low)
      r.fail(path + ".high",
             "got " + text(d.high) + ", expected a number at least low (" + text(d.low) + ")");
    for (const char* k : {".sigma", ".bound"})
      if (r.given(path + k)) r.fail(path + k, "a key of a normal distribution, not of uniform");
  }
  return d;
}

void read_failure(Reader& r, FailureBounds& b) {
  if (r.has("robustness.failure.drift"))
    b.drift_m = r.number("robustness.failure.drift", positive(100.0));
  b.slip_m = r.number_or("robustness.failure.slip", b.slip_m, positive(100.0));
  b.saturation_s = r.number_or("robustness.failure.saturation", b.saturation_s, nonnegative(1e6));
  b.stub_tilt_rad =
      r.number_or("robustness.failure.stub_tilt", b.stub_tilt_rad, closed(0.0, M_PI / 2.0));
  b.stub_force_fraction =
      r.number_or("robustness.failure.stub_force", b.stub_force_fraction, nonnegative(10.0));
}

void read_tolerance(Reader& r, ToleranceSearch& t) {
  if (!r.given("robustness.tolerance")) return;
  t.enabled = true;
  const int replays = t.replays, bisections = t.bisections;
  t.replays = r.integer("robustness.tolerance.replays", 1, kMaxRobustnessReplays, &replays);
  t.max_scale = r.number_or("robustness.tolerance.max_scale", t.max_scale, positive(1e6));
  t.bisections = r.integer("robustness.tolerance.bisections", 0, 30, &bisections);
  t.target = r.number_or("robustness.tolerance.target", t.target, closed(0.0, 1.0));
}

}  // namespace

void read_robustness(Reader& r, Scene& s) {
  if (!r.given("robustness")) return;
  RobustnessParams& p = s.robustness;
  const int replays = kDefaultRobustnessReplays, seed = 1;
  p.replays = r.integer("robustness.replays", 1, kMaxRobustnessReplays, &replays);
  p.seed = static_cast<std::uint64_t>(
      r.integer("robustness.seed", 0, std::numeric_limits<int>::max(), &seed));
  for (int i = 0; i < kPerturbationCount; ++i) {
    const std::string path =
        std::string("robustness.perturbations.") + perturbation_name(static_cast<P>(i));
    if (r.has(path)) p.perturbations.of[static_cast<std::size_t>(i)] = read_distribution(r, path);
  }
  read_failure(r, p.failure);
  read_tolerance(r, p.search);
  if (const auto problem = perturbation_problem(p.perturbations, s))
    r.fail(problem->key, problem->message);
}

}  // namespace hexdyn::scene_keys
