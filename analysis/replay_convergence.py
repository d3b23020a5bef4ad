#!/usr/bin/python3
"""Speed against error of the forward replay (docs/validation/replay.md#speed-against-error):
one scene planned once with `hexdyn run`, replayed with `hexdyn replay` at every integrator
step x tolerance (replay.step, replay.tolerance; docs/theory/replay.md), each replay's report
compared with the finest one's (the smallest step at the smallest tolerance).

    /usr/bin/python3 analysis/replay_convergence.py OUTDIR [--hexdyn build/hexdyn]
        [--scene configs/paper.yaml] [--set key=value ...] [--replay-set key=value ...]
        [--steps 4e-3 ... 6.25e-5]
        [--tolerances 0.2 0.05 0.01] [--repeat N] [--table]

Writes into OUTDIR: result.h5 (the plan), replays/step<h>_tol<t>.h5, and
  replay_convergence.csv  one line per (step, tolerance): the drift at the end (replayed minus
                          planned trunk position at the last sample) and its distance from the
                          reference's, the slip, touchdown (normal damping) and joint energies
                          and their errors relative to the reference's, the balance of energy's
                          residual against the joints' signed work, the largest tracking error,
                          steps, forced steps and the wall time (/replay/seconds, the median of
                          --repeat replays; the rest does not change between repeats);
  replay_convergence.png  each error against the wall time, a line per tolerance.
--table prints the main columns as a Markdown table. The replays run one at a time, so that
their wall times are those of one core.
"""

import argparse
import math
import os
import statistics
import subprocess

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, save_atomically, write_csv_atomically
import h5py
import matplotlib.pyplot as plt
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
STEPS = (4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5)
TOLERANCES = (0.2, 0.05, 0.01)
ENERGIES = (("slip_energy_J", "slip"), ("touchdown_energy_J", "touchdown"),
            ("energy_J", "joint energy"))
COLUMNS = ("step_s", "tolerance", "reached_top", "drift_x_m", "drift_y_m", "drift_z_m",
           "drift_error_m", "slip_energy_J", "slip_energy_error", "touchdown_energy_J",
           "touchdown_energy_error", "energy_J", "energy_error", "actuator_work_J",
           "energy_residual_J", "residual_share", "max_tracking_error_rad", "steps",
           "forced_steps", "seconds")


def read_report(path):
    """The values of one replay file that the study compares."""
    with h5py.File(path, "r") as f:
        rp = f["replay"]
        return {
            "reached_top": int(rp["reached_top"][()]),
            "message": rp["message"][()],
            "drift": np.asarray(rp["final_position_error"][()], dtype=float),
            "slip_energy_J": float(np.sum(rp["slip_energy"][()])),
            "touchdown_energy_J": float(np.sum(rp["touchdown_energy"][()])),
            "energy_J": float(rp["energy"][()]),
            "actuator_work_J": float(rp["actuator_work"][()]),
            "energy_residual_J": float(rp["energy_residual"][()]),
            "max_tracking_error_rad": float(rp["max_tracking_error"][()]),
            "steps": int(rp["steps"][()]),
            "forced_steps": int(rp["forced_steps"][()]),
            "seconds": float(rp["seconds"][()]),
        }


def replay(hexdyn, result, out, step, tol, repeat, sets=()):
    """Replays `result` at (step, tol) `repeat` times into `out`, with the further key=value
    overrides `sets`; the report with the median wall time."""
    seconds = []
    cmd = [hexdyn, "replay", result, "-o", out, "--set", f"replay.step={step!r}",
           "--set", f"replay.tolerance={tol!r}"]
    for kv in sets:
        cmd += ["--set", kv]
    for _ in range(repeat):
        subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)
        seconds.append(read_report(out)["seconds"])
    rep = read_report(out)
    rep["seconds"] = statistics.median(seconds)
    return rep


def relative(x, ref):
    return abs(x - ref) / abs(ref) if ref != 0 else (0.0 if x == 0 else math.inf)


def compare(rows, ref):
    """Adds each row's errors against the reference row `ref`."""
    for r in rows:
        r["drift_error_m"] = float(np.linalg.norm(r["drift"] - ref["drift"]))
        for key, _ in ENERGIES:
            r[key.replace("_J", "_error")] = relative(r[key], ref[key])
        work = abs(r["actuator_work_J"])
        r["residual_share"] = abs(r["energy_residual_J"]) / work if work > 0 else math.nan
        r["drift_x_m"], r["drift_y_m"], r["drift_z_m"] = (float(v) for v in r["drift"])


