#!/usr/bin/env python3
"""How soon Ctrl-C interrupts `hexdyn.run` (the limit: within 0.5 s, for every back end;
docs/user/faults.md#signals).

For each allocation back end, `--repeat` times: a Python process runs configs/paper.yaml with
output.impact_samples 8000 (5 s with the active set, 15 s with Ipopt), receives SIGINT 1.5 s
in, and reports the time from the signal's arrival (its own SIGINT handler notes it) to the
KeyboardInterrupt in the caller. Prints each latency and the largest.

    PYTHONPATH=build/python /usr/bin/python3 bench/interrupt_latency.py [--repeat 5]
"""
import argparse
import os
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CHILD = r"""
import signal, sys, time, hexdyn
arrived = []
def on_int(signum, frame):
    arrived.append(time.monotonic())
    raise KeyboardInterrupt
signal.signal(signal.SIGINT, on_int)
print("ready", flush=True)
try:
    hexdyn.run(sys.argv[1], {"output.impact_samples": 8000, "allocation.solver": sys.argv[2]})
    print("finished")
except KeyboardInterrupt:
    print(f"latency {time.monotonic() - arrived[0]:.4f}")
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    scene = os.path.join(ROOT, "configs", "paper.yaml")
    for solver in ("active-set", "ipopt"):
        latencies = []
        for _ in range(args.repeat):
            p = subprocess.Popen([sys.executable, "-c", CHILD, scene, solver],
                                 stdout=subprocess.PIPE, text=True)
            assert p.stdout.readline().strip() == "ready"
            time.sleep(1.5)
            p.send_signal(signal.SIGINT)
            out = p.stdout.read()
            p.wait()
            if not out.startswith("latency"):
                sys.exit(f"{solver}: not interrupted: {out.strip()}")
            latencies.append(float(out.split()[1]))
        print(f"{solver:10s} latency [s]: {', '.join(f'{x:.3f}' for x in latencies)}"
              f"  (largest {max(latencies):.3f})")


if __name__ == "__main__":
    main()
