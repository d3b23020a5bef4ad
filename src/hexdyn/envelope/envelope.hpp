#pragma once
/// \file envelope.hpp
/// The climbable envelope (docs/user/envelope.md): the largest stair riser a robot
/// can climb, per tread depth, duty factor and peak speed, under three criteria:
///
///   kinematic  the planned motion is admitted by the legs (planning/posture.hpp): with
///              motion.posture.height auto, some trunk height keeps every foot target
///              at least robot.ik_min_margin (or the envelope's kinematic_margin) from
///              full extension and fold with every joint inside its limits; with a
///              given posture, that posture does.
///   torque     the whole run (run_scene) has no relaxed support sample with the torque
///              limit of the scene and friction lifted (μ = 10);
///   friction   the whole run has no relaxed support sample with the scene's friction
///              and the torque limit lifted (10⁶ N m).
/// A relaxed support sample is an allocation sample whose status is relaxed or failed
/// while no leg is in a touchdown transient (/contacts/phase ≠ 1 for every leg): the
/// transients prescribe impact forces that the trunk rows cannot always balance (the
/// paper run has 270 such samples, all inside transients), so they do not count. Each
/// dynamic criterion is run on its own, with the other limit lifted, because the
/// allocation's slack weights let the torque rows give way first whatever is binding:
/// one run could not say which limit it met. A run that throws (reach, planning) fails
/// every criterion with its message.
///
/// Search, per cell and criterion: the riser is scanned from `from` in steps of `step`
/// up to `to` until the first failure, then bisected between the last success and that
/// failure down to `tolerance`. The scan makes the answer the lower boundary of the
/// climbable set (a riser below it that fails would be found by a finer step, not
/// skipped by the bisection); the dynamic criteria are not probed above the kinematic
/// boundary, where they fail for kinematic reasons.
///
/// Friction search (`search: friction`, docs/user/envelope.md#the-least-friction-per-riser):
/// instead of the tallest riser at the scene's μ, the least μ per riser. The required
/// friction of a sample (docs/theory/grip.md#required-friction) does not depend on the
/// scene's contact.friction_coefficient, so one run per cell and riser gives the answer
/// exactly: μ*(riser) = the largest /contacts/required_friction over the run's support
/// samples, with the torque limit lifted as for the friction criterion (NaN when a support
/// sample admits no μ: the support legs cannot produce the trunk motion). The risers are the
/// scan's, from `from` in steps of `step` to `to`; the file also holds the friction
/// criterion's boundary at the scene's μ on that scan (riser_max: the last riser of the
/// passing run from `from`, μ* ≤ μ), without bisection.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hexdyn/config/cases.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

enum class EnvelopeCriterion : std::int8_t { kKinematic = 0, kTorque = 1, kFriction = 2 };
const char* criterion_name(EnvelopeCriterion c);

/// What an envelope searches: the tallest riser per criterion, or the least μ per riser.
enum class EnvelopeSearch : std::int8_t { kRiser = 0, kFriction = 1 };

/// An envelope file (configs/envelope/paper.yaml documents every key).
struct EnvelopeSpec {
  std::string name;
  std::string spec_yaml;         ///< the file's text
  std::string base_path;         ///< the base scene (relative paths resolved)
  std::string base_tree_yaml;    ///< the base scene tree after inherit: and set:
  std::string base_config_yaml;  ///< the base scene validated and fully resolved
  /// The envelope file, the base scene, its inherited files and its URDF, hashed
  /// (config/inputs.hpp): /meta input_sha256.
  std::vector<InputFile> inputs;
  double riser_from_m = 0.0, riser_to_m = 0.3, riser_step_m = 0.01, tolerance_m = 0.001;
  std::vector<double> tread_depth_m;        ///< W values (the base scene's when not given)
  std::vector<double> duty_factor;          ///< B values
  std::vector<double> peak_speed_mps;       ///< V values
  std::vector<EnvelopeCriterion> criteria;  ///< C values, in file order
  double kinematic_margin_m = -1.0;         ///< required reach margin; < 0: robot.ik_min_margin
  /// `cases:` (config/cases.hpp): D designs, each its keys set on the base scene; empty: one
  /// design, the base scene's, and no `case` dimension in the file.
  CaseList cases;
  EnvelopeSearch search = EnvelopeSearch::kRiser;  ///< `search`: riser (default) or friction
  /// `direction`: +1 up (default), −1 down: each probe's terrain.riser_height is direction ×
  /// the riser searched, so that a descent's envelope is the deepest step the gait walks down
  /// (the file's risers are magnitudes; /meta direction says which way).
  int direction = 1;
  /// Number of cells: D × W × B × V (D = 1 without cases).
  int cell_count() const;
  /// The scan's risers: from, from + step, …, to (the last step may be shorter) [m].
  std::vector<double> scan_risers() const;
};

