// The rows of the keys of contact, replay, allocation and output (scene_key_table.hpp;
// docs/user/configuration.md#contact and the sections after it).
#include "hexdyn/config/run_limits.hpp"
#include "hexdyn/config/scene_key_rows.hpp"
#include "hexdyn/core/value_bounds.hpp"

namespace hexdyn {

using namespace scene_keys;
namespace f = key_fields;

namespace {

void add_contact(std::deque<SceneKey>& t) {
  const SectionRows add{t, "contact"};
  const KeyRead table = KeyRead::kTable;
  add({.path = "contact.model",
       .kind = KeyKind::kChoice,
       .choices = "compliant rigid",
       .meaning = "`compliant`: each touchdown is an impact transient under the IMPACT "
                  "law; `rigid`: the foot supports from touchdown on, no transient",
       .read = table,
       .field = f::choice<&Scene::contact, &ContactParams::model>()});
  add({.path = "contact.touchdown",
       .kind = KeyKind::kChoice,
       .choices = "paper loaded",
       .meaning = "`loaded`: a touchdown's force rises through the impact and settles at the "
                  "leg's share of the load, and the leg supports from touchdown on; `paper`: "
                  "the isolated leg's impact, whose force falls back to zero "
                  "([contact](docs/theory/contact.md#loaded-touchdowns))",
       .read = table,
       .field = f::choice<&Scene::contact, &ContactParams::touchdown>()});
  add({.path = "contact.stiffness",
       .range = positive(1e15),
       .required = true,
       .allowed_text = "(0, 1e15] N/m^e",
       .meaning = "K",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::stiffness>()});
  add({.path = "contact.exponent",
       .range = closed(1.0, 5.0),
       .unit = "1",
       .required = true,
       .meaning = "e",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::exponent>()});
  add({.path = "contact.damping_max",
       .range = nonnegative(1e12),
       .unit = "N s/m",
       .required = true,
       .meaning = "C_max",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::damping_max_Nspm>()});
  add({.path = "contact.full_damping_depth",
       .range = positive(1.0),
       .unit = "m",
       .required = true,
       .meaning = "p, the penetration at which damping is full",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::full_damping_depth_m>()});
  add({.path = "contact.friction_coefficient",
       .range = positive(10.0),
       .unit = "1",
       .required = true,
       .meaning = "μ",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::friction_coefficient>()});
}

/// The forward replay's friction law (docs/theory/replay.md#tangential-force).
void add_contact_friction(std::deque<SceneKey>& t) {
  const SectionRows add{t, "contact"};
  const KeyRead table = KeyRead::kTable;
  add({.path = "contact.static_friction",
       .range = positive(10.0),
       .unit = "1",
       .default_text = "`contact.friction_coefficient`",
       .meaning = "μ_s of the forward replay's friction law "
                  "([replay](docs/theory/replay.md#tangential-force))"});
  add({.path = "contact.dynamic_friction",
       .range = positive(10.0),
       .unit = "1",
       .default_text = "μ_s",
       .allowed_text = "[0, μ_s]",
       .meaning = "μ_d, beyond `contact.friction_velocity`"});
  add({.path = "contact.stiction_velocity",
       .range = positive(10.0),
       .unit = "m/s",
       .meaning = "v_s, where μ reaches μ_s",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::stiction_velocity_mps>()});
  add({.path = "contact.friction_velocity",
       .range = positive(100.0),
       .unit = "m/s",
       .default_text = "max(1e-2, 10 v_s)",
       .allowed_text = "(v_s, 100] m/s",
       .meaning = "v_d, from where μ is μ_d"});
  add({.path = "contact.friction_law",
       .kind = KeyKind::kChoice,
       .choices = "stick_slip regularised",
       .meaning = "the replay's tangential law: `stick_slip`, a spring k_t to an anchor "
                  "capped at μ_s F_n, sliding at μ_d F_n "
                  "([stick–slip](docs/theory/replay.md#stick-slip)); `regularised`, μ(v) "
                  "through v_s and v_d",
       .read = table,
       .field = f::choice<&Scene::contact, &ContactParams::friction_law>()});
  add({.path = "contact.tangential_stiffness",
       .range = positive(1e12),
       .unit = "N/m",
       .meaning = "k_t of `stick_slip`",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::tangential_stiffness_Npm>()});
  add({.path = "contact.tangential_damping",
       .range = nonnegative(1e12),
       .unit = "N s/m",
       .meaning = "c_t of `stick_slip`",
       .read = table,
       .field = f::number<&Scene::contact, &ContactParams::tangential_damping_Nspm>()});
}

void add_replay(std::deque<SceneKey>& t) {
  const SectionRows add{t, "replay"};
  const KeyRead table = KeyRead::kTable;
  add({.path = "replay.kp",
       .range = nonnegative(1e9),
       .unit = "N m/rad",
       .default_text = "`auto`",
       .allowed_text = "[0, 1e9] N m/rad, or `auto`",
       .meaning = "joint PD stiffness on the planned angles (0 with `kd` 0: open loop); `auto`: "
                  "10 N m/rad, or 1.1 m g l per rad for a robot whose weight moment m g l "
                  "(l the longest leg's reach) exceeds 50 N m "
                  "([docs/user/replay.md](docs/user/replay.md#gains))",
       .field = f::number<&Scene::replay, &ReplayParams::kp_Nmprad>()});
  add({.path = "replay.kd",
       .range = nonnegative(1e9),
       .unit = "N m s/rad",
       .default_text = "`auto`",
       .allowed_text = "[0, 1e9] N m s/rad, or `auto`",
       .meaning = "joint PD damping on the planned rates; `auto`: the stiffness times 0.01 s",
       .field = f::number<&Scene::replay, &ReplayParams::kd_Nmsprad>()});
  add({.path = "replay.step",
       .range = positive(0.1),
       .unit = "s",
       .meaning = "the integrator's largest step",
       .read = table,
       .field = f::number<&Scene::replay, &ReplayParams::step_s>()});
  add({.path = "replay.tolerance",
       .range = positive(10.0),
       .unit = "1",
       .meaning = "a step is halved while the normal contact force it applied differs "
                  "from the law at its end by more than this × the robot's weight",
       .read = table,
       .field = f::number<&Scene::replay, &ReplayParams::tolerance>()});
  add({.path = "replay.saturate",
       .kind = KeyKind::kChoice,
       .choices = "true false",
       .meaning = "with `actuators:`, bound each joint's drive torque by the torque–speed "
                  "envelope the allocation used, at the replayed joint speed, and report the "
                  "time each joint spent at its bound "
                  "([replay](docs/theory/replay.md#driven-by-the-actuators))",
       .read = table,
       .field = f::flag<&Scene::replay, &ReplayParams::saturate>()});
  add({.path = "replay.early_contact",
       .kind = KeyKind::kChoice,
       .choices = "follow hold",
       .meaning = "a foot that meets the terrain while the plan still swings it: `follow`, the "
                  "PD keeps damping towards the planned rates; `hold`, on a face it could stand "
                  "on (within atan μ_s of level), it damps that leg towards holding its foot "
                  "still until the plan's touchdown, as a controller that detects contact does "
                  "([early contact](docs/theory/replay.md#early-contact))",
       .read = table,
       .field = f::choice<&Scene::replay, &ReplayParams::early_contact>()});
}

void add_allocation(std::deque<SceneKey>& t) {
  const SectionRows add{t, "allocation"};
  const KeyRead table = KeyRead::kTable;
  add({.path = "allocation.friction",
       .kind = KeyKind::kChoice,
       .choices = "pyramid4 pyramid8 cone",
       .meaning = "4- or 8-sided pyramid inscribed in the friction cone, or the exact "
                  "cone \\|F_t\\| ≤ μ F_n",
       .read = table,
       .field = f::choice<&Scene::allocation, &AllocationParams::friction>()});
  add({.path = "allocation.solver",
       .kind = KeyKind::kChoice,
       .choices = "auto active-set ipopt",
       .meaning = "`auto` is `active-set`: hexdyn's dense dual active-set QP, and for the "
                  "exact cone the same QP under sequential outer approximation; `ipopt`: "
                  "Ipopt, the reference, for every friction model"});
  add({.path = "allocation.torque_limit",
       .range = positive(kMaxJointEffort_Nm),
       .unit = "N m",
       .required = true,
       .default_text = "required (URDF robot: `effort`)",
       .allowed_text = "(0, 1e6] N m; URDF robot also `effort`",
       .meaning = "\\|τ\\| bound of every joint; `effort`: each joint's URDF effort "
                  "limit"});
  add({.path = "allocation.min_normal_force",
       .range = nonnegative(1e6),
       .unit = "N",
       .meaning = "least normal force of a support foot",
       .read = table,
       .field = f::number<&Scene::allocation, &AllocationParams::min_normal_force_N>()});
  add({.path = "allocation.tolerance",
       .range = positive(),
       .unit = "1",
       .allowed_text = "(0, 1e-5]",
       .meaning = "solver tolerance; looser solves would miss the fixed 1e-6 violation "
                  "threshold below",
       .read = table,
       .field = f::number<&Scene::allocation, &AllocationParams::tolerance>()});
  add({.path = "allocation.slack_penalty",
       .range = positive(1e12),
       .unit = "1",
       .meaning = "ρ of the exact L1 penalty used when the problem is infeasible",
       .read = table,
       .field = f::number<&Scene::allocation, &AllocationParams::slack_penalty>()});
  add({.path = "allocation.objective",
       .kind = KeyKind::kChoice,
       .choices = "torque_squared copper_loss",
       .meaning = "Σ τ² (the paper's eq. 9; with actuators, of the drive torques), or "
                  "the actuators' copper loss Σ R I² (needs `actuators`; "
                  "[drive-train.md](docs/theory/drive-train.md#objective))",
       .field = f::choice<&Scene::allocation, &AllocationParams::objective>()});
}

void add_output(std::deque<SceneKey>& t) {
  const SectionRows add{t, "output"};
  const KeyRead table = KeyRead::kTable;
  add({.path = "output.sample_step",
       .range = positive(kMaxSampleStep_s),
       .unit = "s",
       .required = true,
       .meaning = "step of the uniform grid (the paper: 0.05 s)",
       .read = table,
       .field = f::number<&Scene::output, &OutputParams::sample_step_s>()});
  add({.path = "output.grid",
       .kind = KeyKind::kChoice,
       .choices = "uniform adaptive",
       .meaning = "`adaptive`: the uniform grid refined at every touchdown and lift-off",
       .read = table,
       .field = f::choice<&Scene::output, &OutputParams::grid>()});
  add({.path = "output.impact_samples",
       .kind = KeyKind::kInteger,
       .range = closed(1, 100000),
       .unit = "1",
       .meaning = "adaptive: intervals across each touchdown transient (its exact peak "
                  "instant is added)",
       .read = table,
       .field = f::integer<&Scene::output, &OutputParams::impact_samples>()});
  add({.path = "output.event_step",
       .range = positive(100.0),
       .unit = "s",
       .allowed_text = "(0, 100] s, at most `sample_step`",
       .meaning = "adaptive: finest step next to touchdowns and lift-offs, graded "
                  "geometrically (×2) up to `sample_step`",
       .read = table,
       .field = f::number<&Scene::output, &OutputParams::event_step_s>()});
  add({.path = "output.tolerance",
       .range = closed(0.0, 0.1),
       .unit = "1",
       .meaning = "adaptive: relative error the grid is refined to, for the energies "
                  "(total and per joint) and the peaks (joint torque, total power, "
                  "contact force); `0`: the grid as built, not refined "
                  "([error control](docs/theory/output-grid.md#error-control))",
       .read = table,
       .field = f::number<&Scene::output, &OutputParams::tolerance>()});
  add({.path = "output.compression",
       .kind = KeyKind::kChoice,
       .choices = "deflate none",
       .meaning = "`deflate`: numeric datasets of at least 4 KiB chunked and compressed "
                  "with shuffle + deflate; `none`: every dataset contiguous and "
                  "uncompressed, about 1.7 times the size and faster to read "
                  "([output.md](docs/user/output.md#compression)). A sweep's or envelope's own "
                  "datasets follow its base scene",
       .read = table,
       .field = f::flag<&Scene::output, &OutputParams::compress>()});
  add({.path = "output.required_friction",
       .kind = KeyKind::kChoice,
       .choices = "true false",
       .meaning = "compute each sample's required friction, the least μ for which its "
                  "rows admit a force distribution, and write "
                  "`/contacts/required_friction` and `/contacts/required_friction_leg` "
                  "([theory/grip.md](docs/theory/grip.md#required-friction)); `false` saves "
                  "its cost (the utilised friction and the slip flags are always written)",
       .read = table,
       .field = f::flag<&Scene::output, &OutputParams::required_friction>()});
}

}  // namespace

void add_run_key_rows(std::deque<SceneKey>& table) {
  add_contact(table);
  add_contact_friction(table);
  add_replay(table);
  add_allocation(table);
  add_output(table);
}

}  // namespace hexdyn
