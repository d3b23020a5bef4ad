#!/usr/bin/env python3
"""The duty factor that minimises the energy of the paper's stair climb, found in process:
scipy.optimize.minimize_scalar calls hexdyn.run (no subprocess, no file) once per
evaluation.

    PYTHONPATH=build/python /usr/bin/python3 examples/optimize_duty_factor.py configs/paper.yaml
    ... [--bounds 0.55 0.9] [--xatol 0.01]

Prints each evaluation and the optimum; writes the optimal run with --output FILE.
"""

import argparse
import time

from scipy.optimize import minimize_scalar

import hexdyn


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--bounds", nargs=2, type=float, default=(0.55, 0.9), metavar=("LOW", "HIGH"))
    ap.add_argument("--xatol", type=float, default=0.01, help="tolerance on the duty factor")
    ap.add_argument("--output", help="write the optimal run's hexdyn-result/1 file here")
    a = ap.parse_args()

    evaluations = []

    def energy(duty):
        r = hexdyn.run(a.scene, set={"gait.duty_factor": float(duty)})
        e = float(r["/energy/total"])
        evaluations.append((duty, e))
        print(f"  duty factor {duty:.4f}: energy {e:.3f} J")
        return e

    t0 = time.perf_counter()
    best = minimize_scalar(energy, bounds=a.bounds, method="bounded", options={"xatol": a.xatol})
    elapsed = time.perf_counter() - t0
    print(f"optimum: duty factor {best.x:.4f}, energy {best.fun:.3f} J "
          f"({len(evaluations)} runs in {elapsed:.2f} s, {1e3 * elapsed / len(evaluations):.0f} ms per run)")
    # The optimum is no worse than every evaluated point (bounded Brent returns the best seen).
    assert best.fun <= min(e for _, e in evaluations) + 1e-9
    if a.output:
        hexdyn.run(a.scene, set={"gait.duty_factor": float(best.x)}).write(a.output)
        print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