/// Most cells of one envelope (10,000; the paper's has 64): each cell is searched per
/// criterion, one run per probe, and validated on the base scene when the file is read.
/// Counted in 64-bit arithmetic before anything is allocated per cell; one list (or the
/// cases) longer than this is refused before its values are compared.
inline constexpr std::uint64_t kMaxEnvelopeCells = 10000;

/// Most probes one envelope may plan (1,000,000; the paper's plans at most 6,912): cells ×
/// criteria × (the riser scan's steps + 1 + the bisection's halvings from riser.step down
/// to riser.tolerance). Every probe is a run (about 0.1 s for the paper robot) and is kept
/// for the file's /probes.
inline constexpr std::uint64_t kMaxEnvelopeProbes = 1000000;

/// Reads and checks an envelope file; the base scene is validated. Throws ConfigError, one
/// line naming the key, also for more than kMaxEnvelopeCells cells or kMaxEnvelopeProbes
/// planned probes.
EnvelopeSpec load_envelope_spec(const std::string& path);

/// One evaluation of a criterion at one riser.
struct EnvelopeProbe {
  int cell = 0;  ///< index into the (W, B, V) grid, or (D, W, B, V) with cases, row-major
  EnvelopeCriterion criterion = EnvelopeCriterion::kKinematic;
  double riser_m = 0.0;
  bool passed = false;
  std::string limit;    ///< short name of what failed ("" when passed)
  std::string message;  ///< one line: why it failed ("" when passed)
  /// A dynamic probe's run: the largest /contacts/required_friction over its support samples
  /// (docs/theory/grip.md#required-friction); NaN for a kinematic probe, a run that throws, a
  /// support sample that admits no μ, or a scene with output.required_friction false.
  double required_friction = std::numeric_limits<double>::quiet_NaN();
};

/// The boundary of one cell and criterion.
struct EnvelopeBoundary {
  double riser_max_m = 0.0;   ///< largest riser found climbable; NaN if `from` fails
  double riser_fail_m = 0.0;  ///< smallest failing riser found; NaN if none up to `to`
  std::string limit;          ///< what fails at riser_fail ("" if none)
  std::string message;
  /// The required μ of the run at riser_max (its last passing probe's required_friction);
  /// NaN as there, or when riser_max is NaN.
  double required_friction = std::numeric_limits<double>::quiet_NaN();
};

struct EnvelopeResult {
  /// (W, B, V, C) row-major: [((w·B + b)·V + v)·C + c]; with cases (D, W, B, V, C).
  std::vector<EnvelopeBoundary> boundary;
  /// (W, B, V), with cases (D, W, B, V): the automatic posture at the kinematic riser_max (NaN when
  /// not auto or not found), and its smallest kinematic margin [m].
  std::vector<double> posture_height_m, posture_foot_lateral_m, posture_margin_m;
  std::vector<EnvelopeProbe> probes;
  /// With search: friction, (W, B, V, R) or (D, W, B, V, R) over the R = scan_risers(): the
  /// least μ (NaN where none suffices or the run failed), its binding leg (−1 none) and the
  /// time of its sample [s] (NaN none). Empty with search: riser.
  std::vector<double> required_friction, required_friction_time_s;
  std::vector<int> required_friction_leg;
  double wall_time_s = 0.0;
};

/// The keys a probe sets on the base tree: the cell's case keys, tread, duty factor and
/// speed, the riser and the criterion's lifted limit.
std::vector<Override> probe_overrides(const EnvelopeSpec& spec, int cell, double riser_m,
                                      EnvelopeCriterion c);

/// A probe's name in messages: "NAME envelope cell 3 (case LABEL) riser 0.05".
std::string probe_source(const EnvelopeSpec& spec, int cell, double riser_m);

/// A probe's scene: the base tree with probe_overrides. Throws ConfigError.
Scene envelope_probe_scene(const EnvelopeSpec& spec, int cell, double riser_m, EnvelopeCriterion c);

/// Evaluates one criterion at one riser (never throws for a scene that cannot be
/// computed: that is a failed probe).
EnvelopeProbe evaluate_probe(const EnvelopeSpec& spec, int cell, double riser_m,
                             EnvelopeCriterion c);

/// The whole envelope. `log` (may be null) gets one line per cell and criterion.
EnvelopeResult compute_envelope(const EnvelopeSpec& spec, std::ostream* log);

/// Writes the hexdyn-envelope/2 file (io/schema.hpp) atomically. Throws IoError.
void write_envelope_file(const std::string& path, const EnvelopeSpec& spec,
                         const EnvelopeResult& result);

}  // namespace hexdyn
