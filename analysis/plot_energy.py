#!/usr/bin/python3
"""Energy breakdown of each scenario of a sweep whose scenes have actuators: stacked bars of
the mechanical energy, the copper loss and the friction loss, what regeneration recovers
below zero, and the electrical energy drawn from the supply marked on each bar.

usage: /usr/bin/python3 analysis/plot_energy.py SWEEP.h5 OUTDIR [--name FILE] [--panel KEY]

Reads the sweep with hexdyn.open_sweep (docs/user/api.md). Per scenario, from /scenarios:
  mechanical   energy                 the integral of sum |tau omega| (the paper's energy)
  copper       energy_copper_loss     the integral of sum R I^2
  friction     energy_friction_loss   the integral of sum (tau_c |omega| + b omega^2)
  regenerated  energy_regenerated     the integral of sum r max(0, -P), drawn below zero
  electrical   energy_electrical      the integral of sum P+, a black bar across the stack
(docs/theory/drive-train.md#energies). The stack is a breakdown, not a balance: the
mechanical energy counts negative link work as a cost, while the electrical energy nets
the motor's mechanical power over the run (its negative part lost without regeneration),
adds the work that accelerates the rotors and, with gear_efficiency below 1, the gearbox's
loss; so the marker may lie above or below the stack's top.

Writes OUTDIR/energy.png (or --name): one panel per value of --panel (default: the sweep's
cases axis, e.g. the servo, when it has one with several values; else one panel), one bar
per scenario labelled by the values of the other axes that vary. Scenarios not computed
are labelled with their status instead of a bar. The figure is saved under a temporary
name and renamed when complete.
"""

import argparse
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (fit_suptitle, fit_title, save_atomically, sweep_axis_units,  # first: Agg
                     with_units)
from hexdyn import results as hr
import matplotlib.pyplot as plt
import numpy as np

# (key in the figure, /scenarios column, legend text, colour)
PARTS = (
    ("mechanical", "energy", "mechanical ∫Σ|τω| dt", "tab:blue"),
    ("copper", "energy_copper_loss", "copper loss ∫Σ R I² dt", "tab:red"),
    ("friction", "energy_friction_loss", "friction loss ∫Σ(τ_c|ω| + b ω²) dt", "tab:olive"),
)
REGENERATED = ("regenerated", "energy_regenerated", "regenerated (returned), below 0",
               "tab:green")
ELECTRICAL = ("electrical", "energy_electrical", "electrical ∫ΣP⁺ dt", "black")
MAX_BARS = 400


def energy_rows(sweep):
    """{"mechanical", "copper", "friction", "regenerated", "electrical": (N,) arrays [J]};
    SystemExit (one line) when no scenario has a drive train."""
    out = {key: np.asarray(sweep.table[col], dtype=float)
           for key, col, _, _ in PARTS + (REGENERATED, ELECTRICAL)}
    if not np.isfinite(out["electrical"]).any():
        raise SystemExit(f"plot_energy: {sweep.path}: no scenario has an electrical energy "
                         "(scenes without `actuators`, or none computed)")
    return out


def value_text(axis, j, units):
    """The j-th value of a sweep axis as the sweep file writes it ("1/2", "0.05 m", a label)."""
    unit = f" {units}" if axis.numeric and units not in (None, "", "1") else ""
    return f"{axis.labels[j]}{unit}"


def panel_axis(sweep, key=None):
    """Index of the axis that gives one panel per value: `key`, else the cases axis with
    several values, else None (one panel)."""
    keys = [a.key for a in sweep.axes]
    if key is not None:
        if key not in keys:
            raise SystemExit(f"plot_energy: {key!r} is not an axis of {sweep.path}; axes: {keys}")
        return keys.index(key)
    for i, a in enumerate(sweep.axes):
        if a.cases is not None and len(a) > 1:
            return i
    return None


def bar_labels(sweep, panel):
    """Per scenario, the values of the varied axes other than the panel's, joined."""
    units = sweep_axis_units(sweep)
    index = np.asarray(sweep.table["axis_index"])
    shown = [i for i, a in enumerate(sweep.axes) if len(a) > 1 and i != panel]
    return ["\n".join(value_text(sweep.axes[i], int(index[s][i]), units[i]) for i in shown)
            for s in range(sweep.size)], shown


