"""Readers of hexdyn's files, with h5py only, driven by one table of file kinds
(FILE_KINDS): results (`hexdyn-result`), sweeps (`hexdyn-sweep`), envelopes
(`hexdyn-envelope`), replays (`hexdyn-replay`), robustness studies (`hexdyn-robustness`) and studies (`hexdyn-study`, of
analysis/study.py). Each row gives the kind's schema and the versions read (the schema's
current one; docs/user/output.md#versions-read), its checks at open, its reader and the type
it returns; open_file opens any of them, checked against its schema, and check_layout checks
any (also what the checks at open leave out).

The layout is the contract of docs/user/output.md, declared in src/hexdyn/io/schema.hpp and
reaching Python as the module hexdyn._schema, generated at build time from the compiled
declarations (hexdyn.schema: SCHEMA and the layouts). Shapes use size symbols: "T"
(samples), "n" (touchdowns), "m" (solver messages), "N" (scenarios), ...

    from hexdyn import open_result
    res = open_result("results/paper/paper.h5")   # a Result, the type hexdyn.run returns
    t = res["/time"]                 # numpy array, shape (T,)
    feet = res["/feet/position"]     # (T, L, 3), world frame [m], L = len(leg_names(res))
    res.units["/joints/torque"]      # "N m"
    res.config["terrain"]            # the resolved configuration (dict)
    res.urdf                         # robot as simulated (str)
    res.write("copy.h5")             # the file's objects, copied

    from hexdyn import open_sweep
    sw = open_sweep("results/sweeps/smoke/smoke.h5")
    sw.axes[0].key, sw.axes[0].values  # "terrain.riser_height", array([0.04, 0.08])
    sw.table["energy"]               # one value per scenario [J], NaN where failed
    sw.grid("energy")                # the same on the grid: shape sw.shape
    sw.run(5)                        # a Result from /runs/000005 (sweeps run with --keep-runs)
    sw.to_xarray(), sw.to_dataframe(), res.to_xarray()   # labelled (hexdyn.xr; xarray, pandas)

    env = open_envelope("envelope.h5")     # an Envelope; env.to_xarray() the /envelope group
    rep = open_replay("replay.h5")     # a Replay: rep["/joints/tracking_error"], rep.to_xarray()
    rob = open_robustness("rob.h5")        # a Robustness: rob.p_success, rob["/replays/failure"]
    st = open_study("study.h5")            # a Study: st.rows, st.verdict, st.references
    open_file("any.h5")                    # whichever kind the file is

Requires h5py, numpy and PyYAML (Debian: /usr/bin/python3); xarray only for to_xarray.
"""

import os

import h5py
import numpy as np

from .energy import ENERGY_RULE_CUBIC, ENERGY_RULE_TRAPEZOID, energy_by_rule
from .data import (Envelope, Replay, Result, Robustness, Study, Sweep, SweepAxis,
                   UnknownGroupError, check_group)
from .h5files import (check_datasets, check_declared, check_filetype_version,
                      check_regular_file, checked_path, datasets_below, decode_text,
                      element_of, file_identity, file_schema, group_attributes, io_error,
                      is_group_coordinate, meta_attributes, open_h5, python_value,
                      read_checked, read_datasets, shape_text, sizes_from_names,
                      yaml_attribute)
