"""Readers of hexdyn's files, with h5py only: results (`hexdyn-result/3`), sweeps
(`hexdyn-sweep/3`), envelopes (`hexdyn-envelope/2`), replays (`hexdyn-replay/1`) and studies
(`hexdyn-study/1`, of analysis/study.py); results and sweeps of version 2 open too (the
same paths; their energies by the trapezoid), and of version 1 (mapped to version 2 on
reading). Every file is checked against its schema when opened;
check_layout checks any.

The layout is the contract of docs/user/output.md, declared in src/hexdyn/io/schema.hpp and
reaching Python as the module hexdyn._schema, generated at build time from the compiled
declarations (SCHEMA below). Shapes use size symbols: "T" (samples), "n" (touchdowns), "m"
(solver messages), "N" (scenarios), ...

    from hexdyn import open_result
    res = open_result("results/paper/paper.h5")   # a Result, the type hexdyn.run returns
    t = res["/time"]                 # numpy array, shape (T,)
    feet = res["/feet/position"]     # (T, 6, 3), world frame [m]
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
    rep = open_replay("replay.h5")         # a Replay: rep["/joints/tracking_error"], rep.to_xarray()
    st = open_study("study.h5")            # a Study: st.rows, st.verdict, st.references

Requires h5py, numpy and PyYAML (Debian: /usr/bin/python3); xarray only for to_xarray.
"""

import os
import secrets
import stat
from collections.abc import Mapping

import h5py
import numpy as np
import yaml


def checked_path(path):
    """os.fspath(path) (a str or bytes path; TypeError for anything else), after refusing a
    path with a NUL character with a ValueError in one line: the C++ side and the operating
    system stop at the first NUL, so "paper.yaml\\0junk" would name paper.yaml. Every function of
    the package that takes a path calls this first."""
    text = os.fspath(path)
    if ("\0" if isinstance(text, str) else b"\0") in text:
        raise ValueError(f"path {text!r} contains a NUL character")
    return text


# ---------------------------------------------------------------------------- the schema
# The layout is declared once, in the C++ headers src/hexdyn/io/schema.hpp (and the parts it
# includes). The module hexdyn._schema holds those declarations as Python data: it is
# generated at build time from the compiled declarations (bindings/python/schema/schema_py.cpp,
# cmake/python.cmake) and lies next to this module in the build tree and in an installation.
# SCHEMA below is {constant name: value} of every declaration, in the order of the headers.
from . import _schema  # noqa: E402
from .atomic_file import output_error, publish_atomically, why_not_replaceable  # noqa: E402

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

# Every dataset declaration by its path (a result's, a sweep's, an envelope's; paths of
# different file kinds do not collide but for the templates of the sweep axes).
SPECS = {}
for _spec in SCHEMA.values():
    if isinstance(_spec, DatasetSpec):
        SPECS.setdefault(_spec.path, _spec)
FLAGS = {f.path: f.meanings for f in SCHEMA.values() if isinstance(f, FlagSpec)}
# Every declaration of each path, in declaration order (an envelope with cases declares its
# grids again with the leading dimension `case`; an axis of numbers or of words).
DECLARED = {}
for _spec in SCHEMA.values():
    if isinstance(_spec, DatasetSpec):
        DECLARED.setdefault(_spec.path, []).append(_spec)

# Versions this reader opens: the current one, 2 (the same paths, its energies the trapezoid
# over /power/total: no /meta energy_rule) and 1 (mapped on reading, V1_RENAMED).
READABLE_VERSIONS = (1, 2, RESULT_SCHEMA_VERSION)
ENVELOPE_SCHEMA = SCHEMA["kEnvelopeSchema"]
ENVELOPE_SCHEMA_VERSION = SCHEMA["kEnvelopeSchemaVersion"]
# Envelope files of version 1 differ only in /envelope/limit and /envelope/message, stored
# flattened (W·B·S·C strings).
READABLE_ENVELOPE_VERSIONS = (1, ENVELOPE_SCHEMA_VERSION)


def _layout(*declarations):
    """{path: [DatasetSpec, ...]} in declaration order, for the checks at open: a path declared
    twice with different element types (an axis of numbers or of words) accepts either."""
    out = {}
    for decls in declarations:
        for d in decls:
            alternatives = out.setdefault(d.path, [])
            if all(a.element != d.element for a in alternatives):
                alternatives.append(d)
    return out


# What each file kind holds, as checked at open (check_result_datasets, check_sweep_file,
# check_envelope_file), and which of it every file has. The declarations that fix a size
# come first: /time (T), /scenarios/id (N), the envelope's axes (W, B, S, C; D, K).
def _coordinate_lists(kind):
    """Every declaration list of coordinate variables of a file kind ("Result": the lists
    kResult*Coordinates), in declaration order."""
    return [v for k, v in SCHEMA.items() if k.startswith(f"k{kind}") and
            k.endswith("Coordinates") and isinstance(v, list) and
            all(isinstance(d, DatasetSpec) for d in v)]


RESULT_LAYOUT = _layout([SCHEMA["kTime"]], SCHEMA["kModelDatasets"], SCHEMA["kUrdfRobotDatasets"],
                        SCHEMA["kKinematicDatasets"], SCHEMA["kSphereFootDatasets"],
                        SCHEMA["kDynamicsDatasets"], SCHEMA["kRequiredFrictionDatasets"],
                        SCHEMA["kDriveTrainDatasets"], *_coordinate_lists("Result"))
RESULT_REQUIRED = {d.path for d in (*SCHEMA["kModelDatasets"], *SCHEMA["kKinematicDatasets"])}
RESULT_V1_REQUIRED = {SCHEMA["kTime"].path}
SWEEP_TABLE_LAYOUT = _layout([SCHEMA["kScenarioId"]], SCHEMA["kScenarioDatasets"])
SWEEP_TABLE_REQUIRED = {SCHEMA[k].path for k in ("kScenarioId", "kScenarioAxisIndex",
                                                 "kScenarioStatus")}
SWEEP_AXIS_COLUMN_LAYOUT = _layout([SCHEMA["kScenarioAxisNumbers"], SCHEMA["kScenarioAxisWords"]])
SWEEP_AXIS_LAYOUT = _layout([SCHEMA[k] for k in ("kAxisKey", "kAxisNumbers", "kAxisWords",
                                                 "kAxisLabels", "kAxisCaseKeys",
                                                 "kAxisCaseValues")])
SWEEP_AXIS_REQUIRED = {SCHEMA[k].path for k in ("kAxisKey", "kAxisNumbers", "kAxisLabels")}
SWEEP_ROOT_LAYOUT = _layout([SCHEMA["kSweepJointNames"]], *_coordinate_lists("Sweep"))
ENVELOPE_LAYOUT = _layout(SCHEMA["kEnvelopeDatasets"], SCHEMA["kEnvelopeGripDatasets"],
                          *_coordinate_lists("Envelope"))
# With cases: the case axes first, then the grid with its leading dimension D.
_ENVELOPE_CASES = _layout(SCHEMA["kEnvelopeCaseDatasets"])
ENVELOPE_CASES_LAYOUT = {**{p: s for p, s in _ENVELOPE_CASES.items() if p not in ENVELOPE_LAYOUT},
                         **{p: _ENVELOPE_CASES.get(p, s) for p, s in ENVELOPE_LAYOUT.items()}}
ENVELOPE_REQUIRED = {d.path for d in SCHEMA["kEnvelopeDatasets"]}
ENVELOPE_V1_FLATTENED = (SCHEMA["kEnvelopeLimit"].path, SCHEMA["kEnvelopeMessage"].path)

# hexdyn-replay/1 (schema_replay.hpp): the replayed motion in the result file's names and the
# replay's own, the robot and terrain copied from the result, the report; every replay file
# has all three lists. A dataset of the replay's own (a kReplay* declaration) in none of them
# is checked when present. The coordinates are those of a result (leg, joint, xyz, wxyz, and
# the index ones of the dimensions it uses: gait_cycle, terrain_point).
REPLAY_SCHEMA = SCHEMA["kReplaySchema"]
REPLAY_SCHEMA_VERSION = SCHEMA["kReplaySchemaVersion"]
_REPLAY_LISTS = (SCHEMA["kReplaySeriesDatasets"], SCHEMA["kReplayModelDatasets"],
                 SCHEMA["kReplayReportDatasets"])
