#!/usr/bin/python3
"""Speed of this tree's build against an older commit's, three figures in one run: the paper
run, RNEA per evaluation and the 1,000-scenario stairs grid.

    /usr/bin/python3 bench/compare_with_base.py COMMIT [--build build] [--repeat 5]
        [--sweep bench/sweep_1000.yaml] [--sweep-repeat 1] [--skip {paper,rnea,sweep}]

COMMIT's hexdyn and bench_dynamics are built in build/side-COMMIT, a git worktree of the
commit (tests/regression/side_build.py; reused when it is there); this tree's come from
--build (build them first: `hexdyn_build hexdyn bench_dynamics`). Each figure is measured
old and new alternately, so that both binaries see the same load:
  - paper: wall time of `hexdyn run configs/paper.yaml -o FILE` (process start and file
    writing included), --repeat times each;
  - rnea: bench_dynamics' BM_Rnea (with and without foot forces) per evaluation, Google
    Benchmark's real time, --repeat runs of each binary of --min-time seconds each;
  - sweep: wall time of `mpirun -np 1 hexdyn sweep` of --sweep (the 1,000-scenario grid by
    default; a smaller grid checks the script in a minute), --sweep-repeat times each, the
    old binary on its own commit's copy of the sweep and scenes (bench/sweep_speed.py).
Prints a table of medians with new / old (< 1: the new build is faster) against issue 43's
limits (paper 1.1, RNEA 1.15, grid 1.1) and the machine's load. The figures are timings on
a shared machine: compare them only within one run. Exit status 0 whatever the ratios
(1 when a run fails).
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "regression"))
sys.path.insert(0, HERE)
import side_build  # noqa: E402
import sweep_speed  # noqa: E402

LIMITS = {"paper": 1.1, "rnea": 1.15, "sweep": 1.1}  # issue 43, new / old at most


def paper_run(hexdyn, out):
    """Wall time [s] of `hexdyn run configs/paper.yaml -o out`."""
    if os.path.exists(out):
        os.remove(out)
    cmd = [hexdyn, "run", os.path.join(ROOT, "configs", "paper.yaml"), "-o", out]
    start = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit(f"compare_with_base: {' '.join(cmd)} failed (exit {proc.returncode}):\n"
                 f"{proc.stderr}")
    return wall


def rnea_times(bench, min_time):
    """{benchmark name: real time per evaluation [ns]} of bench_dynamics' BM_Rnea, run on
    the paper scene of its own tree (the folder above its build folder)."""
    cmd = [bench, "--benchmark_filter=BM_Rnea", "--benchmark_format=json",
           f"--benchmark_min_time={min_time}"]
    tree = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(bench))))
    proc = subprocess.run(cmd, capture_output=True, text=True,
                          env=dict(os.environ, HEXDYN_SOURCE_DIR=tree))
    if proc.returncode != 0:
        sys.exit(f"compare_with_base: {' '.join(cmd)} failed:\n{proc.stderr}")
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
    return {b["name"]: b["real_time"] * scale[b["time_unit"]]
            for b in json.loads(proc.stdout)["benchmarks"] if b.get("run_type") != "aggregate"}


def alternate(measure, repeat):
    """{'old': [...], 'new': [...]}: measure('old'), measure('new'), repeat times."""
    out = {"old": [], "new": []}
    for _ in range(repeat):
        for which in out:
            out[which].append(measure(which))
    return out


def row(name, unit, old, new, limit):
    mo, mn = statistics.median(old), statistics.median(new)
    ratio = mn / mo
    verdict = "within" if ratio <= limit else "OVER"
    print(f"{name:<34} {mo:>12.4g} {mn:>12.4g} {unit:<3} {ratio:>7.3f}  "
          f"(limit {limit:g}: {verdict}; n = {len(old)}, "
          f"new/old per pair {', '.join(f'{b / a:.3f}' for a, b in zip(old, new))})")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("commit", help="the older commit (B)")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"),
                    help="this tree's build folder (default %(default)s)")
    ap.add_argument("--repeat", type=int, default=5, help="paper and RNEA runs of each binary")
    ap.add_argument("--min-time", type=float, default=0.5,
                    help="seconds per BM_Rnea benchmark and run (default %(default)g)")
    ap.add_argument("--sweep", default=os.path.join(ROOT, "bench", "sweep_1000.yaml"))
    ap.add_argument("--sweep-repeat", type=int, default=1, help="sweep runs of each binary")
    ap.add_argument("--skip", action="append", choices=("paper", "rnea", "sweep"), default=[],
                    help="leave a figure out (repeatable)")
    args = ap.parse_args()
    new = {"hexdyn": os.path.join(args.build, "hexdyn"),
           "bench": os.path.join(args.build, "bench", "bench_dynamics")}
    for path in new.values():
        if not os.access(path, os.X_OK):
            sys.exit(f"compare_with_base: {path} is not an executable "
                     f"(build it: hexdyn_build hexdyn bench_dynamics)")
    old_build = side_build.checked_build(args.commit, targets=("hexdyn", "bench_dynamics"),
                                         who="compare_with_base")
    old = {"hexdyn": os.path.join(old_build, "hexdyn"),
           "bench": os.path.join(old_build, "bench", "bench_dynamics")}
    exe = {"old": old, "new": new}
    load = os.getloadavg()
    print(f"compare_with_base: {args.commit} ({old_build}) against {args.build}; "
          f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} on {os.cpu_count()} cores")
    print(f"{'figure':<34} {'old':>12} {'new':>12} {'':<3} {'new/old':>7}")
    with tempfile.TemporaryDirectory(prefix="hexdyn_speed_") as work:
        if "paper" not in args.skip:
            t = alternate(lambda w: paper_run(exe[w]["hexdyn"], os.path.join(work, f"{w}.h5")),
                          args.repeat)
            row("paper run (hexdyn run)", "s", t["old"], t["new"], LIMITS["paper"])
        if "rnea" not in args.skip:
            t = alternate(lambda w: rnea_times(exe[w]["bench"], args.min_time), args.repeat)
            for name in t["new"][0]:
                row(f"RNEA {name}", "ns", [r[name] for r in t["old"]], [r[name] for r in t["new"]],
                    LIMITS["rnea"])
        if "sweep" not in args.skip:
            sweeps = {"old": sweep_speed.old_sweep(args.sweep, old["hexdyn"], work),
                      "new": args.sweep}

            def sweep(w):
                return sweep_speed.run_sweep(exe[w]["hexdyn"], sweeps[w],
                                             os.path.join(work, f"{w}_sweep.h5"))[0]
            t = alternate(sweep, args.sweep_repeat)
            row(f"sweep {os.path.relpath(args.sweep, ROOT)}", "s", t["old"], t["new"],
                LIMITS["sweep"])
    load = os.getloadavg()
    print(f"compare_with_base: load average at the end {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
