#!/usr/bin/python3
"""Pinned whole-pipeline regression: the paper run's and the smoke sweep's key results
against tests/regression/reference.json, to stated tolerances.

    /usr/bin/python3 tests/regression/regression.py check  --hexdyn build/hexdyn [--source .] [--workdir DIR]
    /usr/bin/python3 tests/regression/regression.py update --hexdyn build/hexdyn [--source .] --reason "TEXT"
    /usr/bin/python3 tests/regression/regression.py noise  --hexdyn build/hexdyn [--ulps=-1,1]

(PYTHONPATH=build/python, as ctest sets it: the file's text is read by hexdyn.decode_text.)

All run, on one rank and without mpirun,
    hexdyn run   SOURCE/configs/paper.yaml         -o WORKDIR/paper.h5
    hexdyn sweep SOURCE/configs/sweeps/smoke.yaml  -o WORKDIR/smoke.h5
and extract the quantities below. WORKDIR is a temporary directory removed at the end
unless --workdir is given (then the files are left there).

`check` compares them with the reference: one line per quantity that differs (name,
reference, got, tolerance); exit status 1 if any does, 0 if all agree. ctest runs it as
`regression.paper_and_smoke`.

`update` is the explicit switch that rewrites the reference (temporary file + rename).
It requires --reason, a sentence on the deliberate change that moved the results, which
is stored in the file so that it shows in the diff; it first prints how every quantity
moved. No test runs it. When an update is legitimate: docs/dev/testing.md#updating-the-pin.

`noise` reruns both with one input of configs/paper.yaml at a time moved by a few units
in the last place and prints, per quantity, the largest change against its rtol: the
measurement behind TOLERANCES (exit status 1 if a margin is below 10).

Tolerance rule, per quantity (rtol written next to each quantity in reference.json):
    |got_i - ref_i| <= rtol * scale   for every element i,
    scale = max |ref| over the quantity's elements (NaN ignored; 1 if all are 0),
NaN must match NaN (written null in the JSON); rtol 0 means exact (integers, strings,
counts, shapes). The rtol values are set in TOLERANCES below, with their reasons.

Paper run (hexdyn-result/5) quantities:
    samples                     T, number of samples
    total_mass                  /model/total_mass [kg]
    duration                    /time[-1] - /time[0] [s]
    energy_total, energy_joint  /energy/total, /energy/per_joint (18) [J]
    cost_of_transport, distance /energy/cost_of_transport [1], /energy/distance [m]
    impacts_count               n, number of touchdowns
    impacts_leg                 /impacts/leg (n) + 1: 1-based (the file counts from 0)
    impacts_t_start, impacts_duration, impacts_peak_force, impacts_impulse   (n) [s, s, N, N s]
    peak_torque                 max over samples of |tau_k|, per joint (18) [N m]
    rms_torque                  sqrt(int tau_k^2 dt / duration), the integral by the trapezoid
                                rule over /time, per joint (18) [N m] (the sweep's rms_torque)
    solver_status_counts        samples with /solver/status 0 (optimal), 1 (relaxed), 2 (failed)
    peak_torque_between_impacts, rms_torque_between_impacts
                                the same over the samples / intervals between impacts defined
                                below (the RMS over those intervals' total length)
    fz_between_impacts_*        sum over legs of /contacts/force[..., z] (the vertical force the
                                terrain exerts on the robot), over the samples where no leg is
                                in phase 1 (impact): _samples (count), _time (length of the
                                intervals between two consecutive such samples [s]), _mean (its
                                trapezoid time integral over those intervals / _time [N]),
                                _min, _max [N], _mean_over_weight (_mean / (total_mass * 9.81))
Smoke sweep (hexdyn-sweep/5) quantities: scenarios (count), and the /scenarios columns
    id, status, message, axis_0.., energy, cost_of_transport, peak_impact_force, duration,
    distance, peak_torque (N,18), rms_torque (N,18), relaxed_samples, failed_samples, samples.
"""