_REPLAY_OWN = [d for name, d in SCHEMA.items()
               if name.startswith("kReplay") and isinstance(d, DatasetSpec)]
REPLAY_LAYOUT = _layout(*_REPLAY_LISTS, _REPLAY_OWN, *_coordinate_lists("Replay"),
                        *_coordinate_lists("Result"))
REPLAY_REQUIRED = {d.path for decls in _REPLAY_LISTS for d in decls}

# hexdyn-result/1 paths renamed in version 2 (version 1 -> 2); /impacts/leg counted from 1.
V1_RENAMED = {"/power/joint": "/power/per_joint", "/energy/joint": "/energy/per_joint"}

PHASE_SWING, PHASE_IMPACT, PHASE_SUPPORT = 0, 1, 2
LEG_NAMES = tuple(f"L{i}" for i in range(1, 7))
JOINT_NAMES = tuple(f"L{i}_{j}" for i in range(1, 7) for j in ("coxa", "femur", "tibia"))


def decode_text(value):
    """str from an HDF5 string value (h5py gives str or bytes depending on storage; a 0-d
    array holds one). The one decoder of hexdyn's HDF5 text: the readers and analysis/ use it."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.shape == ():
        return decode_text(value[()])
    return value


def check_filetype_version(h5_root, expected_schema, expected_version, source="file",
                           require_version=True):
    """Raise ValueError unless <h5_root>/meta names `expected_schema` and version
    (`expected_version` an int or a tuple of the versions accepted); the version found.

    `h5_root` is an open h5py File or Group; `source` names it in messages. A schema
    "hexdyn-result/1" is accepted for an expected "hexdyn-result/3" when 1 is among the
    accepted versions.
    """
    accepted = expected_version if isinstance(expected_version, tuple) else (expected_version,)
    if "meta" not in h5_root:
        raise ValueError(f"{source}: not a {expected_schema} file (no /meta group)")
    attrs = h5_root["meta"].attrs
    if "schema" not in attrs:
        raise ValueError(f"{source}: not a {expected_schema} file (/meta has no 'schema')")
    schema = decode_text(attrs["schema"])
    base = expected_schema.rsplit("/", 1)[0]
    if schema in {f"{base}/{v}" for v in accepted}:
        schema = expected_schema
    if schema != expected_schema:
        raise ValueError(f"{source}: file schema is {schema!r}, expected {expected_schema!r}")
    if "schema_version" not in attrs:
        if require_version:
            raise ValueError(f"{source}: /meta has no 'schema_version' "
                             f"(expected {expected_version})")
        return accepted[-1]
    version = attrs["schema_version"]
    try:
        version = int(np.asarray(version).item())
    except (TypeError, ValueError):
        raise ValueError(f"{source}: /meta schema_version {version!r} is not an integer")
    if version not in accepted:
        raise ValueError(f"{source}: {expected_schema} schema_version is {version}, this reader "
                         f"supports {', '.join(map(str, accepted))}")
    return version


class UnknownGroupError(KeyError, ValueError):
    """to_xarray(group) of a group the file does not have; the message names the known ones."""

    def __str__(self):
        return str(self.args[0]) if self.args else ""


def yaml_attribute(meta, name, source):
    """The /meta attribute `name` parsed as YAML (a dict; {} when absent or empty);
    ValueError naming the file when it is not YAML."""
    try:
        return yaml.safe_load(meta.get(name, "") or "") or {}
    except yaml.YAMLError as e:
        raise ValueError(f"{source}: /meta {name} is not valid YAML: "
                         f"{str(e).splitlines()[0]}") from None


class _Datasets(Mapping):
    """A file's datasets by path (`self.data`, `self.source`): the mapping of Result,
    Envelope and Replay."""

    def __getitem__(self, path):
        try:
            return self.data[path]
        except KeyError:
            raise KeyError(f"{self.source}: no dataset {path}") from None

    def __contains__(self, path):
        return path in self.data

    def __iter__(self):
        return iter(self.data)

    def __len__(self):
        return len(self.data)

    def paths(self):
        return sorted(self.data)

    def groups(self):
        """The groups that hold datasets ("/" for the root), sorted: what to_xarray takes."""
        return sorted({p.rpartition("/")[0] or "/" for p in self.data})


class Result(_Datasets):
    """One hexdyn-result/3 result in memory, computed (hexdyn.run) or read (open_result,
    Sweep.run): a read-only mapping from dataset path ("/joints/torque") to its values.

    res[path]        numpy array of the file's dtype and shape; text as str, a list of texts
                     as a list of str (read) or a numpy array of str (computed)
    res.units[path]  the `units` attribute (datasets that have one)
    res.shapes[path] the shape
    res.meta         the /meta attributes by name (str, int, float)
    res.attrs        res.meta and the other groups' attributes as "/terrain/type"
    res.config       the resolved configuration (/meta config_yaml) as a dict
    res.urdf         /model/urdf, the robot as simulated
    res.source       where it came from: the file (FILE or FILE:/runs/<id>) or the scene run
    res.to_xarray(group=None)   labelled (xarray); res.write(path) the file

    write(path) writes the hexdyn-result/3 file: a computed result through the compiled
    writer (the file `hexdyn run` writes), a read one as a copy of the objects of the file it
    was read from (see write)."""

    def __init__(self, source, data, units, shapes, meta, attributes=None, handle=None,
                 origin=None):
        self.source = source
        self.data = data
        self.units = units
        self.shapes = shapes
        self.meta = meta
        self.attributes = dict(attributes or {})
        self.urdf = data.get("/model/urdf", "")
        self._handle = handle    # the compiled RunHandle of a computed result
        self._origin = origin    # (file, group, identity) of a read result
        self._config = None

    @property
    def attrs(self):
        """The /meta attributes by name and the other groups' as "/terrain/type"."""
        return {**self.meta, **self.attributes}

    @property
    def config(self):
        """The resolved configuration (dict); ValueError if config_yaml is not YAML."""
        if self._config is None:
            self._config = yaml_attribute(self.meta, "config_yaml", self.source)
        return self._config


    @property
    def computed(self):
        """True for a result of hexdyn.run, False for one read from a file."""
        return self._handle is not None

    @property
    def samples(self):
        """T, the number of output samples."""
        return int(self.shapes["/time"][0])

    @property
    def has_dynamics(self):
        return "/joints/torque" in self.data

    def to_xarray(self, group=None):
        """The datasets as an xarray.Dataset with named dimensions and coordinates (time,
        leg, joint, xyz, ...): `group` ("joints", "/contacts") gives that group's datasets
        under their own names, as xarray.open_dataset(file, group=...) does; None all of
        them in one Dataset, named by path ("joints/torque" -> "joints_torque"). A group
        the result does not have raises UnknownGroupError (a KeyError and a ValueError)
        naming the known ones. Needs xarray (hexdyn.xr)."""
        check_group(self, group)
        from hexdyn import xr
        return xr.result_to_xarray(self, group)

    def write(self, path):
        """Writes the hexdyn-result/3 file of this result to `path`, atomically (a temporary
        file in the target's folder, renamed when complete; nothing is left at `path` on an
        error) and never onto an input: `path` must be a new path or a regular file that is
        none of the files the result came from.

        A computed result (hexdyn.run) goes through the compiled writer: the file `hexdyn run
        -o` writes, with its checks of the path against the scene's input files.

        A read result (open_result, Sweep.run) is written as a copy of the objects of the file
        (or kept run group) it was read from, made with h5py: every group, dataset (values,
        type, shape, storage: chunks, compression) and attribute, the dimension scales
        attached again in the copy, so that the file is the one hexdyn wrote, byte for byte in
        each dataset and attribute (a kept run of a sweep becomes a file of its own; /meta
        keeps its created_utc). The source must be unchanged since it was read (same size and
        modification time), and `path` none of it, its hard links, nor the files its /meta
        input_sha256 lists, nor a link or a special file. The copy is built in memory and
        written with write(2) (hexdyn.atomic_file: a full disk is one line with the OS's
        reason, the temporary name fits any valid name); a signal that would end Python
        (SIGTERM, SIGHUP, ...) removes the temporary file and ends the process with one line
        and 128 + signal, Ctrl-C raises KeyboardInterrupt with that line; nothing is written
        in either case (docs/user/faults.md#pythons-writer).

        Errors: hexdyn.IoError with one line; ValueError for a path with a NUL character."""
        if self._handle is not None:
            from . import _hexdyn
            _hexdyn.write(self._handle, checked_path(path))
            return
        write_copy(self._origin, checked_path(path), _listed_inputs(self.meta))

    def __repr__(self):
        kind = "computed" if self.computed else "read"
        return (f"Result({self.source!r}, {kind}, T={self.samples}, "
                f"dynamics={self.has_dynamics}, datasets={len(self.data)})")


