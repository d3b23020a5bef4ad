#!/usr/bin/python3
"""Checks files against the layout declared in src/hexdyn/io/schema.hpp, as
hexdyn.results (bindings/python/hexdyn/results.py) has it from the generated module (the same declaration the C++ writers use):

  check_schema.py --result RESULT.h5 [--sweep SWEEP.h5 ...]

Every declared dataset is present with its `units` (none where declared ""; the unit of
the key on a sweep axis), `long_name`, CF flags, dimension scales, shape and element type, every
declared attribute with its element type, and the files hold nothing undeclared (no
other dataset, group or attribute) but the group coordinates: in a group, a copy of the
root's coordinate of each dimension its datasets use, to which they are attached. A
result file must hold the dynamics datasets; a sweep file is checked with its /runs/<id>
groups as result layouts. Exit 1 with one line per problem."""
import argparse
import re
import sys

import h5py  # noqa: E402
import numpy as np  # noqa: E402

from hexdyn import results as hr  # noqa: E402

S = hr.SCHEMA
problems = []


def problem(text):
    problems.append(text)


def element_of(dtype):
    if h5py.check_string_dtype(dtype) is not None:
        return "string"
    return {("f", 8): "float64", ("i", 1): "int8", ("i", 4): "int32",
            ("i", 8): "int64"}.get((dtype.kind, dtype.itemsize), str(dtype))


def template(path):
    """Regex of a declared path ("{i}" an axis number, "{id}" a scenario id)."""
    return "^" + re.escape(path).replace(r"\{i\}", r"[0-9]+").replace(r"\{id\}", r"[^/]+") + "$"


def concrete(path, i):
    return path.replace("{i}", str(i))


