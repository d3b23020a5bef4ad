"""Reader for hexdyn result files (`hexdyn-result/1`) and sweep files (`hexdyn-sweep/1`).

The layout is the contract of DESIGN.md section 4; the tables below mirror
src/hexdyn/result_schema.hpp (path -> (shape, units, element type)). Shapes use the
symbols "T" (samples), "n" (touchdowns) and "m" (solver messages).

    from hexdyn_results import open_result
    res = open_result("results/paper/paper.h5")
    t = res["/time"]                 # numpy array, shape (T,)
    feet = res["/feet/position"]     # (T, 6, 3), world frame [m]
    res.units["/joints/torque"]      # "N m"
    res.config["terrain"]            # the resolved configuration (dict)
    res.urdf                         # robot as simulated (str)

Requires h5py, numpy and PyYAML (Debian: /usr/bin/python3).
"""

import h5py
import numpy as np
import yaml

RESULT_SCHEMA = "hexdyn-result/1"
RESULT_SCHEMA_VERSION = 1
SWEEP_SCHEMA = "hexdyn-sweep/1"
SWEEP_SCHEMA_VERSION = 1

META_GROUP = "/meta"
META_ATTRIBUTES = ("schema", "schema_version", "version", "git_commit", "created_utc",
                   "config_yaml", "wall_time_s")

MODEL_DATASETS = {
    "/model/urdf": ((), "1", "string"),
    "/model/joint_names": ((18,), "1", "string"),
    "/model/leg_names": ((6,), "1", "string"),
    "/model/total_mass": ((), "kg", "float64"),
}

KINEMATIC_DATASETS = {
    "/time": (("T",), "s", "float64"),
    "/base/position": (("T", 3), "m", "float64"),
    "/base/orientation": (("T", 4), "1", "float64"),  # quaternion w, x, y, z; body -> world
    "/base/linear_velocity": (("T", 3), "m/s", "float64"),
    "/base/angular_velocity": (("T", 3), "rad/s", "float64"),
    "/base/linear_acceleration": (("T", 3), "m/s^2", "float64"),
    "/base/angular_acceleration": (("T", 3), "rad/s^2", "float64"),
    "/joints/position": (("T", 18), "rad", "float64"),
    "/joints/velocity": (("T", 18), "rad/s", "float64"),
    "/joints/acceleration": (("T", 18), "rad/s^2", "float64"),
    "/feet/position": (("T", 6, 3), "m", "float64"),
    "/feet/velocity": (("T", 6, 3), "m/s", "float64"),
    "/com/position": (("T", 3), "m", "float64"),
    "/contacts/phase": (("T", 6), "1", "int8"),  # 0 swing, 1 impact, 2 support
}

DYNAMICS_DATASETS = {
    "/joints/torque": (("T", 18), "N m", "float64"),
    "/contacts/force": (("T", 6, 3), "N", "float64"),  # terrain on foot, world frame
    "/contacts/penetration": (("T", 6), "m", "float64"),
    "/impacts/leg": (("n",), "1", "int32"),  # 1-based leg number
    "/impacts/t_start": (("n",), "s", "float64"),
    "/impacts/duration": (("n",), "s", "float64"),
    "/impacts/peak_force": (("n",), "N", "float64"),
    "/impacts/impulse": (("n",), "N s", "float64"),
    "/impacts/effective_mass": (("n",), "kg", "float64"),
    "/impacts/approach_speed": (("n",), "m/s", "float64"),
    "/power/joint": (("T", 18), "W", "float64"),
    "/power/total": (("T",), "W", "float64"),
    "/energy/total": ((), "J", "float64"),
    "/energy/joint": ((18,), "J", "float64"),
    "/energy/cost_of_transport": ((), "1", "float64"),
    "/energy/distance": ((), "m", "float64"),
    "/solver/status": (("T",), "1", "int8"),  # 0 optimal, 1 relaxed, 2 failed
    "/solver/iterations": (("T",), "1", "float64"),
    "/solver/objective": (("T",), "N^2 m^2", "float64"),
    "/solver/seconds": (("T",), "s", "float64"),
    "/solver/messages": (("m",), "1", "string"),
}

