#!/usr/bin/python3
"""The 1,000-scenario grid on 1 rank, this build against an older commit, side by side in one run.

    /usr/bin/python3 bench/sweep_speed.py [--commit bbaf71c] [--old PATH] [--new build/hexdyn]
        [--ref PATH] [--sweep bench/sweep_1000.yaml] [--repeat 3] [--postures {all,none,N}]
        [--friction {on,off,both}] [--tolerance T]

--commit names the older commit (bbaf71c by default; 2dbb8e9 for the output grid's error
control, docs/validation/grid-accuracy.md).

Runs `hexdyn sweep` of the grid (bench/sweep_1000.yaml: riser x speed x duty factor on
configs/sweeps/stairs_base.yaml) under `mpirun -np 1`, old and new binary alternately (the old
binary on its own commit's copy of the sweep file and scenes, when its tree has one),
`--repeat` times each, and prints the wall times and the ratio of their medians
(old / new: > 1 means the new binary is faster), with the ratio of every old-new pair.

--friction: the new binary's runs with the required friction (on, the default: the sweep as
it is), without it (off: the sweep with `output.required_friction: false` in its `set:`), or
both, alternately with the old binary in the same run (both: a third row, "new without the
required friction", its ratio against the old binary, and the required friction's share of the
new binary's median wall time). The option reaches the new binary only: 2dbb8e9 and bbaf71c
predate the required friction.

--tolerance T: the new binary's runs with `output.tolerance: T` in the sweep's `set:` (the
old binary runs the sweep as it is: 2dbb8e9 and bbaf71c have the grid as built only), so that
`--commit 2dbb8e9 --tolerance 1e-4 --friction both` gives the cost of 1e-4 against 2dbb8e9,
with and without the required friction, in one run.

--old takes the older commit's binary from a path. Without it, the commit is checked out in a
side folder, build/side-COMMIT (a git worktree), and its hexdyn built there once; later runs
reuse that build (--build-old: build it in a temporary folder instead, removed after).

Then it compares the sweep files, scenario by scenario:
  - against the old binary: status; energy, cost of transport, peak and RMS torques, each
    difference named. bbaf71c's energy is the integral over its samples; since the
    file-layout change (left-limit samples at every contact event, /sample_kind, trapezoid
    energy) a scenario has more samples, and its energy, peak and RMS torques may differ:
    the table counts those scenarios and gives the largest relative difference.
  - against --ref, when given, a binary of the same physics as the new one (for example a
    build of the commit before a change that should not alter results): status, energy and
    cost of transport to 1e-9 relative, peak and RMS torques likewise.
  - --postures: the automatic posture of every scenario (all, none, or every N-th), from
    `hexdyn run` of the scenario's scene by the new binary and by --ref and the old one:
    the trunk's start P0 and the feet at t = 0 must be equal to the last bit. The kinematic
    margin is a function of the scene and of that posture, so equal postures have equal
    margins (the check of "margin >= old margin - 1e-9 m" on every scenario).
Exit status 1 when a check fails. Sets the root permissions Open MPI needs when run as root.
"""

import argparse
import itertools
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np
import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "regression"))
import side_build  # noqa: E402
OLD_COMMIT = "bbaf71c"  # --commit
SIDE_FOLDER = os.path.join(ROOT, "build", f"side-{OLD_COMMIT}")


def set_old_commit(commit):
    global OLD_COMMIT, SIDE_FOLDER
    OLD_COMMIT = commit
    SIDE_FOLDER = os.path.join(ROOT, "build", f"side-{OLD_COMMIT}")