class FileCheck:
    """Declared items of one file (below `root`), and what was found."""

    def __init__(self, f, root, source):
        self.f, self.root, self.source = f, root.rstrip("/"), source
        self.seen_datasets, self.seen_attributes, self.seen_groups = set(), set(), {"/"}

    def full(self, path):
        return self.root + path

    def axis_keys(self):
        """The keys of the file's sweep axes (/axes/{i}/key); none below a kept run or in a
        file without axes."""
        axes = self.f.get("/axes")
        if not isinstance(axes, h5py.Group):
            return []
        return [hr.decode_text(g["key"][()]) for g in axes.values()
                if isinstance(g, h5py.Group) and "key" in g]

    def dataset(self, spec, sizes, path=None):
        path = path or spec.path
        where = f"{self.source}:{self.full(path)}"
        obj = self.f.get(self.full(path))
        if not isinstance(obj, h5py.Dataset):
            problem(f"{where}: declared dataset missing")
            return None
        self.seen_datasets.add(self.full(path))
        want = tuple(sizes[d] if isinstance(d, str) else d for d in spec.shape)
        if obj.shape != want:
            problem(f"{where}: shape {obj.shape}, declared {spec.shape} = {want}")
        if element_of(obj.dtype) != spec.element:
            problem(f"{where}: element {element_of(obj.dtype)}, declared {spec.element}")
        units = obj.attrs.get(S["kUnitsAttribute"])
        units = units.decode() if isinstance(units, bytes) else units
        if spec.units == "key":  # a sweep axis: the unit of its key, or none (words)
            if units == "SI" or units == "":
                problem(f"{where}: units {units!r}, declared the unit of the axis key")
        elif units != (spec.units or None):
            problem(f"{where}: units {units!r}, declared {spec.units!r}")
        long_name = hr.decode_text(obj.attrs.get(S["kLongNameAttribute"]))
        # An axis's values are named by the quantity its key sweeps, the key's last word
        # spaced (terrain.riser_height: "riser height"); its other datasets lead their long
        # name with that quantity ("riser height: values as written in the sweep file").
        swept = {k.rsplit(".", 1)[-1].replace("_", " ") for k in self.axis_keys()}
        if spec.long_name == S["kSweptQuantityName"] and long_name in swept:
            long_name = spec.long_name
        elif ": " in long_name and long_name.split(": ", 1)[0] in swept:
            long_name = long_name.split(": ", 1)[1]
        if long_name != spec.long_name:
            problem(f"{where}: long_name {long_name!r}, declared {spec.long_name!r}")
        if spec.path in hr.FLAGS:
            meanings = hr.decode_text(obj.attrs.get("flag_meanings", ""))
            values = list(np.asarray(obj.attrs.get("flag_values", [])))
            if meanings.split() != hr.FLAGS[spec.path] or values != list(range(len(hr.FLAGS[spec.path]))):
                problem(f"{where}: flags {values} {meanings!r}, declared {hr.FLAGS[spec.path]}")
            if np.asarray(obj.attrs.get("flag_values", [])).dtype != obj.dtype:
                problem(f"{where}: flag_values not of the dataset's type")
        # Dimension scales: a scale of its own name, or one attached per axis, from the
        # dataset's own group (the group coordinates of schema.hpp).
        if obj.ndim > 0 and "CLASS" not in obj.attrs and len(obj.dims[0]) == 0:
            problem(f"{where}: no dimension scale attached")
        group = obj.parent.name
        for k in range(obj.ndim if "CLASS" not in obj.attrs else 0):
            for scale in obj.dims[k].values():
                if scale.parent.name != group:
                    problem(f"{where}: axis {k} attached to {scale.name}, not a coordinate of "
                            f"{group}")
        for name in (S["kUnitsAttribute"], S["kLongNameAttribute"], "flag_values", "flag_meanings",
                     "DIMENSION_LIST", "CLASS", "NAME", "REFERENCE_LIST"):
            self.seen_attributes.add((self.full(path), name))
        return obj

    def attribute(self, spec, obj_path=None):
        obj_path = self.full(obj_path or spec.object)
        where = f"{self.source}:{obj_path} attribute {spec.name!r}"
        if obj_path not in self.f or spec.name not in self.f[obj_path].attrs:
            problem(f"{where}: declared attribute missing")
            return
        self.seen_attributes.add((obj_path, spec.name))
        value = self.f[obj_path].attrs[spec.name]
        got = "string" if isinstance(value, (str, bytes)) else element_of(np.asarray(value).dtype)
        if got != spec.element or np.asarray(value).shape not in ((), (1,)):
            problem(f"{where}: {got} of shape {np.asarray(value).shape}, declared a scalar "
                    f"{spec.element}")

    def group(self, path):
        self.seen_groups.add(self.full(path))

    def group_coordinate(self, obj):
        """True when `obj`, a dataset the tables do not declare, is a group coordinate
        G/D (schema.hpp): a dimension scale D in a group below the root, a copy of the
        root's coordinate /D (element type, values, units, long_name); a problem when it is a
        scale but not such a copy."""
        if not h5py.h5ds.is_scale(obj.id) or obj.parent.name == (self.root or "/"):
            return False
        name = obj.name.rsplit("/", 1)[1]
        root = self.f.get(f"{self.root}/{name}")
        where = f"{self.source}:{obj.name}"
        if not isinstance(root, h5py.Dataset) or root.name not in self.seen_datasets:
            problem(f"{where}: a dimension scale with no declared coordinate {self.root}/{name}")
            return True
        same = (element_of(obj.dtype) == element_of(root.dtype) and obj.shape == root.shape
                and np.array_equal(obj[()], root[()]))
        for attr in (S["kUnitsAttribute"], S["kLongNameAttribute"]):
            same = same and hr.decode_text(obj.attrs.get(attr)) == hr.decode_text(root.attrs.get(attr))
        if not same:
            problem(f"{where}: not a copy of the coordinate {root.name}")
        if hr.decode_text(h5py.h5ds.get_scale_name(obj.id)) != name:
            problem(f"{where}: dimension scale named {h5py.h5ds.get_scale_name(obj.id)!r}")
        for attr in (S["kUnitsAttribute"], S["kLongNameAttribute"], "CLASS", "NAME",
                     "REFERENCE_LIST"):
            self.seen_attributes.add((obj.name, attr))
        return True

    def undeclared(self, below=None, skip=()):
        """Everything below `below` (default: this check's root) not declared."""
        start = self.f[below or (self.root or "/")]

        def visit(name, obj):
            path = obj.name
            if any(path == s or path.startswith(s + "/") for s in skip):
                return
            if isinstance(obj, h5py.Dataset):
                if path not in self.seen_datasets and not self.group_coordinate(obj):
                    problem(f"{self.source}:{path}: dataset not declared in the schema")
            elif path not in self.seen_groups and not any(
                    d.startswith(path + "/") for d in self.seen_datasets | self.seen_groups):
                problem(f"{self.source}:{path}: group not declared in the schema")
            for name in obj.attrs:
                if (path, name) not in self.seen_attributes:
                    problem(f"{self.source}:{path}: attribute {name!r} not declared")

        for name in start.attrs:
            if (start.name, name) not in self.seen_attributes:
                problem(f"{self.source}:{start.name}: attribute {name!r} not declared")
        start.visititems(visit)


