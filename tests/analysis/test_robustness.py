#!/usr/bin/python3
"""The robustness study end to end, in its quick form (pipelines/robustness.sh --quick,
docs/validation/robustness.md).

Runs the pipeline with the given binary into a temporary directory and checks, from the files
it wrote and against computations made here:
  - the figures are PNG files and the table has one row per scenario of the four sweeps;
  - every row's P(success) is its sweep file's /scenarios/p_success and equals
    (replays - failed replays) / replays from the failure counts of the same row, its interval
    the Wilson interval of those counts (closed form here);
  - every scenario of the sweeps computed (status 0) with its replays;
  - convergence.csv's P after n replays is the mean of the study's first n /replays/reached_top.

    test_robustness.py --hexdyn BINARY --source SOURCE_DIR
"""

import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

Z = 1.959963984540054
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def wilson(k, n):
    p = k / n
    centre = (p + Z * Z / (2 * n)) / (1 + Z * Z / n)
    half = Z / (1 + Z * Z / n) * math.sqrt(p * (1 - p) / n + Z * Z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    a = ap.parse_args()
    out = tempfile.mkdtemp(prefix="hexdyn_robustness_pipeline_")
    p = subprocess.run(["bash", os.path.join(a.source, "pipelines", "robustness.sh"), "--quick",
                        "--hexdyn", a.hexdyn, "--out", out], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"pipelines/robustness.sh --quick failed:\n{p.stderr}")
    for png in ("robustness.png", "convergence.png"):
        with open(os.path.join(out, png), "rb") as f:
            check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"{png} is a PNG")
    with open(os.path.join(out, "robustness.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 16, f"one row per scenario of the four sweeps ({len(rows)})")
    by_sweep = {}
    for r in rows:
        by_sweep.setdefault(f"{r['robot']}_{r['sweep']}", []).append(r)
    for name, sel in sorted(by_sweep.items()):
        with h5py.File(os.path.join(out, f"{name}.h5"), "r") as f:
            s = f["scenarios"]
            check((s["status"][()] == 0).all() and (s["replays"][()] == 3).all(),
                  f"{name}: every scenario computed with its 3 replays")
            for i, r in enumerate(sel):
                n = int(r["replays"])
                failed = sum(int(r[c]) for c in ("slipped", "stubbed", "saturated", "fell",
                                                 "drifted"))
                k = n - failed
                low, high = wilson(k, n)
                check(float(r["p_success"]) == s["p_success"][i] == k / n and
                      math.isclose(float(r["p_low"]), low, abs_tol=1e-12) and
                      math.isclose(float(r["p_high"]), high, abs_tol=1e-12),
                      f"{name} row {i}: P = {k}/{n} with its Wilson interval")
    with h5py.File(os.path.join(out, "paper_1000.h5"), "r") as f:
        reached = f["replays/reached_top"][()]
    with open(os.path.join(out, "convergence.csv"), newline="") as f:
        conv = list(csv.DictReader(f))
    check([int(c["replays"]) for c in conv] == [10, 20] and all(
        float(c["p_success"]) == np.mean(reached[:int(c["replays"])]) for c in conv),
        "convergence.csv: P after n replays = mean of the first n outcomes")
    shutil.rmtree(out, ignore_errors=True)
    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("robustness pipeline: every check passed")


if __name__ == "__main__":
    main()
