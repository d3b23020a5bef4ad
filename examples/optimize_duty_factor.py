#!/usr/bin/env python3
"""The duty factor that minimises the cost of transport of a stair climb at equal travel,
found in process: scipy.optimize.minimize_scalar calls hexdyn.run (no subprocess, no file)
once per evaluation.

    PYTHONPATH=build/python /usr/bin/python3 examples/optimize_duty_factor.py configs/paper.yaml
    ... [--bounds 0.5 0.9] [--xatol 0.01] [--treads 3] [--peak-speed 0.1] [--ramp 0.8]

Every duty factor climbs the same distance. With a fixed number of gait cycles the trunk
travels cycles x s0/beta, so a larger duty factor would climb less (the paper's three
cycles: 0.76 m along the slope at beta = 1/2, 0.50 m at beta = 0.77) and its smaller
energy would compare different tasks. Here the scene's motion is given by the travel
instead (docs/user/configuration.md#travel-instead-of-cycles): `motion.travel: {treads: N}`
with the speed keys `motion.peak_speed` and `motion.ramp_duration` in place of the scene's
`motion.cycle_durations` or `motion.cycles`; the cycles then follow from the travel, the
stride shrinking to cover it exactly. The objective is the cost of transport
E/(m g d) (/energy/cost_of_transport), with d (/energy/distance) the same for every
evaluation; each evaluation prints its cycles, stroke, travel, energy and cost of transport.
The defaults (3 treads, 0.1 m/s, 0.8 s ramps) are the paper's climb: its three treads, its
quoted peak speed and its speed ramps (configs/paper.yaml).

Prints each evaluation and the optimum; writes the optimal run with --output FILE.
"""

import argparse
import time

from scipy.optimize import minimize_scalar

import hexdyn


def equal_travel(treads, peak_speed, ramp):
    """The overrides that give the motion by its travel (the same for every duty factor)."""
    return {"motion.cycle_durations": None, "motion.cycles": None,
            "motion.travel": {"treads": treads}, "motion.peak_speed": peak_speed,
            "motion.ramp_duration": ramp}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--bounds", nargs=2, type=float, default=(0.5, 0.9), metavar=("LOW", "HIGH"))
    ap.add_argument("--xatol", type=float, default=0.01, help="tolerance on the duty factor")
    ap.add_argument("--treads", type=int, default=3, help="treads climbed by every run (default 3)")
    ap.add_argument("--peak-speed", type=float, default=0.1, help="cruise speed [m/s] (default 0.1)")
    ap.add_argument("--ramp", type=float, default=0.8, help="speed ramp duration [s] (default 0.8)")
    ap.add_argument("--output", help="write the optimal run's hexdyn-result/5 file here")
    a = ap.parse_args()
    fixed = equal_travel(a.treads, a.peak_speed, a.ramp)

    evaluations = []

    def run(duty):
        return hexdyn.run(a.scene, set={**fixed, "gait.duty_factor": float(duty)})

    def cost_of_transport(duty):
        r = run(duty)
        e, d = float(r["/energy/total"]), float(r["/energy/distance"])
        cot = float(r["/energy/cost_of_transport"])
        evaluations.append((duty, e, d, cot))
        print(f"  duty factor {duty:.4f}: {len(r['/energy/cycle'])} cycles of stroke "
              f"{float(r.config['gait']['stroke']):.4f} m, travel {d:.4f} m, energy {e:.3f} J, "
              f"cost of transport {cot:.4f}")
        return cot

    print(f"{a.scene}: every duty factor climbs {a.treads} treads at {a.peak_speed:g} m/s "
          f"(ramps {a.ramp:g} s)")
    t0 = time.perf_counter()
    best = minimize_scalar(cost_of_transport, bounds=a.bounds, method="bounded",
                           options={"xatol": a.xatol})
    elapsed = time.perf_counter() - t0
    travels = [d for _, _, d, _ in evaluations]
    spread = max(travels) - min(travels)
    print(f"travel of every evaluation {min(travels):.4f} to {max(travels):.4f} m "
          f"(spread {spread:.2e} m): the costs compare the same climb")
    # The runs are comparable only if they cover the same distance.
    assert spread <= 1e-6 * max(travels), f"travel differs between duty factors by {spread} m"
    energy = min(evaluations, key=lambda row: row[3])[1]
    print(f"optimum: duty factor {best.x:.4f}, cost of transport {best.fun:.4f} "
          f"(energy {energy:.3f} J over {travels[0]:.4f} m; {len(evaluations)} runs in "
          f"{elapsed:.2f} s, {1e3 * elapsed / len(evaluations):.0f} ms per run)")
    # The optimum is no worse than every evaluated point (bounded Brent returns the best seen).
    assert best.fun <= min(c for *_, c in evaluations) + 1e-9
    if a.output:
        run(best.x).write(a.output)
        print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
