"""The layout of hexdyn's files as Python data: every declaration of the schema headers and,
for each file kind, what its files hold.

The layout is declared once, in the C++ headers src/hexdyn/io/schema.hpp (and the parts it
includes). The module hexdyn._schema holds those declarations as Python data: it is
generated at build time from the compiled declarations (bindings/python/schema/schema_py.cpp,
cmake/python.cmake) and lies next to this module in the build tree and in an installation.
SCHEMA is {constant name: value} of every declaration, in the order of the headers; the
readers (hexdyn.results) check files against the layouts below, which are built from it.

Shapes use size symbols: "T" (samples), "L" (legs) and "J" (joints) of the robot, "n"
(touchdowns), "m" (solver messages), "N" (scenarios), "A" (axes), "V" (values of an axis), ...
L and J are the file's own: the lengths of its names (SIZE_NAMES, SWEEP_SIZE_NAMES).
"""

from . import _schema

SCHEMA_HEADER = "src/hexdyn/io/schema.hpp"  # the header _schema was generated from


class DatasetSpec:
    """A dataset of the contract: path (may hold "{i}", "{id}" or "{key}"), units ("" no
    `units` attribute; "key" the unit of a sweep axis's key), shape (a tuple of ints and
    size symbols "T", "n", "m", "N", "A", "V", ...), element ("float64", "int8", "int32",
    "int64", "string"), long_name, dims (the netCDF dimension names of its axes);
    `name` is the C++ constant (kTime)."""

    def __init__(self, name, path, units, shape, element, long_name="", dims=()):
        self.name, self.path, self.units, self.shape, self.element = (
            name, path, units, tuple(shape), element)
        self.long_name, self.dims = long_name, tuple(dims)

    def __iter__(self):  # (shape, units, element), the tuples of the tables below
        return iter((self.shape, self.units, self.element))

    def __repr__(self):
        return f"DatasetSpec({self.path!r}, {self.units!r}, {self.shape}, {self.element!r})"


class FlagSpec:
    """CF flags of a dataset of codes 0, 1, ...: `path` and the words of `meanings`."""

    def __init__(self, const, path, meanings):
        self.const, self.path = const, path
        self.meanings = meanings.split() if isinstance(meanings, str) else list(meanings)

    def __repr__(self):
        return f"FlagSpec({self.path!r}, {self.meanings})"


class AttributeSpec:
    """An attribute of the contract: `name` on the object `object` (may hold "{i}")."""

    def __init__(self, const, obj, name, element):
        self.const, self.object, self.name, self.element = const, obj, name, element

    def __repr__(self):
        return f"AttributeSpec({self.object!r}, {self.name!r}, {self.element!r})"


def schema_declarations(module=_schema):
    """{constant name: value} of the generated schema module, in the order of the headers:
    str or int (CONSTANTS), DatasetSpec, AttributeSpec, FlagSpec, list of str (TEXT_LISTS) or
    list of the declarations a std::array list holds (LISTS)."""
    decls = {}
    for name in module.ORDER:
        if name in module.CONSTANTS:
            decls[name] = module.CONSTANTS[name]
        elif name in module.DATASETS:
            decls[name] = DatasetSpec(name, *module.DATASETS[name])
        elif name in module.ATTRIBUTES:
            decls[name] = AttributeSpec(name, *module.ATTRIBUTES[name])
        elif name in module.FLAGS:
            decls[name] = FlagSpec(name, *module.FLAGS[name])
        elif name in module.TEXT_LISTS:
            decls[name] = list(module.TEXT_LISTS[name])
        else:
            decls[name] = [decls[item] for item in module.LISTS[name][1]]
    return decls


SCHEMA = schema_declarations()

RESULT_SCHEMA = SCHEMA["kResultSchema"]
RESULT_SCHEMA_VERSION = SCHEMA["kResultSchemaVersion"]
SWEEP_SCHEMA = SCHEMA["kSweepSchema"]
SWEEP_SCHEMA_VERSION = SCHEMA["kSweepSchemaVersion"]
ENVELOPE_SCHEMA = SCHEMA["kEnvelopeSchema"]
ENVELOPE_SCHEMA_VERSION = SCHEMA["kEnvelopeSchemaVersion"]
REPLAY_SCHEMA = SCHEMA["kReplaySchema"]
REPLAY_SCHEMA_VERSION = SCHEMA["kReplaySchemaVersion"]
ROBUSTNESS_SCHEMA = SCHEMA["kRobustnessSchema"]
ROBUSTNESS_SCHEMA_VERSION = SCHEMA["kRobustnessSchemaVersion"]
# hexdyn-study/1 is written by analysis/study.py, not by the C++ side: no header declares it.
STUDY_SCHEMA = "hexdyn-study/1"
STUDY_SCHEMA_VERSION = 1
STUDY_GROUPS = ("runs", "references", "verdict")