from .schema import (DECLARED, DYNAMICS_DATASETS, ENVELOPE_CASES_LAYOUT, ENVELOPE_LAYOUT,
                     ENVELOPE_REQUIRED, ENVELOPE_SCHEMA, ENVELOPE_SCHEMA_VERSION, FLAGS,
                     KINEMATIC_DATASETS, LEG_JOINT_COUNTS, META_ATTRIBUTES, META_GROUP,
                     MODEL_DATASETS, PHASE_IMPACT, PHASE_SUPPORT, PHASE_SWING, REPLAY_LAYOUT,
                     REPLAY_REQUIRED, REPLAY_SCHEMA, REPLAY_SCHEMA_VERSION, RESULT_LAYOUT,
                     ROBUSTNESS_LAYOUT, ROBUSTNESS_REQUIRED, ROBUSTNESS_SCHEMA,
                     ROBUSTNESS_SCHEMA_VERSION,
                     RESULT_REQUIRED, RESULT_SCHEMA, RESULT_SCHEMA_VERSION, SCENARIO_DATASETS,
                     SCENARIOS_GROUP, SCHEMA, SCHEMA_HEADER, SIZE_NAMES, SPECS, STUDY_GROUPS,
                     STUDY_SCHEMA, SWEEP_SIZE_NAMES,
                     STUDY_SCHEMA_VERSION, SWEEP_AXIS_COLUMN_LAYOUT, SWEEP_AXIS_LAYOUT,
                     SWEEP_AXIS_REQUIRED, SWEEP_META_ATTRIBUTES, SWEEP_ROOT_LAYOUT, SWEEP_SCHEMA,
                     SWEEP_SCHEMA_VERSION, SWEEP_STATUS, SWEEP_TABLE_LAYOUT,
                     SWEEP_TABLE_REQUIRED, AttributeSpec, DatasetSpec, FlagSpec,
                     expected_shape)


# ---------------------------------------------------------------------------- checks at open
# Each kind's checks of an open file (or kept run group) `root` whose schema and version
# were checked: every dataset against its declaration (hexdyn.h5files.check_datasets), from
# h5py's metadata alone. hexdyn.IoError in one line on a mismatch or a missing dataset.

def _envelope_layout(root):
    """An envelope's layout: with cases (/axes/case) the grids lead with the dimension D."""
    return ENVELOPE_CASES_LAYOUT if SCHEMA["kEnvelopeCaseLabels"].path in root else ENVELOPE_LAYOUT


def _by_layout(layout, required):
    """The checks at open of a kind whose datasets are all declared (a result, an envelope, a
    replay): each dataset of `layout` (a dict, or a function of the open root giving one)
    against its declaration, every one of `required` present; L and J the numbers of the
    root's leg and joint names (SIZE_NAMES)."""
    def check(root, source, kind):
        declared = layout(root) if callable(layout) else layout
        check_datasets(source, datasets_below(root), declared, required,
                       sizes_from_names(root, SIZE_NAMES), kind)
    return check


def _check_sweep(f, source, kind):
    """The table and the axes of a sweep file: every /scenarios column has N rows (N =
    len(/scenarios/id)) and its declared element type and columns (J: the number of
    /joint_names), /scenarios/axis_index (N, A) with A the groups of /axes, each axis's
    values and labels one length V, and N the product of those lengths. Kept runs
    (/runs/<id>) are checked when opened (Sweep.run)."""
    for group in ("scenarios", "axes"):
        if not isinstance(f.get(group), h5py.Group):
            raise io_error(f"{source}: no group /{group}, which every {kind} file has")
    axes = f["axes"]
    sizes = {"A": (len(axes), "/axes"), **sizes_from_names(f, SWEEP_SIZE_NAMES)}
    table = datasets_below(f, SCENARIOS_GROUP)
    check_datasets(source, table, SWEEP_TABLE_LAYOUT, SWEEP_TABLE_REQUIRED, sizes, kind)
    n = sizes["N"][0]
    lengths = []
    for i in range(len(axes)):
        if not isinstance(axes.get(str(i)), h5py.Group):
            raise io_error(f"{source}: no group /axes/{i} (/axes has {len(axes)} members)")
        axis_sizes = dict(sizes)
        layout = {p.replace("{i}", str(i)): s for p, s in SWEEP_AXIS_LAYOUT.items()}
        check_datasets(source, datasets_below(f, f"axes/{i}"), layout,
                       {p.replace("{i}", str(i)) for p in SWEEP_AXIS_REQUIRED}, axis_sizes, kind)
        lengths.append(axis_sizes["V"][0])
        column = {p.replace("{i}", str(i)): s for p, s in SWEEP_AXIS_COLUMN_LAYOUT.items()}
        check_datasets(source, table, column, set(), sizes, kind)
    declared = set(SWEEP_TABLE_LAYOUT) | {f"{SCENARIOS_GROUP}/axis_{i}" for i in range(len(axes))}
    others = {p: DECLARED[p] for p in table if p not in declared and p in DECLARED}
    check_datasets(source, table, others, set(), sizes, kind)  # e.g. coordinates
    declared |= set(others)
    for path, ds in table.items():  # the columns of /scenarios the schema does not name
        if path not in declared and (ds.shape is None or len(ds.shape) == 0 or ds.shape[0] != n):
            raise io_error(f"{source}: dataset {path} is {element_of(ds.dtype)} "
                           f"{shape_text(None if ds.shape is None else tuple(ds.shape))}, "
                           f"expected one row per scenario (N = {n} from /scenarios/id)")
    root = {p: f[p] for p in SWEEP_ROOT_LAYOUT if isinstance(f.get(p), h5py.Dataset)}
    check_datasets(source, root, SWEEP_ROOT_LAYOUT, set(), sizes, kind)
    if int(np.prod(lengths)) != n:
        raise io_error(f"{source}: dataset /scenarios/id has {n} rows, expected "
                       f"{int(np.prod(lengths))}, the product of the axis lengths {lengths}")


