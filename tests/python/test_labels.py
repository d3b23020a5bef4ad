#!/usr/bin/python3
"""The files as netCDF-4 readers see them (docs/user/output.md#dimensions-and-coordinates):

  test_labels.py HEXDYN SOURCE_DIR

Writes a result (configs/paper.yaml), a sweep with kept runs (configs/sweeps/smoke.yaml)
and an envelope (tests/data/envelope_quick.yaml), then checks on each: `ncdump -h` reads
it; xarray opens every group with both engines (h5netcdf, netcdf4) with named dimensions
and no phony ones, each dataset on the dimensions its shape declares (schema.hpp's
dimension_names); every group opened alone (a kept run's too) has a coordinate for each
dimension of its variables, holding what h5py reads independently from the datasets that
define it (/model/joint_names, /model/leg_names, /time, the axes; 0..n-1 for an index);
a group's coordinates are copies of the root's and its datasets are attached to them
(schema.hpp, group coordinates); every `units` parses with UDUNITS-2
(`udunits2`), every dataset has its declared `long_name`, the declared CF flags are
there; Result/Sweep.to_xarray and Sweep.to_dataframe agree with the scenario table and
label each variable by its long_name and units, no "[1]" and a sweep axis by its key's name
("riser height [m]"); a file of version 1 (never released) is refused with a ValueError.
Exit 0 when all hold; ncdump or udunits2 missing are skipped with a message.
"""
import os
import shutil
import subprocess
import sys
import tempfile
import warnings

import h5py
import numpy as np
import xarray as xr

import hexdyn
from hexdyn import results as hr
from hexdyn import xr as hx

HEXDYN, SRC = sys.argv[1], sys.argv[2]
ENGINES = ("h5netcdf", "netcdf4")
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL {what}", file=sys.stderr)


def run(*args):
    subprocess.run([HEXDYN, *args], check=True, stderr=subprocess.DEVNULL,
                   env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                            OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))


def groups_and_datasets(path):
    groups, datasets = ["/"], []
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            (groups if isinstance(obj, h5py.Group) else datasets).append("/" + name)
        f.visititems(visit)
    return groups, datasets


def declared(path, root_key=None):
    """The DatasetSpec of a dataset path (below a kept run's group too) and the dims it
    declares ("{key}" replaced by the axis key of `root_key`)."""
    rel = path
    if path.startswith("/runs/"):
        rel = "/" + path.split("/", 3)[3]
    spec = hr.SPECS.get(rel)
    if spec is None and rel.startswith("/axes/"):
        spec = hr.SPECS.get("/axes/{i}/" + rel.rsplit("/", 1)[1])
    if spec is None and rel.startswith("/scenarios/axis_") and rel != "/scenarios/axis_index":
        spec = hr.SPECS["/scenarios/axis_{i}"]
    if spec is None and root_key is not None and rel.strip("/") in root_key:
        spec = hr.SPECS["/{key}"]
    return spec


def run_root(path):
    """The root a path belongs to: "/runs/<id>" below a kept run, else "" (the file's)."""
    parts = path.split("/")
    return "/".join(parts[:3]) if len(parts) >= 3 and parts[1] == "runs" else ""


def is_group_coordinate(ds):
    """A dimension scale in a group below its root: a copy of the root's coordinate
    (schema.hpp, group coordinates)."""
    return bool(h5py.h5ds.is_scale(ds.id)) and ds.parent.name != (run_root(ds.name) or "/")


def text_or_array(values):
    values = np.asarray(values)
    if values.dtype.kind in "OSU":
        return [hr.decode_text(v) for v in values.ravel()]
    return values