LOAD = os.getloadavg()
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def build_old(src):
    """Checks OLD_COMMIT out at `src` (a git worktree, unless there already) and builds its
    hexdyn in src/build (tests/regression/side_build.py). Returns the binary's path."""
    return os.path.join(side_build.build(OLD_COMMIT, src, ("hexdyn",), "sweep_speed"), "hexdyn")


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_sweep(hexdyn, sweep, out):
    """Wall time and CPU time (user + system of every process of the run) [s]."""
    for leftover in (out, out + ".checkpoint"):
        if os.path.exists(leftover):
            os.remove(leftover)
    cmd = ["mpirun", "--oversubscribe", "-np", "1", hexdyn, "sweep", sweep, "-o", out]
    cpu0, start = cpu_of_children(), time.perf_counter()
    proc = subprocess.run(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall, cpu = time.perf_counter() - start, cpu_of_children() - cpu0
    if proc.returncode != 0:
        sys.exit(f"sweep_speed: {' '.join(cmd)} failed:\n{proc.stderr}")
    return wall, cpu


def old_sweep(sweep, old_binary, work):
    """The old binary's copy of the sweep file: the same path in the old commit's tree (the
    folder above its build folder) when the sweep lies in this tree and the old tree has it,
    so that each binary reads its own commit's scenes (a newer scene may set keys an older
    binary refuses); else a copy of the sweep in `work` on the old tree's copy of its base
    when the old tree has one; else the sweep itself."""
    old_root = os.path.dirname(os.path.dirname(os.path.abspath(old_binary)))
    rel = os.path.relpath(os.path.abspath(sweep), ROOT)
    mine = os.path.join(old_root, rel)
    if not rel.startswith("..") and os.path.exists(mine):
        return mine
    with open(sweep) as f:
        spec = yaml.safe_load(f)
    base = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(sweep)), spec["base"]))
    rel_base = os.path.relpath(base, ROOT)
    old_base = os.path.join(old_root, rel_base)
    if rel_base.startswith("..") or not os.path.exists(old_base):
        return sweep
    spec["base"] = old_base
    path = os.path.join(work, "old.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(spec, f, sort_keys=False)
    return path


def new_sweep(sweep, work, name, settings):
    """A copy of the sweep file `sweep` in `work` (NAME.yaml) with `settings` added to its
    `set:` (for example output.required_friction: false, the runs without the required
    friction); returns its path."""
    with open(sweep) as f:
        spec = yaml.safe_load(f)
    spec["base"] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(sweep)),
                                                 spec["base"]))
    spec["name"] = f"{spec.get('name', 'sweep')}_{name}"
    spec.setdefault("set", {}).update(settings)
    path = os.path.join(work, f"{name}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(spec, f, sort_keys=False)
    return path


def read_sweep(path):
    with h5py.File(path, "r") as f:
        s = f["scenarios"]
        return {k: s[k][()] for k in ("status", "energy", "cost_of_transport", "peak_torque",
                                      "rms_torque", "samples")}


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = np.maximum(np.abs(a), np.abs(b))
    d = np.abs(a - b)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(scale > 0, d / scale, 0.0)
    return np.where(np.isnan(a) & np.isnan(b), 0.0, r)


def compare(new, other, name, exact):
    """Lines describing the differences; `exact`: a difference beyond 1e-9 is a failure."""
    lines, ok = [], True
    same_status = new["status"] == other["status"]
    lines.append(f"- status: {int(same_status.sum())} of {same_status.size} scenarios the same as "
                 f"{name}")
    ok &= bool(same_status.all())
    both = same_status & (new["status"] == 0)
    more = new["samples"] > other["samples"]
    for key in ("energy", "cost_of_transport", "peak_torque", "rms_torque"):
        r = rel(new[key], other[key])
        r = r.max(axis=1) if r.ndim == 2 else r
        r = np.where(both, r, 0.0)
        bad = r > 1e-9
        if not bad.any():
            a, b = np.asarray(new[key]), np.asarray(other[key])
            same = (a == b) | (np.isnan(a) & np.isnan(b))
            same = same.all(axis=1) if same.ndim == 2 else same
            lines.append(f"- {key}: equal to 1e-9 relative on all {int(both.sum())} computed "
                         f"scenarios ({int((same & both).sum())} bit for bit)")
            continue
        lines.append(f"- {key}: {int(bad.sum())} of {int(both.sum())} computed scenarios differ "
                     f"by more than 1e-9 relative (largest {r.max():.3g}); of these, "
                     f"{int((bad & more).sum())} have more samples than with {name} (a grid "
                     f"refined further)")
        if exact:
            ok = False
    return lines, ok


def scenario_sets(sweep_path):
    with open(sweep_path) as f:
        spec = yaml.safe_load(f)
    base = os.path.normpath(os.path.join(os.path.dirname(sweep_path), spec["base"]))
    return base, [a["key"] for a in spec["axes"]]


def posture_of(hexdyn, base, sets, out):
    cmd = [hexdyn, "run", base, "-o", out] + list(itertools.chain(*[["--set", s] for s in sets]))
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if proc.returncode != 0:
        return ("exit", proc.returncode)
    with h5py.File(out, "r") as f:
        p = (f["base/position"][0].tobytes(), f["feet/position"][0].tobytes())
    os.remove(out)
    return p


def check_postures(binaries, sweep_path, new_file, every, work):
    base, keys = scenario_sets(sweep_path)
    with h5py.File(new_file, "r") as f:
        axes = [f["scenarios"][f"axis_{k}"][()] for k in range(len(keys))]
    n = len(axes[0])
    lines, ok = [], True
    for name, hexdyn in binaries[1:]:
        same = differ = 0
        for i in range(0, n, every):
            sets = [f"{k}={float(a[i])!r}" for k, a in zip(keys, axes)]
            mine = posture_of(binaries[0][1], base, sets, os.path.join(work, "p_new.h5"))
            theirs = posture_of(hexdyn, base, sets, os.path.join(work, "p_old.h5"))
            if mine == theirs:
                same += 1
            else:
                differ += 1
                lines.append(f"  - scenario {i} ({', '.join(sets)}): posture differs from {name}")
        lines.append(f"- posture (P0 and feet at t = 0, bit for bit): {same} of {same + differ} "
                     f"scenarios the same as {name}")
        ok &= differ == 0
    return lines, ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--commit", default=OLD_COMMIT, help="the older commit (default %(default)s)")
    ap.add_argument("--old", help=f"{OLD_COMMIT}'s hexdyn (default: built in {SIDE_FOLDER})")
    ap.add_argument("--build-old", action="store_true",
                    help=f"build {OLD_COMMIT} in a temporary folder, removed after")
    ap.add_argument("--new", default=os.path.join(ROOT, "build", "hexdyn"))
    ap.add_argument("--ref", help="a binary of the same physics as --new (optional)")
    ap.add_argument("--sweep", default=os.path.join(ROOT, "bench", "sweep_1000.yaml"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--postures", default="all")
    ap.add_argument("--friction", choices=("on", "off", "both"), default="on",
                    help="the new binary with the required friction, without, or both")
    ap.add_argument("--tolerance", type=float,
                    help="the new binary's output.tolerance (default: the sweep's)")
    args = ap.parse_args()
    set_old_commit(args.commit)
    with tempfile.TemporaryDirectory(prefix="hexdyn_speed_") as work:
        old_src = None
        if args.build_old:
            old_src = os.path.join(work, "old_src")
            args.old = build_old(old_src)
        elif args.old is None:
            args.old = os.path.join(SIDE_FOLDER, "build", "hexdyn")
            if not os.path.exists(args.old):
                build_old(SIDE_FOLDER)
        try:
            grid = {} if args.tolerance is None else {"output.tolerance": args.tolerance}
            bare = new_sweep(args.sweep, work, "without_friction",
                             {**grid, "output.required_friction": False})
            runs = {"on": ("old", "new"), "off": ("old", "new"), "both": ("old", "new", "bare")}
            sweeps = {"old": old_sweep(args.sweep, args.old, work),
                      "new": bare if args.friction == "off" else
                      new_sweep(args.sweep, work, "new", grid) if grid else args.sweep,
                      "bare": bare}
            walls = {k: [] for k in runs[args.friction]}
            cpus = {k: [] for k in runs[args.friction]}
            for r in range(args.repeat):
                for which in runs[args.friction]:  # alternately, same machine, same run
                    exe = args.old if which == "old" else args.new
                    wall, cpu = run_sweep(exe, sweeps[which], os.path.join(work, f"{which}.h5"))
                    walls[which].append(wall)
                    cpus[which].append(cpu)
                    print(f"sweep_speed: run {r + 1} {which}: {wall:.2f} s wall, {cpu:.2f} s CPU",
                          file=sys.stderr)
            old, new = read_sweep(os.path.join(work, "old.h5")), read_sweep(
                os.path.join(work, "new.h5"))
            n = len(new["status"])
            med = {k: (statistics.median(walls[k]), statistics.median(cpus[k])) for k in walls}
            grid_text = ("" if args.tolerance is None else
                         f", the new binary at output.tolerance {args.tolerance:g}")
            print(f"Sweep `{os.path.relpath(args.sweep, ROOT)}`{grid_text}: {n} scenarios "
                  f"({int((new['status'] == 0).sum())} computed) on 1 rank, {args.repeat} runs "
                  f"of each binary alternately; {os.cpu_count()} cores, load average before "
                  f"the runs {LOAD[0]:.1f}.\n")
            print("| binary | wall times [s] | median wall [s] | CPU times [s] | median CPU [s] |")
            print("|---|---|---:|---|---:|")
            labels = {"old": f"old ({OLD_COMMIT})",
                      "new": "new" + (" without the required friction"
                                      if args.friction == "off" else ""),
                      "bare": "new without the required friction"}
            for k, label in ((k, labels[k]) for k in walls):
                print(f"| {label} | {', '.join(f'{w:.2f}' for w in walls[k])} | {med[k][0]:.2f} "
                      f"| {', '.join(f'{c:.2f}' for c in cpus[k])} | {med[k][1]:.2f} |")
            pairs = [o / w for o, w in zip(walls["old"], walls["new"])]
            print(f"\nRatio old / new of the median wall times: **{med['old'][0] / med['new'][0]:.2f}x** "
                  f"(pairs: {', '.join(f'{p:.2f}' for p in pairs)}); of the median CPU times: "
                  f"{med['old'][1] / med['new'][1]:.2f}x\n")
            if "bare" in walls:
                pairs = [o / w for o, w in zip(walls["old"], walls["bare"])]
                print(f"Without the required friction, old / new of the median wall times: "
                      f"**{med['old'][0] / med['bare'][0]:.2f}x** (pairs: "
                      f"{', '.join(f'{p:.2f}' for p in pairs)}); the required friction's share "
                      f"of the new binary's median wall time: "
                      f"{1.0 - med['bare'][0] / med['new'][0]:.0%}; new / new without it: "
                      f"{med['new'][0] / med['bare'][0]:.2f}x\n")
            ok = True
            print(f"Results against the old binary ({OLD_COMMIT}):")
            lines, good = compare(new, old, OLD_COMMIT, exact=False)
            print("\n".join(lines))
            ok &= bool((new["status"] == old["status"]).all())
            binaries = [("new", args.new), (OLD_COMMIT, args.old)]
            if args.ref:
                run_sweep(args.ref, args.sweep, os.path.join(work, "ref.h5"))
                print(f"\nResults against the reference of the same physics ({args.ref}):")
                lines, good = compare(new, read_sweep(os.path.join(work, "ref.h5")), "the reference",
                                      exact=True)
                print("\n".join(lines))
                ok &= good
                binaries.insert(1, ("the reference", args.ref))
            if args.postures != "none":
                every = 1 if args.postures == "all" else int(args.postures)
                print("\nAutomatic postures:")
                lines, good = check_postures(binaries, args.sweep, os.path.join(work, "new.h5"),
                                             every, work)
                print("\n".join(lines))
                ok &= good
        finally:
            if old_src:
                subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", old_src])
    print("\nAll checks passed." if ok else "\nA check FAILED.")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