def draw(rows, outdir):
    panels = (("drift_error_m", "drift at the end: distance from the reference [m]"),
              ("slip_energy_error", "slip energy: relative error"),
              ("touchdown_energy_error", "touchdown energy: relative error"),
              ("energy_error", "joint energy: relative error"),
              ("residual_share", "|energy residual| / joint work"))
    tols = sorted({r["tolerance"] for r in rows}, reverse=True)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    flat = axes.ravel()
    for ax, (key, title) in zip(flat, panels):
        ax.set_title(title, fontsize=9)
        if not any(r[key] > 0 for r in rows):  # one setting alone: the reference, error 0
            ax.text(0.5, 0.5, "no error to draw", ha="center", va="center",
                    transform=ax.transAxes)
            continue
        for tol in tols:
            sel = sorted((r for r in rows if r["tolerance"] == tol and r[key] > 0),
                         key=lambda r: r["seconds"])
            ax.plot([r["seconds"] for r in sel], [r[key] for r in sel], "o-",
                    label=f"tolerance {tol:g}")
            for r in sel:
                ax.annotate(f"{r['step_s']:g}", (r["seconds"], r[key]), fontsize=6,
                            xytext=(3, 3), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time of the replay [s]")
        ax.grid(True, which="both", alpha=0.3)
    flat[0].legend(fontsize=8)
    flat[-1].axis("off")
    flat[-1].text(0.0, 0.5, "points labelled with replay.step [s];\nreference: the smallest "
                  "step at the\nsmallest tolerance (error 0, not drawn)", fontsize=9)
    fit_suptitle(fig, "Forward replay: error against cost per integrator step and tolerance")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return save_atomically(fig, outdir, "replay_convergence.png")


def markdown_table(rows):
    head = ("| step [s] | tolerance | drift at the end [mm] | its error [mm] | slip [J] | "
            "touchdown [J] | joint energy [J] | residual [J] | forced steps | wall time [s] |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        lines.append(
            f"| {r['step_s']:g} | {r['tolerance']:g} | {1e3 * np.linalg.norm(r['drift']):.3f} | "
            f"{1e3 * r['drift_error_m']:.3f} | {r['slip_energy_J']:.4f} | "
            f"{r['touchdown_energy_J']:.4f} | {r['energy_J']:.3f} | "
            f"{r['energy_residual_J']:.4f} | {r['forced_steps']} | {r['seconds']:.3f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--hexdyn", default=os.path.join(SOURCE, "build", "hexdyn"))
    ap.add_argument("--scene", default=os.path.join(SOURCE, "configs", "paper.yaml"))
    ap.add_argument("--set", action="append", default=[], help="an override of the run")
    ap.add_argument("--replay-set", action="append", default=[],
                    help="an override of every replay (replay.* or contact.*), not of the plan")
    ap.add_argument("--steps", type=float, nargs="+", default=STEPS)
    ap.add_argument("--tolerances", type=float, nargs="+", default=TOLERANCES)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--table", action="store_true")
    args = ap.parse_args()
    os.makedirs(os.path.join(args.outdir, "replays"), exist_ok=True)
    result = os.path.join(args.outdir, "result.h5")
    cmd = [args.hexdyn, "run", args.scene, "-o", result]
    for s in args.set:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)
    rows = []
    for tol in sorted(args.tolerances, reverse=True):
        for step in sorted(args.steps, reverse=True):
            out = os.path.join(args.outdir, "replays", f"step{step:g}_tol{tol:g}.h5")
            r = replay(args.hexdyn, result, out, step, tol, args.repeat, args.replay_set)
            r["step_s"], r["tolerance"] = step, tol
            rows.append(r)
    ref = next(r for r in rows if r["step_s"] == min(args.steps) and
               r["tolerance"] == min(args.tolerances))
    compare(rows, ref)
    write_csv_atomically(os.path.join(args.outdir, "replay_convergence.csv"), COLUMNS,
                         [[repr(r[c]) if isinstance(r[c], float) else r[c] for c in COLUMNS]
                          for r in rows])
    draw(rows, args.outdir)
    if args.table:
        print(markdown_table(rows))


if __name__ == "__main__":
    main()
