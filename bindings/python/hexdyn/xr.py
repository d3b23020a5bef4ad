"""Labelled views of hexdyn files: xarray Datasets and pandas DataFrames.

The dimensions are those of the files (docs/user/output.md#dimensions-and-coordinates), as
declared in src/hexdyn/io/schema.hpp (`dimension_names`): time, leg, joint, xyz, wxyz,
impact, message, one per sweep axis named by its key, scenario, and those of the envelope.
A computed result (hexdyn.run) and one read from its file give equal Datasets.

Labels: each variable carries the schema's `long_name` and `units` (xarray's plots label
an axis "long_name [units]"), but a dimensionless quantity (units "1") has no `units`, so
that it reads "cost of transport E/(m g d)", not "... [1]"; a sweep axis is named by its
key's last word ("terrain.riser_height": "riser height", units "m").

    import hexdyn
    res = hexdyn.open_result("paper.h5")
    res.to_xarray("joints").torque.sel(joint="L2_femur")     # one group, its own names
    res.to_xarray().joints_torque                            # all groups, named by path
    sw = hexdyn.open_sweep("smoke.h5")
    sw.to_xarray().cost_of_transport.sel({"terrain.riser_height": 0.04})
    sw.to_dataframe()["peak_torque[L2_femur]"]
    hexdyn.open_envelope("envelope.h5").to_xarray().riser_max.sel(criterion="torque")
    hexdyn.open_replay("replay.h5").to_xarray("joints").tracking_error.sel(joint="L2_femur")

xarray and pandas are imported when a function is called (Debian: python3-xarray,
python3-pandas).
"""

import numpy as np

from hexdyn import results as hr

COMPONENTS = {"xyz": ["x", "y", "z"], "wxyz": ["w", "x", "y", "z"]}


def _attrs(spec, units):
    """The attributes of a variable: the schema's long_name, its units (none for "" and
    the dimensionless "1") and CF flags."""
    attrs = {}
    if units and units != "1":
        attrs["units"] = units
    if spec is not None and spec.long_name:
        attrs["long_name"] = spec.long_name
    if spec is not None and spec.path in hr.FLAGS:
        meanings = hr.FLAGS[spec.path]
        attrs["flag_values"] = np.arange(len(meanings), dtype=np.int8)
        attrs["flag_meanings"] = " ".join(meanings)
    return attrs


def _values(value):
    if isinstance(value, list):
        return np.array(value, dtype=object)
    return np.asarray(value)


def _spec(path, ndim):
    """The declaration of `path` with `ndim` dimensions (an envelope with cases declares its
    grids again with the dimension `case`), or None."""
    return next((s for s in hr.DECLARED.get(path, ()) if len(s.dims) == ndim), None)


def _coordinate(res, dim, group=None):
    """(dim, values, attrs) of the dimension `dim` of a result or envelope: its coordinate
    variable in `group` ("GROUP/dim") or at the root ("/dim"), else the component labels;
    None when it has none."""
    here = None if group in (None, "/") else f"{group}/{dim}"
    for path in (here, "/" + dim):
        if path is not None and path in res and np.ndim(_values(res[path])) == 1:
            spec = _spec(path, 1)
            attrs = _attrs(spec, res.units.get(path, ""))
            return (dim, _values(res[path]), attrs)
    if dim in COMPONENTS:
        return (dim, np.array(COMPONENTS[dim], dtype=object))
    return None


def result_to_xarray(res, group=None):
    """An xarray.Dataset of a hexdyn.Result, Envelope or Replay (see Result.to_xarray): the
    datasets of `group` (None: all, named by path), each on the dimensions its declaration
    names, with the coordinates of those dimensions."""
    import xarray as xr
    hr.check_group(res, group)
    if group is not None:
        group = "/" + group.strip("/")
    variables = {}
    for path in res.paths():
        parent, _, name = path.rpartition("/")
        parent = parent or "/"
        if group is not None and parent != group:
            continue
        value = _values(res[path])
        if value.ndim == 1 and _spec(path, 1) is not None and _spec(path, 1).dims == (name,):
            continue  # a coordinate variable (of the root or of its group)
        spec = _spec(path, value.ndim)
        dims = spec.dims if spec is not None else tuple(
            f"{name}_dim_{k}" for k in range(value.ndim))
        key = name if group is not None else path.strip("/").replace("/", "_")
        variables[key] = (dims, value, _attrs(spec, res.units.get(path, "")))
    used = list(dict.fromkeys(d for dims, _, _ in variables.values() for d in dims))
    coords = {}
    for dim in used:
        c = _coordinate(res, dim, group)
        if c is not None:
            coords[dim] = c
    ds = xr.Dataset(variables, coords=coords)
    ds.attrs.update({k: v for k, v in res.meta.items() if isinstance(v, (str, int, float))})
    return ds