import argparse
import datetime
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
from hexdyn import decode_text
import numpy as np

from regression_compare import (  # this folder: the comparison half
    UNITS, to_json, format_json, deviation, compare_all)

FORMAT = "hexdyn-regression/1"
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_REFERENCE = os.path.join(HERE, "reference.json")
DEFAULT_SOURCE = os.path.normpath(os.path.join(HERE, "..", ".."))
PAPER_CONFIG = "configs/paper.yaml"
SMOKE_SWEEP = "configs/sweeps/smoke.yaml"
# m/s², docs/theory/conventions.md#frames; only for the weight in fz_between_impacts
STANDARD_GRAVITY = 9.81

# Tolerances. One binary gives bit-identical files run after run, and a Debug (-O0)
# build of the same commit gives the same bits as the Release build; but any change of
# the floating-point operations (a refactor, another compiler or Eigen) perturbs the
# computation at the rounding level, and some quantities amplify that: the touchdown
# transients are integrated with adaptive steps and their samples are relaxed
# allocations, so a sample inside a transient moves by up to ~1e-3 of the torque scale
# when an input moves by one ulp. `regression.py noise` measures this (each of 12 inputs
# of configs/paper.yaml moved by +-1..4 ulp, 96 runs); the largest change of each
# quantity, relative to its scale, is in the comment. Every rtol is at least ~15 times
# that and as tight as it allows (a build with -march=native -ffp-contract=fast, i.e.
# FMA, moves the quantities by as much as these perturbations and passes); quantities outside the transients stay at 1e-9, which
# catches a 1e-8 change of gravity (docs/dev/testing.md#regression-pin).
EXACT = 0.0
SMOOTH = 1e-9        # no transient sample involved: noise <= 1e-14
EVENT = 1e-8         # touchdown ODE with event location: noise <= 5e-11
TRANSIENT_SUM = 1e-5    # paper-run integrals that include the relaxed transient samples
COARSE_SUM = 1e-4       # smoke integrals where one sample inside a transient weighs 0.05 s
TRANSIENT_PEAK = 1e-2   # where one relaxed transient sample can be the value itself
TOLERANCES = {
    # paper run                                      measured noise (96 runs)
    "samples": EXACT,
    "total_mass": SMOOTH,                            # 0
    "duration": SMOOTH,                              # 1.0e-15
    "energy_total": TRANSIENT_SUM,                   # 7.4e-8
    "energy_joint": TRANSIENT_SUM,                   # 3.5e-7
    "cost_of_transport": TRANSIENT_SUM,              # 7.4e-8
    "distance": SMOOTH,                              # 8.7e-16
    "impacts_count": EXACT,
    "impacts_leg": EXACT,
    "impacts_t_start": SMOOTH,                       # 2.1e-16
    "impacts_duration": EVENT,                       # 5.3e-11
    "impacts_peak_force": EVENT,                     # 2.3e-11
    "impacts_impulse": EVENT,                        # 9.9e-15
    "peak_torque": TRANSIENT_PEAK,                   # 2.5e-4
    "rms_torque": TRANSIENT_SUM,                     # 1.4e-7
    "peak_torque_between_impacts": SMOOTH,           # 1.2e-14
    "rms_torque_between_impacts": SMOOTH,            # 5.4e-15
    "solver_status_counts": EXACT,
    "fz_between_impacts_samples": EXACT,
    "fz_between_impacts_time": SMOOTH,               # 4.0e-15
    "fz_between_impacts_mean": SMOOTH,               # 2.2e-16
    "fz_between_impacts_min": SMOOTH,                # 4.4e-16
    "fz_between_impacts_max": SMOOTH,                # 4.3e-16
    "fz_between_impacts_mean_over_weight": SMOOTH,   # 2.2e-16
    # smoke sweep
    "scenarios": EXACT,
    "id": EXACT,
    "status": EXACT,
    "message": EXACT,
    "axis_*": EXACT,                                 # the sweep file's values, parsed
    "energy": COARSE_SUM,                            # 5.1e-6
    "cost_of_transport (smoke)": COARSE_SUM,         # 5.1e-6
    "peak_impact_force": EVENT,                      # 1.7e-11
    "duration (smoke)": SMOOTH,                      # 3.2e-15
    "distance (smoke)": SMOOTH,                      # 8.5e-16
    "peak_torque (smoke)": TRANSIENT_PEAK,           # 6.3e-4
    "rms_torque (smoke)": TRANSIENT_PEAK,            # 1.7e-4
    "relaxed_samples": EXACT,
    "failed_samples": EXACT,
    "samples (smoke)": EXACT,
}
SMOKE_COLUMNS = ("id", "status", "message", "energy", "cost_of_transport", "peak_impact_force",
                 "duration", "distance", "peak_torque", "rms_torque", "relaxed_samples",
                 "failed_samples", "samples")