PHASE_SWING, PHASE_IMPACT, PHASE_SUPPORT = 0, 1, 2
LEG_NAMES = tuple(f"L{i}" for i in range(1, 7))
JOINT_NAMES = tuple(f"L{i}_{j}" for i in range(1, 7) for j in ("coxa", "femur", "tibia"))


def _text(value):
    """str from an HDF5 string value (h5py gives str or bytes depending on storage)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.shape == ():
        return _text(value[()])
    return value


def check_filetype_version(h5_root, expected_schema, expected_version, source="file",
                           require_version=True):
    """Raise ValueError unless <h5_root>/meta names `expected_schema` and version.

    `h5_root` is an open h5py File or Group; `source` names it in messages.
    """
    if "meta" not in h5_root:
        raise ValueError(f"{source}: not a {expected_schema} file (no /meta group)")
    attrs = h5_root["meta"].attrs
    if "schema" not in attrs:
        raise ValueError(f"{source}: not a {expected_schema} file (/meta has no 'schema')")
    schema = _text(attrs["schema"])
    if schema != expected_schema:
        raise ValueError(f"{source}: file schema is {schema!r}, expected {expected_schema!r}")
    if "schema_version" not in attrs:
        if require_version:
            raise ValueError(f"{source}: /meta has no 'schema_version' "
                             f"(expected {expected_version})")
        return
    version = attrs["schema_version"]
    try:
        version = int(np.asarray(version).item())
    except (TypeError, ValueError):
        raise ValueError(f"{source}: /meta schema_version {version!r} is not an integer")
    if version != expected_version:
        raise ValueError(f"{source}: {expected_schema} schema_version is {version}, this reader "
                         f"supports {expected_version}")


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

    def __repr__(self):
        return (f"Result({self.source!r}, T={self.samples}, "
                f"dynamics={self.has_dynamics}, datasets={len(self.data)})")


def _read_dataset(ds):
    string_info = h5py.check_string_dtype(ds.dtype)
    if string_info is not None:
        values = ds.asstr()[()]
        if ds.shape == ():
            return _text(values)
        return [_text(v) for v in np.asarray(values).ravel()]
    return ds[()]


def read_result_group(group, source="result"):
    """Reads a result laid out under an open h5py File or Group (e.g. a sweep's
    /runs/<id>) after checking its schema. Returns a Result."""
    check_filetype_version(group, RESULT_SCHEMA, RESULT_SCHEMA_VERSION, source)
    data, units, shapes = {}, {}, {}
    base = group.name.rstrip("/")

    def visit(name, obj):
        if not isinstance(obj, h5py.Dataset):
            return
        path = obj.name[len(base):] if base else obj.name
        data[path] = _read_dataset(obj)
        shapes[path] = tuple(obj.shape)
        if "units" in obj.attrs:
            units[path] = _text(obj.attrs["units"])

    group.visititems(visit)
    meta = {}
    for key, value in group["meta"].attrs.items():
        value = _text(value)
        if isinstance(value, np.generic):
            value = value.item()
        meta[key] = value
    return Result(source, data, units, shapes, meta)


def open_result(path, group="/"):
    """Opens a hexdyn-result/1 file, checks its schema and returns a Result with every
    dataset in memory (the file is closed on return). `group` selects a result stored
    below the file root (e.g. "/runs/<id>" of a sweep file)."""
    with h5py.File(path, "r") as f:
        return read_result_group(f[group], source=str(path) if group == "/" else
                                 f"{path}:{group}")


def open_sweep(path):
    """Opens a hexdyn-sweep/1 file read-only after checking its schema; returns the
    h5py.File (the caller closes it)."""
    f = h5py.File(path, "r")
    try:
        check_filetype_version(f, SWEEP_SCHEMA, SWEEP_SCHEMA_VERSION, str(path),
                               require_version=False)
    except Exception:
        f.close()
        raise
    return f


def expected_shape(shape, samples, impacts=None, messages=None):
    """Concrete shape of a contract shape tuple ("T" -> samples, "n", "m")."""
    sizes = {"T": samples, "n": impacts, "m": messages}
    return tuple(sizes[d] if isinstance(d, str) else d for d in shape)
