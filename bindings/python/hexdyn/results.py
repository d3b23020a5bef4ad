"""Reader for hexdyn result files (`hexdyn-result/2`) and sweep files (`hexdyn-sweep/2`);
files of version 1 open too (their layout is mapped to version 2's on reading).

The layout is the contract of docs/user/output.md; the tables below mirror
src/hexdyn/io/schema.hpp (path -> (shape, units, element type)). Shapes use the
symbols "T" (samples), "n" (touchdowns) and "m" (solver messages).

    from hexdyn import open_result
    res = open_result("results/paper/paper.h5")
    t = res["/time"]                 # numpy array, shape (T,)
    feet = res["/feet/position"]     # (T, 6, 3), world frame [m]
    res.units["/joints/torque"]      # "N m"
    res.config["terrain"]            # the resolved configuration (dict)
    res.urdf                         # robot as simulated (str)

    from hexdyn import open_sweep
    sw = open_sweep("results/sweeps/smoke/smoke.h5")
    sw.axes[0].key, sw.axes[0].values  # "terrain.riser_height", array([0.04, 0.08])
    sw.table["energy"]               # one value per scenario [J], NaN where failed
    sw.grid("energy")                # the same on the grid: shape sw.shape
    sw.run(5)                        # a Result from /runs/000005 (sweeps run with --keep-runs)
    sw.to_xarray(), sw.to_dataframe(), res.to_xarray()   # labelled (hexdyn.xr; xarray, pandas)

Requires h5py, numpy and PyYAML (Debian: /usr/bin/python3).
"""

import os
import re
import stat

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
# The layout is declared once, in the C++ header src/hexdyn/io/schema.hpp; this module
# parses that header at import. The header is looked for, in this order, at
# $HEXDYN_SCHEMA_HPP, next to this module (schema.hpp: the copy the build tree and an
# installation put there) and in the source tree (../../../src/hexdyn/io/schema.hpp from
# bindings/python/hexdyn/).
_HERE = os.path.dirname(os.path.abspath(__file__))
SCHEMA_HEADER_CANDIDATES = tuple(p for p in (
    os.environ.get("HEXDYN_SCHEMA_HPP"),
    os.path.join(_HERE, "schema.hpp"),
    os.path.join(_HERE, "..", "..", "..", "src", "hexdyn", "io", "schema.hpp"),
) if p)


class DatasetSpec:
    """A dataset of the contract: path (may hold "{i}", "{id}" or "{key}"), units ("" no
    `units` attribute; "key" the unit of a sweep axis's key), shape (a tuple of ints and
    size symbols "T", "n", "m", "N", "A", "V"), element ("float64", "int8", "int32",
    "int64", "string"), long_name, dims (the netCDF dimension names of its axes);
    `name` is the C++ constant (kTime)."""

    def __init__(self, name, path, units, shape, element, long_name="", dims=()):
        self.name, self.path, self.units, self.shape, self.element = (
            name, path, units, shape, element)
        self.long_name, self.dims = long_name, dims

    def __iter__(self):  # (shape, units, element), the tuples of the tables below
        return iter((self.shape, self.units, self.element))

    def __repr__(self):
        return f"DatasetSpec({self.path!r}, {self.units!r}, {self.shape}, {self.element!r})"


class FlagSpec:
    """CF flags of a dataset of codes 0, 1, ...: `path` and the words of `meanings`."""

    def __init__(self, const, path, meanings):
        self.const, self.path, self.meanings = const, path, meanings.split()

    def __repr__(self):
        return f"FlagSpec({self.path!r}, {self.meanings})"


class AttributeSpec:
    """An attribute of the contract: `name` on the object `object` (may hold "{i}")."""

    def __init__(self, const, obj, name, element):
        self.const, self.object, self.name, self.element = const, obj, name, element

    def __repr__(self):
        return f"AttributeSpec({self.object!r}, {self.name!r}, {self.element!r})"


def _strip_comments(text):
    return re.sub(r'("(?:[^"\\]|\\.)*")|//[^\n]*', lambda m: m.group(1) or "", text)


def _split_args(text):
    return [a.strip() for a in re.findall(r'\s*("(?:[^"\\]|\\.)*"|[^,]+)', text) if a.strip()]


