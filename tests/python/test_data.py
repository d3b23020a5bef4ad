"""One data layer, the package hexdyn: a result computed in process (hexdyn.run) and the same
result read from the file it writes (hexdyn.open_result) are one type with equal datasets,
.meta, .attrs, .units, .config and to_xarray() Datasets, and those Datasets hold the file's
values on the file's dimensions (read back with h5py, independently); write() of a read
result (a file, and a kept run of a sweep) writes the objects of its source: every group,
dataset (type, shape, storage, bytes) and attribute, dimension scales attached as in the
source, compared object by object with h5py; it refuses its source, a directory and a source
changed since it was read, leaving nothing behind. to_xarray of a group the file lacks raises
an error naming the known groups. open_envelope matches xarray's own reading of the file, and
open_study a study file written by analysis/study.py's writer, read back with h5py; every
reader, check_layout and decode_text work with xarray and the compiled part unimportable;
open_file opens each kind by its /meta schema and refuses another schema in one line.
    test_data.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)"""

import hashlib
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import xarray as xr

import hexdyn
from common import args

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")


def cli(*argv):
    p = subprocess.run([HEXDYN, *argv], capture_output=True, text=True)
    assert p.returncode == 0, f"hexdyn {argv}: {p.stderr}"


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def raises(kind, call, *a):
    try:
        call(*a)
    except kind as e:
        return str(e)
    raise AssertionError(f"{call} did not raise {kind.__name__}")


def dim_names(f, ds):
    """The dimensions of an h5py dataset as its dimension scales name them (its own name for
    a scale), read without the package."""
    if ds.attrs.get("CLASS") == b"DIMENSION_SCALE":
        return (ds.name.rsplit("/", 1)[1],)
    names = []
    for refs in ds.attrs.get("DIMENSION_LIST", []):
        names.append(f[refs[0]].name.rsplit("/", 1)[1])
    return tuple(names)


def plain(v):
    """h5py's value as numbers or a list of str, for comparing."""
    if h5py.check_string_dtype(v.dtype) is not None:
        values = v.asstr()[()]
        return values if v.shape == () else [str(s) for s in np.asarray(values).ravel()]
    return v[()]


def as_compared(value):
    """A value as compared: a list of str for text, else a numpy array."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, list):
        return [str(v) for v in value]
    value = np.asarray(value)
    return [str(v) for v in value.ravel()] if value.dtype.kind in "OUS" else value


def same_values(a, b):
    a, b = as_compared(a), as_compared(b)
    if isinstance(a, list) or isinstance(b, list):
        return a == b
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def check_xarray_against_file(ds, path, group):
    """Each variable of `ds` (to_xarray(group) of the result of the file `path`) is the file's
    dataset: values, dimensions as the file's scales name them, units (none for the
    dimensionless "1"); each coordinate the file's coordinate variable."""
    with h5py.File(path, "r") as f:
        by_name = {}
        for p in _paths(f):
            parent, _, leaf = p.rpartition("/")
            if group is None:
                by_name[p.strip("/").replace("/", "_")] = p
            elif (parent or "/") == "/" + group.strip("/"):
                by_name[leaf] = p
        for name, var in ds.data_vars.items():
            h5 = f[by_name[name]]
            assert same_values(var.values, plain(h5)), f"{path}:{h5.name}: values differ"
            assert var.dims == dim_names(f, h5), (h5.name, var.dims, dim_names(f, h5))
            units = h5.attrs.get("units")
            units = units.decode() if isinstance(units, bytes) else units
            # The file's units, but none for the dimensionless "1" (no "[1]" in labels).
            assert var.attrs.get("units") == (None if units == "1" else units), (h5.name,
                                                                                var.attrs)
        for dim in ds.dims:
            if "/" + dim in f:
                assert same_values(ds[dim].values, plain(f["/" + dim])), dim


def _paths(f):
    out = []
    f.visititems(lambda n, o: out.append("/" + n) if isinstance(o, h5py.Dataset) else None)
    return out