def references(f, root):
    """{dimension: its values} read with h5py from the datasets that define them (not from
    the coordinate variables): the model's names, /time, the axes; None for an index."""
    ref = {"xyz": list("xyz"), "wxyz": list("wxyz")}
    for dim, p in (("time", "time"), ("joint", "model/joint_names"), ("leg", "model/leg_names"),
                   ("joint", "joint_names"), ("tread_depth", "axes/tread_depth"),
                   ("duty_factor", "axes/duty_factor"), ("peak_speed", "axes/peak_speed"),
                   ("criterion", "axes/criteria"), ("case", "axes/case"),
                   ("case_key", "axes/case_keys")):
        if f"{root}/{p}" in f and isinstance(f[f"{root}/{p}"], h5py.Dataset):
            ref[dim] = text_or_array(f[f"{root}/{p}"][()])
    axes = f.get("axes")
    if axes is not None and isinstance(axes.get("0"), h5py.Group):  # a sweep's axes
        ref["axis"] = [hr.decode_text(axes[i]["key"][()]) for i in sorted(axes, key=int)]
        for i in axes:
            ref[hr.decode_text(axes[i]["key"][()])] = text_or_array(axes[i]["values"][()])
            if "case_keys" in axes[i]:
                ref[hr.decode_text(axes[i]["key"][()]) + "_key"] = text_or_array(
                    axes[i]["case_keys"][()])
    for dim in ("impact", "message", "gait_cycle", "terrain_point", "scenario", "probe"):
        ref[dim] = None
    return ref


def same_values(got, want):
    got = text_or_array(got)
    if isinstance(want, list) or isinstance(got, list):
        return list(got) == list(want)
    return got.shape == want.shape and np.array_equal(got, want)


def check_group_coordinate(path, f, ds):
    """A group coordinate G/D equals the root's /D: element type, values, units, long_name;
    a dimension scale named D."""
    name = ds.name.rsplit("/", 1)[1]
    root = f.get(f"{run_root(ds.name)}/{name}")
    check(isinstance(root, h5py.Dataset), f"{path}:{ds.name} has a root coordinate")
    if not isinstance(root, h5py.Dataset):
        return
    check(ds.dtype == root.dtype and same_values(ds[()], text_or_array(root[()])),
          f"{path}:{ds.name} values of {root.name}")
    for attr in ("units", "long_name"):
        check(hr.decode_text(ds.attrs.get(attr)) == hr.decode_text(root.attrs.get(attr)),
              f"{path}:{ds.name} {attr} of {root.name}")
    check(hr.decode_text(h5py.h5ds.get_scale_name(ds.id)) == name, f"{path}:{ds.name} scale name")