def _check_study(f, source, kind):
    """The groups /runs, /references and /verdict, every /runs column a one-dimensional
    dataset with one value per run."""
    for g in STUDY_GROUPS:
        if not isinstance(f.get(g), h5py.Group):
            raise io_error(f"{source}: no group /{g}, which every {kind} file has")
    n = None
    for name, ds in f["runs"].items():
        if not isinstance(ds, h5py.Dataset) or ds.shape is None or len(ds.shape) != 1:
            raise io_error(f"{source}: /runs/{name} is not a dataset of one value per run")
        if n is None:
            n = (ds.shape[0], name)
        elif ds.shape[0] != n[0]:
            raise io_error(f"{source}: dataset /runs/{name} has {ds.shape[0]} values, expected "
                           f"{n[0]} (from /runs/{n[1]})")


# ---------------------------------------------------------------------------- readers
# Each kind's reader of a checked root: the object it returns, every value in memory.

def _by_mapping(cls, text_arrays=False):
    """The reader of a kind whose object is a mapping of its datasets (Result, Envelope,
    Replay): every dataset by path (hexdyn.h5files.read_datasets), /meta, the other groups'
    attributes and where it was read (for Result.write)."""
    def read(root, source):
        data, units, shapes = read_datasets(datasets_below(root), source, text_arrays)
        filename = root.file.filename
        return cls(source, data, units, shapes, meta_attributes(root),
                   group_attributes(root, META_GROUP),
                   origin=(filename, root.name, file_identity(filename)))
    return read


def _columns(root, group, source):
    """The datasets of `group` (one level, "runs", "scenarios") read by name: (values, units)
    with each value a numpy array or a list of str."""
    data, units, _ = read_datasets(datasets_below(root, group), source)
    prefix = "/" + group.strip("/") + "/"
    values = {p[len(prefix):]: v if isinstance(v, list) else np.asarray(v)
              for p, v in data.items()}
    return values, {p[len(prefix):]: u for p, u in units.items()}


def _case_column(texts):
    """One key's values over the cases: a float array when every value is a number, else
    the list of texts (YAML, as /axes/<i>/case_values stores them)."""
    try:
        return np.array([float(t) for t in texts])
    except ValueError:
        return list(texts)


def _read_axis(g, source):
    values = read_checked(g["values"], source)
    units = None
    if not isinstance(values, list):
        values = np.asarray(values, dtype=float)
        attrs = g["values"].attrs
        units = decode_text(attrs["units"]) if "units" in attrs else None
    cases = None
    if "case_keys" in g:  # a cases axis: each key's value per case
        keys = read_checked(g["case_keys"], source)
        table = np.array(read_checked(g["case_values"], source), dtype=object).reshape(
            len(values), len(keys))
        cases = {k: _case_column([str(t) for t in table[:, n]]) for n, k in enumerate(keys)}
    return SweepAxis(read_checked(g["key"], source), values, read_checked(g["labels"], source),
                     cases, units)