def objects(path, group="/"):
    """Every object below `group` of an HDF5 file, read with h5py: {relative path: what it
    is}: datasets by dtype, shape, storage (chunks, compression, shuffle), bytes and
    attributes; groups by attributes and link order tracking; attributes by value, stored
    type and shape, dimension scale references by the relative paths they name."""
    out = {}
    with h5py.File(path, "r") as f:
        root = f[group]
        cut = len(root.name.rstrip("/"))

        def attrs(obj):
            a = {}
            for k in obj.attrs:
                aid = obj.attrs.get_id(k)
                v = obj.attrs[k]
                if k == "DIMENSION_LIST":
                    v = [[f[r].name[cut:] for r in refs] for refs in v]
                elif k == "REFERENCE_LIST":
                    v = sorted((f[r[0]].name[cut:], int(r[1])) for r in v)
                else:
                    v = (repr(v), aid.dtype.str, repr(h5py.check_string_dtype(aid.dtype)),
                         aid.shape)
                a[k] = v
            return a

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                data = obj[()]
                out[name] = ("dataset", obj.dtype.str, repr(h5py.check_string_dtype(obj.dtype)),
                             obj.shape, obj.chunks, obj.compression, obj.compression_opts,
                             obj.shuffle, data.tobytes() if obj.dtype.kind in "fiu" else repr(data),
                             attrs(obj))
            else:
                out[name] = ("group", attrs(obj), obj.id.get_create_plist().get_link_creation_order())
        root.visititems(visit)
        out["."] = ("root", attrs(root))
    return out


def check_copy(source, group, copy):
    a, b = objects(source, group), objects(copy)
    assert a.keys() == b.keys(), f"{copy}: only in the source {sorted(a.keys() - b.keys())}, " \
        f"only in the copy {sorted(b.keys() - a.keys())}"
    differ = [k for k in a if a[k] != b[k]]
    assert not differ, f"{copy}: differs from {source}:{group} in {differ[:5]}"
    return len(a)


