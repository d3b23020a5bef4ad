#!/usr/bin/python3
"""Compare two hexdyn result files dataset by dataset, floats to a tolerance: the check
that a refactor changed no result.

    /usr/bin/python3 tests/regression/compare_results.py A.h5 B.h5 [--rtol 1e-9]
        [--allow-new-datasets] [--ignore-layout-version]

A and B are files of `hexdyn run` (hexdyn-result/N), kept runs of a sweep
(FILE.h5:/runs/<id>) or files of `hexdyn replay` (hexdyn-replay/N), both of one kind and of
one layout version (/meta attribute `schema`).

Every group, dataset and attribute present in either file is compared (the tree walk of
tests/sweep/compare_sweeps.py). Ignored: the /meta attributes created_utc, wall_time_s,
git_commit and (replays) source_created_utc, and the values of /solver/seconds and
/replay/seconds.

Rule for a float dataset with values a (file A) and b (file B):
    |a_i - b_i| <= rtol * max(1, M)   for every element i,   M = max(|a|, |b|) over the dataset
that is, relative to the dataset's largest magnitude, with an absolute floor of rtol for
datasets whose values are below 1 (penetrations, accelerations near zero). NaN must match
NaN and infinities must be equal. Shapes and element types must be equal; integer and
string datasets, and all attributes (units, config_yaml, ...), must be equal exactly.

Prints, for every dataset that violates the rule, its worst scaled difference
max|a - b| / max(1, M) with the element and both values; exit status 1 if any dataset
or attribute differs, 0 otherwise.

Two switches compare a file of a newer layout (B) with one of an older (A), each printing
one line per thing it ignored:
  --allow-new-datasets     groups, datasets and attributes present in B only are ignored
                           (those present in A only still fail);
  --ignore-layout-version  the /meta attributes `schema` and `schema_version` may differ in
                           their version (the kind, hexdyn-result or hexdyn-replay, may not).
"""

import argparse
import os
import sys

import numpy as np

import importlib.util  # noqa: E402