def draw_panel(ax, rows, sel, labels, status):
    """The bars of the scenarios `sel` (indices) on one axes; returns the artists."""
    x = np.arange(len(sel), dtype=float)
    out = {"ids": list(sel), "x": x}
    bottom = np.zeros(len(sel))
    for key, _, legend, color in PARTS:
        h = np.nan_to_num(rows[key][sel])
        out[key] = ax.bar(x, h, 0.75, bottom=bottom, color=color, label=legend)
        bottom = bottom + h
    key, _, legend, color = REGENERATED
    out[key] = ax.bar(x, -np.nan_to_num(rows[key][sel]), 0.75, color=color, label=legend)
    key, _, legend, color = ELECTRICAL
    out[key] = ax.hlines(rows[key][sel], x - 0.45, x + 0.45, color=color, lw=2.2,
                         label=legend, zorder=5)
    out["status"] = []
    for xi, s in zip(x, sel):
        if status[s] != "ok":
            out["status"].append(ax.text(xi, 0.0, status[s], rotation=90, ha="center",
                                         va="bottom", fontsize=7, color="0.3"))
    ax.axhline(0.0, color="0.3", lw=0.6)
    ax.set_xticks(x, [labels[s] for s in sel], fontsize=6)
    ax.set_ylabel(with_units("energy", "J"), fontsize=8)
    ax.tick_params(axis="y", labelsize=7)
    ax.grid(axis="y", alpha=0.3)
    return out


def draw_energy(sweep, panel_key=None):
    """The figure and {"panels": {panel label: artists of draw_panel}, "rows": energy_rows}."""
    rows = energy_rows(sweep)
    if sweep.size > MAX_BARS:
        raise SystemExit(f"plot_energy: {sweep.path} has {sweep.size} scenarios; one bar each "
                         f"is readable up to {MAX_BARS}: plot a smaller sweep")
    panel = panel_axis(sweep, panel_key)
    labels, shown = bar_labels(sweep, panel)
    index = np.asarray(sweep.table["axis_index"])
    groups = ([("", list(range(sweep.size)))] if panel is None else
              [(sweep.axes[panel].labels[j],
                [s for s in range(sweep.size) if int(index[s][panel]) == j])
               for j in range(len(sweep.axes[panel]))])
    per_panel = max(len(sel) for _, sel in groups)
    fig, axs = plt.subplots(len(groups), 1, squeeze=False, sharey=True,
                            figsize=(max(4.0, 1.2 + 0.42 * per_panel) + 3.3,
                                     1.2 + 2.9 * len(groups)), constrained_layout=True)
    out = {"panels": {}, "rows": rows}
    for (label, sel), ax in zip(groups, axs[:, 0]):
        out["panels"][label] = draw_panel(ax, rows, sel, labels, sweep.status_names)
        if panel is not None:
            fit_title(ax, f"{sweep.axes[panel].key} = {label}", fontsize=9)
    axs[0, 0].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    axes_text = ", ".join(sweep.axes[i].key for i in shown) or "scenario"
    fit_suptitle(fig, f"{sweep.meta.get('name', 'sweep')}: energy breakdown per scenario "
                 f"(bars labelled by {axes_text}); the stack is a breakdown, not a balance: "
                 "the black bar, the electrical energy, nets the motors' mechanical power "
                 "and adds the rotors' work", fontsize=9)
    return fig, out


def open_sweep_file(path):
    """The sweep at `path` (hexdyn.open_sweep); SystemExit with one line for a file of
    another kind (a hexdyn-study/1 file holds no energy breakdown) or one that cannot be read."""
    try:
        return hr.open_sweep(path)
    except ValueError as e:
        raise SystemExit(f"plot_energy: {path}: {e}; the energy breakdown reads a sweep file "
                         "(hexdyn-sweep) of scenes with actuators")
    except OSError as e:
        raise SystemExit(f"plot_energy: {path}: {e}")


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="plot_energy.py", description=__doc__.strip().split("\n\n")[0],
        epilog=__doc__.strip().split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep", help="a hexdyn-sweep file whose scenes have actuators")
    ap.add_argument("outdir")
    ap.add_argument("--name", default="energy.png", help="file name (default energy.png)")
    ap.add_argument("--panel", help="one panel per value of this axis (default: a cases axis)")
    args = ap.parse_args(argv)
    sweep = open_sweep_file(args.sweep)
    os.makedirs(args.outdir, exist_ok=True)
    fig, _ = draw_energy(sweep, args.panel)
    path = save_atomically(fig, args.outdir, args.name, dpi=110)
    print(f"plot_energy: wrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