def _read_sweep(f, source):
    axes = [_read_axis(f["axes"][str(i)], source) for i in range(len(f["axes"]))]
    table, units = _columns(f, SCENARIOS_GROUP, source)
    units = {name: units.get(name, "") for name in table}
    joint_names = read_checked(f["joint_names"], source) if "joint_names" in f else None
    run_ids = set(f["runs"].keys()) if "runs" in f else set()
    return Sweep(source, meta_attributes(f), axes, table, units, joint_names, run_ids)


def _read_study(f, source):
    rows, units = _columns(f, "runs", source)
    verdict = {k: python_value(v) for k, v in f["verdict"].attrs.items()}
    references, reference_data = {}, {}
    for name, g in f["references"].items():
        references[name] = {k: python_value(v) for k, v in g.attrs.items()}
        reference_data[name] = {k: read_checked(d, source) for k, d in g.items()
                                if isinstance(d, h5py.Dataset)}
    return Study(source, meta_attributes(f), rows, units, verdict, references, reference_data)


# ---------------------------------------------------------------------------- the file kinds
class FileKind:
    """One kind of hexdyn file, a row of FILE_KINDS.

    name             "hexdyn-result", the /meta schema without its version
    schema           the schema of the current version, "hexdyn-result/5" (what is written)
    versions         the versions this reader opens (a tuple)
    type             the type the reader returns (Result, Sweep, ...)
    check(root, source, schema)   the checks at open (datasets against their declarations)
    read(root, source)            the object, every value in memory
    layout(root)     the declared datasets, for check_layout's check of undeclared datasets
                     and their units (None: not checked)
    meta_attributes  the /meta attributes every file has (AttributeSpecs; check_layout)
    members          (group, kind name): each member group of `group` is a file of that kind
                     (a sweep's kept runs /runs/<id>), checked by check_layout
    """

    def __init__(self, schema, versions, type, check, read, layout=None, meta_attributes=(),
                 members=None):
        self.schema = schema
        self.name = schema.rsplit("/", 1)[0]
        self.versions = tuple(versions)
        self.type = type
        self.check = check
        self.read = read
        self.layout = layout
        self.meta_attributes = tuple(meta_attributes)
        self.members = members

    def check_version(self, root, source):
        """The file's version, after checking its /meta schema and schema_version
        (ValueError for another kind or a version not in `versions`)."""
        return check_filetype_version(root, self.schema, self.versions, source)

    def __repr__(self):
        return f"FileKind({self.schema!r}, versions={self.versions}, {self.type.__name__})"


# The versions read are those each file kind was released in (CHANGELOG.md, "File formats"):
# reading an older version too is one more number in its row. Results and sweeps of version 2
# (0.1.0) have the same paths; their energies are the trapezoid's, and /meta has no
# energy_rule. Results of version 3, sweeps of version 3 (their kept runs) and replays of
# version 1 have the same paths but /model/leg_joint_counts (schema.py LEG_JOINT_COUNTS).
# Results and sweeps of version 4 have the same paths but the drive train's
# /joints/drive_torque_lower_limit, the thermal model's /thermal/* and the sweep's thermal
# columns, none of them required.
FILE_KINDS = {k.name: k for k in (
    FileKind(RESULT_SCHEMA, (2, 3, 4, RESULT_SCHEMA_VERSION), Result,
             _by_layout(RESULT_LAYOUT, RESULT_REQUIRED), _by_mapping(Result),
             layout=lambda root: RESULT_LAYOUT, meta_attributes=SCHEMA["kResultMetaAttributes"]),
    FileKind(SWEEP_SCHEMA, (2, 3, 4, SWEEP_SCHEMA_VERSION), Sweep, _check_sweep, _read_sweep,
             meta_attributes=SCHEMA["kSweepMetaAttributes"], members=("runs", "hexdyn-result")),
    FileKind(ENVELOPE_SCHEMA, (ENVELOPE_SCHEMA_VERSION,), Envelope,
             _by_layout(_envelope_layout, ENVELOPE_REQUIRED), _by_mapping(Envelope, True),
             layout=_envelope_layout, meta_attributes=SCHEMA["kEnvelopeMetaAttributes"]),
    FileKind(REPLAY_SCHEMA, (1, 2, REPLAY_SCHEMA_VERSION), Replay,
             _by_layout(REPLAY_LAYOUT, REPLAY_REQUIRED), _by_mapping(Replay),
             layout=lambda root: REPLAY_LAYOUT, meta_attributes=SCHEMA["kReplayMetaAttributes"]),
    FileKind(ROBUSTNESS_SCHEMA, (ROBUSTNESS_SCHEMA_VERSION,), Robustness,
             _by_layout(ROBUSTNESS_LAYOUT, ROBUSTNESS_REQUIRED), _by_mapping(Robustness),
             layout=lambda root: ROBUSTNESS_LAYOUT,
             meta_attributes=SCHEMA["kRobustnessMetaAttributes"]),
    FileKind(STUDY_SCHEMA, (STUDY_SCHEMA_VERSION,), Study, _check_study, _read_study),
)}