# tests/sweep/compare_sweeps.py (tree walk, reading), loaded by its path.
_spec = importlib.util.spec_from_file_location(
    "compare_sweeps", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep", "compare_sweeps.py"))
compare_sweeps = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(compare_sweeps)

IGNORED_META_ATTRS = {"created_utc", "wall_time_s", "git_commit", "source_created_utc"}
IGNORED_VALUES = {"/replay/seconds"}  # a replay's time, as /solver/seconds is a run's
LAYOUT_ATTRS = {"schema", "schema_version"}  # /meta, ignored with --ignore-layout-version
KINDS = ("hexdyn-result/", "hexdyn-replay/")


def float_difference(a, b, rtol):
    """None when float arrays a and b (same shape) agree under the rule above, else a
    description of the worst element."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    nan_a, nan_b = np.isnan(a), np.isnan(b)
    if not np.array_equal(nan_a, nan_b):
        i = np.unravel_index(np.argmax(nan_a != nan_b), a.shape)
        return f"NaN in one file only at {tuple(int(k) for k in i)}: {a[i]!r} vs {b[i]!r}"
    inf = np.isinf(a) | np.isinf(b)
    if not np.array_equal(a[inf], b[inf]):
        return "infinities differ"
    finite = ~(nan_a | inf)
    if not finite.any():
        return None
    scale = max(1.0, float(np.max(np.maximum(np.abs(a[finite]), np.abs(b[finite])))))
    diff = np.where(finite, np.abs(a - b), 0.0)
    worst = float(np.max(diff))
    if worst <= rtol * scale:
        return None
    i = np.unravel_index(np.argmax(diff), a.shape)
    where = tuple(int(k) for k in i)
    return (f"worst scaled difference {worst / scale:.3e} > rtol {rtol:g} "
            f"(at {where}: {a[i]!r} vs {b[i]!r}; scale max(1, max|x|) = {scale:.6g})")


class ToleranceRules(compare_sweeps.Rules):
    """Result files; floats to rtol (rule in the module docstring), the rest exactly."""

    def __init__(self, rtol, ignore_layout_version=False):
        super().__init__(sweep=False)
        self.rtol = rtol
        self.ignore_layout_version = ignore_layout_version

    def ignored_attrs(self, path):
        names = super().ignored_attrs(path)
        if path == "/meta":
            names |= IGNORED_META_ATTRS
            if self.ignore_layout_version:
                names |= LAYOUT_ATTRS
        return names

    def ignored_dataset(self, path):
        return super().ignored_dataset(path) or path in IGNORED_VALUES

    def values_differ(self, path, a, b):
        if a.dtype.kind == "f":
            return float_difference(a[()], b[()], self.rtol)
        return super().values_differ(path, a, b)


def text(value):
    return value.decode() if isinstance(value, bytes) else value


def schema_of(g):
    """The /meta attribute `schema` of group g (None without one)."""
    return text(g["meta"].attrs.get("schema")) if "meta" in g else None


def check_schemas(ga, gb, a, b, ignore_layout_version):
    """None when the two files are of one kind and (unless ignore_layout_version) of one
    layout version, else the reason. Prints what --ignore-layout-version ignored."""
    schemas = (schema_of(ga), schema_of(gb))
    for schema, name in zip(schemas, (a, b)):
        if not isinstance(schema, str) or not schema.startswith(KINDS):
            return f"{name}: schema {schema!r}, expected one of {', '.join(k + 'N' for k in KINDS)}"
    kinds = [s[:s.index("/") + 1] for s in schemas]
    if kinds[0] != kinds[1]:
        return f"{a} is a {schemas[0]} file, {b} a {schemas[1]} file"
    if schemas[0] != schemas[1] and not ignore_layout_version:
        return (f"{a} has layout {schemas[0]}, {b} {schemas[1]} "
                f"(--ignore-layout-version compares them)")
    if ignore_layout_version:
        for attr in sorted(LAYOUT_ATTRS):
            va, vb = (g["meta"].attrs.get(attr) for g in (ga, gb))
            if text(va) != text(vb):
                print(f"compare_results: ignored (--ignore-layout-version): /meta@{attr} "
                      f"{text(va)!r} vs {text(vb)!r}")
    return None


def members(g):
    """Every object path below group g and every attribute as 'PATH@NAME' (the notation of
    compare_sweeps.compare's lines)."""
    out = {f"/@{n}" for n in g.attrs}

    def visit(name, obj):
        out.add(f"/{name}")
        out.update(f"/{name}@{n}" for n in obj.attrs)
    g.visititems(visit)
    return out


def dimension_references(g, path, keep=None):
    """The datasets (path, axis) that attach the dimension scale at `path` of group g, from its
    HDF5 REFERENCE_LIST attribute; only those whose path is in `keep` when given."""
    refs = set()
    for ref, axis in g[path].attrs["REFERENCE_LIST"]:
        name = g.file[ref].name
        if keep is None or name in keep:
            refs.add((name, int(axis)))
    return refs


def drop_new(diffs, ga, gb):
    """diffs without the lines of objects and attributes present in gb only (below an
    object present in gb only: one line for the object), and without a dimension scale's
    REFERENCE_LIST that differs only by datasets present in gb only (HDF5's record of the
    datasets attached to the scale); prints each as ignored."""
    only_b = members(gb) - members(ga)
    suffix = ": present in one file only"
    kept = []
    for d in diffs:
        where = d[:-len(suffix)] if d.endswith(suffix) else None
        if where is not None and where in only_b:
            print(f"compare_results: ignored (--allow-new-datasets): {where} (second file only)")
            continue
        path = d[:-len("@REFERENCE_LIST: differs")] if d.endswith("@REFERENCE_LIST: differs") \
            else None
        if path is not None and path in ga and path in gb:
            in_a = {"/" + m.lstrip("/") for m in members(ga) if "@" not in m}
            if dimension_references(ga, path) == dimension_references(gb, path, in_a):
                print(f"compare_results: ignored (--allow-new-datasets): {path}@REFERENCE_LIST "
                      f"(datasets attached in the second file only)")
                continue
        kept.append(d)
    return kept


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a", help="result or replay file (or FILE.h5:/runs/<id> of a sweep)")
    ap.add_argument("b", help="result or replay file (or FILE.h5:/runs/<id> of a sweep)")
    ap.add_argument("--rtol", type=float, default=1e-9,
                    help="relative tolerance on float datasets (default 1e-9)")
    ap.add_argument("--allow-new-datasets", action="store_true",
                    help="ignore groups, datasets and attributes present in B only")
    ap.add_argument("--ignore-layout-version", action="store_true",
                    help="ignore the layout version of /meta schema and schema_version")
    args = ap.parse_args()
    fa, ga = compare_sweeps.open_target(args.a)
    fb, gb = compare_sweeps.open_target(args.b)
    with fa, fb:
        reason = check_schemas(ga, gb, args.a, args.b, args.ignore_layout_version)
        if reason:
            print(f"compare_results: {reason}", file=sys.stderr)
            return 1
        diffs = []
        compare_sweeps.compare(ga, gb, "", ToleranceRules(args.rtol, args.ignore_layout_version),
                               diffs)
        if args.allow_new_datasets:
            diffs = drop_new(diffs, ga, gb)
    for d in diffs:
        print(f"compare_results: {d}")
    if diffs:
        print(f"compare_results: {args.a} and {args.b} differ ({len(diffs)} datasets or "
              f"attributes beyond rtol {args.rtol:g})")
        return 1
    print(f"compare_results: {args.a} and {args.b} agree to rtol {args.rtol:g} "
          f"(created_utc, wall_time_s, git_commit, source_created_utc, /solver/seconds, "
          f"/replay/seconds excluded)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
