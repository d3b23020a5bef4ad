#!/usr/bin/python3
"""tests/regression/compare_results.py on hand-made files: the rule on floats, the kinds of
file it reads, and what --allow-new-datasets and --ignore-layout-version ignore (and print)
and what they do not.

    /usr/bin/python3 tests/regression/test_compare_results.py
"""

import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

COMPARE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "compare_results.py")


def write(path, schema="hexdyn-result/3", version=3, extra=None, x=None):
    """A small file of the given layout: /meta, one float and one integer dataset."""
    with h5py.File(path, "w") as f:
        meta = f.create_group("meta")
        meta.attrs["schema"], meta.attrs["schema_version"] = schema, version
        meta.attrs["created_utc"] = path  # ignored: differs between any two files here
        f["base/position"] = np.array([[0.5, 2.0], [3.0, -4.0]]) if x is None else x
        f["solver/status"] = np.array([0, 1], dtype=np.int8)
        f["solver/seconds"] = np.array([len(path) * 1e-3])  # ignored values
        for name, value in (extra or {}).items():
            f[name] = value


def compare(a, b, *options):
    proc = subprocess.run([sys.executable, COMPARE, a, b] + list(options), capture_output=True,
                          text=True)
    return proc.returncode, proc.stdout + proc.stderr


def main():
    failures = []

    def expect(what, got, code, *words):
        if got[0] != code or any(w not in got[1] for w in words):
            failures.append(f"{what}: exit {got[0]} (expected {code}), output:\n{got[1]}")

    with tempfile.TemporaryDirectory() as d:
        p = {k: os.path.join(d, f"{k}.h5") for k in
             ("a", "same", "near", "far", "new", "v4", "v4new", "replay", "replay2", "v2")}
        write(p["a"])
        write(p["same"])
        near = np.array([[0.5, 2.0], [3.0, -4.0 * (1 + 1e-13)]])
        write(p["near"], x=near)
        write(p["far"], x=np.array([[0.5, 2.0], [3.0, -4.0 * (1 + 1e-9)]]))
        write(p["new"], extra={"model/leg_joint_counts": np.array([3, 3])})
        write(p["v4"], "hexdyn-result/4", 4)
        write(p["v4new"], "hexdyn-result/4", 4, {"model/leg_joint_counts": np.array([3, 3])})
        write(p["replay"], "hexdyn-replay/1", 1)
        write(p["replay2"], "hexdyn-replay/1", 1, extra={"replay/seconds": np.array([9.0])})
        write(p["v2"], "hexdyn-result/2", 2)
        with h5py.File(p["replay"], "a") as f:
            f["replay/seconds"] = np.array([1.0])

        expect("equal files", compare(p["a"], p["same"], "--rtol", "0"), 0, "agree")
        expect("1e-13 within rtol 1e-12", compare(p["a"], p["near"], "--rtol", "1e-12"), 0)
        expect("1e-13 beyond rtol 0", compare(p["a"], p["near"], "--rtol", "0"), 1,
               "/base/position")
        expect("1e-9 beyond rtol 1e-12", compare(p["a"], p["far"], "--rtol", "1e-12"), 1,
               "/base/position: worst scaled difference")
        expect("a new dataset", compare(p["a"], p["new"]), 1, "present in one file only")
        expect("a new dataset allowed", compare(p["a"], p["new"], "--allow-new-datasets"), 0,
               "ignored (--allow-new-datasets): /model (second file only)")
        expect("a dataset of the first file only", compare(p["new"], p["a"],
                                                          "--allow-new-datasets"), 1,
               "present in one file only")
        expect("another layout version", compare(p["a"], p["v4"]), 1, "--ignore-layout-version")
        expect("another layout version ignored",
               compare(p["a"], p["v4"], "--ignore-layout-version"), 0,
               "ignored (--ignore-layout-version): /meta@schema 'hexdyn-result/3' vs "
               "'hexdyn-result/4'", "/meta@schema_version 3 vs 4")
        expect("both switches", compare(p["a"], p["v4new"], "--ignore-layout-version",
                                        "--allow-new-datasets"), 0, "second file only")
        expect("replays, /replay/seconds ignored", compare(p["replay"], p["replay2"]), 0)
        expect("a replay against a result", compare(p["a"], p["replay"],
                                                    "--ignore-layout-version"), 1,
               "hexdyn-replay/1 file")
        expect("version 2 files", compare(p["v2"], p["v2"]), 0)
        # A dimension scale's REFERENCE_LIST records the datasets attached to it: one attached
        # in the second file only is allowed with the new dataset; one detached is not.
        scaled = {k: os.path.join(d, f"{k}.h5") for k in ("dims", "dims_new", "dims_lost")}
        for name, attached in (("dims", ["base/position"]),
                               ("dims_new", ["base/position", "model/leg_joint_counts"]),
                               ("dims_lost", [])):
            write(scaled[name], extra={"model/leg": np.array([0, 1]),
                                       "model/leg_joint_counts": np.array([3, 3])}
                  if name != "dims" else {"model/leg": np.array([0, 1])})
            with h5py.File(scaled[name], "a") as f:
                f["model/leg"].make_scale("leg")
                for ds in attached:
                    f[ds].dims[0].attach_scale(f["model/leg"])
        expect("a dataset attached to a scale in the second file only",
               compare(scaled["dims"], scaled["dims_new"], "--allow-new-datasets"), 0,
               "/model/leg@REFERENCE_LIST (datasets attached in the second file only)")
        expect("the same, not allowed", compare(scaled["dims"], scaled["dims_new"]), 1,
               "REFERENCE_LIST")
        expect("a dataset detached from its scale",
               compare(scaled["dims"], scaled["dims_lost"], "--allow-new-datasets"), 1)
    for f in failures:
        print(f"test_compare_results: {f}")
    if failures:
        return 1
    print("test_compare_results: 16 cases pass")
    return 0


if __name__ == "__main__":
    sys.exit(main())