def parse_schema_header(text):
    """The declarations of schema.hpp as a dict: constant name -> str, int, DatasetSpec,
    AttributeSpec or list (the std::array lists). Raises ValueError on a declaration
    this parser does not understand (keep the header on its regular pattern)."""
    shapes = {}
    enum = re.search(r"enum class Shape \{(.*?)\};", text, re.S)
    if not enum:
        raise ValueError("schema header: no `enum class Shape`")
    for name, dims in re.findall(r"(k\w+),\s*///<\s*\(([^)]*)\)", enum.group(1)):
        shapes[name] = tuple(int(d) if d.strip().isdigit() else d.strip()
                             for d in dims.split(",") if d.strip())
    code = _strip_comments(text)
    dims = {name: tuple(names.split()) for name, names in
            re.findall(r'case Shape::(k\w+): return "([^"]*)";', code)}
    missing = set(shapes) - set(dims)
    if missing:
        raise ValueError(f"schema header: no dimension_names() case for {sorted(missing)}")
    decls = {}

    def value(token):
        if token.startswith('"'):
            return token[1:-1]
        if token in decls:
            return decls[token]
        raise ValueError(f"schema header: unknown name {token!r}")

    def element(token):
        m = re.fullmatch(r"Element::k(\w+)", token)
        if not m:
            raise ValueError(f"schema header: {token!r} is not an Element")
        return m.group(1).lower()

    pattern = re.compile(r"inline\s+constexpr\s+(const\s+char\s*\*|std::int64_t|DatasetSpec|"
                         r"AttributeSpec|FlagSpec|std::array)\s+(k\w+)\s*(?:=\s*([^;]*?)|\{([^;]*?)\})\s*;",
                         re.S)
    found = pattern.findall(code)
    if len(found) != len(re.findall(r"inline\s+constexpr", code)):
        raise ValueError("schema header: a declaration off the pattern `inline constexpr TYPE kName"
                         "{...};` or `= ...;` (TYPE const char*, std::int64_t, DatasetSpec, "
                         "AttributeSpec, std::array)")
    for kind, name, assigned, braced in found:
        kind = re.sub(r"\s+", " ", kind)
        if kind.startswith("const char"):
            decls[name] = value(assigned.strip())
        elif kind == "std::int64_t":
            decls[name] = int(assigned.strip())
        elif kind == "DatasetSpec":
            args = _split_args(braced)
            shape = re.fullmatch(r"Shape::(k\w+)", args[2] if len(args) > 2 else "Shape::kScalar")
            decls[name] = DatasetSpec(name, value(args[0]), value(args[1]),
                                      shapes[shape.group(1)],
                                      element(args[3]) if len(args) > 3 else "float64",
                                      value(args[4]) if len(args) > 4 else "",
                                      dims[shape.group(1)])
        elif kind == "FlagSpec":
            args = _split_args(braced)
            decls[name] = FlagSpec(name, value(args[0]), value(args[1]))
        elif kind == "AttributeSpec":
            args = _split_args(braced)
            decls[name] = AttributeSpec(name, value(args[0]), value(args[1]),
                                        element(args[2]) if len(args) > 2 else "string")
        else:
            decls[name] = [value(a) for a in _split_args(braced)]
    return decls


_SCHEMA_PART = re.compile(r'^#include "hexdyn/io/(schema_\w+\.hpp)".*$', re.M)


def read_schema_text(path):
    """The text of the schema header at `path` with the parts it includes at its end
    (`#include "hexdyn/io/schema_*.hpp"`, read from the same folder) put in place."""
    path = checked_path(path)
    with open(path, encoding="utf-8") as f:
        text = f.read()

    def part(m):
        with open(os.path.join(os.path.dirname(path), m.group(1)), encoding="utf-8") as f:
            return f.read()
    return _SCHEMA_PART.sub(part, text)


def load_schema(candidates=SCHEMA_HEADER_CANDIDATES):
    """Parses the first schema header found among `candidates`; (path, declarations)."""
    for path in candidates:
        if os.path.isfile(checked_path(path)):
            return os.path.abspath(path), parse_schema_header(read_schema_text(path))
    raise ImportError("hexdyn.results: cannot find the schema header src/hexdyn/io/schema.hpp "
                      f"(looked at {', '.join(candidates)}); set HEXDYN_SCHEMA_HPP")


SCHEMA_HEADER, SCHEMA = load_schema()

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

# Versions this reader opens: the current one, and 1 (mapped on reading, V1_RENAMED).
READABLE_VERSIONS = (1, RESULT_SCHEMA_VERSION)
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
RESULT_LAYOUT = _layout([SCHEMA["kTime"]], SCHEMA["kModelDatasets"], SCHEMA["kUrdfRobotDatasets"],
                        SCHEMA["kKinematicDatasets"], SCHEMA["kDynamicsDatasets"],
                        SCHEMA["kResultCoordinates"], SCHEMA["kResultIndexCoordinates"])
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
SWEEP_ROOT_LAYOUT = _layout([SCHEMA["kSweepJointNames"]], SCHEMA["kSweepCoordinates"])
ENVELOPE_LAYOUT = _layout(SCHEMA["kEnvelopeDatasets"], SCHEMA["kEnvelopeCoordinates"])
# With cases: the case axes first, then the grid with its leading dimension D.
_ENVELOPE_CASES = _layout(SCHEMA["kEnvelopeCaseDatasets"])
ENVELOPE_CASES_LAYOUT = {**{p: s for p, s in _ENVELOPE_CASES.items() if p not in ENVELOPE_LAYOUT},
                         **{p: _ENVELOPE_CASES.get(p, s) for p, s in ENVELOPE_LAYOUT.items()}}
