#!/usr/bin/python3
"""Grip of one run, leg by leg over time (docs/theory/grip.md): the friction each foot uses,
the friction the sample needs, the scene's mu, the touchdown transients and the slip samples.

usage: /usr/bin/python3 analysis/plot_grip.py RESULT.h5 OUTDIR [--name FILE]

Writes OUTDIR/grip.png (or --name), every axis linear:

  top, wide: the sample's required friction mu* (/contacts/required_friction) over time,
         each sample coloured by the leg that binds it (/contacts/required_friction_leg);
         the axis ends a fifth above the largest mu* outside touchdown transients, and the
         samples above it (the transients' mu* reaches hundreds) are triangles on its top
         edge; the scene's mu (contact.friction_coefficient of /meta config_yaml) dashed
         red when it is on the axis, else named in the title;
  below, one panel per leg (/model/leg_names), the left legs in the left column and the
         right legs in the right one, front to rear (figures.leg_panels): the leg's
         utilised friction |F_t| / F_n (/contacts/utilized_friction; NaN in swing and not
         drawn), the scene's mu dashed, and the leg's slip samples (/contacts/slip 1) as red
         crosses on the mu line.

Touchdown transients (/contacts/phase 1, where the trunk rows may be relaxed) are shaded in
every panel, each widened to at least 0.6 % of the run (a transient lasts milliseconds) and
named in the legend, which sits below the panels.

A file without these datasets is refused: one line on stderr, exit status 2. The figure is
saved under a temporary name and renamed when complete.
"""

import argparse
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (MIN_SPAN, bottom_panels, fit_suptitle, fit_title, leg_color,  # first: Agg
                     leg_panels, save_atomically, shade_runs)
from hexdyn import results as hr
import matplotlib.pyplot as plt
import numpy as np

DATASETS = ("/time", "/contacts/phase", "/contacts/utilized_friction",
            "/contacts/required_friction", "/contacts/required_friction_leg",
            "/contacts/slip")
TRANSIENT_COLOR, SLIP_COLOR, MU_COLOR, REQUIRED_COLOR = "0.8", "tab:red", "tab:red", "0.45"
TRANSIENT_LABEL = f"touchdown transient (shaded at least {100 * MIN_SPAN:g} % of the run wide)"


def grip_data(res):
    """The arrays the figure draws: t (T,), phase, utilised, slip (T,L), required (T,),
    binding leg (T,), the scene's mu (NaN when the configuration has none) and the leg
    names (L)."""
    mu = res.config.get("contact", {}).get("friction_coefficient", np.nan)
    return {"t": np.asarray(res["/time"], dtype=float),
            "phase": np.asarray(res["/contacts/phase"]),
            "utilized": np.asarray(res["/contacts/utilized_friction"], dtype=float),
            "required": np.asarray(res["/contacts/required_friction"], dtype=float),
            "leg": np.asarray(res["/contacts/required_friction_leg"]),
            "slip": np.asarray(res["/contacts/slip"]),
            "mu": float(mu), "leg_names": hr.leg_names(res)}


def shade_transients(ax, t, transient):
    """The touchdown transients of `transient` (T,) as shaded spans (figures.shade_runs)."""
    return shade_runs(ax, t, transient, TRANSIENT_COLOR, TRANSIENT_LABEL)


def required_top(d):
    """The top of the required-friction axis: a fifth above the largest finite mu* outside
    the touchdown transients (1.0 when there is none)."""
    outside = ~(d["phase"] == hr.PHASE_IMPACT).any(axis=1)
    values = d["required"][outside & np.isfinite(d["required"])]
    return 1.2 * float(values.max()) if values.size and values.max() > 0 else 1.0