def check_result(f, root, source):
    c = FileCheck(f, root, source)
    sizes = {"T": None, "n": None, "m": None, "Y": None, "K": None, "L": None, "J": None}
    for spec in S["kResultMetaAttributes"]:
        c.attribute(spec)
    c.group(S["kMetaGroup"])
    if c.full(S["kTime"].path) in f:
        sizes["T"] = f[c.full(S["kTime"].path)].shape[0]
    if c.full(S["kImpactLeg"].path) in f:
        sizes["n"] = f[c.full(S["kImpactLeg"].path)].shape[0]
    if c.full(S["kSolverMessages"].path) in f:
        sizes["m"] = f[c.full(S["kSolverMessages"].path)].shape[0]
    if c.full(S["kGaitCycleStart"].path) in f:
        sizes["Y"] = f[c.full(S["kGaitCycleStart"].path)].shape[0]
    if c.full(S["kTerrainY"].path) in f:
        sizes["K"] = f[c.full(S["kTerrainY"].path)].shape[0]
    for symbol, path in hr.SIZE_NAMES.items():  # L and J: the robot's names
        if c.full(path) in f:
            sizes[symbol] = f[c.full(path)].shape[0]
    c.attribute(S["kTerrainType"])
    c.group(S["kTerrainGroup"])
    tables = ["kModelDatasets", "kKinematicDatasets", "kDynamicsDatasets"]
    if c.full(S["kModelLegMapping"].path) in f:  # a robot read from a URDF
        tables.append("kUrdfRobotDatasets")
    if c.full(S["kRequiredFriction"].path) in f:  # unless output.required_friction is false
        tables.append("kRequiredFrictionDatasets")
    if c.full(S["kDriveTorque"].path) in f:  # a scene with actuators
        tables.append("kDriveTrainDatasets")
    if c.full(S["kFeetCenter"].path) in f:  # a robot with a sphere foot
        tables.append("kSphereFootDatasets")
    for table in tables + ["kResultCoordinates"]:
        for spec in S[table]:
            c.dataset(spec, sizes)
    for spec in S["kResultIndexCoordinates"]:  # present when their dimension is used
        if c.full(spec.path) in f:
            c.dataset(spec, {**sizes, "Y": f[c.full(spec.path)].shape[0],
                             "K": f[c.full(spec.path)].shape[0]})
    c.undeclared()
    return c