def axis_name(key):
    """The name of the quantity a sweep axis sweeps: its key's last word, in words
    ("terrain.riser_height": "riser height")."""
    return key.rsplit(".", 1)[-1].replace("_", " ")


def _axis_coordinate(axis, units):
    values = np.asarray(axis.values, dtype=float) if axis.numeric else np.array(
        axis.values, dtype=object)
    attrs = {"long_name": axis_name(axis.key)}
    if axis.numeric and units and units not in ("1", "key"):
        attrs["units"] = units
    return (axis.key, values, attrs)


def _sweep_columns(sw):
    """(name, values, spec) of the table's columns but the axis ones."""
    for name, value in sw.table.items():
        if name == "axis_index" or name.startswith("axis_"):
            continue
        yield name, _values(value), hr.SPECS.get(f"{hr.SCENARIOS_GROUP}/{name}")


def sweep_to_xarray(sw):
    """An xarray.Dataset of a hexdyn.results.Sweep, one dimension per axis; a cases
    axis's dimension is indexed by its labels and carries each key it sets as a coordinate
    along it (ds["robot.urdf"])."""
    import xarray as xr
    keys = [a.key for a in sw.axes]
    coords = {}
    for i, a in enumerate(sw.axes):
        coords[a.key] = _axis_coordinate(a, sw.units.get(f"axis_{i}", ""))
        for key, column in (a.cases or {}).items():  # a cases axis: what each case sets
            coords[key] = (a.key, _values(column),
                           {"long_name": f"{axis_name(key)} in each {a.key}"})
    if sw.joint_names is not None:  # /joint_names: the labels of the dimension joint
        coords["joint"] = ("joint", np.array(sw.joint_names, dtype=object),
                           {"long_name": "joint name, leg-major"})
    variables = {}
    for name, value, spec in _sweep_columns(sw):
        grid = value.reshape(sw.shape + value.shape[1:])
        dims = tuple(keys) + (("joint",) if value.ndim == 2 else ())
        variables[name] = (dims, grid, _attrs(spec, sw.units.get(name, "")))
    ds = xr.Dataset(variables, coords=coords)
    ds.attrs.update({k: v for k, v in sw.meta.items() if isinstance(v, (str, int, float))})
    return ds


def sweep_to_dataframe(sw):
    """A pandas.DataFrame of a hexdyn.results.Sweep, one row per scenario."""
    import pandas as pd
    columns = {}
    if "id" in sw.table:
        columns["id"] = list(sw.table["id"])
    index = np.asarray(sw.table["axis_index"]).reshape(sw.size, len(sw.axes))
    for i, a in enumerate(sw.axes):
        values = np.asarray(a.values, dtype=float) if a.numeric else np.array(a.values, object)
        columns[a.key] = values[index[:, i]]
        for key, column in (a.cases or {}).items():
            columns[key] = np.asarray(_values(column))[index[:, i]]
    for name, value, _ in _sweep_columns(sw):
        if name == "id":
            continue
        if value.ndim == 2:
            for j, joint in enumerate(sw.joint_names or range(value.shape[1])):
                columns[f"{name}[{joint}]"] = value[:, j]
        else:
            columns[name] = value
    return pd.DataFrame(columns)


def open_envelope(path):
    """The /envelope group of a hexdyn-envelope file with the grid's coordinates
    (tread_depth, duty_factor, peak_speed, criterion; case), as an xarray.Dataset:
    hexdyn.open_envelope(path).to_xarray(). Errors as hexdyn.open_envelope."""
    return hr.open_envelope(path).to_xarray()


def open_replay(path, group=None):
    """A hexdyn-replay file as an xarray.Dataset, labelled as a result (time, leg, joint,
    xyz, gait_cycle): hexdyn.open_replay(path).to_xarray(group). Errors as
    hexdyn.open_replay."""
    return hr.open_replay(path).to_xarray(group)