def draw_required(ax, d):
    """The top panel: mu* per sample, coloured by its binding leg; returns its artists."""
    t, req = d["t"], np.where(np.isfinite(d["required"]), d["required"], np.nan)
    top = required_top(d)
    spans = shade_transients(ax, t, (d["phase"] == hr.PHASE_IMPACT).any(axis=1))
    line, = ax.plot(t, req, color=REQUIRED_COLOR, lw=0.8, label="required mu* (sample)")
    binds = []
    for k, name in enumerate(d["leg_names"]):
        on = (d["leg"] == k) & (req <= top)
        dots, = ax.plot(t[on], req[on], ".", ms=3, color=leg_color(k), label=f"{name} binds")
        binds.append(dots)
    above = req > top
    over, = ax.plot(t[above], np.full(int(above.sum()), top), "^", ms=4, color=REQUIRED_COLOR,
                    clip_on=False, label=f"mu* above {top:.3g}")
    mu = None
    title = "Required friction mu* of each sample"
    if np.isfinite(d["mu"]) and d["mu"] <= top:
        mu = ax.axhline(d["mu"], color=MU_COLOR, ls="--", lw=1, label=f"scene mu = {d['mu']:g}")
    elif np.isfinite(d["mu"]):
        title += f" (the scene's mu = {d['mu']:g}, above the axis)"
    ax.set_ylim(0, top)
    fit_title(ax, title, fontsize=9)
    ax.set_ylabel("mu*")
    ax.grid(alpha=0.3)
    return {"spans": spans, "required": line, "binds": binds, "above": over, "mu": mu,
            "top": top}


def draw_leg(ax, d, k):
    """Panel of leg k (0-based): its utilised friction; returns its artists by role."""
    t = d["t"]
    spans = shade_transients(ax, t, d["phase"][:, k] == hr.PHASE_IMPACT)
    u = np.where(np.isfinite(d["utilized"][:, k]), d["utilized"][:, k], np.nan)
    used, = ax.plot(t, u, color=leg_color(k), lw=1, label="utilised |F_t|/F_n")
    mu = ax.axhline(d["mu"], color=MU_COLOR, ls="--", lw=1, label=f"scene mu = {d['mu']:g}")
    slips = d["slip"][:, k] == 1
    slip, = ax.plot(t[slips], np.full(int(slips.sum()), d["mu"]), "x", ms=5, color=SLIP_COLOR,
                    label="slip sample")
    if np.isfinite(d["mu"]):
        ax.set_ylim(0, 1.5 * d["mu"])
    ax.set_title(f"{d['leg_names'][k]}: utilised friction, {int(slips.sum())} slip sample(s)",
                 fontsize=9)
    ax.grid(alpha=0.3)
    return {"spans": spans, "utilized": used, "mu": mu, "slip": slip}


def draw(res):
    """The figure, its artists ({"required": top panel's, "legs": one dict per leg}) and the
    data drawn."""
    d = grip_data(res)
    rows, cells = leg_panels(len(d["leg_names"]))
    ratios = (1.3,) + (1,) * rows
    fig = plt.figure(figsize=(11, 10 * sum(ratios) / 4.3))  # 11 x 10 in with three rows
    grid = fig.add_gridspec(1 + rows, 2, height_ratios=ratios)
    top = fig.add_subplot(grid[0, :])
    legs = [fig.add_subplot(grid[1 + row, col], sharex=top) for row, col in cells]
    artists = {"required": draw_required(top, d),
               "legs": [draw_leg(ax, d, k) for k, ax in enumerate(legs)]}
    bottom = bottom_panels(cells)
    for k, ax in enumerate(legs):
        if k in bottom:
            ax.set_xlabel("time [s]")
        else:
            ax.tick_params(labelbottom=False)
        if cells[k][1] == 0:
            ax.set_ylabel("|F_t| / F_n")
    handles, labels = [], []
    for ax in [top, legs[0]]:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    fit_suptitle(fig, "Grip: the friction each sample needs (top) and each leg uses (below)")
    fig.subplots_adjust(left=0.07, right=0.98, top=0.92, bottom=0.12, hspace=0.5, wspace=0.15)
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=8, frameon=False)
    return fig, artists, d


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="plot_grip.py", description=__doc__.strip().split("\n\n")[0],
        epilog=__doc__.strip().split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="a hexdyn result file with the grip datasets")
    ap.add_argument("outdir")
    ap.add_argument("--name", default="grip.png", help="file name (default grip.png)")
    args = ap.parse_args(argv)
    try:
        res = hr.open_result(args.result)
        missing = [p for p in DATASETS if p not in res]
        if missing:
            raise ValueError(f"no dataset {', '.join(missing)} (docs/theory/grip.md)")
        fig, _, _ = draw(res)
    except (OSError, ValueError, KeyError) as e:
        why = str(e).strip("'\"")
        where = "" if why.startswith(args.result) else f"{args.result}: "
        print(f"plot_grip: {where}{why}", file=sys.stderr)
        return 2
    os.makedirs(args.outdir, exist_ok=True)
    path = save_atomically(fig, args.outdir, args.name, dpi=110)
    print(f"plot_grip: wrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
