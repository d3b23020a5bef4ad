#!/usr/bin/python3
"""The figure of the slip-and-impact study (pipelines/replay.sh, docs/validation/replay.md),
drawn from the CSV of analysis/replay_sweep.py.

    /usr/bin/python3 analysis/plot_replay.py REPLAY.csv OUTDIR [--name NAME]

Writes OUTDIR/NAME_shares.png (NAME: replay): one column of panels per surface friction mu,
against the duty factor, a line per peak speed: the energy lost to slip (top row) and to normal
contact damping, touchdowns and support (middle row), each as a share of the replay's joint
energy, and the trunk's drift at the end (bottom row), on log scales. A filled marker is a
replay that reached the top of the stairs; an open one did not (a cross: it ended early); a
grey square marks a plan with relaxed support samples, whose torques do not make it exact.
"""

import argparse
import csv

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, fraction_text, save_atomically
import matplotlib.pyplot as plt
import numpy as np

ROWS = (("slip_share", "slip energy / joint energy", 100.0, "%"),
        ("touchdown_share", "damping energy / joint energy", 100.0, "%"),
        ("drift_m", "trunk drift at the end", 1e3, "mm"))


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            if k not in ("message", "file"):
                r[k] = float(v)
    return rows


def draw(rows, outdir, name):
    mus = sorted({r["mu_static"] for r in rows})
    speeds = sorted({r["peak_speed_mps"] for r in rows})
    duties = sorted({r["duty_factor"] for r in rows})
    colors = plt.cm.viridis(np.linspace(0.0, 0.85, max(len(speeds), 1)))
    fig, axes = plt.subplots(len(ROWS), len(mus), figsize=(3.2 * len(mus) + 1.0, 8.0),
                             sharex=True, sharey="row", squeeze=False)
    for j, mu in enumerate(mus):
        for i, (key, label, scale, unit) in enumerate(ROWS):
            ax = axes[i][j]
            for c, v in zip(colors, speeds):
                sel = sorted((r for r in rows if r["mu_static"] == mu and r["peak_speed_mps"] == v),
                             key=lambda r: r["duty_factor"])
                x = [r["duty_factor"] for r in sel]
                y = [max(scale * r[key], 1e-6) for r in sel]
                ax.plot(x, y, "-", color=c, lw=1.2,
                        label=f"{v:.2f} m/s" if (i, j) == (0, 0) else None)
                for xx, yy, r in zip(x, y, sel):
                    if r["plan_relaxed_support_samples"] > 0:
                        ax.plot(xx, yy, "s", mfc="none", mec="0.5", ms=12, mew=1.0)
                    if r["reached_top"]:
                        ax.plot(xx, yy, "o", color=c, ms=6)
                    elif r["completed"]:
                        ax.plot(xx, yy, "o", mfc="white", mec=c, ms=7, mew=1.5)
                    else:
                        ax.plot(xx, yy, "x", color=c, ms=8, mew=2)
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
            if i == 0:
                ax.set_title(f"μ = {mu:g}", fontsize=10)
            if j == 0:
                ax.set_ylabel(f"{label} [{unit}]", fontsize=9)
            if i == len(ROWS) - 1:
                ax.set_xlabel("duty factor")
                ax.set_xticks(duties)
                ax.set_xticklabels([fraction_text(d) for d in duties])
    handles, labels = axes[0][0].get_legend_handles_labels()
    handles += [plt.Line2D([], [], ls="", marker="o", color="0.3"),
                plt.Line2D([], [], ls="", marker="o", mfc="white", mec="0.3"),
                plt.Line2D([], [], ls="", marker="x", color="0.3", mew=2),
                plt.Line2D([], [], ls="", marker="s", mfc="none", mec="0.5", ms=10)]
    labels += ["reached the top", "did not", "ended early",
               "plan with relaxed support samples"]
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
    fit_suptitle(fig, "Forward replay of the paper stairs' plans: energy lost to slip and to "
                 "contact damping, and drift, against gait and speed, per surface friction μ")
    fig.tight_layout(rect=(0, 0.05, 1, 0.95))
    return save_atomically(fig, outdir, f"{name}_shares.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv")
    ap.add_argument("outdir")
    ap.add_argument("--name", default="replay")
    args = ap.parse_args()
    rows = read_csv(args.csv)
    if not rows:
        raise SystemExit(f"plot_replay.py: error: {args.csv} has no line")
    draw(rows, args.outdir, args.name)


if __name__ == "__main__":
    main()