def check_group_alone(path, g, engine, ref):
    """xarray opens group `g` alone with `engine`: every dimension of its variables has a
    coordinate of that name whose values are those read with h5py (`ref`)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with xr.open_dataset(path, engine=engine, group=g) as ds:
            phony = [d for d in ds.dims if str(d).startswith("phony_dim")]
            check(not phony, f"{path}:{g} ({engine}) phony dims {phony}")
            ds.load()
            for dim in sorted({str(d) for v in ds.variables.values() for d in v.dims}):
                where = f"{path}:{g} ({engine}) coordinate {dim}"
                check(dim in ref, f"{where}: a dimension the test knows")
                if dim not in ds.coords or dim not in ref:
                    check(False, f"{where}: present")
                    continue
                want = ref[dim] if ref[dim] is not None else np.arange(ds.sizes[dim])
                check(same_values(ds[dim].values, want), f"{where}: values")
            return set(ds.dims)


def check_file(path, units_seen):
    groups, datasets = groups_and_datasets(path)
    with h5py.File(path, "r") as f:
        keys = set()
        if "axes" in f and isinstance(f["axes"].get("0"), h5py.Group):  # a sweep
            keys = {hr.decode_text(f["axes"][i]["key"][()]) for i in f["axes"]}
        for p in datasets:
            ds = f[p]
            spec = declared(p, keys)
            if spec is None and is_group_coordinate(ds):
                check_group_coordinate(path, f, ds)
                continue
            check(spec is not None, f"{path}:{p} declared")
            if spec is None:
                continue
            # An axis's values are named by the quantity their key sweeps, its last word
            # spaced ("terrain.riser_height": "riser height", found here from the keys); its
            # other datasets lead their long name with it.
            long_name = hr.decode_text(ds.attrs.get("long_name"))
            swept = {k.split(".")[-1].replace("_", " ") for k in keys}
            if spec.long_name == "swept quantity":
                check(long_name in swept, f"{path}:{p} long_name {long_name!r} in {swept}")
            else:
                check(long_name == spec.long_name or
                      any(long_name == f"{q}: {spec.long_name}" for q in swept),
                      f"{path}:{p} long_name {long_name!r}")
            if "units" in ds.attrs:
                units_seen.add(hr.decode_text(ds.attrs["units"]))
            if spec.path in hr.FLAGS:
                check(hr.decode_text(ds.attrs.get("flag_meanings", "")).split() == hr.FLAGS[spec.path],
                      f"{path}:{p} flag_meanings")
            want = tuple(d if d != "{key}" else None for d in spec.dims)
            got = tuple(h5py.h5ds.get_scale_name(ds.dims[k][0].id).decode() if len(ds.dims[k])
                        else "" for k in range(ds.ndim))
            if "CLASS" in ds.attrs:  # a coordinate: its own scale
                got = (p.rsplit("/", 1)[1],)
            check(all(w is None or w == g for w, g in zip(want, got)) and len(want) == len(got),
                  f"{path}:{p} dims {got}, declared {spec.dims}")
            # Attached to the coordinates of its own group.
            for k in range(ds.ndim if "CLASS" not in ds.attrs else 0):
                check(all(s.parent.name == ds.parent.name for s in ds.dims[k].values()),
                      f"{path}:{p} axis {k} attached to its group's coordinate")
        for name, value in f["meta"].attrs.items():  # numeric attributes with units
            if name.endswith("_units"):
                units_seen.add(hr.decode_text(value))
        refs = {r: references(f, r) for r in {run_root(g) for g in groups}}
    if shutil.which("ncdump"):
        check(subprocess.run(["ncdump", "-h", path], capture_output=True).returncode == 0,
              f"ncdump -h {path}")
    else:
        print("skip: ncdump (Debian netcdf-bin) not installed")
    # Every group, but of the kept runs (all alike) the first one only: time.
    runs = sorted({g.split("/")[2] for g in groups if g.startswith("/runs/")})
    groups = [g for g in groups if not g.startswith("/runs/") or g.split("/")[2] == runs[0]]
    dims = set()
    for engine in ENGINES:
        for g in groups:
            dims |= check_group_alone(path, g, engine, refs[run_root(g)])
    return groups, dims


def check_exercised(files, groups, dims):
    """What the files exercise: the named and valued coordinates, the kept run's groups."""
    result, sweep, envelope = files
    check({"time", "joint", "leg", "xyz", "wxyz", "impact", "message", "gait_cycle",
           "terrain_point"} <= dims[result], f"result dimensions {sorted(dims[result])}")
    check({"time", "joint", "leg", "scenario", "axis", "terrain.riser_height"} <= dims[sweep]
          and any(g.startswith("/runs/") and g.endswith("/joints") for g in groups[sweep]),
          f"sweep dimensions {sorted(dims[sweep])}")
    check({"tread_depth", "duty_factor", "peak_speed", "criterion", "probe"} <= dims[envelope],
          f"envelope dimensions {sorted(dims[envelope])}")


