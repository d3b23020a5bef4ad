"""hexdyn in Python: run scenes in process, read result and sweep files.

    import hexdyn
    r = hexdyn.run("configs/paper.yaml", set={"gait.duty_factor": "3/4"})
    r["/energy/total"]            # numpy float64 (0-d array) [J]
    r["/joints/torque"]           # (T, 18) numpy array [N m], bit for bit the file's dataset
    r.config["gait"]              # the resolved configuration, as a dict
    r.write("out.h5")             # the file `hexdyn run` would write
    hexdyn.validate("configs/sweeps/smoke.yaml")
    res = hexdyn.open_result("out.h5")   # reading files (hexdyn.results)

Errors are hexdyn.Error and its family (ConfigError, a ValueError; IoError, an OSError;
ReachError, PlanningError, SolverError; InternalError), each with the one-line message
`hexdyn` prints after "hexdyn: error: ". A path with a NUL character raises ValueError (the
C++ side would stop at the NUL) in every function that takes a path; the readers raise
hexdyn.IoError for a file whose datasets are off the schema. run() releases the GIL while
the scene computes: threads run scenes in parallel.
"""

import json
from collections.abc import Mapping

from ._version import __git_commit__, __version__
from .results import checked_path as _path
from .results import decode_text, open_result, open_sweep

_compiled = None


def _lib():
    """The compiled part (_hexdyn*.so), imported on first use: reading files needs only h5py."""
    global _compiled
    if _compiled is None:
        from . import _hexdyn as compiled
        _compiled = compiled
    return _compiled


def _value_text(value):
    """An override value as `--set` text: strings as given (YAML-parsed, "p/q" a fraction, as
    on the command line), numbers exactly (repr), None as null, lists and maps as JSON (a
    subset of YAML)."""
    if isinstance(value, str):
        return value
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple, Mapping)):
        return json.dumps(value, allow_nan=False, default=_json_default)
    if hasattr(value, "item"):  # numpy scalars
        return _value_text(value.item())
    raise TypeError(f"set: value {value!r} of type {type(value).__name__} is not a number, string, "
                    "list, map or None")


def _json_default(value):
    if hasattr(value, "item"):
        return value.item()
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"set: value {value!r} cannot be written as YAML")


def _overrides(set):
    if set is None:
        return []
    if not isinstance(set, Mapping):
        raise TypeError(f"set: expected a dict from dotted key to value, got {type(set).__name__}")
    out = []
    for key, value in set.items():
        if not isinstance(key, str):
            raise TypeError(f"set: key {key!r} is not a string")
        out.append(f"{key}={_value_text(value)}")
    return out


class Result(Mapping):
    """One computed scene: a read-only mapping from HDF5 path ("/joints/torque") to its
    dataset, as `hexdyn run` writes it: numpy arrays of the file's dtype and shape (0-d for a
    scalar), numpy arrays of str for string lists, str for /model/urdf.
    `attrs` holds the /meta attributes by name and the other groups' as "/terrain/type",
    `config` the resolved configuration as a dict,
    `write(path)` writes the file."""

    def __init__(self, handle, datasets, attrs):
        self._handle = handle
        self._datasets = datasets
        self.attrs = attrs
        self._config = None

    def __getitem__(self, path):
        return self._datasets[path]

    def __iter__(self):
        return iter(self._datasets)

    def __len__(self):
        return len(self._datasets)

    def __repr__(self):
        return f"<hexdyn.Result '{self.attrs.get('schema')}', {len(self)} datasets>"

    @property
    def config(self):
        """The resolved configuration (/meta config_yaml) as a dict."""
        if self._config is None:
            import yaml
            self._config = yaml.safe_load(self.attrs["config_yaml"])
        return self._config

    def write(self, path):
        """Writes the hexdyn-result/2 file `hexdyn run` would write, with its checks on the
        path (a new path or a regular file that is none of the scene's input files)."""
        _lib().write(self._handle, _path(path))


def run(scene, set=None, *, allow_large=False):
    """Runs the scene file `scene` (a path) with the overrides `set` (a dict from dotted key to
    value, as `--set key=value`) and returns its Result. allow_large: as `--allow-large`."""
    handle, datasets, attrs = _lib().run(_path(scene), _overrides(set), bool(allow_large))
    return Result(handle, datasets, attrs)


def validate(scene, set=None):
    """Checks a scene file or a sweep file as `hexdyn validate` does; raises on the first error.
    Returns {"kind": "scene", "name": ..., "messages": [...]} ("messages": the lines
    `hexdyn validate` prints), or for a sweep file also "scenarios", "out_of_range"
    (scenarios that would be rows with status config) and "first_out_of_range" (the first
    one's message)."""
    return _lib().validate(_path(scene), _overrides(set))


def __getattr__(name):
    # The exception family lives in the compiled part; hexdyn.ConfigError etc. load it.
    if name in ("Error", "ConfigError", "IoError", "ReachError", "PlanningError", "SolverError",
                "InternalError"):
        return getattr(_lib(), name)
    raise AttributeError(f"module 'hexdyn' has no attribute {name!r}")


__all__ = ["run", "validate", "Result", "open_result", "open_sweep", "decode_text", "Error", "ConfigError",
           "IoError", "ReachError", "PlanningError", "SolverError", "InternalError",
           "__version__", "__git_commit__"]