def check_group(obj, group):
    """Raises UnknownGroupError unless `group` (None: all) is one of obj.groups()."""
    if group is None:
        return
    name = "/" + str(group).strip("/")
    known = obj.groups()
    if name not in known:
        raise UnknownGroupError(f"{obj.source}: no group {name!r} holding datasets (groups: "
                                f"{', '.join(known)})")


def is_group_coordinate(path, obj, root):
    """True for a group coordinate (docs/user/output.md#dimensions-and-coordinates): in a
    group below `root` (a file, or a sweep's kept run /runs/<id>), the copy G/D of the root's
    coordinate D that the group's datasets are attached to, so that the group opened alone
    has its coordinates. `path` is relative to `root` ("/joints/time"). It is an HDF5
    dimension scale, declared by no table of the schema, and `root` has a dataset of its
    name. The readers leave it out: the root's D is read once."""
    if path.count("/") < 2 or path in DECLARED or not isinstance(obj, h5py.Dataset):
        return False
    return (isinstance(root.get(path.rsplit("/", 1)[1]), h5py.Dataset)  # relative to root
            and bool(h5py.h5ds.is_scale(obj.id)))


def _read_dataset(ds):
    string_info = h5py.check_string_dtype(ds.dtype)
    if string_info is not None:
        values = ds.asstr()[()]
        if ds.shape == ():
            return decode_text(values)
        return [decode_text(v) for v in np.asarray(values).ravel()]
    return ds[()]


def _file_identity(path):
    """What tells a file apart from another, and from itself after a change."""
    st = os.stat(path)
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _group_attributes(group, skip):
    """{"/GROUP/NAME": value} of the attributes of the groups below `group` but `skip`
    (paths relative to `group`), values as Python values."""
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Group) and "/" + name != skip:
            for key, value in obj.attrs.items():
                out[f"/{name}/{key}"] = _python_value(value)
    group.visititems(visit)
    return out


def read_result_group(group, source="result"):
    """Reads a result laid out under an open h5py File or Group (e.g. a sweep's
    /runs/<id>) after checking its schema and every dataset's element type and shape
    (check_result_datasets). Returns a Result."""
    version = check_filetype_version(group, RESULT_SCHEMA, READABLE_VERSIONS, source)
    datasets = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and not is_group_coordinate("/" + name, obj, group):
            path = "/" + name
            datasets[V1_RENAMED.get(path, path) if version == 1 else path] = obj

    group.visititems(visit)
    check_result_datasets(datasets, version, source)
    data, units, shapes = {}, {}, {}
    for path, obj in datasets.items():
        data[path] = _read_checked(obj, source)
        if version == 1 and path == "/impacts/leg":
            data[path] = data[path] - 1  # 1-based in version 1
        shapes[path] = tuple(obj.shape)
        if "units" in obj.attrs:
            units[path] = decode_text(obj.attrs["units"])
    filename = group.file.filename
    origin = (filename, group.name, _file_identity(filename))
    return Result(source, data, units, shapes, _meta_attributes(group),
                  _group_attributes(group, META_GROUP), origin=origin)


def _one_line(text):
    """`text` on one line, as hexdyn's messages are (core/errors.hpp one_line)."""
    return str(text).replace("\n", "\\n").replace("\r", "\\r")


def _io_error(message):
    """hexdyn.IoError (an OSError) when the compiled part is there, else OSError; the
    message on one line."""
    message = _one_line(message)
    try:
        from . import _hexdyn
        return _hexdyn.IoError(message)
    except ImportError:
        return OSError(message)


def check_regular_file(path):
    """Raises hexdyn.IoError with one line unless `path` names a regular file (a link to one
    counts): a FIFO, a device, a socket or a directory is refused before anything opens it
    (opening a FIFO for reading waits for a writer, for ever). ValueError for a path with a
    NUL character (checked_path)."""
    path = checked_path(path)
    try:
        mode = os.stat(path).st_mode
    except OSError as e:
        raise _io_error(f"{os.fsdecode(path)}: cannot be read: {e.strerror}") from None
    if stat.S_ISREG(mode):
        return
    kind = ("a FIFO" if stat.S_ISFIFO(mode) else "a directory" if stat.S_ISDIR(mode) else
            "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else
            "a socket" if stat.S_ISSOCK(mode) else "a special file")
    raise _io_error(f"{os.fsdecode(path)}: is {kind}, not a regular file")


def open_h5(path):
    """h5py.File(path, "r") of a regular file (check_regular_file); a file HDF5 cannot open
    (not HDF5, truncated, damaged) raises hexdyn.IoError with one line naming it."""
    path = checked_path(path)
    check_regular_file(path)
    try:
        return h5py.File(path, "r")
    except OSError as e:
        raise _io_error(f"{os.fsdecode(path)}: cannot be read as HDF5: "
                        f"{str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__}"
                        ) from None


def _read_checked(ds, source):
    """_read_dataset, with a failed read (a damaged file) as hexdyn.IoError naming the
    dataset."""
    try:
        return _read_dataset(ds)
    except (OSError, UnicodeDecodeError) as e:
        raise _io_error(f"{source}: dataset {ds.name} cannot be read: "
                        f"{str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__}"
                        ) from None


# ---------------------------------------------------------------------------- checks at open
# Every dataset the schema declares is checked against its declaration when a file is
# opened, from h5py's metadata alone (dtype, shape; no data is read): its element type and
# its shape, each size symbol ("T", "N", "W", ...) fixed by the first dataset that has it
# (/time for T, /scenarios/id for N, the axes of an envelope). A dataset declared for every
# file must be there; others may be absent. A mismatch raises hexdyn.IoError with one line
# naming the file, the dataset, what was found and what was expected.

def _element_of(dtype):
    """The schema's element name of an h5py dtype ("float64", "int8", "string", ...)."""
    if h5py.check_string_dtype(dtype) is not None:
        return "string"
    kinds = {"f": "float", "i": "int", "u": "uint"}
    if dtype.kind in kinds and dtype.fields is None:
        return f"{kinds[dtype.kind]}{8 * dtype.itemsize}"
    return str(dtype)


def _shape_text(shape):
    if shape is None:
        return "with no dataspace"
    return "(" + ", ".join(map(str, shape)) + ("," if len(shape) == 1 else "") + ")"


def _check_dataset(source, path, ds, specs, sizes):
    """`ds` (an h5py.Dataset at `path`) against its declarations `specs` (alternatives of
    element type, one shape); `sizes` {symbol: (size, dataset it came from)} is completed with
    the symbols this dataset fixes first."""
    elements = [s.element for s in specs]
    shape = specs[0].shape
    found_element = _element_of(ds.dtype)
    found = None if ds.shape is None else tuple(ds.shape)
    expected = tuple(d if isinstance(d, int) else sizes.get(d, (None,))[0] for d in shape)
    if (found_element not in elements or found is None or len(found) != len(shape)
            or any(e is not None and e != n for e, n in zip(expected, found))):
        want = tuple(d if e is None else e for d, e in zip(shape, expected))
        whence = [f"{d} = {sizes[d][0]} from {sizes[d][1]}" for d in shape
                  if isinstance(d, str) and d in sizes]
        raise _io_error(f"{source}: dataset {path} is {found_element} {_shape_text(found)}, "
                        f"expected {' or '.join(elements)} {_shape_text(want)}"
                        + (f" ({', '.join(whence)})" if whence else ""))
    for d, n in zip(shape, found):
        if isinstance(d, str) and d not in sizes:
            sizes[d] = (n, path)