def check_result_values(result):
    """The result's coordinates and values against h5py; the reader's Result. Returns it."""
    with h5py.File(result, "r") as f:
        torque = f["joints/torque"][()]
        times = f["time"][()]
        legs0 = f["impacts/leg"][()]
        # The labels of the dimensions leg and joint: the names the file stores.
        leg_names = [str(hexdyn.decode_text(n)) for n in f["model/leg_names"][()]]
        joint_names = [str(hexdyn.decode_text(n)) for n in f["model/joint_names"][()]]
    for engine in ENGINES:
        with xr.open_dataset(result, engine=engine) as root, \
                xr.open_dataset(result, engine=engine, group="joints") as j:
            check(list(root.joint.values) == joint_names, f"joint names ({engine})")
            check(list(root.leg.values) == leg_names, f"leg names ({engine})")
            check(list(root.wxyz.values) == list("wxyz"), f"wxyz labels ({engine})")
            t = j.torque.assign_coords(joint=root.joint)
            check(np.array_equal(t.sel(joint="L2_femur").values, torque[:, 4]),
                  f"torque.sel(joint='L2_femur') ({engine})")
            # The group alone: its own coordinates select.
            alone = {"joint", "time"} <= set(j.coords)
            check(alone and np.array_equal(j.torque.sel(joint="L2_femur").values, torque[:, 4]),
                  f"torque of the group alone .sel(joint='L2_femur') ({engine})")
            check(alone and np.array_equal(j.torque.sel(time=times[5]).values, torque[5]),
                  f"torque of the group alone .sel(time=...) ({engine})")
            check(j.torque.attrs.get("units") == "N m", f"torque units ({engine})")
            check(j.torque.dims == ("time", "joint"), f"torque dims ({engine})")
    res = hexdyn.open_result(result)
    ds = res.to_xarray("contacts")
    check(ds.force.dims == ("time", "leg", "xyz") and list(ds.leg.values) == leg_names,
          "Result.to_xarray('contacts')")
    check(set(legs0) <= set(range(len(leg_names))) and res.to_xarray().impacts_leg.dims == ("impact",),
          "/impacts/leg 0-based on the impact dimension")
    return res


def check_sweep_reader(sweep):
    sw = hexdyn.open_sweep(sweep)
    with xr.open_dataset(sweep, engine="netcdf4") as root:
        for a in sw.axes:
            check(np.allclose(root[a.key].values, a.values), f"axis {a.key} coordinate")
        check(root["terrain.riser_height"].attrs.get("units") == "m", "axis units m")
        check(root["gait.duty_factor"].attrs.get("units") == "1", "axis units 1")
    x = sw.to_xarray()
    mask = np.isclose(np.asarray(sw.table["axis_0"]), 0.04)
    sel = x.cost_of_transport.sel({"terrain.riser_height": 0.04}).values.ravel()
    check(np.allclose(np.sort(sel), np.sort(sw.table["cost_of_transport"][mask])),
          "Sweep.to_xarray sel by riser height")
    check(x.peak_torque.dims[-1] == "joint", "per-joint metric on the joint dimension")
    df = sw.to_dataframe()
    check(np.allclose(df["peak_torque[L2_femur]"], sw.table["peak_torque"][:, 4]),
          "to_dataframe per-joint column")
    check(np.allclose(df["terrain.riser_height"], sw.table["axis_0"]), "to_dataframe axis")


def check_envelope_reader(envelope):
    env = hx.open_envelope(envelope)
    with h5py.File(envelope, "r") as f:
        criteria = [hr.decode_text(c) for c in f["axes/criteria"][()]]
    check(env.riser_max.dims == ("tread_depth", "duty_factor", "peak_speed", "criterion")
          and list(env.criterion.values) == criteria, "envelope dims and criteria")


def check_units(units):
    if shutil.which("udunits2"):
        for u in sorted(units):
            r = subprocess.run(["udunits2", "-H", u, "-W", ""], capture_output=True,
                               stdin=subprocess.DEVNULL)
            check(r.returncode == 0 and not r.stderr, f"udunits2 parses {u!r}")
    else:
        print("skip: udunits2 (Debian udunits-bin) not installed")
    check({"s", "m", "N m", "N^2 m^2", "1"} <= units, f"units seen {sorted(units)}")


