"""The types the readers return, one per file kind (hexdyn.results.FILE_KINDS): Result,
Sweep (with its SweepAxis), Envelope, Replay and Study, each a file read into memory (the
file is closed). Result is also what hexdyn.run returns.
"""

from collections.abc import Mapping

import numpy as np

from .h5copy import listed_inputs, write_copy
from .h5files import checked_path, yaml_attribute
from .schema import SCHEMA, SWEEP_STATUS


class UnknownGroupError(KeyError, ValueError):
    """to_xarray(group) of a group the file does not have; the message names the known ones."""

    def __str__(self):
        return str(self.args[0]) if self.args else ""


def check_group(obj, group):
    """Raises UnknownGroupError unless `group` (None: all) is one of obj.groups()."""
    if group is None:
        return
    name = "/" + str(group).strip("/")
    known = obj.groups()
    if name not in known:
        raise UnknownGroupError(f"{obj.source}: no group {name!r} holding datasets (groups: "
                                f"{', '.join(known)})")


class _Datasets(Mapping):
    """A file's datasets by path, read into memory: the mapping of Result, Envelope and
    Replay. `source` (where it came from), `data` {path: values}, `units` {path: `units`
    attribute}, `shapes` {path: shape}, `meta` (the /meta attributes), `attributes` (the
    other groups' attributes as "/terrain/type"), `origin` ((file, group, identity when
    read), for a copy)."""

    def __init__(self, source, data, units, shapes, meta, attributes=None, origin=None):
        self.source = source
        self.path = source
        self.data = data
        self.units = units
        self.shapes = shapes
        self.meta = meta
        self.attributes = dict(attributes or {})
        self.urdf = data.get("/model/urdf", "")
        self._origin = origin
        self._config = None

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

    @property
    def attrs(self):
        """The /meta attributes by name and the other groups' as "/terrain/type"."""
        return {**self.meta, **self.attributes}

    @property
    def config(self):
        """The resolved configuration, /meta config_yaml (dict); ValueError if it is not
        YAML."""
        if self._config is None:
            self._config = yaml_attribute(self.meta, "config_yaml", self.source)
        return self._config

    @property
    def samples(self):
        """T, the number of samples (of /time)."""
        return int(self.shapes["/time"][0])

    def to_xarray(self, group=None):
        """The datasets as an xarray.Dataset with named dimensions and coordinates (time,
        leg, joint, xyz, ...): `group` ("joints", "/contacts") gives that group's datasets
        under their own names, as xarray.open_dataset(file, group=...) does; None all of
        them in one Dataset, named by path ("joints/torque" -> "joints_torque"). Each
        variable's `long_name` and `units` are the schema's, but a dimensionless quantity
        (units "1") has none, so that xarray labels it by its name alone. A group the file
        does not have raises UnknownGroupError (a KeyError and a ValueError) naming the
        known ones. Needs xarray (hexdyn.xr)."""
        check_group(self, group)
        from hexdyn import xr
        return xr.result_to_xarray(self, group)


