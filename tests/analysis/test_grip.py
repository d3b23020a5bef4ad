#!/usr/bin/python3
"""The grip figure (analysis/plot_grip.py, docs/theory/grip.md) on the paper scene with the scene's
mu lowered below what its support samples need (so that some samples slip), checked on the
returned artists against h5py and yaml readings of the file:

  - each leg's utilised-friction line is /contacts/utilized_friction, non-finite values blank;
  - the required-friction line is /contacts/required_friction, on an axis that ends 1.2 times
    its largest value outside transients; the dots of leg k are the samples on the axis whose
    /contacts/required_friction_leg is k, one triangle per sample above it;
  - the mu lines sit at contact.friction_coefficient of /meta config_yaml;
  - one shaded span per run of /contacts/phase == 1 of the leg (of any leg on top), found
    here by a loop;
  - one slip cross per sample with /contacts/slip == 1, and some slip exists;
  - the script writes the PNG, and refuses a result written with output.required_friction
    false: exit status 2, one line on stderr, no figure.

usage: test_grip.py --hexdyn BUILD/hexdyn --source SOURCE_DIR   (PYTHONPATH=BUILD/python)
"""

import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml

MU = 0.02  # below the paper's support samples' required friction (~0.045), so feet slip
failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + str(detail) if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def same_curve(artist, values):
    y = np.asarray(artist.get_ydata(), dtype=float)
    v = np.where(np.isfinite(values), values, np.nan)
    return y.shape == v.shape and np.array_equal(np.isnan(y), np.isnan(v)) and \
        np.array_equal(y[~np.isnan(y)], v[~np.isnan(v)])


def transient_runs(phase_k):
    """Number of runs of consecutive phase-1 samples, by a plain loop."""
    runs, inside = 0, False
    for p in phase_k:
        if p == 1 and not inside:
            runs += 1
        inside = p == 1
    return runs


def hexdyn_run(args, path, *sets):
    cmd = [args.hexdyn, "run", os.path.join(args.source, "configs", "paper.yaml"), "-o", path]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import plot_grip
    from hexdyn.results import open_result

    script = os.path.join(args.source, "analysis", "plot_grip.py")
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "slip.h5")
        hexdyn_run(args, path, f"contact.friction_coefficient={MU}")
        fig, artists, _ = plot_grip.draw(open_result(path))
        with h5py.File(path, "r") as f:
            c = f["contacts"]
            u, req = c["utilized_friction"][()], c["required_friction"][()]
            leg, slip, phase = c["required_friction_leg"][()], c["slip"][()], c["phase"][()]
            mu = yaml.safe_load(f["meta"].attrs["config_yaml"])["contact"]["friction_coefficient"]
        check(mu == MU, "the scene's mu is the one set")
        check(int((slip == 1).sum()) > 0, "some samples slip at the lowered mu")
        top_panel = artists["required"]
        transient_any = (phase == 1).any(axis=1)
        outside = req[~transient_any & np.isfinite(req)]
        top = 1.2 * float(outside.max())
        check(abs(top_panel["top"] - top) <= 1e-12 * top, "the required axis ends 1.2 x the "
              "largest mu* outside transients", f"{top_panel['top']} vs {top}")
        check(same_curve(top_panel["required"], req), "required line")
        check(len(top_panel["spans"]) == transient_runs(transient_any.astype(int)),
              "transient spans of the required panel")
        finite = np.where(np.isfinite(req), req, np.inf)
        check(len(top_panel["above"].get_xdata()) == int((np.isfinite(req) & (req > top)).sum()),
              "one triangle per sample above the axis")
        check(top_panel["mu"] is not None
              and float(np.asarray(top_panel["mu"].get_ydata())[0]) == mu, "mu line on top")
        for k, a in enumerate(artists["legs"]):
            name = f"L{k + 1}"
            check(same_curve(a["utilized"], u[:, k]), f"{name} utilised line")
            check(np.array_equal(np.asarray(top_panel["binds"][k].get_ydata()),
                                 req[(leg == k) & (finite <= top)]), f"{name} binding dots")
            check(float(np.asarray(a["mu"].get_ydata())[0]) == mu, f"{name} mu line")
            check(len(a["spans"]) == transient_runs(phase[:, k]), f"{name} transient spans",
                  f"{len(a['spans'])} vs {transient_runs(phase[:, k])}")
            check(len(a["slip"].get_xdata()) == int((slip[:, k] == 1).sum()),
                  f"{name} slip crosses")
        import matplotlib.pyplot as plt
        plt.close(fig)

        out = os.path.join(d, "out")
        r = subprocess.run([sys.executable, script, path, out], capture_output=True, text=True)
        check(r.returncode == 0 and os.path.getsize(os.path.join(out, "grip.png")) > 0,
              "plot_grip.py writes grip.png", r.stderr)

        bare = os.path.join(d, "bare.h5")
        hexdyn_run(args, bare, "output.required_friction=false")
        r = subprocess.run([sys.executable, script, bare, os.path.join(d, "none")],
                           capture_output=True, text=True)
        check(r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
              and "required_friction" in r.stderr and not os.path.exists(os.path.join(d, "none")),
              "a result without the required friction is refused in one line", r.stderr)
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
