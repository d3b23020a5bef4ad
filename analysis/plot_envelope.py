#!/usr/bin/python3
"""Plot of a hexdyn-envelope/2 file (`hexdyn envelope`, docs/user/envelope.md):
the largest climbable riser over peak speed as small multiples, one row per criterion
(kinematic, torque, friction; per case and criterion for a file with cases), one column per
tread depth, and in each panel one line per duty factor, each with its own colour and marker
and drawn a little to the side of the true speed (the duty factors in order, left to
right), so that lines with equal values stay apart.

    /usr/bin/python3 analysis/plot_envelope.py ENVELOPE.h5 OUTDIR [--check] [--table]

Writes OUTDIR/envelope.png (saved under a temporary name and renamed when complete).
A criterion that fails already at the lowest riser probed is drawn as a cross at that
riser. --check verifies the file against the layout declared in src/hexdyn/io/schema.hpp
(hexdyn.check_layout: every dataset declared, with its units, shape and element type); --table prints the
envelope as a text table (riser in mm, and what limits it) on stdout.
"""

import argparse
import os

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, fraction_text, save_atomically  # first: Agg
import hexdyn
from hexdyn import results as hr
import matplotlib.pyplot as plt
import numpy as np

S = hr.SCHEMA
DUTY_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")
DODGE = 0.02  # the lines' sideways offset, a fraction of the speed range per duty factor


def read_envelope(path):
    """The envelope file as a dict: axes, criteria, riser_max/fail (D,W,B,S,C; D = 1 without
    cases), limit and message strings on the same grid, posture (D,W,B,S), meta."""
    try:
        env = hexdyn.open_envelope(path)
    except (OSError, ValueError) as e:
        raise SystemExit(f"plot_envelope: {e}")
    d = {"meta": env.meta, "cases": env.cases, "criteria": env.criteria,
         "probes": int(env.shapes[S["kProbeRiser"].path][0])}
    for key, name in (("tread", "kEnvelopeTreadDepth"), ("duty", "kEnvelopeDutyFactor"),
                      ("speed", "kEnvelopePeakSpeed"), ("riser_max", "kEnvelopeRiserMax"),
                      ("riser_fail", "kEnvelopeRiserFail"), ("limit", "kEnvelopeLimit"),
                      ("message", "kEnvelopeMessage"), ("posture_height", "kEnvelopePostureHeight"),
                      ("posture_foot_lateral", "kEnvelopePostureFootLateral")):
        d[key] = env[S[name].path]
    d["riser_from"] = float(env[S["kEnvelopeRiserFrom"].path])
    d["riser_to"] = float(env[S["kEnvelopeRiserTo"].path])
    if d["cases"] is None:  # with cases (a design each) a leading dimension `case`; without, one
        for k in ("riser_max", "riser_fail", "limit", "message", "posture_height",
                  "posture_foot_lateral"):
            d[k] = d[k][np.newaxis]
    return d


def check_layout(path):
    """The file against the layout declared in schema.hpp (hexdyn.check_layout)."""
    try:
        hexdyn.check_layout(path)
    except (OSError, ValueError) as e:
        raise SystemExit(f"plot_envelope: {e}")


def duty_label(beta):
    return fraction_text(beta)


def table(d):
    lines = []
    for i, case in enumerate(d["cases"] or [None]):
        lines += case_table(d, i, case)
    return "\n".join(lines)


