#!/usr/bin/python3
"""Mechanical against electrical energy of the paper's stair climb per duty factor, at equal
travel, with one servo on every joint: the table of docs/validation/drive-train.md.

    PYTHONPATH=build/python /usr/bin/python3 analysis/drive_train_duty.py
        [--scene configs/paper.yaml] [--servo dynamixel_mx64] [--duty 1/2 2/3 3/4 5/6]
        [--treads 3] [--peak-speed 0.1] [--ramp 0.8] [--set KEY=VALUE ...]

Each duty factor runs in process (hexdyn.run) on the scene with
  actuators: {default: {model: SERVO}}
and its motion given by the travel (docs/user/configuration.md#travel-instead-of-cycles):
motion.travel {treads: N} with motion.peak_speed and motion.ramp_duration in place of the
scene's cycle durations, so that every duty factor climbs the same treads (the defaults,
three treads at 0.1 m/s with 0.8 s ramps, are the paper's climb, as in
examples/optimize_duty_factor.py). A second run of each with regeneration 1 gives the
electrical energy if the drivers returned all negative power to the supply.

Prints a Markdown table, one row per duty factor: gait cycles, mechanical energy E
(/energy/total, the integral of sum |tau omega|), electrical energy E_el
(/energy/electrical), their ratio, the copper and friction losses, E_el with regeneration
1, both costs of transport, the rank of each duty factor by E and by E_el (1 = least), and
the relaxed samples: all of them and those outside touchdown transients (no leg in phase
impact), where a drive's bound (peak or voltage) or the trunk's equations gave way in the
gait itself. Then one line saying whether the ranking changes. Nothing is written.
"""

import argparse
import sys

import numpy as np

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
import hexdyn


def parse_set(items):
    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep:
            raise SystemExit(f"drive_train_duty: --set: got {item!r}, expected KEY=VALUE")
        out[key] = value
    return out


def overrides(args):
    """The overrides every run shares: the servo and the motion by travel."""
    return {"actuators": {"default": {"model": args.servo}},
            "motion.cycle_durations": None, "motion.cycles": None,
            "motion.travel": {"treads": args.treads}, "motion.peak_speed": args.peak_speed,
            "motion.ramp_duration": args.ramp, **parse_set(args.set)}


def measure(scene, fixed, duty):
    """The row of one duty factor."""
    r = hexdyn.run(scene, set={**fixed, "gait.duty_factor": duty})
    regen = hexdyn.run(scene, set={**fixed, "gait.duty_factor": duty,
                                   "actuators": {"default": {"model": fixed["actuators"]
                                                             ["default"]["model"],
                                                             "regeneration": 1}}})
    status = np.asarray(r["/solver/status"])
    transient = (np.asarray(r["/contacts/phase"]) == 1).any(axis=1)
    value = {k: float(r[f"/energy/{k}"]) for k in (
        "total", "electrical", "copper_loss", "friction_loss", "cost_of_transport",
        "cost_of_transport_electrical", "distance")}
    value.update(duty=duty, cycles=len(r["/gait/cycle_start"]),
                 stroke=float(r.config["gait"]["stroke"]),
                 electrical_regen=float(regen["/energy/electrical"]),
                 relaxed=int((status == 1).sum()),
                 relaxed_gait=int(((status == 1) & ~transient).sum()),
                 failed=int((status == 2).sum()), samples=int(status.size),
                 commit=r.meta.get("git_commit", "unknown"))
    return value


def ranks(values):
    """1 for the smallest."""
    order = np.argsort(values, kind="stable")
    out = np.empty(len(values), dtype=int)
    out[order] = np.arange(1, len(values) + 1)
    return out


def table(rows):
    e = np.array([r["total"] for r in rows])
    el = np.array([r["electrical"] for r in rows])
    rank_e, rank_el = ranks(e), ranks(el)
    lines = ["| β | cycles | stroke [m] | E [J] | E_el [J] | E_el/E | copper [J] | friction [J] "
             "| E_el, r = 1 [J] | CoT | CoT_el | rank by E | rank by E_el | relaxed (gait) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r, a, b in zip(rows, rank_e, rank_el):
        lines.append(
            f"| {r['duty']} | {r['cycles']} | {r['stroke']:.4g} | {r['total']:.2f} | "
            f"{r['electrical']:.1f} | {r['electrical'] / r['total']:.2f} | "
            f"{r['copper_loss']:.1f} | {r['friction_loss']:.2f} | {r['electrical_regen']:.1f} | "
            f"{r['cost_of_transport']:.3f} | {r['cost_of_transport_electrical']:.2f} | {a} | {b} "
            f"| {r['relaxed']} ({r['relaxed_gait']}) |")

    def order(rk):
        return " < ".join(rows[i]["duty"] for i in np.argsort(rk, kind="stable"))

    changed = not np.array_equal(rank_e, rank_el)
    lines += ["", f"by E: {order(rank_e)}; by E_el: {order(rank_el)}: the ranking "
              f"{'changes' if changed else 'does not change'}.",
              f"distance {rows[0]['distance']:.4f} m for every duty factor "
              f"(spread {np.ptp([r['distance'] for r in rows]):.1e} m); git commit "
              f"{rows[0]['commit']}"]
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.strip().split("\n\n")[0],
                                 epilog=__doc__.strip().split("\n\n", 1)[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="configs/paper.yaml")
    ap.add_argument("--servo", default="dynamixel_mx64", help="a model of the servo table")
    ap.add_argument("--duty", nargs="+", default=["1/2", "2/3", "3/4", "5/6"])
    ap.add_argument("--treads", type=int, default=3)
    ap.add_argument("--peak-speed", type=float, default=0.1, help="m/s (default 0.1)")
    ap.add_argument("--ramp", type=float, default=0.8, help="s (default 0.8)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a further override of every run, as hexdyn run --set")
    args = ap.parse_args(argv)
    fixed = overrides(args)
    try:
        rows = [measure(args.scene, fixed, d) for d in args.duty]
    except hexdyn.Error as e:
        print(f"drive_train_duty: {e}", file=sys.stderr)
        return 2
    print("\n".join(table(rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
