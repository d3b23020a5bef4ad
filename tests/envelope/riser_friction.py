#!/usr/bin/python3
"""The required friction per envelope cell (docs/user/envelope.md#the-required-friction-per-cell):
`hexdyn envelope` on tests/data/envelope_quick.yaml (two cells, three criteria, a few seconds);
for every cell and dynamic criterion with a riser_max, the same scene is run here with
`hexdyn run` (the base scene with the cell's duty factor and speed, riser_max, and the
criterion's lifted limit: μ = 10 for torque, torque limit 10⁶ N m for friction), and the
largest /contacts/required_friction over its support samples (no leg in phase 1), read with
h5py, is /envelope/riser_max_required_friction; NaN for the kinematic criterion.

usage: riser_friction.py HEXDYN SOURCE_DIR
"""

import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

LIFTED = {"torque": "contact.friction_coefficient=10", "friction": "allocation.torque_limit=1e6"}


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def support_required_friction(path):
    """Largest required friction over the support samples; NaN if one of them is NaN."""
    with h5py.File(path, "r") as f:
        mu = f["contacts/required_friction"][()]
        support = ~(f["contacts/phase"][()] == 1).any(axis=1)
    return math.nan if np.isnan(mu[support]).any() else float(mu[support].max())


def main():
    hexdyn, source = sys.argv[1], sys.argv[2]
    base = os.path.join(source, "configs", "sweeps", "stairs_base.yaml")
    failures, checked = 0, 0
    with tempfile.TemporaryDirectory() as d:
        env = os.path.join(d, "env.h5")
        subprocess.run([hexdyn, "envelope", os.path.join(source, "tests", "data",
                                                         "envelope_quick.yaml"), "-o", env],
                       check=True, stderr=subprocess.DEVNULL)
        with h5py.File(env, "r") as f:
            treads, duties = f["axes/tread_depth"][()], f["axes/duty_factor"][()]
            speeds = f["axes/peak_speed"][()]
            crits = [text(c) for c in f["axes/criteria"][()]]
            rmax = f["envelope/riser_max"][()]
            mu = f["envelope/riser_max_required_friction"][()]
        for idx in np.ndindex(rmax.shape):
            w, b, v, c = idx
            if crits[c] == "kinematic" or not np.isfinite(rmax[idx]):
                ok = math.isnan(mu[idx])
                print(f"{'ok  ' if ok else 'FAIL'} cell {idx} {crits[c]}: NaN")
                failures += not ok
                continue
            run = os.path.join(d, f"run_{w}_{b}_{v}_{c}.h5")
            sets = [f"terrain.riser_height={rmax[idx]!r}", f"terrain.tread_depth={treads[w]!r}",
                    f"gait.duty_factor={duties[b]!r}", f"motion.peak_speed={speeds[v]!r}",
                    LIFTED[crits[c]]]
            subprocess.run([hexdyn, "run", base, "-o", run] + sum([["--set", s] for s in sets], []),
                           check=True, stderr=subprocess.DEVNULL)
            want = support_required_friction(run)
            ok = (math.isnan(want) and math.isnan(mu[idx])) or want == mu[idx]
            checked += 1
            print(f"{'ok  ' if ok else 'FAIL'} cell {idx} {crits[c]} at {rmax[idx]:g} m: "
                  f"{mu[idx]!r} vs {want!r}")
            failures += not ok
    if checked == 0:
        print("FAIL no dynamic criterion has a riser_max")
        failures += 1
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