def tolerance(name, section):
    for key in (f"{name} ({section})", name):
        if key in TOLERANCES:
            return TOLERANCES[key]
    if name.startswith("axis_"):
        return TOLERANCES["axis_*"]
    raise KeyError(f"no tolerance stated for {section}.{name} (TOLERANCES in {__file__})")


# ---------------------------------------------------------------- extraction

def text(value):
    return str(decode_text(value))


def check_schema(f, expected, path):
    schema = text(f["meta"].attrs.get("schema", b"")) if "meta" in f else ""
    if schema != expected:
        raise RuntimeError(f"{path}: schema {schema!r}, expected {expected!r}")


def trapezoid(y, t, axis=0):
    """Trapezoid integral of y over t along axis 0 (numpy-version independent)."""
    dt = np.diff(t)
    mid = 0.5 * (y[1:] + y[:-1])
    return np.tensordot(dt, mid, axes=(0, axis))


def paper_quantities(path):
    with h5py.File(path, "r") as f:
        check_schema(f, "hexdyn-result/5", path)
        t = f["/time"][()]
        tau = f["/joints/torque"][()]
        phase = f["/contacts/phase"][()]
        force = f["/contacts/force"][()]
        status = f["/solver/status"][()]
        mass = float(f["/model/total_mass"][()])
        q = {
            "samples": int(t.size),
            "total_mass": mass,
            "duration": float(t[-1] - t[0]),
            "energy_total": float(f["/energy/total"][()]),
            "energy_joint": f["/energy/per_joint"][()],
            "cost_of_transport": float(f["/energy/cost_of_transport"][()]),
            "distance": float(f["/energy/distance"][()]),
            "impacts_count": int(f["/impacts/leg"].shape[0]),
            # pinned 1-based; the file counts from 0 since hexdyn-result/2
            "impacts_leg": f["/impacts/leg"][()].astype(np.int64) + 1,
            "impacts_t_start": f["/impacts/t_start"][()],
            "impacts_duration": f["/impacts/duration"][()],
            "impacts_peak_force": f["/impacts/peak_force"][()],
            "impacts_impulse": f["/impacts/impulse"][()],
        }
    q["peak_torque"] = np.max(np.abs(tau), axis=0)
    q["rms_torque"] = np.sqrt(trapezoid(tau * tau, t) / (t[-1] - t[0]))
    q["solver_status_counts"] = np.array([int(np.sum(status == s)) for s in (0, 1, 2)])
    # Vertical contact force between impacts: samples with no leg in phase 1, intervals
    # whose two ends are such samples.
    fz = force[:, :, 2].sum(axis=1)
    free = ~np.any(phase == 1, axis=1)
    both = free[:-1] & free[1:]
    dt = np.diff(t)
    span = float(np.sum(dt[both]))
    integral = float(np.sum((0.5 * (fz[:-1] + fz[1:]) * dt)[both]))
    mean = integral / span if span > 0 else math.nan
    q["peak_torque_between_impacts"] = (np.max(np.abs(tau[free]), axis=0) if free.any()
                                        else np.full(tau.shape[1], math.nan))
    tau2 = 0.5 * (tau[:-1] ** 2 + tau[1:] ** 2) * dt[:, None]
    q["rms_torque_between_impacts"] = (np.sqrt(np.sum(tau2[both], axis=0) / span) if span > 0
                                       else np.full(tau.shape[1], math.nan))
    q["fz_between_impacts_samples"] = int(np.sum(free))
    q["fz_between_impacts_time"] = span
    q["fz_between_impacts_mean"] = mean
    q["fz_between_impacts_min"] = float(np.min(fz[free])) if free.any() else math.nan
    q["fz_between_impacts_max"] = float(np.max(fz[free])) if free.any() else math.nan
    q["fz_between_impacts_mean_over_weight"] = mean / (mass * STANDARD_GRAVITY)
    return q


