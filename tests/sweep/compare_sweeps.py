#!/usr/bin/python3
"""Compare two hexdyn HDF5 files object by object, ignoring the fields that may differ
between otherwise identical sweeps (timing and the run's environment).

    /usr/bin/python3 tests/sweep/compare_sweeps.py A.h5 B.h5 [--result]

Every group, dataset (shape, type, values, NaN equal to NaN) and attribute must be equal,
except (sweep files):
    /meta attributes created_utc, wall_time_s, ranks, resumed_scenarios
    /scenarios/wall_time_s
    /runs/<id>/meta attributes created_utc, wall_time_s
    /runs/<id>/solver/seconds
With --result the files are hexdyn-result/5 files (a run of `hexdyn run`, or a group
given as FILE.h5:/runs/<id>): /meta created_utc, wall_time_s and /solver/seconds are
ignored, and so is /meta input_sha256 (a kept run records its sweep's input files, a
`hexdyn run` its scene's). Exit status 0 when equal, 1 with one line per difference otherwise.
"""

import argparse
import re
import sys

import h5py
import numpy as np

SWEEP_IGNORED_ATTRS = {"/meta": {"created_utc", "wall_time_s", "ranks", "resumed_scenarios"}}
IGNORED_DATASETS = [r"^/scenarios/wall_time_s$", r"^/runs/[^/]+/solver/seconds$",
                    r"^/solver/seconds$"]
IGNORED_ATTR_PATTERNS = [(r"^(/runs/[^/]+)?/meta$", {"created_utc", "wall_time_s"})]


def ignored_attrs(path, sweep):
    names = set()
    if sweep:
        names |= SWEEP_IGNORED_ATTRS.get(path, set())
    for pattern, attrs in IGNORED_ATTR_PATTERNS:
        if re.match(pattern, path):
            names |= attrs
            if not sweep:
                names.add("input_sha256")
    return names


def ignored_dataset(path):
    return any(re.match(p, path) for p in IGNORED_DATASETS)


def values_equal(a, b):
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
            return False
        if a.dtype.kind == "f":
            return bool(np.array_equal(a, b, equal_nan=True))
        return bool(np.array_equal(a, b))
    if isinstance(a, float) and isinstance(b, float) and np.isnan(a) and np.isnan(b):
        return True
    return a == b


def read(obj):
    if h5py.check_string_dtype(obj.dtype) is not None:
        v = obj.asstr()[()]
        return np.asarray(v, dtype=object) if obj.shape != () else v
    return obj[()]


class Rules:
    """What compare() skips and how it compares dataset values. This class: exact
    equality (NaN equal to NaN) with the timing fields above ignored; tests/regression/
    compare_results.py derives a tolerance on floats from it."""

    def __init__(self, sweep):
        self.sweep = sweep

    def ignored_attrs(self, path):
        return ignored_attrs(path, self.sweep)

    def ignored_dataset(self, path):
        return ignored_dataset(path)

    def values_differ(self, path, a, b):
        """None when the values of datasets a and b (same shape and type) agree, else a
        short description."""
        return None if values_equal(read(a), read(b)) else "values differ"


_PATHS = {}


def object_path(obj, ref):
    """The path of the object `ref` points to in the file of `obj`. h5py's `.name` of a
    dereferenced object searches the whole file each time; this maps addresses to paths
    once per file."""
    fid = obj.id
    paths = _PATHS.get(fid.fileno)
    if paths is None:
        paths = {}

        def visit(name, info):
            paths.setdefault(info.addr, "/" if name == b"." else "/" + name.decode())
        h5py.h5o.visit(obj.file.id, visit, info=True)
        _PATHS[fid.fileno] = paths
    return paths[h5py.h5o.get_info(h5py.h5r.dereference(ref, fid)).addr]


def attribute(obj, name):
    """An attribute's value; the dimension-scale attributes, which hold object references
    (addresses in their file), as the paths they point to, below a kept run's group."""
    value = obj.attrs[name]
    if name not in ("DIMENSION_LIST", "REFERENCE_LIST"):
        return value

    def where(ref):
        return re.sub(r"^/runs/[^/]+", "", object_path(obj, ref))
    if name == "DIMENSION_LIST":
        return [[where(r) for r in refs] for refs in value]
    return sorted((where(r), int(i)) for r, i in value)


def compare(ga, gb, path, rules, out):
    """Appends one line per difference between groups ga and gb (at `path`)."""
    attrs_a, attrs_b = set(ga.attrs), set(gb.attrs)
    skip = rules.ignored_attrs(path or "/")
    for name in sorted((attrs_a | attrs_b) - skip):
        if name not in attrs_a or name not in attrs_b:
            out.append(f"{path or '/'}@{name}: present in one file only")
        elif not values_equal(attribute(ga, name), attribute(gb, name)):
            out.append(f"{path or '/'}@{name}: differs")
    if not isinstance(ga, h5py.Group):
        return
    names_a, names_b = set(ga), set(gb)
    for name in sorted(names_a ^ names_b):
        out.append(f"{path}/{name}: present in one file only")
    for name in sorted(names_a & names_b):
        a, b, p = ga[name], gb[name], f"{path}/{name}"
        if isinstance(a, h5py.Group) != isinstance(b, h5py.Group):
            out.append(f"{p}: group in one file, dataset in the other")
            continue
        if isinstance(a, h5py.Group):
            compare(a, b, p, rules, out)
            continue
        compare_attrs_only = rules.ignored_dataset(p)
        if not compare_attrs_only:
            if a.shape != b.shape or a.dtype != b.dtype:
                out.append(f"{p}: shape/type {a.shape} {a.dtype} vs {b.shape} {b.dtype}")
            else:
                message = rules.values_differ(p, a, b)
                if message:
                    out.append(f"{p}: {message}")
        elif a.shape != b.shape:
            out.append(f"{p}: shape {a.shape} vs {b.shape}")
        compare(a, b, p, rules, out)


def open_target(spec):
    """FILE or FILE:/group -> (h5py.File, group object, group path prefix)."""
    m = re.match(r"^(.*\.h5):(/.*)$", spec)
    path, group = (m.group(1), m.group(2)) if m else (spec, "/")
    f = h5py.File(path, "r")
    return f, f[group]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--result", action="store_true",
                    help="compare hexdyn-result/5 layouts (FILE or FILE.h5:/runs/<id>)")
    args = ap.parse_args()
    fa, ga = open_target(args.a)
    fb, gb = open_target(args.b)
    with fa, fb:
        diffs = []
        compare(ga, gb, "", Rules(sweep=not args.result), diffs)
    for d in diffs:
        print(f"compare_sweeps: {d}", file=sys.stderr)
    if diffs:
        print(f"compare_sweeps: {args.a} and {args.b} differ ({len(diffs)} differences)",
              file=sys.stderr)
        return 1
    print(f"compare_sweeps: {args.a} and {args.b} are equal (timing fields excluded)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