def _check_layout(source, datasets, layout, required, sizes, kind):
    """Each dataset of `layout` ({path: [DatasetSpec]}) present in `datasets` ({path:
    h5py.Dataset}) checked, in the layout's order; one of `required` missing raises."""
    for path, specs in layout.items():
        if path in datasets:
            _check_dataset(source, path, datasets[path], specs, sizes)
        elif path in required:
            raise _io_error(f"{source}: no dataset {path}, which every {kind} file has")


def _datasets_in(group, prefix):
    """{prefix/name: h5py.Dataset} of the datasets directly in `group` (`prefix` its path in
    the file), group coordinates left out."""
    return {f"{prefix}/{name}": obj for name, obj in group.items()
            if isinstance(obj, h5py.Dataset)
            and not is_group_coordinate(f"{prefix}/{name}", obj, group.file)}


def check_result_datasets(datasets, version, source):
    """Checks a result's datasets ({path: h5py.Dataset}, paths of version 2) against the
    schema: element type, and shape with T = len(/time) and the declared column counts (n
    touchdowns, m messages, ... as their first dataset has them). hexdyn.IoError in one line
    on a mismatch or a missing dataset of every file (version 1: /time only)."""
    _check_layout(source, datasets, RESULT_LAYOUT,
                  RESULT_REQUIRED if version >= 2 else RESULT_V1_REQUIRED, {}, RESULT_SCHEMA)


def check_sweep_file(f, source):
    """Checks the table and the axes of an open sweep file against the schema: every
    /scenarios column has N rows (N = len(/scenarios/id)) and its declared element type and
    columns, /scenarios/axis_index (N, A) with A the groups of /axes, each axis's values and
    labels one length V, and N the product of those lengths. hexdyn.IoError in one line on a
    mismatch. Kept runs (/runs/<id>) are checked when opened (Sweep.run)."""
    for group in ("scenarios", "axes"):
        if not isinstance(f.get(group), h5py.Group):
            raise _io_error(f"{source}: no group /{group}, which every {SWEEP_SCHEMA} file has")
    axes = f["axes"]
    sizes = {"A": (len(axes), "/axes")}
    table = _datasets_in(f["scenarios"], SCENARIOS_GROUP)
    _check_layout(source, table, SWEEP_TABLE_LAYOUT, SWEEP_TABLE_REQUIRED, sizes, SWEEP_SCHEMA)
    n = sizes["N"][0]
    lengths = []
    for i in range(len(axes)):
        if not isinstance(axes.get(str(i)), h5py.Group):
            raise _io_error(f"{source}: no group /axes/{i} (/axes has {len(axes)} members)")
        axis_sizes = dict(sizes)
        layout = {p.replace("{i}", str(i)): s for p, s in SWEEP_AXIS_LAYOUT.items()}
        _check_layout(source, _datasets_in(axes[str(i)], f"/axes/{i}"), layout,
                      {p.replace("{i}", str(i)) for p in SWEEP_AXIS_REQUIRED}, axis_sizes,
                      SWEEP_SCHEMA)
        lengths.append(axis_sizes["V"][0])
        column = {p.replace("{i}", str(i)): s for p, s in SWEEP_AXIS_COLUMN_LAYOUT.items()}
        _check_layout(source, table, column, set(), sizes, SWEEP_SCHEMA)
    declared = set(SWEEP_TABLE_LAYOUT) | {f"{SCENARIOS_GROUP}/axis_{i}" for i in range(len(axes))}
    others = {p: DECLARED[p] for p in table if p not in declared and p in DECLARED}
    _check_layout(source, table, others, set(), sizes, SWEEP_SCHEMA)  # e.g. coordinates
    declared |= set(others)
    for path, ds in table.items():  # the columns of /scenarios the schema does not name
        if path not in declared and (ds.shape is None or len(ds.shape) == 0 or ds.shape[0] != n):
            raise _io_error(f"{source}: dataset {path} is {_element_of(ds.dtype)} "
                            f"{_shape_text(None if ds.shape is None else tuple(ds.shape))}, "
                            f"expected one row per scenario (N = {n} from /scenarios/id)")
    root = {p: f[p] for p in SWEEP_ROOT_LAYOUT if isinstance(f.get(p), h5py.Dataset)}
    _check_layout(source, root, SWEEP_ROOT_LAYOUT, set(), sizes, SWEEP_SCHEMA)
    if int(np.prod(lengths)) != n:
        raise _io_error(f"{source}: dataset /scenarios/id has {n} rows, expected "
                        f"{int(np.prod(lengths))}, the product of the axis lengths {lengths}")


def check_envelope_file(f, source):
    """Checks an open envelope file's schema and version and every dataset against the
    schema: the grids (W, B, S, C) after the axes /axes/tread_depth, duty_factor, peak_speed
    and criteria, (D, W, B, S, C) with cases (D = len(/axes/case)), the posture grids (W, B,
    S), the probes one length P; version 1's flattened /envelope/limit and message W·B·S·C.
    hexdyn.IoError in one line on a mismatch; ValueError for another schema (as
    check_filetype_version). Returns the file's version."""
    version = check_filetype_version(f, ENVELOPE_SCHEMA, READABLE_ENVELOPE_VERSIONS, source)
    datasets = _all_datasets(f)
    cases = SCHEMA["kEnvelopeCaseLabels"].path in datasets
    layout = ENVELOPE_CASES_LAYOUT if cases else ENVELOPE_LAYOUT
    sizes = {}
    if version == 1:
        axes = {p: layout[p] for p in (SCHEMA[k].path for k in (
            "kEnvelopeTreadDepth", "kEnvelopeDutyFactor", "kEnvelopePeakSpeed",
            "kEnvelopeCriteria"))}
        _check_layout(source, datasets, axes, set(axes), sizes, ENVELOPE_SCHEMA)
        sizes["G"] = (int(np.prod([sizes[d][0] for d in "WBSC"])), "W·B·S·C")
        layout = dict(layout)
        for p in ENVELOPE_V1_FLATTENED:
            d = layout[p][0]
            layout[p] = [DatasetSpec(d.name, d.path, d.units, ("G",), d.element)]
    _check_layout(source, datasets, layout, ENVELOPE_REQUIRED, sizes, ENVELOPE_SCHEMA)
    return version


ENERGY_RULE_CUBIC = SCHEMA["kEnergyRuleCubic"]
ENERGY_RULE_TRAPEZOID = SCHEMA["kEnergyRuleTrapezoid"]


def _abs_polynomial_integrals(c):
    """∫_0^1 |Σ_i c[..., i] u^i| du for polynomial coefficients c (..., n), lowest first: where
    the polynomial keeps its sign at 33 points of [0, 1] the signed integral, elsewhere split at
    its real roots in (0, 1) (numpy.roots)."""
    n = c.shape[-1]
    u = np.linspace(0.0, 1.0, 33)
    values = np.einsum("...i,ui->...u", c, u[:, None] ** np.arange(n))
    signed = np.sum(c / np.arange(1, n + 1), axis=-1)
    out = np.abs(signed)
    mixed = (values.min(axis=-1) < 0) & (values.max(axis=-1) > 0)
    for index in zip(*np.nonzero(mixed)):
        coef = c[index]
        roots = np.roots(coef[::-1]) if np.any(coef[1:]) else np.array([])
        cuts = np.sort([r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 1])
        points = np.r_[0.0, cuts, 1.0]
        anti = np.r_[0.0, coef / np.arange(1, n + 1)]  # antiderivative coefficients
        prim = np.polynomial.polynomial.polyval(points, anti)
        out[index] = np.sum(np.abs(np.diff(prim)))
    return out


