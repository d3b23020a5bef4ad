#!/usr/bin/python3
"""`hexdyn robustness` (docs/user/robustness.md) and its hexdyn-robustness/1 file, against
second computations:

  test_robustness_cli.py HEXDYN SOURCE_DIR

  - a study of zero error is the plain replay (of the scene planned again, and of a result
    file's stored plan): every /replays/energy and /replays/steps equal
    `hexdyn replay`'s /replay/energy and /replay/steps of `hexdyn run`'s result, bit for bit,
    P = 1 and the Wilson interval [n/(n + z^2), 1];
  - the file is the same on 1 and 2 threads but for its timing fields;
  - the drawn errors recorded in the file follow their distributions: scipy's
    Kolmogorov-Smirnov test of the riser errors (a truncated normal, scipy.stats.truncnorm)
    and of the friction errors (uniform), at the 0.1 % level;
  - /summary against /replays: the success fraction, the failure counts per class, the
    Wilson interval from its closed form;
  - hexdyn.open_robustness and xarray read every group, on the file's dimensions; the
    in-process hexdyn.robustness returns the file's datasets;
  - bad input: an unknown perturbation, a riser error as large as a riser, an output onto
    the scene: one line naming the key (or the file), exit status 2, no output written and
    the scene untouched.
"""

import math
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import xarray as xr
from scipy import stats

import hexdyn
from common import args, cli_error, file_datasets

Z = 1.959963984540054
failures = []


def check(ok, what, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (f": {detail}" if detail and not ok else ""))
    if not ok:
        failures.append(what)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{p.stderr}")
    return p.stderr


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset)
                     else None)
        meta = dict(f["meta"].attrs)
    return out, meta


def zero_error(hexdyn_bin, src, tmp):
    paper = os.path.join(src, "configs", "paper.yaml")
    run([hexdyn_bin, "run", paper, "-o", f"{tmp}/paper.h5"])
    run([hexdyn_bin, "replay", f"{tmp}/paper.h5", "-o", f"{tmp}/replay.h5"])
    run([hexdyn_bin, "robustness", paper, "-o", f"{tmp}/zero.h5", "-j", "2",
         "--set", "robustness.replays=3"])
    with h5py.File(f"{tmp}/replay.h5", "r") as rep, h5py.File(f"{tmp}/zero.h5", "r") as rob:
        energy, steps = rep["replay/energy"][()], rep["replay/steps"][()]
        check((rob["replays/energy"][()] == energy).all(),
              "zero error: every replay's energy is hexdyn replay's, bit for bit",
              f"{rob['replays/energy'][()]} vs {energy}")
        check((rob["replays/steps"][()] == steps).all(), "zero error: the same integrator steps")
        check(rob["summary/p_success"][()] == 1.0 and (rob["replays/failure"][()] == 0).all(),
              "zero error: P = 1, no failure")
        n = 3
        check(math.isclose(rob["summary/wilson_low"][()], n / (n + Z * Z), rel_tol=1e-12) and
              rob["summary/wilson_high"][()] == 1.0, "zero error: Wilson [n/(n+z^2), 1]")
    # The stored plan of the result file, replayed as it is: the same replays.
    run([hexdyn_bin, "robustness", f"{tmp}/paper.h5", "-o", f"{tmp}/stored.h5",
         "--set", "robustness.replays=2"])
    with h5py.File(f"{tmp}/stored.h5", "r") as rob:
        check((rob["replays/energy"][()] == energy).all() and
              (rob["replays/steps"][()] == steps).all(),
              "a result file's stored plan: the same replays as hexdyn replay's, bit for bit")
    status, line = cli_error(hexdyn_bin, ["robustness", f"{tmp}/paper.h5", "-o",
                                          f"{tmp}/no.h5", "--set", "gait.duty_factor=0.6"])
    check(status == 2 and "gait.duty_factor" in line and not os.path.exists(f"{tmp}/no.h5"),
          "a result file with a key its plan cannot honour: refused", line)