META_GROUP = SCHEMA["kMetaGroup"]
META_ATTRIBUTES = tuple(a.name for a in SCHEMA["kResultMetaAttributes"])
SWEEP_META_ATTRIBUTES = tuple(a.name for a in SCHEMA["kSweepMetaAttributes"])

# path -> DatasetSpec, which unpacks as (shape, units, element)
MODEL_DATASETS = {d.path: d for d in SCHEMA["kModelDatasets"]}
KINEMATIC_DATASETS = {d.path: d for d in SCHEMA["kKinematicDatasets"]}
DYNAMICS_DATASETS = {d.path: d for d in SCHEMA["kDynamicsDatasets"]}

# /scenarios/<name>: one row per scenario (N rows, A axes), keyed by <name>. Metrics are
# NaN where status != 0. The per-axis columns /scenarios/axis_<i> (SCHEMA
# "kScenarioAxisNumbers" / "kScenarioAxisWords") hold each scenario's value of axis i.
SCENARIOS_GROUP = SCHEMA["kScenariosGroup"]
SCENARIO_DATASETS = {d.path[len(SCENARIOS_GROUP) + 1:]: d for d in SCHEMA["kScenarioDatasets"]}
# Status names by code (/scenarios/status).
SWEEP_STATUS = tuple(SCHEMA["kScenarioStatusNames"])

# Every dataset declaration by its path (a result's, a sweep's, an envelope's; paths of
# different file kinds do not collide but for the templates of the sweep axes).
SPECS = {}
# Every declaration of each path, in declaration order (an envelope with cases declares its
# grids again with the leading dimension `case`; an axis of numbers or of words).
DECLARED = {}
for _spec in SCHEMA.values():
    if isinstance(_spec, DatasetSpec):
        SPECS.setdefault(_spec.path, _spec)
        DECLARED.setdefault(_spec.path, []).append(_spec)
FLAGS = {f.path: f.meanings for f in SCHEMA.values() if isinstance(f, FlagSpec)}

PHASE_SWING, PHASE_IMPACT, PHASE_SUPPORT = 0, 1, 2

# The sizes L (legs) and J (joints) of the shapes are the robot's: the per-leg and per-joint
# datasets of a file have one row per name it stores, at these paths (a result's and a
# replay's; a sweep's J: its /joint_names). hexdyn.results.leg_names and joint_names read
# the names of an open file, shape_sizes its L and J.
SIZE_NAMES = {"L": SCHEMA["kModelLegNames"].path, "J": SCHEMA["kModelJointNames"].path}
SWEEP_SIZE_NAMES = {"J": SCHEMA["kSweepJointNames"].path}


def expected_shape(shape, samples=None, impacts=None, messages=None, **sizes):
    """Concrete shape of a contract shape tuple ("T" -> samples, "n", "m"; other
    symbols by keyword, e.g. N=8, A=3, and L, J of the file: **shape_sizes(file)); None for
    a symbol not given."""
    sizes = {"T": samples, "n": impacts, "m": messages, **sizes}
    return tuple(sizes.get(d) if isinstance(d, str) else d for d in shape)


# ---------------------------------------------------------------------------- layouts
# What each file kind holds, as checked at open, and which of it every file has. The
# declarations that fix a size come first: /time (T), /scenarios/id (N), the envelope's axes
# (W, B, S, C; D, K).
def layout(*declarations):
    """{path: [DatasetSpec, ...]} in declaration order, for the checks at open: a path declared
    twice with different element types (an axis of numbers or of words) accepts either."""
    out = {}
    for decls in declarations:
        for d in decls:
            alternatives = out.setdefault(d.path, [])
            if all(a.element != d.element for a in alternatives):
                alternatives.append(d)
    return out


def coordinate_lists(kind):
    """Every declaration list of coordinate variables of a file kind ("Result": the lists
    kResult*Coordinates), in declaration order."""
    return [v for k, v in SCHEMA.items() if k.startswith(f"k{kind}") and
            k.endswith("Coordinates") and isinstance(v, list) and
            all(isinstance(d, DatasetSpec) for d in v)]