def energy_by_rule(time, power, sample_kind, rule=ENERGY_RULE_CUBIC, per_interval=False):
    """The energies (per column of `power`, J) recomputed from /time (T), /power/per_joint
    (T×J, signed) and /sample_kind (T) by the rule /meta energy_rule names (schema.hpp
    kEnergyRuleCubic, docs/theory/output-grid.md#energy-from-the-samples): per piece between a
    left-limit sample (kind 1) and its event, each interval integrates |p| of the polynomial
    interpolating the 4 samples nearest it in the piece (3 on a piece of 2 intervals, 2 on one
    of 1), a left limit's interval the trapezoid; or the trapezoid of |power|. /energy/total is
    their sum. A computation of its own (Vandermonde systems, numpy.roots), not the writer's.
    With per_interval, the integral over each interval instead ((T − 1)×J): they add up to the
    energies, so that a share of the energy (over some of the intervals) is by the same rule."""
    t = np.asarray(time, dtype=float)
    P = np.asarray(power, dtype=float).reshape(len(t), -1)
    h = np.diff(t)
    A = np.abs(P)
    trapezoid = 0.5 * h[:, None] * (A[1:] + A[:-1])
    if rule == ENERGY_RULE_TRAPEZOID:
        return trapezoid if per_interval else trapezoid.sum(axis=0)
    if rule != ENERGY_RULE_CUBIC:
        raise ValueError(f"unknown energy rule {rule!r}")
    kind = np.zeros(len(t), dtype=int) if sample_kind is None else np.asarray(sample_kind)
    ends = [int(k) for k in np.nonzero(kind[:-1] == 1)[0]] + [len(t) - 1]
    interval = np.zeros_like(trapezoid)
    s = 0
    for e in ends:
        if e < len(t) - 1:
            interval[e] = trapezoid[e]  # the left limit's interval
        n = e - s
        if n >= 1:
            k = np.arange(s, e)
            width = min(n + 1, 4)
            first = np.clip(k - 1, s, e + 1 - width) if n >= 3 else np.full(n, s)
            idx = first[:, None] + np.arange(width)
            u = (t[idx] - t[k][:, None]) / h[k][:, None]
            V = u[:, :, None] ** np.arange(width)
            coef = np.linalg.solve(V, P[idx])  # (n, width, J)
            interval[k] = h[k][:, None] * _abs_polynomial_integrals(np.moveaxis(coef, 1, 2))
        s = e + 1
    return interval if per_interval else interval.sum(axis=0)


def open_result(path, group="/"):
    """Opens a hexdyn-result/3 file, checks its schema and every dataset's element type and
    shape (check_result_datasets) and returns a Result (the type hexdyn.run returns) with every
    dataset in memory (the file is closed on return; Result.write copies its objects). `group` selects a result stored below the file root (e.g.
    "/runs/<id>" of a sweep file). Anything but a regular file raises hexdyn.IoError before it
    is opened (check_regular_file), as does a file HDF5 cannot read or a dataset off the
    schema; a path with a NUL character raises ValueError."""
    path = checked_path(path)
    name = os.fsdecode(path)
    with open_h5(path) as f:
        return read_result_group(f[group], source=name if group == "/" else f"{name}:{group}")


# Status names by code (/scenarios/status), as declared in schema.hpp.
SWEEP_STATUS = tuple(SCHEMA["kScenarioStatusNames"])


def _case_column(texts):
    """One key's values over the cases: a float array when every value is a number, else
    the list of texts (YAML, as /axes/<i>/case_values stores them)."""
    try:
        return np.array([float(t) for t in texts])
    except ValueError:
        return list(texts)


class SweepAxis:
    """One swept key: `key` (dotted path), `values` (float array, or list of str for an
    axis of words), `labels` (as written in the sweep file, e.g. "2/3"), `numeric`.
    A cases axis (`cases:` in the sweep file) has `key` its name ("case"), `values` and
    `labels` the case labels, and `cases` {scene key: value per case} (float array or list
    of str), the keys in the order of the sweep file; `cases` is None for other axes."""

    def __init__(self, key, values, labels, cases=None):
        self.key = key
        self.values = values
        self.labels = labels
        self.numeric = isinstance(values, np.ndarray)
        self.cases = cases

    @property
    def is_cases(self):
        return self.cases is not None

    def __len__(self):
        return len(self.labels)

    def __repr__(self):
        return f"SweepAxis({self.key!r}, {list(self.labels)})"


class Sweep:
    """A hexdyn-sweep/3 file read into memory (the file is closed).

    sw.axes             list of SweepAxis; scenario index is row-major over them
    sw.shape            tuple of the axis lengths
    sw.table[name]      numpy array, one row per scenario (SCENARIO_DATASETS)
    sw.units[name]      `units` attribute of /scenarios/<name>
    sw.ok               boolean mask of the scenarios computed (status 0)
    sw.status_names     status of each scenario as a word ("ok", "reach", ...)
    sw.meta             /meta attributes; sw.config the base scene (dict);
                        sw.spec the sweep file (dict)
    sw.grid(name)       a column reshaped to sw.shape (+ the column's own dims)
    sw.scenario(i)      {axis key: value} of scenario i (a cases axis: its label, then
                        each key its case sets)
    sw.run(i)           Result of scenario i (index or id) from /runs/<id>
    """

    def __init__(self, path, meta, axes, table, units, joint_names, run_ids):
        self.path = str(path)
        self.meta = meta
        self.axes = axes
        self.table = table
        self.units = units
        self.joint_names = joint_names
        self.run_ids = run_ids

    @property
    def shape(self):
        return tuple(len(a) for a in self.axes)

    @property
    def size(self):
        return len(self.table["id"])

    @property
    def ok(self):
        return np.asarray(self.table["status"]) == 0

    @property
    def status_names(self):
        return [SWEEP_STATUS[int(c)] if 0 <= int(c) < len(SWEEP_STATUS) else str(int(c))
                for c in self.table["status"]]

    @property
    def config(self):
        return yaml_attribute(self.meta, "base_config_yaml", self.path)

    @property
    def spec(self):
        return yaml_attribute(self.meta, "sweep_yaml", self.path)

    @property
    def has_runs(self):
        return bool(self.run_ids)

    def grid(self, name):
        """Column `name` as an array of shape sw.shape + its trailing dims."""
        col = np.asarray(self.table[name])
        return col.reshape(self.shape + col.shape[1:])

    def scenario(self, i):
        i = self._index(i)
        out = {}
        for a, j in zip(self.axes, self.table["axis_index"][i]):
            out[a.key] = float(a.values[j]) if a.numeric else a.values[j]
            for key, column in (a.cases or {}).items():
                out[key] = float(column[j]) if isinstance(column, np.ndarray) else column[j]
        return out

    def run(self, i):
        """The full result of scenario `i` (index or id string)."""
        scenario_id = self.table["id"][self._index(i)]
        if scenario_id not in self.run_ids:
            status = self.status_names[self._index(i)]
            if not int(self.meta.get("keep_runs", 0)):
                why = ("runs are not stored in this file: the sweep was run without "
                       "--keep-runs; `hexdyn sweep SWEEP -o FILE --keep-runs` stores each "
                       "scenario's full result under /runs/<id>")
            else:
                why = f"the scenario was not computed (status {status})"
            raise KeyError(f"{self.path}: no /runs/{scenario_id}: {why}")
        return open_result(self.path, group=f"/runs/{scenario_id}")

    def to_xarray(self):
        """The scenario table as an xarray.Dataset with one dimension per axis, named by
        its key, holding its values (plus `joint` for per-joint metrics):
        ds.cost_of_transport.sel({"terrain.riser_height": 0.06}). Needs xarray."""
        from hexdyn import xr
        return xr.sweep_to_xarray(self)

    def to_dataframe(self):
        """The scenario table as a pandas.DataFrame, one row per scenario: the axis values
        in columns named by key, each per-joint metric in one column per joint named
        "metric[joint]" ("peak_torque[L2_femur]"). Needs pandas."""
        from hexdyn import xr
        return xr.sweep_to_dataframe(self)

    def _index(self, i):
        if isinstance(i, str):
            return list(self.table["id"]).index(i)
        return int(i)

    def __repr__(self):
        return (f"Sweep({self.path!r}, {self.size} scenarios, axes="
                f"{[a.key for a in self.axes]}, ok={int(self.ok.sum())})")