class Result(_Datasets):
    """One hexdyn-result result in memory, computed (hexdyn.run) or read (open_result,
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

    write(path) writes the result file: a computed result through the compiled writer (the
    file `hexdyn run` writes), a read one as a copy of the objects of the file it was read
    from (see write)."""

    def __init__(self, source, data, units, shapes, meta, attributes=None, handle=None,
                 origin=None):
        super().__init__(source, data, units, shapes, meta, attributes, origin)
        self._handle = handle    # the compiled RunHandle of a computed result

    @property
    def computed(self):
        """True for a result of hexdyn.run, False for one read from a file."""
        return self._handle is not None

    @property
    def has_dynamics(self):
        return "/joints/torque" in self.data

    def write(self, path):
        """Writes the result file of this result to `path`, atomically (a temporary file in
        the target's folder, renamed when complete; nothing is left at `path` on an error)
        and never onto an input: `path` must be a new path or a regular file that is none of
        the files the result came from.

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
        write_copy(self._origin, checked_path(path), listed_inputs(self.meta))

    def __repr__(self):
        kind = "computed" if self.computed else "read"
        return (f"Result({self.source!r}, {kind}, T={self.samples}, "
                f"dynamics={self.has_dynamics}, datasets={len(self.data)})")


class Envelope(_Datasets):
    """A hexdyn-envelope file read into memory (the file is closed), checked against the
    schema.

    env[path]        numpy array of every dataset ("/envelope/riser_max", "/axes/peak_speed");
                     text as str, texts as a numpy array of str of the dataset's shape
    env.units[path]  the `units` attribute; env.shapes[path] the shape
    env.meta         /meta attributes; env.config the envelope file (dict, /meta config_yaml);
                     env.base_config the base scene (dict)
    env.cases        the case labels (list of str), None for a file without `cases:`
    env.criteria     the criteria (list of str)
    env.to_xarray(group="envelope")   the group with the grid's coordinates (xarray)
    """

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
        return super().to_xarray(group)

    def __repr__(self):
        return f"Envelope({self.source!r}, cases={self.cases}, datasets={len(self.data)})"


class Replay(_Datasets):
    """A hexdyn-replay file read into memory (the file is closed), checked against the
    schema: a result's torques replayed through the forward dynamics with compliant contact
    and slip (`hexdyn replay`, docs/theory/replay.md).

    rep[path]        numpy array of every dataset, the replayed motion in the result file's
                     names ("/joints/position", "/contacts/force") and the replay's own
                     ("/joints/tracking_error", "/energy/slip", "/replay/reached_top"); text
                     as str, a list of texts as a list of str
    rep.units[path]  the `units` attribute; rep.shapes[path] the shape
    rep.meta         /meta attributes; rep.config the scene as replayed (dict, /meta
                     config_yaml, its replay: and contact: keys included)
    rep.attrs        rep.meta and the other groups' attributes ("/terrain/type")
    rep.urdf         /model/urdf, the robot as replayed (the result's)
    rep.samples      T, the number of stored samples (up to the end of the replay)
    rep.source_result  the replayed result file (/meta source_result)
    rep.reached_top  True when the robot reached the plan's end (/replay/reached_top)
    rep.to_xarray(group=None)   labelled (xarray), as Result.to_xarray ("joints", "replay")
    """

    @property
    def source_result(self):
        return self.meta.get(SCHEMA["kMetaReplaySource"].name, "")

    @property
    def reached_top(self):
        return bool(int(self.data[SCHEMA["kReplayReachedTop"].path]))

    def __repr__(self):
        return (f"Replay({self.source!r}, T={self.samples}, reached_top={self.reached_top}, "
                f"datasets={len(self.data)})")


class SweepAxis:
    """One swept key: `key` (dotted path), `values` (float array, or list of str for an
    axis of words), `labels` (as written in the sweep file, e.g. "2/3"), `numeric`.
    `units` is the unit of the key the values are in ("m"; None for an axis of words or a
    key without one).
    A cases axis (`cases:` in the sweep file) has `key` its name ("case"), `values` and
    `labels` the case labels, and `cases` {scene key: value per case} (float array or list
    of str), the keys in the order of the sweep file; `cases` is None for other axes."""

    def __init__(self, key, values, labels, cases=None, units=None):
        self.key = key
        self.values = values
        self.labels = labels
        self.numeric = isinstance(values, np.ndarray)
        self.cases = cases
        self.units = units

    @property
    def is_cases(self):
        return self.cases is not None

    def __len__(self):
        return len(self.labels)

    def __repr__(self):
        return f"SweepAxis({self.key!r}, {list(self.labels)})"


class Sweep:
    """A hexdyn-sweep file read into memory (the file is closed).

    sw.axes             list of SweepAxis; scenario index is row-major over them
    sw.shape            tuple of the axis lengths
    sw.table[name]      numpy array, one row per scenario (SCENARIO_DATASETS)
    sw.units[name]      `units` attribute of /scenarios/<name> ("" none)
    sw.ok               boolean mask of the scenarios computed (status 0)
    sw.status_names     status of each scenario as a word ("ok", "reach", ...)
    sw.joint_names      the labels of the dimension joint (/joint_names; None in a file
                        that stores none), J of them
    sw.meta             /meta attributes; sw.config the base scene (dict);
                        sw.spec the sweep file (dict)
    sw.grid(name)       a column reshaped to sw.shape (+ the column's own dims)
    sw.scenario(i)      {axis key: value} of scenario i (a cases axis: its label, then
                        each key its case sets)
    sw.run(i)           Result of scenario i (index or id) from /runs/<id>
    """

    def __init__(self, path, meta, axes, table, units, joint_names, run_ids):
        self.path = str(path)
        self.source = self.path
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
        from .results import open_result
        return open_result(self.path, group=f"/runs/{scenario_id}")

    def to_xarray(self):
        """The scenario table as an xarray.Dataset with one dimension per axis, named by
        its key, holding its values (plus `joint` for per-joint metrics):
        ds.cost_of_transport.sel({"terrain.riser_height": 0.06}). Labels as
        Result.to_xarray: each column's `long_name` and `units`, an axis's name from its key
        ("riser height", units "m"). Needs xarray."""
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


class Study:
    """A hexdyn-study file (analysis/study.py) read into memory (the file is closed).

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


class Robustness(_Datasets):
    """A hexdyn-robustness file read into memory (the file is closed), checked against the
    schema: a plan replayed on perturbed worlds (`hexdyn robustness`,
    docs/user/robustness.md).

    rob[path]        numpy array of every dataset ("/replays/failure", "/perturbations/friction",
                     "/summary/p_success"); text as str, a list of texts as a list of str
    rob.units[path]  the `units` attribute; rob.shapes[path] the shape
    rob.meta         /meta attributes; rob.config the scene with its robustness: section (dict)
    rob.replays      the number of replays
    rob.p_success    the success fraction; rob.interval its Wilson 95 % interval (low, high)
    rob.failure_counts  {failure class: replays}
    rob.to_xarray(group=None)   labelled (xarray): "replays", "perturbations", "summary",
                     "tolerance"
    """

    @property
    def replays(self):
        return int(self.data[SCHEMA["kRobustReplayCount"].path])

    @property
    def p_success(self):
        return float(self.data[SCHEMA["kRobustPSuccess"].path])

    @property
    def interval(self):
        return (float(self.data[SCHEMA["kRobustWilsonLow"].path]),
                float(self.data[SCHEMA["kRobustWilsonHigh"].path]))

    @property
    def failure_counts(self):
        names = self.data[SCHEMA["kFailureClassCoordinate"].path]
        counts = self.data[SCHEMA["kRobustFailureCount"].path]
        return {str(n): int(c) for n, c in zip(names, counts)}

    def __repr__(self):
        return (f"Robustness({self.source!r}, replays={self.replays}, "
                f"p_success={self.p_success:.4g})")
