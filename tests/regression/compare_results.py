#!/usr/bin/python3
"""Compare two hexdyn-result/2 files dataset by dataset, floats to a tolerance: the check
that a refactor changed no result.

    /usr/bin/python3 tests/regression/compare_results.py A.h5 B.h5 [--rtol 1e-9]

Every group, dataset and attribute present in either file is compared (the tree walk of
tests/sweep/compare_sweeps.py). Ignored: the /meta attributes created_utc, wall_time_s
and git_commit, and the values of /solver/seconds.

Rule for a float dataset with values a (file A) and b (file B):
    |a_i - b_i| <= rtol * max(1, M)   for every element i,   M = max(|a|, |b|) over the dataset
that is, relative to the dataset's largest magnitude, with an absolute floor of rtol for
datasets whose values are below 1 (penetrations, accelerations near zero). NaN must match
NaN and infinities must be equal. Shapes and element types must be equal; integer and
string datasets, and all attributes (units, config_yaml, ...), must be equal exactly.

Prints, for every dataset that violates the rule, its worst scaled difference
max|a - b| / max(1, M) with the element and both values; exit status 1 if any dataset
or attribute differs, 0 otherwise.
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

IGNORED_META_ATTRS = {"created_utc", "wall_time_s", "git_commit"}


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

    def __init__(self, rtol):
        super().__init__(sweep=False)
        self.rtol = rtol

    def ignored_attrs(self, path):
        names = super().ignored_attrs(path)
        if path == "/meta":
            names |= IGNORED_META_ATTRS
        return names

    def values_differ(self, path, a, b):
        if a.dtype.kind == "f":
            return float_difference(a[()], b[()], self.rtol)
        return super().values_differ(path, a, b)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a", help="hexdyn-result/2 file (or FILE.h5:/runs/<id> of a sweep)")
    ap.add_argument("b", help="hexdyn-result/2 file (or FILE.h5:/runs/<id> of a sweep)")
    ap.add_argument("--rtol", type=float, default=1e-9,
                    help="relative tolerance on float datasets (default 1e-9)")
    args = ap.parse_args()
    fa, ga = compare_sweeps.open_target(args.a)
    fb, gb = compare_sweeps.open_target(args.b)
    with fa, fb:
        for g, name in ((ga, args.a), (gb, args.b)):
            schema = g["meta"].attrs.get("schema") if "meta" in g else None
            if isinstance(schema, bytes):
                schema = schema.decode()
            if schema != "hexdyn-result/2":
                print(f"compare_results: {name}: schema {schema!r}, expected 'hexdyn-result/2'",
                      file=sys.stderr)
                return 1
        diffs = []
        compare_sweeps.compare(ga, gb, "", ToleranceRules(args.rtol), diffs)
    for d in diffs:
        print(f"compare_results: {d}")
    if diffs:
        print(f"compare_results: {args.a} and {args.b} differ ({len(diffs)} datasets or "
              f"attributes beyond rtol {args.rtol:g})")
        return 1
    print(f"compare_results: {args.a} and {args.b} agree to rtol {args.rtol:g} "
          f"(created_utc, wall_time_s, git_commit, /solver/seconds excluded)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
