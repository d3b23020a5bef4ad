#!/usr/bin/env python3
"""How long `hexdyn validate` takes on sweeps of 10^4, 10^5 and 10^6 scenarios (the limit:
10^6 must answer within 60 s on a 2-core machine; docs/user/faults.md#sizes).

Each sweep has two axes over configs/sweeps/stairs_base.yaml: terrain.riser_height (1000
values) and motion.peak_speed (10, 100, 1000 values). Every size is run `--repeat` times,
sizes alternating; prints seconds and microseconds per scenario (median).

    /usr/bin/python3 bench/validate_scale.py --hexdyn build/hexdyn [--repeat 3]
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def sweep_file(folder, speeds):
    path = os.path.join(folder, f"validate_{1000 * speeds}.yaml")
    with open(path, "w") as f:
        f.write(f"base: {ROOT}/configs/sweeps/stairs_base.yaml\n"
                "axes:\n"
                "  - key: terrain.riser_height\n"
                "    range: {from: 0.0, to: 0.14, count: 1000}\n"
                "  - key: motion.peak_speed\n"
                f"    range: {{from: 0.05, to: 0.2, count: {speeds}}}\n")
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hexdyn", default=os.path.join(ROOT, "build", "hexdyn"))
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        files = {1000 * s: sweep_file(tmp, s) for s in (10, 100, 1000)}
        times = {n: [] for n in files}
        for _ in range(args.repeat):
            for n, path in files.items():
                start = time.monotonic()
                subprocess.run([args.hexdyn, "validate", path], check=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                times[n].append(time.monotonic() - start)
    print("scenarios  seconds (median)  us/scenario  runs")
    for n, ts in times.items():
        m = statistics.median(ts)
        print(f"{n:9d}  {m:16.2f}  {1e6 * m / n:11.1f}  {', '.join(f'{t:.2f}' for t in ts)}")


if __name__ == "__main__":
    main()
