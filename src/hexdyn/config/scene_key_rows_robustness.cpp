// The rows of the keys of robustness: (scene_key_table.hpp; docs/user/configuration.md#robustness),
// read by config/scene_read_robustness.cpp.
#include "hexdyn/config/scene_key_rows.hpp"

namespace hexdyn {

using namespace scene_keys;

namespace {

constexpr std::string_view kPerturbations =
    "riser_height tread_depth nosing friction payload_mass payload_com trunk_mass link_mass "
    "torque_constant resistance joint_friction foot_placement contact_stiffness";

void add_study(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robustness"};
  add({.path = "robustness.replays",
       .kind = KeyKind::kInteger,
       .range = closed(1, kMaxRobustnessReplays),
       .unit = "1",
       .default_text = "`100`",
       .meaning = "perturbed worlds a robustness study replays the plan on "
                  "([robustness](docs/user/robustness.md)); in a sweep, every scenario's study"});
  add({.path = "robustness.seed",
       .kind = KeyKind::kInteger,
       .range = closed(0, 2147483647),
       .unit = "1",
       .default_text = "`1`",
       .meaning = "seed of the draws: replay i's world depends on the seed and i alone "
                  "([draws](docs/theory/robustness.md#draws))"});
  add({.path = "robustness.perturbations.*.distribution",
       .instances = kPerturbations,
       .kind = KeyKind::kChoice,
       .choices = "normal uniform",
       .default_text = "no error",
       .meaning = "the error of each quantity, drawn independently per replay (and per step, "
                  "link or joint): `normal` truncated at ±`bound`, or `uniform` on [`low`, "
                  "`high`]; added in the quantity's unit, or relative (× (1 + error)) for the "
                  "masses, actuators and contact stiffness "
                  "([perturbations](docs/user/robustness.md#perturbations))"});
  add({.path = "robustness.perturbations.*.sigma",
       .instances = kPerturbations,
       .range = nonnegative(1e6),
       .default_text = "required (normal)",
       .meaning = "standard deviation of a normal error, in its unit"});
  add({.path = "robustness.perturbations.*.bound",
       .instances = kPerturbations,
       .range = nonnegative(1e6),
       .default_text = "3 `sigma`",
       .meaning = "largest \\|error\\| of a normal error"});
  add({.path = "robustness.perturbations.*.low",
       .instances = kPerturbations,
       .range = closed(-1e6, 1e6),
       .default_text = "required (uniform)",
       .meaning = "smallest error of a uniform error"});
  add({.path = "robustness.perturbations.*.high",
       .instances = kPerturbations,
       .range = closed(-1e6, 1e6),
       .default_text = "required (uniform)",
       .meaning = "largest error of a uniform error (≥ `low`; `low` = `high` fixes it)"});
}

void add_failure(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robustness"};
  add({.path = "robustness.failure.drift",
       .range = positive(100.0),
       .unit = "m",
       .default_text = "half the shallowest going (5 cm off stairs)",
       .meaning = "largest horizontal distance of the trunk's end from the plan's end"});
  add({.path = "robustness.failure.slip",
       .range = positive(100.0),
       .unit = "m",
       .default_text = "`0.02`",
       .meaning = "largest slip distance of one foot over the replay"});
  add({.path = "robustness.failure.saturation",
       .range = nonnegative(1e6),
       .unit = "s",
       .default_text = "`0.05`",
       .meaning = "longest time one joint's drive may spend at its torque–speed bound"});
  add({.path = "robustness.failure.stub_tilt",
       .range = closed(0.0, M_PI / 2.0),
       .unit = "rad",
       .default_text = "π/4",
       .meaning = "a foot the plan has in swing, loaded on a face tilted more than this from "
                  "the horizontal (a riser, a nosing), has stubbed its toe"});
  add({.path = "robustness.failure.stub_force",
       .range = nonnegative(10.0),
       .unit = "1",
       .default_text = "`0.01`",
       .meaning = "the load that counts for a stub, as a share of the robot's weight"});
}

void add_tolerance(std::deque<SceneKey>& t) {
  const SectionRows add{t, "robustness"};
  add({.path = "robustness.tolerance.replays",
       .kind = KeyKind::kInteger,
       .range = closed(1, kMaxRobustnessReplays),
       .unit = "1",
       .default_text = "`100` (no search without `robustness.tolerance`)",
       .meaning = "replays per scale of the search for each perturbation's largest "
                  "tolerated error ([tolerated error](docs/user/robustness.md#tolerated-error))"});
  add({.path = "robustness.tolerance.max_scale",
       .range = positive(1e6),
       .unit = "1",
       .default_text = "`4`",
       .meaning = "largest scale of a distribution searched"});
  add({.path = "robustness.tolerance.bisections",
       .kind = KeyKind::kInteger,
       .range = closed(0, 30),
       .unit = "1",
       .default_text = "`5`",
       .meaning = "halvings of the scale interval after the probe at `max_scale`"});
  add({.path = "robustness.tolerance.target",
       .range = closed(0.0, 1.0),
       .unit = "1",
       .default_text = "`0.95`",
       .meaning = "the success fraction a tolerated scale keeps"});
}

}  // namespace

void add_robustness_key_rows(std::deque<SceneKey>& table) {
  add_study(table);
  add_failure(table);
  add_tolerance(table);
}

}  // namespace hexdyn