def check_xarray_labels(path, ds, sweep_keys=()):
    """The labels of a reader's Dataset (to_xarray): each variable's long_name is its
    declaration's and its units the file's `units` attribute read with h5py, but none for
    the dimensionless "1", so that no plot label ends in "[1]"; a sweep axis is named by its
    key's last word, in the key's unit (the file's /axes/<i>/values units)."""
    from xarray.plot.utils import label_from_attrs
    with h5py.File(path, "r") as f:
        units = {}  # "/joints/torque": its units attribute, as h5py reads it
        f.visititems(lambda n, o: units.__setitem__("/" + n, hr.decode_text(o.attrs["units"]))
                     if isinstance(o, h5py.Dataset) and "units" in o.attrs
                     and not n.startswith("runs/") else None)
        axis_units = {hr.decode_text(f["axes"][i]["key"][()]):
                      hr.decode_text(f["axes"][i]["values"].attrs.get("units", ""))
                      for i in f["axes"]} if sweep_keys else {}
    seen = 0
    for name, var in ds.variables.items():
        label = label_from_attrs(var).replace("\n", " ")
        check("[1]" not in label, f"{path}: label of {name} {label!r} without [1]")
        if name in sweep_keys:
            short = name.rsplit(".", 1)[1].replace("_", " ")
            want = short + (f" [{axis_units[name]}]" if axis_units[name] not in ("", "1") else "")
            check(label == want, f"{path}: axis {name} labelled {label!r}, expected {want!r}")
            continue
        found = [u for p, u in units.items() if p in ("/" + name, f"/scenarios/{name}")
                 or p.strip("/").replace("/", "_") == name]
        if len(found) == 1:
            seen += 1
            check(var.attrs.get("units") == (None if found[0] == "1" else found[0]),
                  f"{path}: {name} units {var.attrs.get('units')!r}, file {found[0]!r}")
    check(seen > 10, f"{path}: {seen} variables' units compared with the file")


def check_other_versions(result, old):
    """A result file of a version this reader does not read (1, never released) is refused
    with a ValueError naming the version it reads; check_layout too."""
    shutil.copy(result, old)
    with h5py.File(old, "r+") as f:
        f["meta"].attrs["schema"] = "hexdyn-result/1"
        f["meta"].attrs["schema_version"] = np.int64(1)
    for reader in (hexdyn.open_result, hexdyn.check_layout, hexdyn.open_file):
        try:
            reader(old)
            got = "<no exception>"
        except ValueError as e:
            got = str(e)
        check("'hexdyn-result/1'" in got and "\n" not in got and (
            reader is not hexdyn.open_result or f"'{hr.RESULT_SCHEMA}'" in got),
            f"{reader.__name__} of a version-1 file: {got!r}")


def main():
    tmp = tempfile.mkdtemp()
    try:
        files = result, sweep, envelope = tuple(os.path.join(tmp, n)
                                                for n in ("r.h5", "s.h5", "e.h5"))
        run("run", os.path.join(SRC, "configs", "paper.yaml"), "-o", result)
        run("sweep", os.path.join(SRC, "configs", "sweeps", "smoke.yaml"), "-o", sweep,
            "--keep-runs")
        run("envelope", os.path.join(SRC, "tests", "data", "envelope_quick.yaml"), "-o", envelope)
        units, groups, dims = set(), {}, {}
        for path in files:
            groups[path], dims[path] = check_file(path, units)
        check_exercised(files, groups, dims)
        res = check_result_values(result)
        check_sweep_reader(sweep)
        check_envelope_reader(envelope)
        check_units(units)
        check_xarray_labels(result, res.to_xarray())
        sw = hexdyn.open_sweep(sweep)
        check_xarray_labels(sweep, sw.to_xarray(), [a.key for a in sw.axes])
        check_other_versions(result, os.path.join(tmp, "v1.h5"))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print(f"test_labels: {len(failures)} failure(s)", file=sys.stderr)
        sys.exit(1)
    print("test_labels: ok")


if __name__ == "__main__":
    main()
