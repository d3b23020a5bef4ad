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
replay at the reference setting with the new one's.
"""

import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def replay(binary, plan, sets, setting, out):
    """The report of `binary replay plan` at setting "step:tolerance" with the --set pairs."""
    step, tol = setting.split(":")
    cmd = [binary, "replay", plan, "-o", out, "--set", f"replay.step={step}",
           "--set", f"replay.tolerance={tol}"]
    for kv in sets:
        cmd += ["--set", kv]
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"replay_against_binary: {' '.join(cmd)} failed:\n{proc.stderr}")
    with h5py.File(out, "r") as f:
        r = f["replay"]
        return {"p_mm": f["base/position"][-1] * 1e3, "E_J": float(r["energy"][()]),
                "slip_mJ": float(r["slip_energy"][:].sum() * 1e3),
                "td_mJ": float(r["touchdown_energy"][:].sum() * 1e3)}


def row(name, setting, old, new, ref):
    def drift(x):
        return np.linalg.norm(x["p_mm"] - ref["p_mm"])
    return (f"| {name} | {setting.replace(':', ' s, ')} | {drift(old):.2f} | **{drift(new):.2f}** | "
            f"{old['E_J'] - ref['E_J']:+.4f} | **{new['E_J'] - ref['E_J']:+.4f}** | "
            f"{old['slip_mJ']:.2f} | **{new['slip_mJ']:.2f}** | {old['td_mJ']:.1f} | "
            f"**{new['td_mJ']:.1f}** |")


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
        ref = replay(args.new, plan, sets, args.reference, out)
        ref_old = replay(args.old, plan, sets, args.reference, out)
        print(row(name, args.reference + " (reference)", ref_old, ref, ref), flush=True)
        for setting in args.settings:
            old = replay(args.old, plan, sets, setting, out)
            new = replay(args.new, plan, sets, setting, out)
            print(row("", setting, old, new, ref), flush=True)


if __name__ == "__main__":
    main()