def case_table(d, i, case):
    lines = []
    for w, tread in enumerate(d["tread"]):
        lines.append(("" if case is None else f"{case}: ") +
                     f"tread {tread:.2f} m: largest climbable riser [mm] per duty factor (rows) "
                     f"and peak speed (columns), criteria {'/'.join(d['criteria'])}")
        lines.append("  beta   " + "".join(f"{v:>22.2f}" for v in d["speed"]))
        for b, beta in enumerate(d["duty"]):
            cells = []
            for v in range(len(d["speed"])):
                vals = ["-" if not np.isfinite(x) else f"{1e3 * x:.0f}"
                        for x in d["riser_max"][i, w, b, v]]
                cells.append("/".join(vals))
            lines.append(f"  {duty_label(beta):>5}  " + "".join(f"{c:>22}" for c in cells))
        limits = {}
        for b in range(len(d["duty"])):
            for v in range(len(d["speed"])):
                for c, name in enumerate(d["criteria"]):
                    lim = d["limit"][i, w, b, v, c]
                    if lim:
                        key = f"{name}: {lim}"
                        limits[key] = limits.get(key, 0) + 1
        for k, n in sorted(limits.items(), key=lambda kv: -kv[1]):
            lines.append(f"    {n:3d} x {k}")
    return lines


def plot(d, outdir):
    """Small multiples (module comment): rows (case, criterion), columns tread depth, a line
    per duty factor. Returns the path written."""
    W = len(d["tread"])
    cases = d["cases"] or [None]
    rows = [(i, case, c, name) for i, case in enumerate(cases)
            for c, name in enumerate(d["criteria"])]
    fig, grid = plt.subplots(len(rows), W, figsize=(1.0 + 3.3 * W, 1.6 + 2.3 * len(rows)),
                             sharex=True, sharey=True, squeeze=False, constrained_layout=True)
    B = len(d["duty"])
    colors = plt.cm.viridis(np.linspace(0.0, 0.85, B))
    speed = np.asarray(d["speed"], dtype=float)
    span = float(np.ptp(speed)) if speed.size > 1 else max(0.5 * abs(float(speed[0])), 0.05)
    for r, (i, case, c, name) in enumerate(rows):
        for w in range(W):
            ax = grid[r][w]
            for b, beta in enumerate(d["duty"]):
                x = speed + (b - (B - 1) / 2) * DODGE * span
                y = 1e3 * d["riser_max"][i, w, b, :, c]
                ax.plot(x, y, "-", marker=DUTY_MARKERS[b % len(DUTY_MARKERS)], ms=4.5, lw=1.1,
                        color=colors[b], label=f"β = {duty_label(beta)}")
                none = ~np.isfinite(y)
                if none.any():
                    ax.plot(x[none], np.full(none.sum(), 1e3 * d["riser_from"]), "x",
                            color=colors[b], ms=8, mew=1.8)
            if r == 0:
                ax.set_title(f"tread {d['tread'][w]:.2f} m", fontsize=10)
            if r == len(rows) - 1:
                ax.set_xlabel("peak speed [m/s]")
            if w == 0:
                ax.set_ylabel(("" if case is None else f"{case}\n") +
                              f"{name}:\nlargest riser [mm]", fontsize=9)
            ax.set_xticks(speed, [f"{v:g}" for v in speed])
            ax.set_xlim(speed.min() - 0.1 * span, speed.max() + 0.1 * span)
            ax.grid(alpha=0.3)
    handles, labels = grid[0][0].get_legend_handles_labels()
    grid[0][-1].legend(handles, labels, fontsize=8, title="duty factor", title_fontsize=8,
                       loc="best")
    fit_suptitle(fig, f"climbable envelope '{d['meta'].get('name', '')}': the largest riser "
                 "each criterion allows (a row each); the lines of the duty factors are drawn "
                 "slightly apart along the speed axis; x: fails at the lowest riser probed "
                 f"({1e3 * d['riser_from']:g} mm)", fontsize=10)
    path = save_atomically(fig, outdir, "envelope.png")
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("envelope")
    ap.add_argument("outdir")
    ap.add_argument("--check", action="store_true", help="verify the layout against schema.hpp")
    ap.add_argument("--table", action="store_true", help="print the envelope as a text table")
    a = ap.parse_args()
    if a.check:
        check_layout(a.envelope)
    d = read_envelope(a.envelope)
    os.makedirs(a.outdir, exist_ok=True)
    plot(d, a.outdir)
    if a.table:
        print(table(d))


if __name__ == "__main__":
    main()
