#!/usr/bin/python3
"""The robustness study's tables and figures (pipelines/robustness.sh,
docs/validation/robustness.md).

    plot_robustness.py OUT STUDY.h5 SWEEP.h5 ...
        OUT/robustness.csv     one row per scenario of the sweeps of studies: robot, sweep,
                               duty factor, the swept value, replays, P(success), its Wilson
                               interval and the failures by class
        OUT/convergence.csv    P(success) of STUDY.h5 (a hexdyn-robustness/1 file) and its
                               interval after its first n replays, n = 10, 20, 50, ...
        OUT/robustness.png     per robot (rows): P(success) with its interval against the riser
                               error and against the friction offset, one line per gait, and
                               the failures by class of every scenario
        OUT/convergence.png    P(success) and its interval against n
    plot_robustness.py --quick-sweep SWEEP.yaml OUT.yaml
        the sweep file SWEEP.yaml with 3 replays per scenario and the first and last value of
        each axis, its base made absolute (the quick pipeline's sweeps)

The sweeps' robot and kind come from their names (paper_riser, solo12_friction, ...); each
has the axes gait.duty_factor, then the riser error's standard deviation or the friction
offset's cases (configs/robustness/sweeps/).
"""

import csv
import math
import os
import sys

import numpy as np
import yaml

import hexdyn_path

hexdyn_path.ensure()
import h5py  # noqa: E402
import hexdyn  # noqa: E402

Z = 1.959963984540054
CLASSES = ("slipped", "stubbed", "saturated", "fell", "drifted")


def wilson(k, n):
    """The Wilson score interval of k successes in n trials at 95 %."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    centre = (p + Z * Z / (2 * n)) / (1 + Z * Z / n)
    half = Z / (1 + Z * Z / n) * math.sqrt(p * (1 - p) / n + Z * Z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


def quick_sweep(src, dst):
    with open(src, encoding="utf-8") as f:
        spec = yaml.safe_load(f)
    spec["base"] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(src)),
                                                 spec["base"]))
    spec.setdefault("set", {})["robustness.replays"] = 3
    for axis in spec["axes"]:
        for k in ("values", "cases"):
            if k in axis and len(axis[k]) > 2:
                axis[k] = [axis[k][0], axis[k][-1]]
    with open(dst, "w", encoding="utf-8") as f:
        yaml.safe_dump(spec, f, sort_keys=False)


def sweep_rows(path):
    """One dict per scenario of a sweep of studies."""
    name = os.path.splitext(os.path.basename(path))[0]
    robot, kind = name.split("_", 1)
    sw = hexdyn.open_sweep(path)
    table = sw.table
    gaits, values = sw.axes[0], sw.axes[1]
    rows = []
    for i in range(len(table["p_success"])):
        g, v = divmod(i, len(values.values))
        row = {"robot": robot, "sweep": kind, "duty_factor": float(gaits.values[g]),
               "value": str(values.labels[v]), "status": int(table["status"][i]),
               "replays": int(table["replays"][i]), "p_success": float(table["p_success"][i]),
               "p_low": float(table["p_success_low"][i]),
               "p_high": float(table["p_success_high"][i])}
        for c in CLASSES:
            row[c] = int(table[f"replays_{c}"][i])
        rows.append(row)
    return rows


def convergence(study):
    with h5py.File(study, "r") as f:
        reached = f["replays/reached_top"][()].astype(int)
    out = []
    for n in (10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000):
        if n > len(reached):
            break
        k = int(reached[:n].sum())
        low, high = wilson(k, n)
        out.append({"replays": n, "successes": k, "p_success": k / n, "p_low": low,
                    "p_high": high})
    return out


def write_csv(path, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def plot(out, rows, conv):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    robots = sorted({r["robot"] for r in rows})
    fig, axes = plt.subplots(len(robots), 3, figsize=(13, 3.6 * len(robots)), squeeze=False)
    for i, robot in enumerate(robots):
        for j, (kind, label) in enumerate((("riser", "riser error sigma [mm]"),
                                           ("friction", "friction offset"))):
            ax = axes[i][j]
            sel = [r for r in rows if r["robot"] == robot and r["sweep"] == kind]
            for beta in sorted({r["duty_factor"] for r in sel}):
                pts = [r for r in sel if r["duty_factor"] == beta]
                x = [float(r["value"]) * (1000.0 if kind == "riser" else 1.0) for r in pts]
                p = np.array([r["p_success"] for r in pts])
                err = [p - [r["p_low"] for r in pts], [r["p_high"] for r in pts] - p]
                ax.errorbar(x, p, yerr=err, marker="o", capsize=3, label=f"beta = {beta:.3g}")
            ax.set_xlabel(label)
            ax.set_ylabel("P(success)")
            ax.set_ylim(-0.05, 1.05)
            ax.set_title(f"{robot}: against the {kind}")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        ax = axes[i][2]
        sel = [r for r in rows if r["robot"] == robot]
        bottom = np.zeros(len(sel))
        for c in CLASSES:
            v = np.array([r[c] for r in sel], dtype=float)
            ax.bar(range(len(sel)), v, bottom=bottom, label=c)
            bottom += v
        ax.set_xticks(range(len(sel)))
        ax.set_xticklabels([f"{r['sweep'][0]} {r['duty_factor']:.2g} {r['value']}" for r in sel],
                           rotation=90, fontsize=6)
        ax.set_ylabel("failed replays")
        ax.set_title(f"{robot}: failures by class")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "robustness.png"), dpi=110)
    plt.close(fig)
    if conv:
        fig, ax = plt.subplots(figsize=(6, 3.6))
        n = [c["replays"] for c in conv]
        p = np.array([c["p_success"] for c in conv])
        ax.errorbar(n, p, yerr=[p - [c["p_low"] for c in conv], [c["p_high"] for c in conv] - p],
                    marker="o", capsize=3)
        ax.set_xscale("log")
        ax.set_xlabel("replays n")
        ax.set_ylabel("P(success), Wilson 95 %")
        ax.set_title("paper scene, every perturbation: P after n replays")
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "convergence.png"), dpi=110)
        plt.close(fig)


def main(argv):
    if len(argv) == 3 and argv[0] == "--quick-sweep":
        quick_sweep(argv[1], argv[2])
        return 0
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out, study, sweeps = argv[0], argv[1], argv[2:]
    rows = [r for path in sweeps for r in sweep_rows(path)]
    conv = convergence(study)
    write_csv(os.path.join(out, "robustness.csv"), rows)
    if conv:
        write_csv(os.path.join(out, "convergence.csv"), conv)
    plot(out, rows, conv)
    for r in rows:
        print(f"{r['robot']:7s} {r['sweep']:9s} beta {r['duty_factor']:.3g} {r['value']:>8s}: "
              f"P = {r['p_success']:.3f} [{r['p_low']:.3f}, {r['p_high']:.3f}]"
              + "".join(f" {c} {r[c]}" for c in CLASSES if r[c]))
    for c in conv:
        print(f"first {c['replays']} replays: P = {c['p_success']:.3f} "
              f"[{c['p_low']:.3f}, {c['p_high']:.3f}]")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