with tempfile.TemporaryDirectory() as d:
    # ---- a computed and a read Result of the same scene
    computed = hexdyn.run(PAPER, set={"gait.duty_factor": "3/4"})
    computed.write(f"{d}/run.h5")
    read = hexdyn.open_result(f"{d}/run.h5")
    assert type(computed) is type(read) is hexdyn.Result
    assert computed.computed and not read.computed
    assert set(computed) == set(read), set(computed) ^ set(read)
    for path in computed:
        assert same_values(computed[path], read[path]), f"{path}: computed and read differ"
    assert computed.meta == read.meta, (computed.meta, read.meta)
    assert computed.attrs == read.attrs and "/terrain/type" in read.attrs
    assert computed.units == read.units and read.units["/joints/torque"] == "N m"
    assert computed.config == read.config and read.config["gait"]["duty_factor"] == 0.75
    assert computed.shapes == read.shapes
    assert computed.groups() == read.groups()
    for group in [None] + read.groups():
        a, b = computed.to_xarray(group), read.to_xarray(group)
        xr.testing.assert_identical(a, b)
        check_xarray_against_file(b, f"{d}/run.h5", None if group is None else group)
    print(f"computed = read: {len(read)} datasets, {len(read.groups())} groups to_xarray")

    # ---- to_xarray of a group the file does not have
    for res in (computed, read):
        message = raises(hexdyn.UnknownGroupError, res.to_xarray, "nosuch")
        assert "'/nosuch'" in message and "/joints" in message, message
        assert isinstance(hexdyn.UnknownGroupError(""), KeyError)
        assert isinstance(hexdyn.UnknownGroupError(""), ValueError)

    # ---- write() of a read result: the objects of the file
    read.write(f"{d}/copy.h5")
    n = check_copy(f"{d}/run.h5", "/", f"{d}/copy.h5")
    assert hexdyn.check_layout(f"{d}/copy.h5") == "hexdyn-result/5"
    print(f"copy of a file: {n} objects equal")
    # ... and of a kept run of a sweep, as a file of its own.
    cli("sweep", os.path.join(SRC, "configs", "sweeps", "smoke.yaml"), "-o", f"{d}/sweep.h5",
        "--keep-runs")
    sw = hexdyn.open_sweep(f"{d}/sweep.h5")
    run = sw.run(1)
    run.write(f"{d}/run1.h5")
    run_id = sw.table["id"][1]
    n = check_copy(f"{d}/sweep.h5", f"/runs/{run_id}", f"{d}/run1.h5")
    assert hexdyn.open_result(f"{d}/run1.h5").meta == run.meta
    print(f"copy of a kept run: {n} objects equal")

    # ... never onto its source, a directory, nor from a source changed since it was read.
    before = digest(f"{d}/run.h5")
    for target in (f"{d}/run.h5", d, f"{d}/nofolder/x.h5"):
        message = raises(OSError, read.write, target)
        assert "\n" not in message and message.startswith("cannot write output"), message
    assert digest(f"{d}/run.h5") == before
    os.link(f"{d}/run.h5", f"{d}/hardlink.h5")
    assert "same device and inode" in raises(OSError, read.write, f"{d}/hardlink.h5")
    os.remove(f"{d}/hardlink.h5")
    changed = hexdyn.open_result(f"{d}/copy.h5")
    with h5py.File(f"{d}/copy.h5", "a") as f:
        f["meta"].attrs["version"] = "changed"
    assert "changed since it was read" in raises(OSError, changed.write, f"{d}/new.h5")
    assert not os.path.exists(f"{d}/new.h5")
    assert not [n for n in os.listdir(d) if ".tmp." in n], os.listdir(d)

    # ---- open_envelope: h5py only; its to_xarray as xarray reads the file
    envelope = f"{d}/envelope.h5"
    cli("envelope", os.path.join(SRC, "tests", "data", "envelope_quick.yaml"), "-o", envelope)
    env = hexdyn.open_envelope(envelope)
    with h5py.File(envelope, "r") as f:
        for path in _paths(f):
            name = "/" + path.rsplit("/", 1)[1]
            if path.count("/") > 1 and h5py.h5ds.is_scale(f[path].id) and name in f \
                    and path not in env:  # a group's copy of a root coordinate: read once
                assert np.array_equal(f[path][()], f[name][()]), path
                continue
            assert same_values(env[path], plain(f[path])), path
    with xr.open_dataset(envelope, engine="h5netcdf") as root, \
            xr.open_dataset(envelope, engine="h5netcdf", group="envelope") as group:
        want = group.assign_coords({k: root[k] for k in group.dims if k in root}).load()
    got = env.to_xarray()
    assert sorted(got.data_vars) == sorted(want.data_vars)
    for name in want.data_vars:
        assert got[name].dims == want[name].dims, name
        units = want[name].attrs.get("units")  # none for the dimensionless "1"
        assert got[name].attrs.get("units") == (None if units == "1" else units), name
        a, b = got[name].values, want[name].values
        assert (np.array_equal(a, b, equal_nan=True) if a.dtype != object
                else list(a.ravel()) == list(b.ravel())), name
    for dim in want.dims:
        assert list(got[dim].values) == list(want[dim].values), dim
    assert hexdyn.xr.open_envelope(envelope).identical(got)
    assert "'/nosuch'" in raises(hexdyn.UnknownGroupError, env.to_xarray, "nosuch")
    assert hexdyn.check_layout(envelope) == "hexdyn-envelope/2"
    print(f"envelope: {len(env)} datasets as h5py and xarray read them")

    # ---- open_study: a small study file written by analysis/study.py's own writer
    study = f"{d}/study.h5"
    sys.path.insert(0, os.path.join(SRC, "analysis"))
    import study as study_writer
    rows = []
    for i, label in enumerate(("reference converged", "default", "grid 0.05")):
        row = {name: (f"{label} {name}" if kind == "str" else i + 0.5 if kind == "f8" else i)
               for name, _, kind in study_writer.COLUMNS}
        row["label"] = label
        rows.append(row)
    study_writer.write_study(
        study, {"schema": study_writer.STUDY_SCHEMA,
                "schema_version": np.int64(study_writer.STUDY_SCHEMA_VERSION)},
        rows, {"converged": ({"floor_err_energy": 1e-5, "scene": "paper"},
                             {"energy": ("J", np.array([1.0, 2.0]))})},
        {"err_peak": 0.001, "pass_peak": np.int8(1)})
    st = hexdyn.open_study(study)
    with h5py.File(study, "r") as f:
        assert set(st.rows) == set(f["runs"]) and len(st) == f["runs"]["label"].shape[0]
        for name, ds in f["runs"].items():
            assert same_values(st.rows[name], plain(ds)), name
            assert st.units[name] == hexdyn.decode_text(ds.attrs["units"]), name
        assert st.verdict == {k: hexdyn.decode_text(v).item() if hasattr(v, "item")
                              else hexdyn.decode_text(v) for k, v in f["verdict"].attrs.items()}
        assert set(st.references) == set(f["references"])
        assert st.references["converged"]["scene"] == "paper"
        assert same_values(st.reference_data["converged"]["energy"],
                           f["references"]["converged"]["energy"][()])
        assert st.meta["schema"] == "hexdyn-study/1"
    assert hexdyn.check_layout(study) == "hexdyn-study/1"
    print(f"study: {len(st)} runs, references {sorted(st.references)}")

    # ---- open_file: the kind /meta names, one type per kind; another schema refused
    files = {f"{d}/run.h5": hexdyn.Result, f"{d}/sweep.h5": hexdyn.Sweep,
             envelope: hexdyn.Envelope, study: hexdyn.Study}
    for path, kind in files.items():
        with h5py.File(path, "r") as f:
            schema = f["meta"].attrs["schema"]
            schema = schema.decode() if isinstance(schema, bytes) else schema
        got = hexdyn.open_file(path)
        assert type(got) is kind and hexdyn.check_layout(path) == schema, (path, got)
        assert schema.rsplit("/", 1)[0] in hexdyn.results.FILE_KINDS, schema
    odd = f"{d}/odd.h5"
    with h5py.File(odd, "w") as f:
        f.create_group("meta").attrs["schema"] = "hexdyn-odd/1"
    for reader in (hexdyn.open_file, hexdyn.check_layout):
        got = raises(ValueError, reader, odd)
        assert "'hexdyn-odd/1'" in got and all(k in got for k in hexdyn.results.FILE_KINDS), got
    got = raises(ValueError, hexdyn.open_sweep, f"{d}/run.h5")
    assert "'hexdyn-sweep/" in got and "'hexdyn-result/" in got and "\n" not in got, got
    print(f"open_file: {len(files)} kinds by their /meta schema; another schema refused")

    # ---- every reader without xarray and without the compiled part
    script = f"""
import sys
class Refuse:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("xarray", "pandas") or name == "hexdyn._hexdyn":
            raise ImportError(f"{{name}} refused for this test")
sys.meta_path.insert(0, Refuse())
import hexdyn
env = hexdyn.open_envelope({envelope!r})
assert env.criteria and env["/envelope/riser_max"].ndim == 4
res = hexdyn.open_result({d + "/run.h5"!r})
assert res.units["/joints/torque"] == "N m"
hexdyn.open_sweep({d + "/sweep.h5"!r}).run(1)
hexdyn.open_study({study!r})
for path in ({envelope!r}, {d + "/run.h5"!r}, {d + "/sweep.h5"!r}, {study!r}):
    hexdyn.check_layout(path)
res.write({d + "/nocompiled.h5"!r})
assert hexdyn.decode_text(b"x") == "x" and hexdyn.results.decode_text is hexdyn.decode_text
assert "xarray" not in sys.modules and "hexdyn._hexdyn" not in sys.modules
try:
    res.to_xarray()
except ImportError:
    pass
else:
    raise AssertionError("to_xarray without xarray")
print("readers without xarray: ok")
"""
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    check_copy(f"{d}/run.h5", "/", f"{d}/nocompiled.h5")
    print(p.stdout.strip())
print("python data: ok")
