#!/usr/bin/python3
"""Scenarios per second of `hexdyn sweep` at 1, 2, ... ranks and the parallel efficiency.

    /usr/bin/python3 bench/bench_sweep.py [--hexdyn build/hexdyn] [--sweep bench/sweep_bench.yaml]
                                          [--ranks 1 2] [--repeat 3]

Runs the sweep under `mpirun -np N` (N = 1 too, so that every figure includes the MPI
start-up) `--repeat` times per rank count and prints a Markdown table of the medians:
end-to-end wall time (start-up, validation, the scenarios, the sweep file), scenarios
per second = scenarios / wall time, parallel efficiency = rate(N) / (N · rate(1)), and
the summed time of the scenarios themselves (/scenarios/wall_time_s), which grows with
N when the ranks compete for cores, memory bandwidth or caches, and the rank
utilisation = summed scenario time / (N · wall time), the share of the ranks' time spent
in scenarios (the rest is start-up, validation, checkpoints, waiting for work and
writing the file). Sets the root permissions Open MPI needs when run as root. Writes
into a temporary directory.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_once(hexdyn, sweep, ranks, workdir):
    out = os.path.join(workdir, f"bench_{ranks}.h5")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), hexdyn, "sweep", sweep, "-o", out]
    start = time.perf_counter()
    proc = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit(f"bench_sweep: {' '.join(cmd)} failed:\n{proc.stderr}")
    with h5py.File(out, "r") as f:
        n = int(f["meta"].attrs["scenarios"])
        busy = float(np.sum(f["scenarios/wall_time_s"][()]))
        ok = int(np.sum(f["scenarios/status"][()] == 0))
    os.remove(out)
    return wall, n, busy, ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hexdyn", default=os.path.join(ROOT, "build", "hexdyn"))
    ap.add_argument("--sweep", default=os.path.join(ROOT, "bench", "sweep_bench.yaml"))
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="hexdyn_bench_") as work:
        for ranks in args.ranks:
            runs = [run_once(args.hexdyn, args.sweep, ranks, work) for _ in range(args.repeat)]
            wall = statistics.median(r[0] for r in runs)
            busy = statistics.median(r[2] for r in runs)
            n, ok = runs[0][1], runs[0][3]
            rows.append((ranks, n, ok, wall, n / wall, busy))
            print(f"bench_sweep: {ranks} rank(s): {n} scenarios in {wall:.2f} s "
                  f"(runs: {', '.join(f'{r[0]:.2f}' for r in runs)})", file=sys.stderr)
    base_rate = rows[0][4] / rows[0][0]
    print(f"Sweep `{os.path.relpath(args.sweep, ROOT)}`: {rows[0][1]} scenarios "
          f"({rows[0][2]} computed, {rows[0][1] - rows[0][2]} rows of scenarios that cannot "
          f"be); median of {args.repeat} runs; {os.cpu_count()} cores.\n")
    print("| ranks | wall time [s] | scenarios/s | parallel efficiency "
          "| summed scenario time [s] | rank utilisation |")
    print("|---:|---:|---:|---:|---:|---:|")
    for ranks, n, ok, wall, rate, busy in rows:
        eff = rate / (ranks * base_rate)
        print(f"| {ranks} | {wall:.2f} | {rate:.2f} | {eff:.0%} | {busy:.1f} "
              f"| {busy / (ranks * wall):.0%} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
