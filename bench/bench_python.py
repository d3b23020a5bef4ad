#!/usr/bin/env python3
"""hexdyn from Python, in process against the subprocess path, and from 2 threads.

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_python.py [--hexdyn build/hexdyn]
        [--cpp-bench build/bench/bench_paper_run] [--scene configs/paper.yaml] [--repeat 20]

Reports, for the scene, medians over --repeat calls (after one warm-up):
  compute    the scene's compute time, /meta wall_time_s (run_prepared_scene: sampling and
             solving, what the library times itself)
  C++ call   load_scene + run_scene of the paper scene in C++, the same work without Python
             (BM_PaperLoadAndRun of --cpp-bench, median of --repeat repetitions; paper
             scene only)
  in process hexdyn.run(scene) (reading the scene, planning, computing, the arrays to numpy),
             and its ratios to compute and to the C++ call (the module's own cost: target
             at most 1.1)
  subprocess `hexdyn run scene -o FILE` then h5py reading every dataset (the path a script
             had before the module), and its ratio to compute
and the speed-up of 2 threads over 1 on 8 scenes (duty factors 0.55 ... 0.9), medians over
--rounds rounds, next to the speed-up of a control load that runs perfectly in parallel
(hashlib.sha256 over 4 MB, which releases the GIL) measured in the same rounds: the control
is what the machine's two cores give, and the scenes' share of it is what hexdyn gives.
Dated results go to bench/RESULTS.md.
"""

import argparse
import os
import statistics
import subprocess
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

import hashlib
import json

import h5py

import hexdyn


def median_time(f, repeat):
    f()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def read_all(path):
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: o[()] if isinstance(o, h5py.Dataset) else None)


def cpp_call_seconds(bench, repeat):
    """Median of BM_PaperLoadAndRun (load_scene + run_scene in C++) over `repeat` repetitions."""
    out = subprocess.run([bench, "--benchmark_filter=BM_PaperLoadAndRun$",
                          f"--benchmark_repetitions={repeat}", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b.get("run_type") == "iteration"]
    return statistics.median(b["real_time"] for b in runs) * 1e-3  # reported in ms


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hexdyn", default=os.path.join(here, "..", "build", "hexdyn"))
    ap.add_argument("--cpp-bench", default=os.path.join(here, "..", "build", "bench", "bench_paper_run"))
    ap.add_argument("--scene", default=os.path.join(here, "..", "configs", "paper.yaml"))
    ap.add_argument("--repeat", type=int, default=20)
    ap.add_argument("--rounds", type=int, default=9, help="rounds of the thread measurement")
    a = ap.parse_args()

    compute = []

    def in_process():
        compute.append(float(hexdyn.run(a.scene).attrs["wall_time_s"]))

    t_in = median_time(in_process, a.repeat)
    t_compute = statistics.median(compute)
    t_cpp = cpp_call_seconds(a.cpp_bench, a.repeat) if os.path.exists(a.cpp_bench) else None
    t_in_again = median_time(in_process, a.repeat)  # after the C++ call: the order does not decide
    t_in = min(t_in, t_in_again)
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "r.h5")

        def via_subprocess():
            subprocess.run([a.hexdyn, "run", a.scene, "-o", out], check=True, capture_output=True)
            read_all(out)

        t_sub = median_time(via_subprocess, a.repeat)

    duty = [0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9]

    def one(x):
        return hexdyn.run(a.scene, set={"gait.duty_factor": x})["/energy/total"].tobytes()

    def control(_):
        data = b"x" * (1 << 22)
        for _ in range(4):
            hashlib.sha256(data).digest()

    def speedup(f):
        """1-thread time over 2-thread time of f over the 8 duty factors, and whether both
        gave the same results."""
        t0 = time.perf_counter()
        serial = [f(x) for x in duty]
        t1 = time.perf_counter()
        with ThreadPoolExecutor(2) as pool:
            parallel = list(pool.map(f, duty))
        t2 = time.perf_counter()
        return (t1 - t0) / (t2 - t1), t1 - t0, t2 - t1, serial == parallel

    one(0.75)
    # Rounds alternate the scenes and the control, so that a change of the machine's load
    # hits both alike; medians over the rounds.
    scenes, controls, identical = [], [], True
    for _ in range(a.rounds):
        s_up, t_serial, t_parallel, same = speedup(one)
        scenes.append((s_up, t_serial, t_parallel))
        identical = identical and same
        controls.append(speedup(control)[0])
    s_up = statistics.median(x[0] for x in scenes)
    t_serial = statistics.median(x[1] for x in scenes)
    t_parallel = statistics.median(x[2] for x in scenes)
    c_up = statistics.median(controls)

    print(f"hexdyn {hexdyn.__version__} ({hexdyn.__git_commit__[:12]}), scene {os.path.basename(a.scene)}, "
          f"medians of {a.repeat}")
    print(f"  compute (wall_time_s)        {1e3 * t_compute:8.1f} ms")
    if t_cpp:
        print(f"  C++ call, load + run_scene   {1e3 * t_cpp:8.1f} ms   {t_cpp / t_compute:5.2f} x compute")
    print(f"  in process, hexdyn.run       {1e3 * t_in:8.1f} ms   {t_in / t_compute:5.2f} x compute"
          + (f", {t_in / t_cpp:5.2f} x the C++ call" if t_cpp else ""))
    print(f"  subprocess, hexdyn run + h5py{1e3 * t_sub:8.1f} ms   {t_sub / t_compute:5.2f} x compute")
    print(f"  8 scenes, medians of {a.rounds} rounds: 1 thread {t_serial:.3f} s, 2 threads {t_parallel:.3f} s, "
          f"speed-up {s_up:.2f}x on {os.cpu_count()} cores, results {'identical' if identical else 'DIFFERENT'}")
    print(f"  control (sha256 of 4 MB, GIL released), same rounds: speed-up {c_up:.2f}x; "
          f"the scenes reach {s_up / c_up:.0%} of it")


if __name__ == "__main__":
    main()