def _python_value(value):
    """An attribute's value as Python has it: str for text, int or float for a number."""
    value = decode_text(value)
    return value.item() if isinstance(value, np.generic) else value


def _meta_attributes(group):
    """The /meta attributes of a file (or of a kept run's group) as Python values."""
    return {key: _python_value(value) for key, value in group["meta"].attrs.items()}


def open_sweep(path):
    """Opens a hexdyn-sweep/3 file, checks its schema and version and its table and axes
    against the schema (check_sweep_file) and returns a Sweep with the axes and the scenario
    table in memory (the file is closed on return). Anything but a regular file raises
    hexdyn.IoError before it is opened, as does a file HDF5 cannot read or a dataset off the
    schema; a path with a NUL character raises ValueError."""
    path = checked_path(path)
    source = os.fsdecode(path)
    with open_h5(path) as f:
        check_filetype_version(f, SWEEP_SCHEMA, READABLE_VERSIONS, source)
        check_sweep_file(f, source)
        meta = _meta_attributes(f)
        axes = []
        for i in range(len(f["axes"])):
            g = f["axes"][str(i)]
            values = _read_checked(g["values"], source)
            if not isinstance(values, list):
                values = np.asarray(values, dtype=float)
            cases = None
            if "case_keys" in g:  # a cases axis: each key's value per case
                keys = _read_checked(g["case_keys"], source)
                table = np.array(_read_checked(g["case_values"], source), dtype=object).reshape(
                    len(values), len(keys))
                cases = {k: _case_column([str(t) for t in table[:, n]])
                         for n, k in enumerate(keys)}
            axes.append(SweepAxis(_read_checked(g["key"], source), values,
                                  _read_checked(g["labels"], source), cases))
        table, units = {}, {}
        for name, ds in f["scenarios"].items():
            if is_group_coordinate(f"{SCENARIOS_GROUP}/{name}", ds, f):
                continue
            value = _read_checked(ds, source)
            table[name] = value if isinstance(value, list) else np.asarray(value)
            units[name] = decode_text(ds.attrs.get("units", ""))
        joint_names = (_read_checked(f["joint_names"], source) if "joint_names" in f
                       else list(JOINT_NAMES))
        run_ids = set(f["runs"].keys()) if "runs" in f else set()
    return Sweep(source, meta, axes, table, units, joint_names, run_ids)


def expected_shape(shape, samples=None, impacts=None, messages=None, **sizes):
    """Concrete shape of a contract shape tuple ("T" -> samples, "n", "m"; other
    symbols by keyword, e.g. N=8, A=3)."""
    sizes = {"T": samples, "n": impacts, "m": messages, **sizes}
    return tuple(sizes[d] if isinstance(d, str) else d for d in shape)


# ---------------------------------------------------------------------------- envelopes
class Envelope(_Datasets):
    """A hexdyn-envelope/2 file read into memory (the file is closed), checked against the
    schema (check_envelope_file).

    env[path]        numpy array of every dataset ("/envelope/riser_max", "/axes/peak_speed");
                     text as str, texts as a numpy array of str of the dataset's shape (a
                     version 1 file's flattened /envelope/limit and message reshaped to the grid)
    env.units[path]  the `units` attribute; env.shapes[path] the shape
    env.meta         /meta attributes; env.config the envelope file (dict, /meta config_yaml);
                     env.base_config the base scene (dict)
    env.cases        the case labels (list of str), None for a file without `cases:`
    env.criteria     the criteria (list of str)
    env.to_xarray(group="envelope")   the group with the grid's coordinates (xarray)
    """

    def __init__(self, source, data, units, shapes, meta, version):
        self.source = source
        self.path = source
        self.data = data
        self.units = units
        self.shapes = shapes
        self.meta = meta
        self.version = version

    @property
    def config(self):
        return yaml_attribute(self.meta, "config_yaml", self.source)

    @property
    def base_config(self):
        return yaml_attribute(self.meta, "base_config_yaml", self.source)

    @property
    def cases(self):
        path = SCHEMA["kEnvelopeCaseLabels"].path
        return list(self.data[path]) if path in self.data else None

    @property
    def criteria(self):
        return list(self.data[SCHEMA["kEnvelopeCriteria"].path])

    def to_xarray(self, group="envelope"):
        """The datasets of `group` ("envelope", "probes", "axes"; None: all, named by path)
        as an xarray.Dataset on the file's dimensions, with the coordinates of the grid
        (tread_depth, duty_factor, peak_speed, criterion; case with cases):
        env.to_xarray().riser_max.sel(criterion="torque"). A group the file does not have
        raises UnknownGroupError naming the known ones. Needs xarray (hexdyn.xr)."""
        check_group(self, group)
        from hexdyn import xr
        return xr.result_to_xarray(self, group)

    def __repr__(self):
        return f"Envelope({self.source!r}, cases={self.cases}, datasets={len(self.data)})"


def _read_array(ds, source):
    """A dataset's values with the shape of the dataset: numbers as h5py gives them, text as
    str (scalar) or a numpy array of str."""
    value = _read_checked(ds, source)
    if isinstance(value, list):
        return np.array(value, dtype=object).reshape(ds.shape)
    return value


def open_envelope(path):
    """Opens a hexdyn-envelope/2 file (version 1 too), checks its schema and every dataset
    against the schema (check_envelope_file) and returns an Envelope with every dataset in
    memory (the file is closed on return). Needs h5py only. Anything but a regular file
    raises hexdyn.IoError before it is opened, as does a file HDF5 cannot read or a dataset
    off the schema; ValueError for a file of another schema or a path with a NUL character."""
    path = checked_path(path)
    source = os.fsdecode(path)
    data, units, shapes = {}, {}, {}
    with open_h5(path) as f:
        version = check_envelope_file(f, source)
        for p, ds in _all_datasets(f).items():
            data[p] = _read_array(ds, source)
            shapes[p] = tuple(ds.shape)
            if "units" in ds.attrs:
                units[p] = decode_text(ds.attrs["units"])
        meta = _meta_attributes(f)
    if version == 1:  # limit and message flattened: on the grid of riser_max
        grid = shapes[SCHEMA["kEnvelopeRiserMax"].path]
        for p in ENVELOPE_V1_FLATTENED:
            data[p] = np.asarray(data[p], dtype=object).reshape(grid)
            shapes[p] = grid
    return Envelope(source, data, units, shapes, meta, version)


# ---------------------------------------------------------------------------- replays
class Replay(_Datasets):
    """A hexdyn-replay/1 file read into memory (the file is closed), checked against the
    schema (check_replay_file): a result's torques replayed through the forward dynamics
    with compliant contact and slip (`hexdyn replay`, docs/theory/replay.md).

    rep[path]        numpy array of every dataset, the replayed motion in the result file's
                     names ("/joints/position", "/contacts/force") and the replay's own
                     ("/joints/tracking_error", "/energy/slip", "/replay/reached_top"); text
                     as str, a list of texts as a list of str
    rep.units[path]  the `units` attribute; rep.shapes[path] the shape
    rep.meta         /meta attributes; rep.config the scene as replayed (dict, /meta
                     config_yaml, its replay: and contact: keys included)
    rep.attrs        rep.meta and the other groups' attributes ("/terrain/type")
    rep.urdf         /model/urdf, the robot as replayed (the result's)
    rep.source_result  the replayed result file (/meta source_result)
    rep.reached_top  True when the robot reached the plan's end (/replay/reached_top)
    rep.to_xarray(group=None)   labelled (xarray), as Result.to_xarray
    """

    def __init__(self, source, data, units, shapes, meta, attributes=None):
        self.source = source
        self.path = source
        self.data = data
        self.units = units
        self.shapes = shapes
        self.meta = meta
        self.attributes = dict(attributes or {})
        self.urdf = data.get("/model/urdf", "")

    @property
    def attrs(self):
        """The /meta attributes by name and the other groups' as "/terrain/type"."""
        return {**self.meta, **self.attributes}

    @property
    def config(self):
        """The scene as replayed (dict); ValueError if config_yaml is not YAML."""
        return yaml_attribute(self.meta, "config_yaml", self.source)

    @property
    def samples(self):
        """T, the number of stored samples (up to the end of the replay)."""
        return int(self.shapes["/time"][0])

    @property
    def source_result(self):
        return self.meta.get(SCHEMA["kMetaReplaySource"].name, "")

    @property
    def reached_top(self):
        return bool(int(self.data[SCHEMA["kReplayReachedTop"].path]))

    def to_xarray(self, group=None):
        """The datasets as an xarray.Dataset with named dimensions and coordinates (time,
        leg, joint, xyz, gait_cycle, ...), as Result.to_xarray: `group` ("joints", "replay")
        gives that group's datasets under their own names, None all of them named by path
        ("energy/slip" -> "energy_slip"). A group the file does not have raises
        UnknownGroupError naming the known ones. Needs xarray (hexdyn.xr)."""
        check_group(self, group)
        from hexdyn import xr
        return xr.result_to_xarray(self, group)

    def __repr__(self):
        return (f"Replay({self.source!r}, T={self.samples}, reached_top={self.reached_top}, "
                f"datasets={len(self.data)})")