def file_kind(root, source, expected=None):
    """The FileKind of an open file or group: `expected` (a kind's name, "hexdyn-result")
    when given, else the one its /meta schema names. ValueError naming the known schemas for
    a file of none."""
    if expected is not None:
        return FILE_KINDS[expected]
    schema = file_schema(root)
    kind = FILE_KINDS.get(schema.rsplit("/", 1)[0])
    if kind is None:
        known = ", ".join(k.schema for k in FILE_KINDS.values())
        raise ValueError(f"{source}: not a hexdyn file (/meta schema {schema!r}; known: {known})")
    return kind


def open_file(path, kind=None, group="/"):
    """Opens a hexdyn file, checks its schema and version and every dataset against the
    schema (the checks at open of its kind, from h5py's metadata alone) and returns the
    object of its kind (FILE_KINDS: a Result, Sweep, Envelope, Replay or Study) with every
    value in memory (the file is closed on return). `kind` ("hexdyn-result", ...) refuses a
    file of another kind; None takes the kind /meta names. `group` selects what is stored
    below the file root (a sweep's kept run "/runs/<id>", a result).

    Anything but a regular file raises hexdyn.IoError before it is opened
    (check_regular_file), as does a file HDF5 cannot read or a dataset off the schema;
    ValueError for a file of another kind, of a version this reader does not read, or a path
    with a NUL character."""
    path = checked_path(path)
    name = os.fsdecode(path)
    with open_h5(path) as f:
        root = f[group]
        source = name if group in ("/", "") else f"{name}:{group}"
        k = file_kind(root, source, kind)
        k.check_version(root, source)
        k.check(root, source, k.schema)
        return k.read(root, source)


def open_result(path, group="/"):
    """open_file of a result file (a Result, the type hexdyn.run returns; Result.write copies
    its objects); `group` a result stored below the file root ("/runs/<id>" of a sweep)."""
    return open_file(path, "hexdyn-result", group)


def open_sweep(path):
    """open_file of a sweep file: a Sweep with the axes and the scenario table (its kept runs
    are read and checked by Sweep.run)."""
    return open_file(path, "hexdyn-sweep")


def open_envelope(path):
    """open_file of an envelope file: an Envelope (hexdyn.xr.open_envelope: its Dataset)."""
    return open_file(path, "hexdyn-envelope")


def open_replay(path):
    """open_file of a replay file (`hexdyn replay`): a Replay."""
    return open_file(path, "hexdyn-replay")


def open_robustness(path):
    """open_file of a robustness file (`hexdyn robustness`): a Robustness."""
    return open_file(path, "hexdyn-robustness")


def open_study(path):
    """open_file of a study file (analysis/study.py): a Study."""
    return open_file(path, "hexdyn-study")


def _check_all(kind, root, source):
    kind.check_version(root, source)
    kind.check(root, source, kind.schema)
    check_declared(source, root, None if kind.layout is None else kind.layout(root),
                   kind.meta_attributes)
    if kind.members is not None:
        group, member = kind.members
        for name, g in (root[group].items() if group in root else ()):
            _check_all(FILE_KINDS[member], g, f"{source}:/{group}/{name}")


