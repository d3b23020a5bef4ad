#!/usr/bin/python3
"""Whole-program sweep figures: start time and parallel efficiency.

    /usr/bin/python3 bench/bench_sweep_scale.py [--hexdyn build/hexdyn] [--start] [--grid]
                                                [--repeat 3]

--start  Time from launching `hexdyn sweep -v` (one rank, no mpirun) to the start of the
         first scenario (its line's arrival minus its own time) and to the first
         progress line, for sweeps of 10^3, 10^5 and 10^6 scenarios (axes over
         configs/sweeps/stairs_base.yaml); the sweep is stopped after that.
--grid   The 1,000-scenario grid bench/sweep_1000.yaml on 1 and 2 ranks (mpirun for
         both, so both include MPI's start-up), end to end: wall time, summed scenario
         time Σ (scene construction + physics, /scenarios/wall_time_s), parallel
         efficiency T1 / (2 T2), and wall / (Σ / ranks) (target ≤ 1.15). Also the CPU
         time of the processes, so that a machine busy with other work shows.
--idle   Idle ranks: a sweep of one scenario on 3 ranks (--oversubscribe), so that one
         process works and every other waits; the scenario lasts 10 s on purpose, whatever
         the machine's speed (the test-only switch HEXDYN_TEST_HOLD_SECONDS makes its
         process wait before computing it). The CPU time of each hexdyn process (/proc/PID/stat, utime + stime) is read
         three times a second apart, once every process is up, and the smaller of its shares
         of the two windows printed (start-up work on a loaded machine falls in the first
         only): a waiting rank that spins shows ~100 %, one that sleeps ~0 %. With --max-idle F
         (a fraction), exits 1 if any process used more than F of a core: while the
         scenario is held, every one of them waits (ctest sweep.idle_ranks_do_not_spin).
Prints Markdown tables (medians of --repeat runs). Writes into a temporary directory.
"""

import argparse
import os
import resource
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def sweep_file(work, counts):
    base = os.path.join(ROOT, "configs", "sweeps", "stairs_base.yaml")
    path = os.path.join(work, f"start_{'x'.join(map(str, counts))}.yaml")
    with open(path, "w") as f:
        f.write(f"base: {base}\nset:\n  output.grid: uniform\n  motion.cycles: 1\naxes:\n")
        f.write(f"  - key: terrain.riser_height\n    range: {{from: 0.02, to: 0.08, count: {counts[0]}}}\n")
        f.write(f"  - key: motion.peak_speed\n    range: {{from: 0.05, to: 0.2, count: {counts[1]}}}\n")
        f.write(f"  - key: gait.duty_factor\n    range: {{from: 0.5, to: 0.8, count: {counts[2]}}}\n")
    return path