def threads_and_draws(hexdyn_bin, src, tmp):
    scene = f"{tmp}/draws.yaml"
    with open(scene, "w") as f:
        f.write(f"""inherit: {src}/configs/paper.yaml
robustness:
  replays: 84
  seed: 11
  perturbations:
    riser_height: {{distribution: normal, sigma: 0.0004, bound: 0.001}}
    friction: {{distribution: uniform, low: -0.08, high: 0.02}}
""")
    run([hexdyn_bin, "robustness", scene, "-o", f"{tmp}/j1.h5", "-j", "1",
         "--set", "robustness.replays=6"])
    run([hexdyn_bin, "robustness", scene, "-o", f"{tmp}/j2.h5", "-j", "2",
         "--set", "robustness.replays=6"])
    a, ma = datasets(f"{tmp}/j1.h5")
    b, mb = datasets(f"{tmp}/j2.h5")
    timing = {"replays/wall_time", "summary/plan_wall_time"}
    same = a.keys() == b.keys() and all(
        np.array_equal(a[k], b[k], equal_nan=a[k].dtype.kind == "f") for k in a if k not in timing)
    check(same, "the file is the same on 1 and 2 threads (timing fields aside)")
    check(all(ma[k] == mb[k] for k in ma if k not in ("created_utc", "wall_time_s")),
          "the same /meta on 1 and 2 threads")

    run([hexdyn_bin, "robustness", scene, "-o", f"{tmp}/draws.h5"])
    with h5py.File(f"{tmp}/draws.h5", "r") as f:
        risers = f["perturbations/riser_height"][()]
        mu = f["perturbations/friction"][()]
        reached = f["replays/reached_top"][()]
        failure = f["replays/failure"][()]
        counts = f["summary/failure_count"][()]
        names = [hexdyn.decode_text(x) for x in f["failure_class"][()]]
        p = f["summary/p_success"][()]
        low, high = f["summary/wilson_low"][()], f["summary/wilson_high"][()]
    check(risers.shape == (84, 12) and mu.shape == (84,), "the draws' shapes: (replays, steps)",
          str(risers.shape))
    ks_r = stats.kstest(risers.ravel(), stats.truncnorm(-2.5, 2.5, scale=0.0004).cdf)
    ks_m = stats.kstest(mu, stats.uniform(loc=-0.08, scale=0.1).cdf)
    check(ks_r.pvalue > 1e-3, "riser errors follow the truncated normal (KS)", str(ks_r))
    check(ks_m.pvalue > 1e-3, "friction errors follow the uniform (KS)", str(ks_m))
    n, k = len(reached), int(reached.sum())
    check(p == k / n, "/summary/p_success = mean of /replays/reached_top")
    check(list(counts) == [int(np.count_nonzero(failure == c)) for c in range(6)] and
          names == ["none", "slipped", "stubbed", "saturated", "fell", "drifted"],
          "/summary/failure_count per /failure_class", f"{counts} {names}")
    centre = (p + Z * Z / (2 * n)) / (1 + Z * Z / n)
    half = Z / (1 + Z * Z / n) * math.sqrt(p * (1 - p) / n + Z * Z / (4 * n * n))
    check(math.isclose(low, max(0.0, centre - half), abs_tol=1e-12) and
          math.isclose(high, min(1.0, centre + half), abs_tol=1e-12), "the Wilson interval")
    print(f"     {n} replays: P = {p:.3f} [{low:.3f}, {high:.3f}], failures {dict(zip(names, counts))}")

    # In process: hexdyn.robustness holds the file's datasets (timing aside), on any threads.
    mem = hexdyn.robustness(scene, set={"robustness.replays": 6}, threads=2)
    stored, _ = file_datasets(f"{tmp}/j1.h5")  # group coordinates left out
    def same_values(x, y):
        x, y = np.asarray(x), np.asarray(y)
        if y.dtype.kind in "OSU":  # texts: bytes in the file, str in memory
            return [hexdyn.decode_text(v) for v in x.ravel()] == \
                [hexdyn.decode_text(v) for v in y.ravel()]
        return np.array_equal(x, y, equal_nan=y.dtype.kind == "f")
    differ = [p for p in stored
              if p[1:] not in timing and not same_values(mem.data.get(p), stored[p][0])]
    check(not differ and set(mem.data) == set(stored),
          "hexdyn.robustness: the same datasets as the file of hexdyn robustness",
          f"{differ} {set(mem.data) ^ set(stored)}")
    rob = hexdyn.open_robustness(f"{tmp}/draws.h5")
    check(rob.replays == n and rob.p_success == p and rob.interval == (low, high),
          "open_robustness: replays, p_success, interval")
    check(hexdyn.check_layout(f"{tmp}/draws.h5") == "hexdyn-robustness/1", "check_layout")
    for engine in ("h5netcdf", "netcdf4"):
        pert = xr.open_dataset(f"{tmp}/draws.h5", group="perturbations", engine=engine)
        reps = xr.open_dataset(f"{tmp}/draws.h5", group="replays", engine=engine)
        check(pert.riser_height.dims == ("replay", "step") and
              np.array_equal(pert.riser_height.values, risers) and
              list(pert.step.values) == list(range(1, 13)) and
              reps.reached_top.dims == ("replay",), f"xarray ({engine}) reads the groups")


def bad_input(hexdyn_bin, src, tmp):
    paper = os.path.join(src, "configs", "paper.yaml")
    out = f"{tmp}/bad.h5"
    status, line = cli_error(hexdyn_bin, [
        "robustness", paper, "-o", out,
        "--set", "robustness.perturbations.wobble.distribution=normal"])
    check(status == 2 and "robustness.perturbations.wobble" in line and not os.path.exists(out),
          "an unknown perturbation: one line naming it, exit 2, no file", line)
    status, line = cli_error(hexdyn_bin, [
        "robustness", paper, "-o", out,
        "--set", "robustness.perturbations.riser_height.distribution=uniform",
        "--set", "robustness.perturbations.riser_height.low=-0.06",
        "--set", "robustness.perturbations.riser_height.high=0"])
    check(status == 2 and "robustness.perturbations.riser_height" in line and "reverse" in line
          and not os.path.exists(out), "a riser error as large as a riser: refused", line)
    copy = f"{tmp}/scene.yaml"
    shutil.copy(paper, copy)
    before = open(copy, "rb").read()
    status, line = cli_error(hexdyn_bin, ["robustness", copy, "-o", copy])
    check(status == 2 and open(copy, "rb").read() == before,
          "an output onto the scene: refused, the scene untouched", line)


def main():
    hexdyn_bin, src = args()
    tmp = tempfile.mkdtemp(prefix="hexdyn_robustness_")
    try:
        zero_error(hexdyn_bin, src, tmp)
        threads_and_draws(hexdyn_bin, src, tmp)
        bad_input(hexdyn_bin, src, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        sys.exit(f"{len(failures)} check(s) failed: {failures}")
    print("robustness: every check passed")


if __name__ == "__main__":
    main()