RESULT_LAYOUT = layout([SCHEMA["kTime"]], SCHEMA["kModelDatasets"], SCHEMA["kUrdfRobotDatasets"],
                       SCHEMA["kKinematicDatasets"], SCHEMA["kSphereFootDatasets"],
                       SCHEMA["kHeightMapDatasets"],
                       SCHEMA["kDynamicsDatasets"], SCHEMA["kRequiredFrictionDatasets"],
                       SCHEMA["kDriveTrainDatasets"], SCHEMA["kThermalDatasets"],
                       *coordinate_lists("Result"))
# /model/leg_joint_counts is new in layout version 4 (results) and 2 (replays): files of the
# versions before, which the readers open too, have none.
LEG_JOINT_COUNTS = SCHEMA["kModelLegJointCounts"].path
RESULT_REQUIRED = {d.path for d in (*SCHEMA["kModelDatasets"], *SCHEMA["kKinematicDatasets"])
                   if d.path != LEG_JOINT_COUNTS}

SWEEP_TABLE_LAYOUT = layout([SCHEMA["kScenarioId"]], SCHEMA["kScenarioDatasets"])
SWEEP_TABLE_REQUIRED = {SCHEMA[k].path for k in ("kScenarioId", "kScenarioAxisIndex",
                                                 "kScenarioStatus")}
SWEEP_AXIS_COLUMN_LAYOUT = layout([SCHEMA["kScenarioAxisNumbers"], SCHEMA["kScenarioAxisWords"]])
SWEEP_AXIS_LAYOUT = layout([SCHEMA[k] for k in ("kAxisKey", "kAxisNumbers", "kAxisWords",
                                                "kAxisLabels", "kAxisCaseKeys",
                                                "kAxisCaseValues")])
SWEEP_AXIS_REQUIRED = {SCHEMA[k].path for k in ("kAxisKey", "kAxisNumbers", "kAxisLabels")}
SWEEP_ROOT_LAYOUT = layout([SCHEMA["kSweepJointNames"]], *coordinate_lists("Sweep"))

ENVELOPE_LAYOUT = layout(SCHEMA["kEnvelopeDatasets"], SCHEMA["kEnvelopeGripDatasets"],
                         *coordinate_lists("Envelope"))
# With cases: the case axes first, then the grid with its leading dimension D.
_ENVELOPE_CASES = layout(SCHEMA["kEnvelopeCaseDatasets"])
ENVELOPE_CASES_LAYOUT = {**{p: s for p, s in _ENVELOPE_CASES.items() if p not in ENVELOPE_LAYOUT},
                         **{p: _ENVELOPE_CASES.get(p, s) for p, s in ENVELOPE_LAYOUT.items()}}
ENVELOPE_REQUIRED = {d.path for d in SCHEMA["kEnvelopeDatasets"]}

# hexdyn-replay (schema_replay.hpp): the replayed motion in the result file's names and the
# replay's own, the robot and terrain copied from the result, the report; every replay file
# has all three lists. A dataset of the replay's own (a kReplay* declaration) in none of them
# is checked when present. The coordinates are those of a result (leg, joint, xyz, wxyz, and
# the index ones of the dimensions it uses: gait_cycle, terrain_point).
_REPLAY_LISTS = (SCHEMA["kReplaySeriesDatasets"], SCHEMA["kReplayModelDatasets"],
                 SCHEMA["kReplayReportDatasets"])
_REPLAY_OWN = [d for name, d in SCHEMA.items()
               if name.startswith("kReplay") and isinstance(d, DatasetSpec)]
REPLAY_LAYOUT = layout(*_REPLAY_LISTS, _REPLAY_OWN, *coordinate_lists("Replay"),
                       *coordinate_lists("Result"))
REPLAY_REQUIRED = {d.path for decls in _REPLAY_LISTS for d in decls if d.path != LEG_JOINT_COUNTS}

# hexdyn-robustness (schema_robustness.hpp): every file has the replays' outcomes and the
# summary; the perturbations the study names, their coordinates (step, link, joint, xyz) and a
# tolerance search's datasets are checked when present.
ROBUSTNESS_LAYOUT = layout(SCHEMA["kRobustnessDatasets"], SCHEMA["kRobustToleranceDatasets"],
                           SCHEMA["kRobustPerturbationDatasets"],
                           SCHEMA["kRobustPerturbationCoordinates"],
                           [SCHEMA["kJointCoordinate"], SCHEMA["kXyzCoordinate"]])
ROBUSTNESS_REQUIRED = {d.path for d in SCHEMA["kRobustnessDatasets"]}
