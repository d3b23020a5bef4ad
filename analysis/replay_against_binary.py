#!/usr/bin/python3
"""Two hexdyn binaries' replays of the same plans against one reference
(docs/validation/replay.md#the-feedforwards-instant): per plan, both binaries replay it at
each setting, and the new binary once more at the reference setting; prints a Markdown row
per plan and setting with the drift error (distance between the trunk's final positions of
the replay and of the reference) [mm], the joint energy error (/replay/energy less the
reference's) [J], and the slip and touchdown energies summed over the feet [mJ], old | new.

    /usr/bin/python3 analysis/replay_against_binary.py --old OLD/hexdyn [--new build/hexdyn]
        --plan NAME=PLAN.h5[,key=value...] ... [--settings 2e-3:0.05 1e-3:0.05 2.5e-4:0.01]
        [--reference 3.125e-5:0.01] [--work DIR]

A plan's key=value pairs are passed to both binaries' `hexdyn replay` as --set (for example
contact.friction_law=regularised). The first row of each plan compares the old binary's
replay at the reference setting with the new one's. Replays and reports are those of
analysis/replay_convergence.py.
"""

import argparse
import os
import tempfile

import numpy as np
from replay_convergence import replay

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def report(binary, plan, sets, setting, out):
    """The report of `binary replay plan` at setting "step:tolerance" with the key=value
    overrides `sets` (replay_convergence.replay, once)."""
    step, tol = (float(x) for x in setting.split(":"))
    return replay(binary, plan, out, step, tol, 1, sets)


def row(name, setting, old, new, ref):
    # Both replays follow the same plan, so the distance between their drifts (replayed minus
    # planned final trunk position) is the distance between their final trunk positions.
    def drift_mm(x):
        return np.linalg.norm(x["drift"] - ref["drift"]) * 1e3

    def energy(x, key):
        return x[key] * 1e3
    return (f"| {name} | {setting.replace(':', ' s, ')} | {drift_mm(old):.2f} | "
            f"**{drift_mm(new):.2f}** | {old['energy_J'] - ref['energy_J']:+.4f} | "
            f"**{new['energy_J'] - ref['energy_J']:+.4f}** | "
            f"{energy(old, 'slip_energy_J'):.2f} | **{energy(new, 'slip_energy_J'):.2f}** | "
            f"{energy(old, 'touchdown_energy_J'):.1f} | "
            f"**{energy(new, 'touchdown_energy_J'):.1f}** |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", required=True, help="the older hexdyn binary")
    ap.add_argument("--new", default=os.path.join(SOURCE, "build", "hexdyn"))
    ap.add_argument("--plan", action="append", required=True, help="NAME=PLAN.h5[,key=value...]")
    ap.add_argument("--settings", nargs="+", default=["2e-3:0.05", "1e-3:0.05", "2.5e-4:0.01"])
    ap.add_argument("--reference", default="3.125e-5:0.01")
    ap.add_argument("--work", default=None, help="folder for the replays (default: a temporary one)")
    args = ap.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="replay_against_binary_")
    os.makedirs(work, exist_ok=True)
    print("| plan | step, tolerance | drift error old | new | joint energy error old | new "
          "| slip energy old | new | touchdown energy old | new |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for spec in args.plan:
        name, rest = spec.split("=", 1)
        plan, *sets = rest.split(",")
        out = os.path.join(work, "replay.h5")
        ref = report(args.new, plan, sets, args.reference, out)
        ref_old = report(args.old, plan, sets, args.reference, out)
        print(row(name, args.reference + " (reference)", ref_old, ref, ref), flush=True)
        for setting in args.settings:
            old = report(args.old, plan, sets, setting, out)
            new = report(args.new, plan, sets, setting, out)
            print(row("", setting, old, new, ref), flush=True)


if __name__ == "__main__":
    main()