def check_replay_file(f, source):
    """Checks an open replay file's schema and version and every dataset against the
    schema (schema_replay.hpp): the replayed series with T = len(/time), the robot and the
    terrain as in a result, the report with Y = len(/replay/cycle_end); every one of them
    present. hexdyn.IoError in one line on a mismatch or a missing dataset; ValueError for
    a file of another schema (check_filetype_version). Returns the file's version."""
    version = check_filetype_version(f, REPLAY_SCHEMA, REPLAY_SCHEMA_VERSION, source)
    _check_layout(source, _all_datasets(f), REPLAY_LAYOUT, REPLAY_REQUIRED, {}, REPLAY_SCHEMA)
    return version


def open_replay(path):
    """Opens a hexdyn-replay/1 file (`hexdyn replay`), checks its schema and every dataset
    against the schema (check_replay_file) and returns a Replay with every dataset in memory
    (the file is closed on return). Needs h5py only. Anything but a regular file raises
    hexdyn.IoError before it is opened, as does a file HDF5 cannot read or a dataset off the
    schema; ValueError for a file of another schema (a result: open_result) or a path with a
    NUL character."""
    path = checked_path(path)
    source = os.fsdecode(path)
    data, units, shapes = {}, {}, {}
    with open_h5(path) as f:
        check_replay_file(f, source)
        for p, ds in _all_datasets(f).items():
            data[p] = _read_checked(ds, source)
            shapes[p] = tuple(ds.shape)
            if "units" in ds.attrs:
                units[p] = decode_text(ds.attrs["units"])
        meta = _meta_attributes(f)
        attributes = _group_attributes(f, META_GROUP)
    return Replay(source, data, units, shapes, meta, attributes)


# ---------------------------------------------------------------------------- studies
# hexdyn-study/1 (analysis/study.py): the speed-against-error study. /meta (schema,
# schema_version and the study's provenance), /runs/<column> one value per run (each with a
# `units` attribute), /references/<name> (attributes and datasets of each reference run),
# /verdict (attributes).
STUDY_SCHEMA = "hexdyn-study/1"
STUDY_SCHEMA_VERSION = 1
STUDY_GROUPS = ("runs", "references", "verdict")


class Study:
    """A hexdyn-study/1 file read into memory (the file is closed).

    st.rows[column]       numpy array (numbers) or list of str, one value per run
    st.units[column]      its `units` attribute
    st.verdict            /verdict attributes (str, int, float)
    st.references[name]   /references/<name> attributes
    st.reference_data[name][dataset]   /references/<name> datasets
    st.meta               /meta attributes
    """

    def __init__(self, source, meta, rows, units, verdict, references, reference_data):
        self.source = source
        self.path = source
        self.meta = meta
        self.rows = rows
        self.units = units
        self.verdict = verdict
        self.references = references
        self.reference_data = reference_data

    def __len__(self):
        return len(next(iter(self.rows.values()), ()))

    def __repr__(self):
        return f"Study({self.source!r}, {len(self)} runs, references={sorted(self.references)})"


def check_study_file(f, source):
    """Checks an open study file's schema and version and its layout: the groups /runs,
    /references and /verdict, every /runs column a one-dimensional dataset with one value per
    run. hexdyn.IoError in one line on a mismatch; ValueError for another schema."""
    check_filetype_version(f, STUDY_SCHEMA, STUDY_SCHEMA_VERSION, source)
    for g in STUDY_GROUPS:
        if not isinstance(f.get(g), h5py.Group):
            raise _io_error(f"{source}: no group /{g}, which every {STUDY_SCHEMA} file has")
    n = None
    for name, ds in f["runs"].items():
        if not isinstance(ds, h5py.Dataset) or ds.shape is None or len(ds.shape) != 1:
            raise _io_error(f"{source}: /runs/{name} is not a dataset of one value per run")
        if n is None:
            n = (ds.shape[0], name)
        elif ds.shape[0] != n[0]:
            raise _io_error(f"{source}: dataset /runs/{name} has {ds.shape[0]} values, expected "
                            f"{n[0]} (from /runs/{n[1]})")


def open_study(path):
    """Opens a hexdyn-study/1 file (analysis/study.py), checks it (check_study_file) and
    returns a Study in memory. Needs h5py only. Errors as open_result."""
    path = checked_path(path)
    source = os.fsdecode(path)
    with open_h5(path) as f:
        check_study_file(f, source)
        rows, units = {}, {}
        for name, ds in f["runs"].items():
            value = _read_checked(ds, source)
            rows[name] = value if isinstance(value, list) else np.asarray(value)
            if "units" in ds.attrs:  # as for results: only the columns that have one
                units[name] = decode_text(ds.attrs["units"])
        verdict = {k: _python_value(v) for k, v in f["verdict"].attrs.items()}
        references, reference_data = {}, {}
        for name, g in f["references"].items():
            references[name] = {k: _python_value(v) for k, v in g.attrs.items()}
            reference_data[name] = {k: _read_checked(d, source) for k, d in g.items()
                                    if isinstance(d, h5py.Dataset)}
        meta = _meta_attributes(f)
    return Study(source, meta, rows, units, verdict, references, reference_data)


# ---------------------------------------------------------------------------- one checker
def _all_datasets(group):
    """{"/path": h5py.Dataset} of every dataset below `group`, paths relative to it, group
    coordinates (is_group_coordinate) left out."""
    out = {}
    group.visititems(lambda name, obj: out.__setitem__("/" + name, obj)
                     if isinstance(obj, h5py.Dataset)
                     and not is_group_coordinate("/" + name, obj, group) else None)
    return out


def _check_declared(source, group, layout, meta_attributes, skip=()):
    """What the checks at open leave to check_layout: every dataset below `group` (but those
    below the groups `skip`) declared in `layout` with its declared `units` attribute (none for
    ""), and every attribute of `meta_attributes` on /meta. hexdyn.IoError in one line."""
    for path, ds in _all_datasets(group).items():
        if any(path.startswith(s + "/") for s in skip):
            continue
        # A dataset of the kind's layout, or one declared elsewhere in the schema (a
        # declaration list the layout of the readers does not name yet).
        if path not in layout and path not in DECLARED:
            raise _io_error(f"{source}: dataset {path} is not declared in the schema")
        declared = {s.units for s in layout.get(path, DECLARED.get(path))}
        if "key" in declared:
            continue  # a sweep axis: the unit of its key
        units = decode_text(ds.attrs["units"]) if "units" in ds.attrs else ""
        if units not in declared:
            raise _io_error(f"{source}: dataset {path} has units {units!r}, expected "
                            f"{' or '.join(repr(u) for u in sorted(declared))}")
    missing = [a.name for a in meta_attributes if a.name not in group["meta"].attrs]
    if missing:
        raise _io_error(f"{source}: /meta has no attribute {', '.join(missing)}")


