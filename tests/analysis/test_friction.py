#!/usr/bin/python3
"""The grip-study pipeline, reduced (pipelines/friction.sh --quick; docs/validation/friction.md),
checked against readings of its files made here with h5py and csv:

  - the pipeline writes its two figures, the CSV and the Markdown table;
  - /scenarios/required_friction_support and _transient of the sweep file are the largest
    finite /contacts/required_friction of the kept run over the samples where no leg, and
    where some leg, is in phase 1, with the binding leg and time of that sample;
    no_friction_samples counts its NaN samples, slip_samples the samples with a slip flag,
    peak_utilized_friction is the largest /contacts/utilized_friction over support samples;
  - the CSV's transient energy share is the energy by the rule /meta energy_rule names over
    the intervals, each half counted to the sample at its end, here by a computation of its
    own (each interval's interpolant by numpy.polyfit through the stencil the rule names, |p|
    by a 2048-part Simpson rule), and its denominator is the run's /energy/total (the
    program's own rule, a second computation of the total);
  - the CSV's support peak is the largest of its per-leg peaks.

usage: test_friction.py --hexdyn BUILD/hexdyn --source SOURCE_DIR   (PYTHONPATH=BUILD/python)
"""

import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def same(a, b, rel=1e-12):
    a, b = float(a), float(b)
    return (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=rel, abs_tol=1e-15)


def expected_peaks(run):
    """(support, transient) tuples (mu, leg, time) and the NaN count of a kept run's group."""
    mu = run["contacts/required_friction"][()]
    leg = run["contacts/required_friction_leg"][()]
    t = run["time"][()]
    transient = (run["contacts/phase"][()] == 1).any(axis=1)
    out = []
    for kind in (~transient, transient):
        sel = np.where(kind & np.isfinite(mu))[0]
        if len(sel) == 0:
            out.append((math.nan, -1, math.nan))
            continue
        i = sel[np.argmax(mu[sel])]
        out.append((mu[i], int(leg[i]), t[i]))
    return out, int(np.isnan(mu).sum())


def interval_energies(t, power, kind, cubic):
    """Σ_j ∫|p_j| over each interval [t_k, t_k+1] (T − 1): by the trapezoid of |power|, or by
    the piecewise-cubic rule (docs/theory/output-grid.md#energy-from-the-samples): pieces end
    at a left-limit sample (kind 1), whose interval to its event takes the trapezoid; on a
    piece of n intervals each interval's polynomial interpolates the min(n + 1, 4) samples of
    the piece nearest it (k - 1 ... k + 2, shifted inwards at the ends), and |p| is integrated
    by Simpson's rule on 2048 parts."""
    h = np.diff(t)
    trap = 0.5 * h * (np.abs(power[1:]) + np.abs(power[:-1])).sum(axis=1)
    if not cubic:
        return trap
    out = trap.copy()
    u = np.linspace(0.0, 1.0, 2049)
    w = np.ones_like(u)
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    w /= 3.0 * 2048
    ends = list(np.nonzero(kind[:-1] == 1)[0]) + [len(t) - 1]
    s = 0
    for e in ends:
        n = e - s
        for k in range(s, e):
            width = min(n + 1, 4)
            first = min(max(k - 1, s), e + 1 - width)
            idx = np.arange(first, first + width)
            x = (t[idx] - t[k]) / h[k]
            coef = np.polyfit(x, power[idx], width - 1)  # (width, J), highest first
            values = np.abs(np.array([np.polyval(coef[:, j], u) for j in range(power.shape[1])]))
            out[k] = h[k] * np.sum(values @ w)
        s = e + 1
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        subprocess.run(["bash", os.path.join(args.source, "pipelines", "friction.sh"), "--quick",
                        "--hexdyn", args.hexdyn, "--out", d], check=True)
        for name in ("friction_required.png", "friction_transient_energy.png", "friction.csv",
                     "friction_table.txt"):
            check(os.path.getsize(os.path.join(d, name)) > 0, f"pipeline writes {name}")
        with open(os.path.join(d, "friction.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        with h5py.File(os.path.join(d, "friction.h5"), "r") as f:
            sc = f["scenarios"]
            ids = [v.decode() if isinstance(v, bytes) else str(v) for v in sc["id"][()]]
            check(len(rows) == len(ids) == 2, "one CSV line per scenario")
            for i, sid in enumerate(ids):
                run = f["runs"][sid]
                (sup, tra), nans = expected_peaks(run)
                for kind, (mu, leg, t) in (("support", sup), ("transient", tra)):
                    check(same(sc[f"required_friction_{kind}"][i], mu),
                          f"{sid} required_friction_{kind} = max over its samples",
                          f"{sc[f'required_friction_{kind}'][i]} vs {mu}")
                    check(int(sc[f"required_friction_{kind}_leg"][i]) == leg,
                          f"{sid} required_friction_{kind}_leg")
                    check(same(sc[f"required_friction_{kind}_time"][i], t),
                          f"{sid} required_friction_{kind}_time")
                check(int(sc["no_friction_samples"][i]) == nans, f"{sid} no_friction_samples")
                slip = run["contacts/slip"][()]
                check(int(sc["slip_samples"][i]) == int((slip != 0).any(axis=1).sum()),
                      f"{sid} slip_samples")
                transient = (run["contacts/phase"][()] == 1).any(axis=1)
                u = run["contacts/utilized_friction"][()][~transient]
                check(same(sc["peak_utilized_friction"][i], np.nanmax(u)),
                      f"{sid} peak_utilized_friction")
                # The transient share, from the intervals: each half of [t_k, t_k+1] belongs
                # to the sample at its end.
                t = run["time"][()]
                cubic = run["meta"].attrs["energy_rule"] in (b"piecewise-cubic", "piecewise-cubic")
                intervals = interval_energies(t, run["power/per_joint"][()],
                                              run["sample_kind"][()], cubic)
                tr = transient.astype(float)
                e_tr = float(np.sum(0.5 * intervals * (tr[:-1] + tr[1:])))
                total = float(run["energy/total"][()])
                check(same(intervals.sum(), total, rel=1e-6), f"{sid} intervals add up to "
                      "/energy/total", f"{intervals.sum()} vs {total}")
                row = rows[i]
                check(same(float(row["transient_energy_share"]), e_tr / total, rel=1e-5),
                      f"{sid} transient energy share", f"{row['transient_energy_share']} vs "
                      f"{e_tr / total}")
                legs = [float(row[f"mu_support_L{k}"]) for k in range(1, 7)]
                check(same(float(row["mu_support"]), np.nanmax(legs)),
                      f"{sid} support peak is the largest per-leg peak")
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
