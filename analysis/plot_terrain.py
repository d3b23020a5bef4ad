#!/usr/bin/python3
"""Figure and table of the terrain examples (pipelines/terrain.sh, docs/validation/terrain.md).

    /usr/bin/python3 analysis/plot_terrain.py OUTDIR UP_DOWN.h5 [UP_DOWN.h5 ...]

UP_DOWN.h5: sweep files over terrain.riser_height (negative: down) and gait.duty_factor, one per
robot (configs/terrain/sweeps/). OUTDIR/runs/ holds the example runs: NAME.h5 for a run that
was computed, NAME.log (its stderr) for every run, the last line of a failed one its error.
Writes
  OUTDIR/terrain_up_down.png  per robot (rows): the joint energy /scenarios/energy (solid),
                              its positive part /scenarios/positive_work (dashed) and its
                              negative part -/scenarios/negative_work (dotted) against the
                              signed riser, and the largest peak joint torque over the joints
                              outside touchdowns (/scenarios/peak_torque_gait, solid) and in
                              touchdown transients (peak_torque_transient, dashed), a colour
                              per duty factor; a scenario
                              not computed is a cross at the bottom of its panel;
  OUTDIR/terrain_runs.csv     every example run: robot, example, status (climbs: computed with
                              no relaxed sample outside touchdowns; relaxed; failed), samples,
                              relaxed samples outside touchdowns, energy, positive and negative
                              work, peak torque, the error message of a failed run;
  OUTDIR/terrain_table.txt    the same as a Markdown table.
"""

import argparse
import glob
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, fraction_text, save_atomically, write_csv_atomically
from hexdyn import open_result, open_sweep
import matplotlib.pyplot as plt
import numpy as np

RISER, DUTY = "terrain.riser_height", "gait.duty_factor"
COLUMNS = ["robot", "example", "status", "samples", "relaxed_gait_samples", "energy_J",
           "positive_work_J", "negative_work_J", "peak_torque_Nm", "message"]


def robot_of(config):
    """The robot's name: its URDF's file stem, or "paper hexapod" for the YAML robot."""
    urdf = (config.get("robot") or {}).get("urdf")
    return os.path.splitext(os.path.basename(urdf))[0] if urdf else "paper hexapod"


def draw_sweep(axes, path):
    """One robot's row: energy and its parts, and the peak torque, against the signed riser."""
    sw = open_sweep(path)
    keys = [a.key for a in sw.axes]
    if keys != [RISER, DUTY]:
        raise SystemExit(f"plot_terrain: {path}: axes {keys}, expected [{RISER}, {DUTY}]")
    t = sw.table
    riser, duty = np.asarray(t["axis_0"]), np.asarray(t["axis_1"])
    ok = np.asarray([s == "ok" for s in sw.status_names])
    gait_peak, transient_peak = (np.nanmax(np.asarray(t[k], dtype=float), axis=1, initial=-np.inf)
                                 for k in ("peak_torque_gait", "peak_torque_transient"))
    name = robot_of(sw.config)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, b in enumerate(np.unique(duty)):
        c, sel = colours[i % len(colours)], duty == b
        order = np.argsort(riser[sel])
        x = riser[sel][order]
        good = ok[sel][order]
        label = f"beta = {fraction_text(b)}"
        e = np.where(good, t["energy"][sel][order], np.nan)
        axes[0].plot(x, e, "-o", color=c, label=label + ", energy")
        axes[0].plot(x, np.where(good, t["positive_work"][sel][order], np.nan), "--", color=c)
        axes[0].plot(x, np.where(good, -t["negative_work"][sel][order], np.nan), ":", color=c)
        axes[1].plot(x, np.where(good, gait_peak[sel][order], np.nan), "-o", color=c, label=label)
        axes[1].plot(x, np.where(good, transient_peak[sel][order], np.nan), "--", color=c)
        for ax in axes:
            ax.plot(x[~good], np.zeros(np.count_nonzero(~good)), "x", color=c, ms=9, mew=2)
    axes[0].set_ylabel(f"{name}\njoint energy [J]")
    axes[1].set_ylabel("peak joint torque [N m]")
    axes[1].plot([], [], "k-", label="outside touchdowns")
    axes[1].plot([], [], "k--", label="in touchdown transients")
    axes[0].plot([], [], "k--", label="positive work")
    axes[0].plot([], [], "k:", label="negative work (magnitude)")
    axes[0].plot([], [], "kx", label="not computed")
    for ax in axes:
        ax.axvline(0.0, color="0.7", lw=0.8)
        ax.set_xlabel("riser [m] (< 0: down, > 0: up)")
        ax.set_ylim(bottom=0.0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return name


def run_rows(outdir):
    """One row per example run of OUTDIR/runs (its .log, and its .h5 when computed)."""
    rows = []
    for log in sorted(glob.glob(os.path.join(outdir, "runs", "*.log"))):
        stem = os.path.splitext(log)[0]
        robot, example = os.path.basename(stem).split("__", 1)
        h5 = stem + ".h5"
        if not os.path.exists(h5):
            with open(log) as f:
                lines = [x.strip() for x in f if x.strip()]
            msg = lines[-1] if lines else "no output"
            rows.append([robot, example, "failed", "", "", "", "", "", "", msg])
            continue
        r = open_result(h5)
        status = np.asarray(r["/solver/status"])
        phase = np.asarray(r["/contacts/phase"])
        gait = int(np.count_nonzero((status != 0) & np.all(phase != 1, axis=1)))
        peak = float(np.abs(np.asarray(r["/joints/torque"])).max())
        rows.append([robot, example, "climbs" if gait == 0 else "relaxed", len(status), gait,
                     f"{float(r['/energy/total']):.4g}", f"{float(r['/energy/positive_work']):.4g}",
                     f"{float(r['/energy/negative_work']):.4g}", f"{peak:.4g}", ""])
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("sweeps", nargs="+")
    a = ap.parse_args()
    fig, axes = plt.subplots(len(a.sweeps), 2, figsize=(11, 4 * len(a.sweeps)), squeeze=False)
    names = [draw_sweep(axes[i], p) for i, p in enumerate(a.sweeps)]
    fit_suptitle(fig, "Ascent against descent per gait: " + ", ".join(names))
    fig.tight_layout()
    print(save_atomically(fig, a.outdir, "terrain_up_down.png"))
    rows = run_rows(a.outdir)
    print(write_csv_atomically(os.path.join(a.outdir, "terrain_runs.csv"), COLUMNS, rows))
    table = os.path.join(a.outdir, "terrain_table.txt")
    tmp = f"{table}.tmp.{os.getpid()}"
    with open(tmp, "w") as f:
        f.write("| " + " | ".join(COLUMNS) + " |\n|" + "---|" * len(COLUMNS) + "\n")
        for r in rows:
            f.write("| " + " | ".join(str(c).replace("|", "/") for c in r) + " |\n")
    os.replace(tmp, table)
    print(table)
    for r in rows:
        print(f"terrain: {r[0]} on {r[1]}: {r[2]}" + (f" ({r[9]})" if r[9] else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
