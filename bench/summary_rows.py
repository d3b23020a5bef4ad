"""Rows of a sweep computed for its rows alone against the same sweep with --keep-runs.

A sweep without --keep-runs settles a sample's required friction by an upper bound where it
cannot reach the scenario's largest (docs/theory/grip.md#in-a-sweep). This runs the sweep both
ways and checks, scenario by scenario: every required friction figure equal to 2e-7, the samples
without a required friction and the slip samples equal, and where the leg or time named for a
maximum differs, the one named without --keep-runs is a tie in the kept run (its sample's
required friction within 2e-7 of the maximum).

    /usr/bin/python3 bench/summary_rows.py [--sweep bench/sweep_1000.yaml] [--ranks 2]

Exit status 1 when a scenario differs otherwise. Sets the root permissions Open MPI needs.
"""

import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(sweep, out, ranks, keep):
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), os.path.join(ROOT, "build", "hexdyn"),
           "sweep", sweep, "-o", out] + (["--keep-runs"] if keep else [])
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def same(x, y):
    return abs(x - y) <= 2e-7 * max(1.0, abs(y))


def compare(fast_path, kept_path):
    """(ties named differently, a line per difference)."""
    with h5py.File(fast_path) as fast, h5py.File(kept_path) as kept:
        a, b = fast["scenarios"], kept["scenarios"]
        ids = [x.decode() if isinstance(x, bytes) else str(x) for x in b["id"][()]]
        ties, bad = 0, []
        for kind in ("support", "transient"):
            va, vb = a[f"required_friction_{kind}"][()], b[f"required_friction_{kind}"][()]
            la, lb = a[f"required_friction_{kind}_leg"][()], b[f"required_friction_{kind}_leg"][()]
            ta, tb = a[f"required_friction_{kind}_time"][()], b[f"required_friction_{kind}_time"][()]
            for i, sid in enumerate(ids):
                if np.isnan(va[i]) and np.isnan(vb[i]):
                    continue
                if not same(va[i], vb[i]):
                    bad.append(f"{sid} {kind}: {va[i]!r} against {vb[i]!r} with --keep-runs")
                    continue
                if la[i] == lb[i] and ta[i] == tb[i]:
                    continue
                run_group = kept[f"runs/{sid}"]
                t = run_group["time"][()]
                mu = run_group["contacts/required_friction"][()]
                k = int(np.argmin(np.abs(t - ta[i])))
                if t[k] != ta[i] or not same(mu[k], vb[i]):
                    bad.append(f"{sid} {kind}: the sample at t = {ta[i]!r} s needs {mu[k]!r}, "
                               f"not the maximum {vb[i]!r}")
                    continue
                ties += 1
        for col in ("no_friction_samples", "slip_samples"):
            for i in np.flatnonzero(a[col][()] != b[col][()]):
                bad.append(f"{ids[i]} {col}: {a[col][i]} against {b[col][i]} with --keep-runs")
        return len(ids), ties, bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sweep", default=os.path.join(ROOT, "bench", "sweep_1000.yaml"))
    ap.add_argument("--ranks", type=int, default=2)
    args = ap.parse_args()
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    with tempfile.TemporaryDirectory() as work:
        fast, kept = os.path.join(work, "rows.h5"), os.path.join(work, "kept.h5")
        run(args.sweep, fast, args.ranks, False)
        run(args.sweep, kept, args.ranks, True)
        n, ties, bad = compare(fast, kept)
    for line in bad:
        print(line)
    print(f"{n} scenarios: {len(bad)} differences; {ties} maxima name another of tied legs or "
          "samples")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