ENVELOPE_REQUIRED = {d.path for d in SCHEMA["kEnvelopeDatasets"]}
ENVELOPE_V1_FLATTENED = (SCHEMA["kEnvelopeLimit"].path, SCHEMA["kEnvelopeMessage"].path)

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
    "hexdyn-result/1" is accepted for an expected "hexdyn-result/2" when 1 is among the
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


class Result:
    """All datasets of one result, read into memory, keyed by contract path.

    res[path]        numpy array (scalars as numpy scalars; strings as str / list of str)
    res.units[path]  the `units` attribute
    res.shapes[path] the stored shape
    res.meta         /meta attributes (strings decoded)
    res.config       yaml.safe_load of /meta config_yaml
    res.urdf         /model/urdf text
    """

    def __init__(self, source, data, units, shapes, meta):
        self.source = source
        self.data = data
        self.units = units
        self.shapes = shapes
        self.meta = meta
        self.urdf = data.get("/model/urdf", "")
        self._config = None

    @property
    def config(self):
        """The resolved configuration (dict); ValueError if config_yaml is not YAML."""
        if self._config is None:
            try:
                self._config = yaml.safe_load(self.meta.get("config_yaml", "") or "") or {}
            except yaml.YAMLError as e:
                raise ValueError(f"{self.source}: /meta config_yaml is not valid YAML: "
                                 f"{str(e).splitlines()[0]}") from None
        return self._config

    def __getitem__(self, path):
        try:
            return self.data[path]
        except KeyError:
            raise KeyError(f"{self.source}: no dataset {path}") from None

    def __contains__(self, path):
        return path in self.data

    def paths(self):
        return sorted(self.data)

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
        them in one Dataset, named by path ("joints/torque" -> "joints_torque"). Needs
        xarray (hexdyn.xr)."""
        from hexdyn import xr
        return xr.result_to_xarray(self, group)

    def __repr__(self):
        return (f"Result({self.source!r}, T={self.samples}, "
                f"dynamics={self.has_dynamics}, datasets={len(self.data)})")


def _read_dataset(ds):
    string_info = h5py.check_string_dtype(ds.dtype)
    if string_info is not None:
        values = ds.asstr()[()]
        if ds.shape == ():
            return decode_text(values)
        return [decode_text(v) for v in np.asarray(values).ravel()]
    return ds[()]


def read_result_group(group, source="result"):
    """Reads a result laid out under an open h5py File or Group (e.g. a sweep's
    /runs/<id>) after checking its schema and every dataset's element type and shape
    (check_result_datasets). Returns a Result."""
    version = check_filetype_version(group, RESULT_SCHEMA, READABLE_VERSIONS, source)
    datasets = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
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
    return Result(source, data, units, shapes, _meta_attributes(group))


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
    """{prefix/name: h5py.Dataset} of the datasets directly in `group`."""
    return {f"{prefix}/{name}": obj for name, obj in group.items()
            if isinstance(obj, h5py.Dataset)}


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
    check_filetype_version)."""
    version = check_filetype_version(f, ENVELOPE_SCHEMA, READABLE_ENVELOPE_VERSIONS, source)
    datasets = {}
    f.visititems(lambda name, obj: datasets.__setitem__("/" + name, obj)
                 if isinstance(obj, h5py.Dataset) else None)
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


def open_result(path, group="/"):
    """Opens a hexdyn-result/2 file, checks its schema and every dataset's element type and
    shape (check_result_datasets) and returns a Result with every dataset in memory (the file
    is closed on return). `group` selects a result stored below the file root (e.g.
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
    """A hexdyn-sweep/2 file read into memory (the file is closed).

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
        return yaml.safe_load(self.meta.get("base_config_yaml", "") or "") or {}

    @property
    def spec(self):
        return yaml.safe_load(self.meta.get("sweep_yaml", "") or "") or {}

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


def _meta_attributes(group):
    """The /meta attributes of a file (or of a kept run's group) as Python values."""
    meta = {}
    for key, value in group["meta"].attrs.items():
        value = decode_text(value)
        if isinstance(value, np.generic):
            value = value.item()
        meta[key] = value
    return meta


def open_sweep(path):
    """Opens a hexdyn-sweep/2 file, checks its schema and version and its table and axes
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