def smoke_quantities(path):
    with h5py.File(path, "r") as f:
        check_schema(f, "hexdyn-sweep/5", path)
        s = f["/scenarios"]
        q = {"scenarios": int(s["id"].shape[0])}
        names = list(SMOKE_COLUMNS)
        names[3:3] = sorted((k for k in s if k.startswith("axis_") and k != "axis_index"),
                            key=lambda k: int(k.split("_")[1]))
        for name in names:
            d = s[name]
            if h5py.check_string_dtype(d.dtype) is not None:
                q[name] = [text(x) for x in d.asstr()[()]]
            elif d.dtype.kind in "iu":
                q[name] = d[()].astype(np.int64)
            else:
                q[name] = d[()]
    return q


def run_hexdyn(hexdyn, source, workdir):
    """Runs the paper scene and the smoke sweep; returns their quantities."""
    paper_h5 = os.path.join(workdir, "paper.h5")
    smoke_h5 = os.path.join(workdir, "smoke.h5")
    for h5 in (paper_h5, smoke_h5):
        if os.path.exists(h5):
            os.remove(h5)
        if os.path.isdir(h5 + ".checkpoint"):
            shutil.rmtree(h5 + ".checkpoint")
    commands = [[hexdyn, "run", os.path.join(source, PAPER_CONFIG), "-o", paper_h5],
                [hexdyn, "sweep", os.path.join(source, SMOKE_SWEEP), "-o", smoke_h5]]
    for cmd in commands:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           timeout=600)
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} exited with {p.returncode}:\n{p.stdout}")
    with h5py.File(paper_h5, "r") as f:
        meta = {k: text(f["meta"].attrs[k]) for k in ("version", "git_commit")}
    return {"paper": paper_quantities(paper_h5), "smoke": smoke_quantities(smoke_h5)}, meta


# ---------------------------------------------------------------- JSON form



# ---------------------------------------------------------------- commands

def build_reference(results, meta, reason):
    commands = {"paper": f"hexdyn run {PAPER_CONFIG} -o paper.h5",
                "smoke": f"hexdyn sweep {SMOKE_SWEEP} -o smoke.h5 (one rank, no mpirun)"}
    ref = {
        "format": FORMAT,
        "about": ("Pinned key results of the paper run and the smoke sweep; checked by "
                  "tests/regression/regression.py check (ctest regression.paper_and_smoke). "
                  "Written only by `regression.py update --reason`; see "
                  "docs/dev/testing.md#updating-the-pin."),
        "tolerance_rule": ("|got_i - ref_i| <= rtol * scale for every element, scale = max "
                           "|ref| over the quantity (NaN ignored; 1 if all are 0); null is "
                           "NaN and must match NaN; rtol 0 is exact"),
        "generated": {
            "hexdyn_version": meta["version"],
            "hexdyn_git_commit": meta["git_commit"],
            "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
            "reason": reason,
        },
    }
    for section in ("paper", "smoke"):
        quantities = {}
        for name, value in results[section].items():
            entry = {"rtol": tolerance(name, section)}
            if name in UNITS:
                entry["unit"] = UNITS[name]
            entry["value"] = to_json(value)
            quantities[name] = entry
        ref[section] = {"command": commands[section], "quantities": quantities}
    return ref