def check_layout(file, source=None):
    """Checks a hexdyn file against its schema, whichever kind it is: `file` a path or an
    open h5py File. The kind comes from /meta schema: a result (the checks of open_result), a
    sweep (those of open_sweep, and every kept run /runs/<id> as a result), an envelope (those
    of open_envelope), a replay (those of open_replay) or a study (check_study_file). A
    result, envelope or replay file of the current version must also hold no undeclared
    dataset, each with its declared units, and every declared /meta attribute (as must a
    sweep file's /meta and its kept runs). Returns the
    schema name ("hexdyn-sweep/3"). hexdyn.IoError in one line naming the file and the
    dataset on a mismatch (and for a path that is no regular HDF5 file); ValueError for a
    file of no hexdyn schema or of a version this reader does not know."""
    if not isinstance(file, (h5py.File, h5py.Group)):
        path = checked_path(file)
        with open_h5(path) as f:
            return check_layout(f, source or os.fsdecode(path))
    f = file
    source = source or f.file.filename
    schema = decode_text(f["meta"].attrs.get("schema", "")) if "meta" in f else ""
    base = schema.rsplit("/", 1)[0]
    if base == RESULT_SCHEMA.rsplit("/", 1)[0]:
        _check_result_layout(f, source)
        return RESULT_SCHEMA
    if base == SWEEP_SCHEMA.rsplit("/", 1)[0]:
        version = check_filetype_version(f, SWEEP_SCHEMA, READABLE_VERSIONS, source)
        check_sweep_file(f, source)
        if version == SWEEP_SCHEMA_VERSION:
            missing = [a.name for a in SCHEMA["kSweepMetaAttributes"] if a.name not in f["meta"].attrs]
            if missing:
                raise _io_error(f"{source}: /meta has no attribute {', '.join(missing)}")
        for run_id, group in (f["runs"].items() if "runs" in f else ()):
            _check_result_layout(group, f"{source}:/runs/{run_id}")
        return SWEEP_SCHEMA
    if base == ENVELOPE_SCHEMA.rsplit("/", 1)[0]:
        if check_envelope_file(f, source) == ENVELOPE_SCHEMA_VERSION:
            cases = SCHEMA["kEnvelopeCaseLabels"].path in f
            _check_declared(source, f, ENVELOPE_CASES_LAYOUT if cases else ENVELOPE_LAYOUT,
                            SCHEMA["kEnvelopeMetaAttributes"])
        return ENVELOPE_SCHEMA
    if base == REPLAY_SCHEMA.rsplit("/", 1)[0]:
        check_replay_file(f, source)
        _check_declared(source, f, REPLAY_LAYOUT, SCHEMA["kReplayMetaAttributes"])
        return REPLAY_SCHEMA
    if base == STUDY_SCHEMA.rsplit("/", 1)[0]:
        check_study_file(f, source)
        return STUDY_SCHEMA
    known = ", ".join((RESULT_SCHEMA, SWEEP_SCHEMA, ENVELOPE_SCHEMA, REPLAY_SCHEMA, STUDY_SCHEMA))
    raise ValueError(f"{source}: not a hexdyn file (/meta schema {schema!r}; known: {known})")


def _check_result_layout(group, source):
    version = check_filetype_version(group, RESULT_SCHEMA, READABLE_VERSIONS, source)
    datasets = {}
    for path, ds in _all_datasets(group).items():
        datasets[V1_RENAMED.get(path, path) if version == 1 else path] = ds
    check_result_datasets(datasets, version, source)
    if version == RESULT_SCHEMA_VERSION:
        _check_declared(source, group, RESULT_LAYOUT, SCHEMA["kResultMetaAttributes"])


# ---------------------------------------------------------------------------- writing a copy
def _listed_inputs(meta):
    """The absolute paths /meta input_sha256 lists ("SHA256  PATH" per line)."""
    paths = []
    for line in str(meta.get("input_sha256", "") or "").splitlines():
        parts = line.split(None, 1)
        if len(parts) == 2:
            paths.append(parts[1])
    return paths


def _check_copy_target(name, source, inputs):
    """The checks of `hexdyn run -o` on an output path, against the file a result was read
    from (`source`, by identity and path) and the files its /meta lists: hexdyn.IoError. An
    existing `name` must be a regular file (a link, a folder or a special file is refused, not
    followed: atomic_file.why_not_replaceable)."""
    if not name:
        raise output_error(name, "empty path")
    folder = os.path.dirname(os.path.abspath(name))
    if not os.path.isdir(folder):
        raise output_error(name, f"folder '{folder}' does not exist")
    why = why_not_replaceable(name)
    if why:
        raise output_error(name, f"it {why}")
    try:
        target = os.stat(name)
    except FileNotFoundError:
        return
    except OSError as e:
        raise output_error(name, e.strerror) from None
    for role, p in [("file the result was read from", source)] + [
            ("input file", p) for p in inputs]:
        try:
            st = os.stat(p)
        except OSError:
            continue
        if (st.st_dev, st.st_ino) == (target.st_dev, target.st_ino):
            raise output_error(name, f"it is the {role} '{p}' (same device and inode), which "
                               "the output would destroy")


def _copy_attributes(src, dst):
    """The attributes of `src` on `dst` with their stored type and shape, but the dimension
    scale references (attached again by _attach_scales)."""
    for key in src.attrs:
        if key in ("DIMENSION_LIST", "REFERENCE_LIST"):
            continue
        aid = src.attrs.get_id(key)
        dst.attrs.create(key, src.attrs[key], shape=aid.shape, dtype=aid.dtype)


def _attach_scales(src_root, dst_root):
    """Each dataset below `dst_root` attached to the dimension scales its original below
    `src_root` is attached to (DIMENSION_LIST), at the same relative paths."""
    prefix = src_root.name.rstrip("/") + "/"

    def visit(name, obj):
        if not isinstance(obj, h5py.Dataset) or "DIMENSION_LIST" not in obj.attrs:
            return
        for k, refs in enumerate(obj.attrs["DIMENSION_LIST"]):
            for ref in refs:
                scale = src_root.file[ref].name
                if not scale.startswith(prefix):
                    raise ValueError(f"dimension scale {scale} of {obj.name} lies outside "
                                     f"{src_root.name}")
                dst_root[name].dims[k].attach_scale(dst_root[scale[len(prefix):]])
    src_root.visititems(visit)


def _copy_image(file, group, check):
    """The bytes of an HDF5 file holding the objects of the group `group` of the file `file`,
    built in memory (h5py's core driver, no backing store): every member copied with h5py
    (H5Ocopy: values, type, shape, storage), every attribute with its stored type, the
    dimension scales attached again. check() is called before each member of the group is
    copied and after the last (atomic_file: it stops the copy once a signal came)."""
    with h5py.File(file, "r") as src:
        root = src[group]
        with h5py.File(f"hexdyn-copy-{secrets.token_hex(8)}.h5", "w", driver="core",
                       backing_store=False, libver=src.libver) as dst:
            for key in root:
                check()
                root.copy(root[key], dst, name=key, without_attrs=True)
            _copy_attributes(root, dst)
            root.visititems(lambda n, obj: _copy_attributes(obj, dst[n]))
            _attach_scales(root, dst)
            check()
            dst.flush()
            return dst.id.get_file_image()


def write_copy(origin, path, inputs=()):
    """Writes the objects of the group `group` of the file `file` (origin: (file, group,
    identity when read)) as the file `path`: the file's image built in memory (_copy_image)
    and published with atomic_file.publish_atomically (a temporary file beside `path`, written
    with write(2), synced and renamed over `path` when complete; removed on any error or
    signal, an existing file at `path` kept). Refuses, with hexdyn.IoError in one line, a
    source changed since it was read and a target that is the source or one of `inputs`
    (_check_copy_target)."""
    file, group, identity = origin
    name = os.fsdecode(path)
    _check_copy_target(name, file, inputs)
    try:
        unchanged = _file_identity(file) == identity
    except OSError as e:
        raise output_error(name, f"the file the result was read from, '{file}', cannot be "
                           f"read: {e.strerror}") from None
    if not unchanged:
        raise output_error(name, f"the file the result was read from, '{file}', changed since "
                           "it was read; open it again")
    publish_atomically(path, lambda check: _copy_image(file, group, check))