def check_layout(file, source=None):
    """Checks a hexdyn file against its schema, whichever kind it is: `file` a path or an
    open h5py File. The kind comes from /meta schema (FILE_KINDS): the checks at open of its
    kind, then (hexdyn.h5files.check_declared) no undeclared dataset, each with its declared
    units (results, envelopes, replays), every declared /meta attribute (results, sweeps,
    envelopes, replays), and each of a sweep's kept runs /runs/<id> as a result. Returns the
    schema name ("hexdyn-sweep/5"). hexdyn.IoError in one line naming the file and the
    dataset on a mismatch (and for a path that is no regular HDF5 file); ValueError for a
    file of no hexdyn schema or of a version this reader does not read."""
    if not isinstance(file, (h5py.File, h5py.Group)):
        path = checked_path(file)
        with open_h5(path) as f:
            return check_layout(f, source or os.fsdecode(path))
    source = source or file.file.filename
    kind = file_kind(file, source)
    _check_all(kind, file, source)
    return kind.schema


def _stored_names(file, path, what):
    """The names at `path` of `file`: an open h5py File or Group, a path, or an object
    hexdyn read (a Result or Replay by its datasets, a Sweep by its attribute `what`)."""
    if isinstance(file, (h5py.File, h5py.Group)):
        ds = file.get(path.lstrip("/"))
        if not isinstance(ds, h5py.Dataset):
            raise io_error(f"{file.file.filename}: no dataset {path}, the {what}")
        return tuple(read_checked(ds, file.file.filename))
    if isinstance(file, (str, bytes, os.PathLike)):
        with open_h5(checked_path(file)) as f:
            return _stored_names(f, path, what)
    if isinstance(file, Sweep):
        if getattr(file, what, None) is None:
            raise io_error(f"{file.path}: a sweep stores no {what}")
        return tuple(getattr(file, what))
    if path not in file:
        raise io_error(f"{file.path}: no dataset {path}, the {what}")
    return tuple(str(name) for name in file[path])


def leg_names(file):
    """The leg names of a result or replay (an open h5py File or Group, a path, a Result or
    Replay), /model/leg_names: the labels of the dimension `leg`, L of them."""
    return _stored_names(file, SIZE_NAMES["L"], "leg_names")


def joint_names(file):
    """The joint names of a result or replay (/model/joint_names) or of a sweep
    (/joint_names; a Sweep): the labels of the dimension `joint`, J of them."""
    is_sweep = isinstance(file, Sweep) or (isinstance(file, (h5py.File, h5py.Group)) and
                                           "model" not in file and "joint_names" in file)
    return _stored_names(file, (SWEEP_SIZE_NAMES if is_sweep else SIZE_NAMES)["J"],
                         "joint_names")


def shape_sizes(file):
    """{"L": legs, "J": joints} of a result or replay, the sizes of its shapes' leg and joint
    dimensions: expected_shape(spec.shape, T, **shape_sizes(res))."""
    return {"L": len(leg_names(file)), "J": len(joint_names(file))}


def joints_by_leg(legs, joints):
    """The indices into `joints` of each leg of `legs` (names), in leg order: joint k belongs
    to the leg whose name, followed by "_", begins its name (the labels of
    docs/theory/conventions.md#legs-and-joints: L1_coxa, L2_j4). ValueError in one line for a
    joint of no leg."""
    out = [[] for _ in legs]
    prefixes = [f"{name}_" for name in legs]
    for k, joint in enumerate(joints):
        owners = [i for i, prefix in enumerate(prefixes) if str(joint).startswith(prefix)]
        if not owners:
            raise ValueError(f"joint {joint!r} (index {k}) belongs to none of the legs "
                             f"{', '.join(map(str, legs))}")
        out[max(owners, key=lambda i: len(prefixes[i]))].append(k)
    return out


# The positional names of the joints of a leg of three joints, hip to foot
# (docs/theory/conventions.md#legs-and-joints); a leg of m joints otherwise: j1 ... jm.
THREE_JOINT_ROLES = ("coxa", "femur", "tibia")