def check_sweep(f, source):
    c = FileCheck(f, "", source)
    for spec in S["kSweepMetaAttributes"]:
        c.attribute(spec)
    c.group(S["kMetaGroup"])
    N = int(f[S["kMetaGroup"]].attrs[S["kMetaScenarios"].name])
    A = len(f[S["kAxesGroup"]]) if S["kAxesGroup"] in f else 0
    if A == 0:
        problem(f"{source}: no axes")
    c.group(S["kAxesGroup"])
    kinds = set()
    for i in range(A):
        c.group(f"{S['kAxesGroup']}/{i}")
        c.dataset(S["kAxisKey"], {}, concrete(S["kAxisKey"].path, i))
        labels = f.get(concrete(S["kAxisLabels"].path, i))
        V = labels.shape[0] if labels is not None else None
        values = f.get(concrete(S["kAxisNumbers"].path, i))
        numeric = values is not None and h5py.check_string_dtype(values.dtype) is None
        kinds.add(numeric)
        spec = S["kAxisNumbers"] if numeric else S["kAxisWords"]
        column = S["kScenarioAxisNumbers"] if numeric else S["kScenarioAxisWords"]
        c.dataset(spec, {"V": V}, concrete(spec.path, i))
        c.dataset(S["kAxisLabels"], {"V": V}, concrete(S["kAxisLabels"].path, i))
        c.dataset(column, {"N": N}, concrete(column.path, i))
        c.attribute(S["kScenarioAxisKey"], concrete(S["kScenarioAxisKey"].object, i))
        key = hr.decode_text(f[concrete(S["kAxisKey"].path, i)][()])
        coordinate = S["kAxisCoordinateNumbers"] if numeric else S["kAxisCoordinateWords"]
        c.dataset(coordinate, {"V": V}, coordinate.path.replace("{key}", key))
        if concrete(S["kAxisCaseKeys"].path, i) in f:  # a cases axis
            K = f[concrete(S["kAxisCaseKeys"].path, i)].shape[0]
            c.dataset(S["kAxisCaseKeys"], {"K": K}, concrete(S["kAxisCaseKeys"].path, i))
            c.dataset(S["kAxisCaseValues"], {"V": V, "K": K},
                      concrete(S["kAxisCaseValues"].path, i))
            c.dataset(S["kCaseKeyCoordinate"], {"K": K},
                      S["kCaseKeyCoordinate"].path.replace("{key}", key))
    joint_names = f.get(S["kSweepJointNames"].path)
    J = joint_names.shape[0] if joint_names is not None and joint_names.shape else None
    c.dataset(S["kSweepJointNames"], {"J": J})
    for spec in S["kSweepCoordinates"]:
        c.dataset(spec, {"N": N, "A": A, "J": J})
    c.group(S["kScenariosGroup"])
    for spec in S["kScenarioDatasets"]:
        c.dataset(spec, {"N": N, "A": A, "J": J})
    for name, value in S.items():
        if isinstance(value, hr.AttributeSpec) and value.object.startswith(S["kScenariosGroup"]) \
                and "{i}" not in value.object:
            c.attribute(value)
    runs = []
    if S["kRunsGroup"] in f:
        c.group(S["kRunsGroup"])
        for run_id in f[S["kRunsGroup"]]:
            path = S["kRunGroup"].replace("{id}", run_id)
            if not re.match(template(S["kRunGroup"]), path):
                problem(f"{source}:{path}: not a declared run group")
            c.group(path)
            runs.append(check_result(f, path, source))
    c.undeclared(skip=[S["kRunGroup"].replace("{id}", r) for r in f.get(S["kRunsGroup"], {})])
    return kinds, len(runs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--result", action="append", default=[])
    parser.add_argument("--sweep", action="append", default=[])
    args = parser.parse_args()
    declared = sum(isinstance(v, (hr.DatasetSpec, hr.AttributeSpec)) for v in S.values())
    used = set()
    for path in args.result:
        with h5py.File(path, "r") as f:
            if S["kJointTorque"].path not in f:
                problem(f"{path}: a result without dynamics does not exercise the whole layout")
            check_result(f, "/", path)
    for path in args.sweep:
        with h5py.File(path, "r") as f:
            kinds, runs = check_sweep(f, path)
            used |= kinds
            if runs == 0:
                problem(f"{path}: no /runs (run the sweep with --keep-runs)")
    if args.sweep and used != {True, False}:
        problem("the sweep files need an axis of numbers and an axis of words")
    for p in problems:
        print(f"check_schema: {p}", file=sys.stderr)
    if problems:
        sys.exit(1)
    print(f"check_schema: ok: {declared} declarations of {hr.SCHEMA_HEADER} against "
          f"{len(args.result)} result and {len(args.sweep)} sweep file(s)")


if __name__ == "__main__":
    main()