def start_time(hexdyn, sweep, work):
    out = os.path.join(work, "start.h5")
    t0 = time.perf_counter()
    proc = subprocess.Popen([hexdyn, "sweep", sweep, "-o", out, "-v"], env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    progress = first = None
    for line in proc.stderr:
        now = time.perf_counter() - t0
        if progress is None and "/" in line and " done" in line:
            progress = now
        if "(rank" in line and line.startswith("hexdyn: sweep: scenario"):
            own = float(line.split("(rank", 1)[1].split(",")[1].split("s)")[0])
            first = now - own
            break
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    subprocess.run(["rm", "-rf", out + ".checkpoint"])
    return first, progress


def grid_run(hexdyn, sweep, ranks, work):
    out = os.path.join(work, f"grid_{ranks}.h5")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(["mpirun", "--oversubscribe", "-np", str(ranks), hexdyn, "sweep", sweep,
                    "-o", out], env=ENV, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with h5py.File(out, "r") as f:
        busy = float(np.sum(f["scenarios/wall_time_s"][()]))
        n = int(f["meta"].attrs["scenarios"])
    os.remove(out)
    return wall, busy, cpu, n


def process_cpu_seconds(pid):
    """utime + stime of a process [s], or None once it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def hexdyn_processes(sweep):
    """PIDs of the processes running `hexdyn sweep SWEEP` (the ranks and their forked
    scenario processes, which keep the rank's command line)."""
    pids = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/cmdline", "rb") as f:
                argv = f.read().split(b"\0")
        except OSError:
            continue
        if b"sweep" in argv and sweep.encode() in argv and not argv[0].endswith(b"mpirun"):
            pids.append(int(name))
    return pids


def idle_cpu(hexdyn, work, ranks=3):
    """[(pid, share of a core: the smaller of two 1 s windows)], sorted by share, largest first."""
    sweep = os.path.join(work, "idle.yaml")
    with open(sweep, "w") as f:
        f.write(f"base: {os.path.join(ROOT, 'configs', 'paper.yaml')}\n"
                "axes:\n  - key: gait.duty_factor\n    values: [1/2]\n")
    out = os.path.join(work, "idle.h5")
    env = dict(ENV, HEXDYN_TEST_HOLD_SECONDS="10")  # the scenario lasts 10 s on purpose
    proc = subprocess.Popen(["mpirun", "--oversubscribe", "-np", str(ranks), "-x",
                             "HEXDYN_TEST_HOLD_SECONDS", hexdyn, "sweep", sweep, "-o", out],
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    try:
        # The ranks and the scenario process rank 0's compute thread forks: MPI start-up
        # takes a second or more on a loaded machine, so wait for them (at most 20 s).
        deadline = time.perf_counter() + 20.0
        pids = hexdyn_processes(sweep)
        while len(pids) < ranks + 1 and time.perf_counter() < deadline:
            time.sleep(0.2)
            pids = hexdyn_processes(sweep)
        time.sleep(0.5)
        pids = hexdyn_processes(sweep)
        # Two windows of 1 s: a rank that spins does so in both, while one still finishing
        # its start-up on a loaded machine does so in the first only; the smaller share counts.
        t0 = time.perf_counter()
        c0 = {p: process_cpu_seconds(p) for p in pids}
        time.sleep(1.0)
        t1 = time.perf_counter()
        c1 = {p: process_cpu_seconds(p) for p in pids}
        time.sleep(1.0)
        c2 = {p: process_cpu_seconds(p) for p in pids}
        t2 = time.perf_counter()
        alive = proc.poll() is None
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:  # the sweep has ended (and `alive` says so)
            pass
        proc.wait()
        subprocess.run(["rm", "-rf", out, out + ".checkpoint"])
    if not alive:
        raise RuntimeError("the one-scenario sweep ended within the window: no idle time measured")
    shares = [(p, min((c1[p] - c0[p]) / (t1 - t0), (c2[p] - c1[p]) / (t2 - t1))) for p in pids
              if None not in (c0[p], c1[p], c2[p])]
    return sorted(shares, key=lambda x: -x[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hexdyn", default=os.path.join(ROOT, "build", "hexdyn"))
    ap.add_argument("--start", action="store_true")
    ap.add_argument("--grid", action="store_true")
    ap.add_argument("--idle", action="store_true")
    ap.add_argument("--max-idle", type=float, default=None)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    if not (args.start or args.grid or args.idle):
        args.start = args.grid = args.idle = True
    with tempfile.TemporaryDirectory(prefix="hexdyn_scale_") as work:
        if args.start:
            print("| scenarios | first scenario starts [s] | first progress line [s] |")
            print("|---:|---:|---:|")
            for counts in ((10, 10, 10), (100, 100, 10), (100, 100, 100)):
                path = sweep_file(work, counts)
                runs = [start_time(args.hexdyn, path, work) for _ in range(args.repeat)]
                n = counts[0] * counts[1] * counts[2]
                print(f"| {n:,} | {statistics.median(r[0] for r in runs):.2f} "
                      f"| {statistics.median(r[1] for r in runs):.2f} |", flush=True)
            print()
        if args.idle:
            shares = idle_cpu(args.hexdyn, work)
            print("| process (3 ranks, each with its scenario process) | CPU share of a core (smaller of two 1 s windows) |")
            print("|---|---:|")
            for pid, share in shares:
                print(f"| hexdyn (pid {pid}) | {share:.1%} |")
            print(flush=True)
            if len(shares) < 4:
                print(f"bench_sweep_scale: found only {len(shares)} hexdyn processes", file=sys.stderr)
                return 1
            # While the scenario is held every process waits: none may use more than F.
            if args.max_idle is not None and any(s > args.max_idle for _, s in shares):
                print(f"bench_sweep_scale: a waiting process used more than {args.max_idle:.0%} of a core",
                      file=sys.stderr)
                return 1
        if args.grid:
            sweep = os.path.join(ROOT, "bench", "sweep_1000.yaml")
            rows = {}
            for ranks in (1, 2):
                runs = [grid_run(args.hexdyn, sweep, ranks, work) for _ in range(args.repeat)]
                runs.sort()
                rows[ranks] = runs[len(runs) // 2]
                print(f"bench_sweep_scale: {ranks} rank(s): "
                      f"{', '.join(f'{r[0]:.2f}' for r in runs)} s", file=sys.stderr)
            t1 = rows[1][0]
            print("| ranks | wall [s] | Σ scenario time [s] | wall / (Σ / ranks) "
                  "| efficiency T1/(N·TN) | CPU time [s] |")
            print("|---:|---:|---:|---:|---:|---:|")
            for ranks, (wall, busy, cpu, n) in rows.items():
                print(f"| {ranks} | {wall:.2f} | {busy:.2f} | {wall / (busy / ranks):.3f} "
                      f"| {t1 / (ranks * wall):.0%} | {cpu:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
