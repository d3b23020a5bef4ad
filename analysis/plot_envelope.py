#!/usr/bin/python3
"""Plot of a hexdyn-envelope/2 file (`hexdyn envelope`, docs/user/envelope.md):
the largest climbable riser over peak speed, one panel per tread depth, one colour per
duty factor, one line style per criterion (kinematic, torque, friction).

    /usr/bin/python3 analysis/plot_envelope.py ENVELOPE.h5 OUTDIR [--check] [--table]

Writes OUTDIR/envelope.png (saved under a temporary name and renamed when complete).
A criterion that fails already at the lowest riser probed is drawn as a cross at that
riser. --check verifies the file against the layout declared in src/hexdyn/io/schema.hpp
(hexdyn.check_layout: every dataset declared, with its units, shape and element type); --table prints the
envelope as a text table (riser in mm, and what limits it) on stdout.
"""

import argparse
import os


import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hexdyn  # noqa: E402
from hexdyn import results as hr  # noqa: E402
from plot_kinematics import save_atomically  # noqa: E402

S = hr.SCHEMA
STYLES = {"kinematic": "-", "torque": "--", "friction": ":"}
MARKERS = {"kinematic": "o", "torque": "s", "friction": "^"}


def read_envelope(path):
    """The envelope file as a dict: axes, criteria, riser_max/fail (D,W,B,S,C; D = 1 without
    cases), limit and message strings on the same grid, posture (D,W,B,S), meta."""
    try:
        env = hexdyn.open_envelope(path)  # version 1 (flattened limit and message) plots too
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
    for q in range(2, 13):
        p = round(beta * q)
        if abs(p / q - beta) < 1e-9:
            return f"{p}/{q}"
    return f"{beta:g}"


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
    W = len(d["tread"])
    cases = d["cases"] or [None]
    fig, grid = plt.subplots(len(cases), W, figsize=(4.2 * W, 4.0 * len(cases)), sharey=True,
                             squeeze=False)
    colors = plt.cm.viridis(np.linspace(0.0, 0.85, len(d["duty"])))
    for (i, case), (w, ax) in ((ic, wa) for ic in enumerate(cases) for wa in enumerate(grid[ic[0]])):
        for b, beta in enumerate(d["duty"]):
            for c, name in enumerate(d["criteria"]):
                y = 1e3 * d["riser_max"][i, w, b, :, c]
                ax.plot(d["speed"], y, STYLES.get(name, "-"), marker=MARKERS.get(name, "o"), ms=4,
                        color=colors[b], label=f"β = {duty_label(beta)}, {name}")
                none = ~np.isfinite(y)
                if none.any():
                    ax.plot(d["speed"][none], np.full(none.sum(), 1e3 * d["riser_from"]), "x",
                            color=colors[b], ms=8)
        ax.set_title(("" if case is None else f"{case}, ") + f"tread {d['tread'][w]:.2f} m")
        ax.set_xlabel("peak speed [m/s]")
        ax.grid(alpha=0.3)
    for row in grid:
        row[0].set_ylabel("largest climbable riser [mm]")
    handles, labels = grid[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(d["duty"]), fontsize=7, frameon=False)
    fig.suptitle(f"climbable envelope '{d['meta'].get('name', '')}' (x: fails at the lowest riser)")
    fig.tight_layout(rect=(0, 0.16 / len(cases), 1, 1 - 0.05 / len(cases)))
    save_atomically(fig, outdir, "envelope.png")
    plt.close(fig)


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