def joint_roles(leg_joint_count):
    """The positional names of a leg's joints, hip to foot, whatever the description calls
    them: coxa, femur, tibia for a leg of three joints, else j1 ... jm (the suffixes of the
    labels L1_coxa, L2_j4 of docs/theory/conventions.md#legs-and-joints)."""
    if leg_joint_count == len(THREE_JOINT_ROLES):
        return THREE_JOINT_ROLES
    return tuple(f"j{j}" for j in range(1, leg_joint_count + 1))


def _has_dataset(file, path):
    """Whether `file` (as for leg_names) holds a dataset at `path`."""
    if isinstance(file, (h5py.File, h5py.Group)):
        return isinstance(file.get(path.lstrip("/")), h5py.Dataset)
    if isinstance(file, (str, bytes, os.PathLike)):
        with open_h5(checked_path(file)) as f:
            return _has_dataset(f, path)
    return not isinstance(file, Sweep) and path in file


def leg_joints(file):
    """The joints of each leg of a result or replay (as leg_names takes it): one list of
    indices into the dimension `joint` per leg, in leg order ([[0, 1, 2], [3, 4, 5], ...] for
    legs of three joints). A robot read from a URDF keeps its description's joint names: its
    /model/leg_mapping lists each leg's ("L1: J1 J2 J3 foot ..."); any other robot's are
    labelled by leg (joints_by_leg of /model/leg_names and /model/joint_names)."""
    legs, joints = leg_names(file), joint_names(file)
    mapping = SCHEMA["kModelLegMapping"].path
    if not _has_dataset(file, mapping):
        return joints_by_leg(legs, joints)
    index = {name: k for k, name in enumerate(joints)}
    out = []
    for entry in _stored_names(file, mapping, "leg_mapping"):
        words = str(entry).split()
        names = words[1:words.index("foot")] if "foot" in words else words[1:]
        missing = [n for n in names if n not in index]
        if missing:
            raise ValueError(f"{mapping} {entry!r}: joint {missing[0]} is not in "
                             f"{SIZE_NAMES['J']}")
        out.append([index[n] for n in names])
    return out


# The names the analysis scripts, the tests and the docs use as hexdyn.results.NAME.
__all__ = [
    "FILE_KINDS", "FileKind", "file_kind", "open_file", "open_result", "open_sweep",
    "open_envelope", "open_replay", "open_study", "check_layout", "leg_names", "joint_names",
    "shape_sizes", "leg_joints", "joints_by_leg", "joint_roles", "THREE_JOINT_ROLES",
    "Result", "Sweep", "SweepAxis", "Envelope", "Replay", "Study", "UnknownGroupError",
    "check_group", "checked_path", "check_regular_file", "open_h5", "decode_text",
    "check_filetype_version", "is_group_coordinate", "yaml_attribute", "io_error",
    "SCHEMA", "SCHEMA_HEADER", "DatasetSpec", "FlagSpec", "AttributeSpec", "SPECS", "DECLARED",
    "FLAGS", "RESULT_SCHEMA", "RESULT_SCHEMA_VERSION", "SWEEP_SCHEMA", "SWEEP_SCHEMA_VERSION",
    "ENVELOPE_SCHEMA", "ENVELOPE_SCHEMA_VERSION", "REPLAY_SCHEMA", "REPLAY_SCHEMA_VERSION",
    "STUDY_SCHEMA", "STUDY_SCHEMA_VERSION", "META_GROUP", "META_ATTRIBUTES",
    "SWEEP_META_ATTRIBUTES", "LEG_JOINT_COUNTS", "MODEL_DATASETS", "KINEMATIC_DATASETS",
    "DYNAMICS_DATASETS",
    "SCENARIOS_GROUP", "SCENARIO_DATASETS", "SWEEP_STATUS", "PHASE_SWING", "PHASE_IMPACT",
    "PHASE_SUPPORT", "SIZE_NAMES", "SWEEP_SIZE_NAMES",
    "expected_shape",
    "ENERGY_RULE_CUBIC", "ENERGY_RULE_TRAPEZOID", "energy_by_rule",
]