def load_reference(path):
    with open(path) as fh:
        ref = json.load(fh)
    if ref.get("format") != FORMAT:
        raise RuntimeError(f"{path}: format {ref.get('format')!r}, expected {FORMAT!r}")
    return ref


def write_atomically(path, text_out):
    d = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".reference.", suffix=".json.tmp", dir=d)
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text_out)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def with_workdir(args, fn):
    if args.workdir:
        os.makedirs(args.workdir, exist_ok=True)
        return fn(args.workdir)
    tmp = tempfile.mkdtemp(prefix="hexdyn-regression-")
    try:
        return fn(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def cmd_check(args):
    reference = load_reference(args.reference)
    results, meta = with_workdir(args, lambda d: run_hexdyn(args.hexdyn, args.source, d))
    lines = compare_all(reference, results)
    n = sum(len(reference[s]["quantities"]) for s in ("paper", "smoke"))
    for line in lines:
        print(f"regression: {line}")
    if lines:
        print(f"regression: FAILED: {len(lines)} of {n} quantities differ from "
              f"{args.reference} (hexdyn {meta['git_commit'][:12]}; reference from "
              f"{reference['generated']['hexdyn_git_commit'][:12]}). If the change is "
              f"deliberate, see docs/dev/testing.md#updating-the-pin before updating.")
        return 1
    print(f"regression: {n} quantities of the paper run and the smoke sweep agree with "
          f"{args.reference}")
    return 0


def cmd_update(args):
    if not args.reason.strip():
        print("regression: update: --reason must say what deliberate change moved the results",
              file=sys.stderr)
        return 2
    results, meta = with_workdir(args, lambda d: run_hexdyn(args.hexdyn, args.source, d))
    if os.path.exists(args.reference):
        old = load_reference(args.reference)
        lines = compare_all(old, results)
        for line in lines:
            print(f"regression: update: {line}")
        print(f"regression: update: {len(lines)} quantities moved beyond the old tolerances")
    new = build_reference(results, meta, args.reason.strip())
    write_atomically(args.reference, format_json(new) + "\n")
    print(f"regression: update: wrote {args.reference}; review its diff and give the reason "
          f"in the commit message")
    return 0


# `noise`: rounding-level perturbations of the inputs, each key of configs/paper.yaml
# (which the smoke sweep inherits) moved by a few units in the last place. Any change of
# the code's floating-point operations (a refactor, another compiler) perturbs the
# computation at that level; the rtol of every quantity must stay well above what
# these perturbations move it by.
NOISE_KEYS = ("stiffness", "exponent", "damping_max", "full_damping_depth",
              "friction_coefficient", "touchdown_speed", "swing_clearance", "stroke",
              "foot_lateral", "riser_height", "tread_depth", "torque_limit")
NOISE_ULPS = (-4, -3, -2, -1, 1, 2, 3, 4)
NOISE_MARGIN = 10.0


def perturbed_configs(source, key, ulps, dest):
    """Copies SOURCE/configs to DEST/configs with `key:` in paper.yaml moved by ulps."""
    shutil.copytree(os.path.join(source, "configs"), os.path.join(dest, "configs"))
    path = os.path.join(dest, PAPER_CONFIG)
    with open(path) as fh:
        yaml_text = fh.read()
    pattern = re.compile(rf"^(\s*{key}:[ \t]*)([-+0-9.eE]+)", re.M)
    found = pattern.findall(yaml_text)
    if len(found) != 1:
        raise RuntimeError(f"{path}: {len(found)} lines set {key!r}, expected one")
    x = float(found[0][1])
    for _ in range(abs(ulps)):
        x = float(np.nextafter(x, math.copysign(math.inf, ulps)))
    with open(path, "w") as fh:
        fh.write(pattern.sub(lambda m: m.group(1) + repr(x), yaml_text, count=1))


def cmd_noise(args):
    reference = load_reference(args.reference)

    def measure(workdir):
        base, _ = run_hexdyn(args.hexdyn, args.source, workdir)
        worst = {(sec, name): 0.0 for sec in base for name in base[sec]}
        for key in NOISE_KEYS:
            for ulps in args.ulps:
                d = os.path.join(workdir, f"{key}{ulps:+d}")
                os.makedirs(d)
                perturbed_configs(args.source, key, ulps, d)
                got, _ = run_hexdyn(args.hexdyn, d, d)
                for sec in base:
                    for name in base[sec]:
                        dev = deviation(base[sec][name], got[sec][name])
                        worst[sec, name] = max(worst[sec, name], dev)
        return worst

    worst = with_workdir(args, measure)
    runs = len(NOISE_KEYS) * len(args.ulps)
    print(f"regression: noise: {runs} runs with one input of configs/paper.yaml moved by "
          f"{', '.join(f'{u:+d}' for u in args.ulps)} ulp; largest |change| / scale per "
          f"quantity against the reference's rtol (margin must be >= {NOISE_MARGIN:g}):")
    low = []
    for (sec, name), dev in worst.items():
        rtol = float(reference[sec]["quantities"][name]["rtol"]) if name in \
            reference[sec]["quantities"] else tolerance(name, sec)
        if dev == 0:
            margin = "inf"
        elif rtol == 0 or dev * NOISE_MARGIN > rtol:
            margin = f"{rtol / dev:.3g}  <-- too small" if rtol else "exact, but moved"
            low.append(f"{sec}.{name}")
        else:
            margin = f"{rtol / dev:.3g}"
        print(f"  {sec + '.' + name:45s} change {dev:9.2e}  rtol {rtol:7.0e}  margin {margin}")
    if low:
        print(f"regression: noise: tolerance margin below {NOISE_MARGIN:g} for: {', '.join(low)}")
        return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="See the module docstring for the quantities and rules.")
    sub = ap.add_subparsers(dest="command", required=True)
    for name, helptext in (("check", "compare a fresh run with the reference (ctest)"),
                           ("update", "rewrite the reference (deliberate changes only)"),
                           ("noise", "how far rounding-level input changes move each "
                                     "quantity, against its rtol")):
        p = sub.add_parser(name, help=helptext)
        p.add_argument("--hexdyn", required=True, help="the hexdyn executable")
        p.add_argument("--source", default=DEFAULT_SOURCE,
                       help="source tree holding configs/ (default: this checkout)")
        p.add_argument("--reference", default=DEFAULT_REFERENCE,
                       help="reference file (default: tests/regression/reference.json)")
        p.add_argument("--workdir", help="keep paper.h5 and smoke.h5 here (default: a "
                                         "temporary directory, removed)")
        if name == "noise":
            p.add_argument("--ulps", default=",".join(str(u) for u in NOISE_ULPS),
                           type=lambda v: [int(u) for u in v.split(",")],
                           help="steps in the last place (default %(default)s)")
        if name == "update":
            p.add_argument("--reason", required=True,
                           help="the deliberate change that moved the results (stored in "
                                "the reference)")
    args = ap.parse_args()
    args.hexdyn = os.path.abspath(args.hexdyn)
    try:
        return {"check": cmd_check, "update": cmd_update, "noise": cmd_noise}[args.command](args)
    except (RuntimeError, OSError, KeyError, subprocess.TimeoutExpired) as e:
        print(f"regression: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
