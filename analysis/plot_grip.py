#!/usr/bin/python3
"""Grip of one run, leg by leg over time (docs/theory/grip.md): the friction each foot uses,
the friction the sample needs, the scene's mu, the touchdown transients and the slip samples.

usage: /usr/bin/python3 analysis/plot_grip.py RESULT.h5 OUTDIR [--name FILE]

Writes OUTDIR/grip.png (or --name): six panels, legs L1 ... L6, time on x, friction
coefficient on y (linear below 0.1, logarithmic above, as the required friction of a
touchdown transient reaches hundreds). In each panel:

  solid, the leg's utilised friction |F_t| / F_n (/contacts/utilized_friction; NaN in
         swing, not drawn; +inf where the foot pulls, not drawn);
  grey,  the sample's required friction (/contacts/required_friction), the same in every
         panel; dots where this leg binds it (/contacts/required_friction_leg);
  dashed red, the scene's mu (contact.friction_coefficient of /meta config_yaml);
  shaded, the leg's touchdown transients (/contacts/phase 1), at least 0.6 % of the run
         wide (a transient lasts milliseconds);
  red crosses, the leg's slip samples (/contacts/slip 1), at the sample's required friction.

A file without these datasets is refused: one line on stderr, exit status 2. The figure is
saved under a temporary name and renamed when complete.
"""

import argparse
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import LEG_COLORS, fit_suptitle, save_atomically  # first: Agg
from hexdyn import results as hr
import matplotlib.pyplot as plt
import numpy as np

DATASETS = ("/time", "/contacts/phase", "/contacts/utilized_friction",
            "/contacts/required_friction", "/contacts/required_friction_leg",
            "/contacts/slip")
MIN_SPAN = 0.006  # shaded width of a transient at least, as a fraction of the run's duration
TRANSIENT_COLOR, SLIP_COLOR, MU_COLOR, REQUIRED_COLOR = "0.8", "tab:red", "tab:red", "0.45"


def runs_of(mask):
    """(first, last) sample indices of each run of True in a boolean vector."""
    padded = np.concatenate(([False], np.asarray(mask, dtype=bool), [False]))
    edges = np.flatnonzero(np.diff(padded.astype(np.int8)))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2])]


def grip_data(res):
    """The arrays the figure draws: t (T,), phase, utilised, slip (T,6), required (T,),
    binding leg (T,), and the scene's mu (NaN when the configuration has none)."""
    mu = res.config.get("contact", {}).get("friction_coefficient", np.nan)
    return {"t": np.asarray(res["/time"], dtype=float),
            "phase": np.asarray(res["/contacts/phase"]),
            "utilized": np.asarray(res["/contacts/utilized_friction"], dtype=float),
            "required": np.asarray(res["/contacts/required_friction"], dtype=float),
            "leg": np.asarray(res["/contacts/required_friction_leg"]),
            "slip": np.asarray(res["/contacts/slip"]),
            "mu": float(mu)}


def shade_transients(ax, t, transient):
    """One grey span per run of touchdown-transient samples, from its first to last time,
    widened to MIN_SPAN of the run's duration: a transient lasts milliseconds."""
    spans = []
    width = MIN_SPAN * (t[-1] - t[0]) if len(t) > 1 else 0.0
    for a, b in runs_of(transient):
        spans.append(ax.axvspan(t[a], max(t[b], t[a] + width), color=TRANSIENT_COLOR, lw=0,
                                zorder=0))
    return spans


def draw_leg(ax, d, k):
    """Panel of leg k (0-based); returns its artists by role."""
    t = d["t"]
    spans = shade_transients(ax, t, d["phase"][:, k] == hr.PHASE_IMPACT)
    u = np.where(np.isfinite(d["utilized"][:, k]), d["utilized"][:, k], np.nan)
    used, = ax.plot(t, u, color=LEG_COLORS[k], lw=1, label="utilised")
    req = np.where(np.isfinite(d["required"]), d["required"], np.nan)
    needed, = ax.plot(t, req, color=REQUIRED_COLOR, lw=0.8, label="required (sample)")
    binds = d["leg"] == k
    bind, = ax.plot(t[binds], req[binds], ".", ms=2.5, color=REQUIRED_COLOR,
                    label=f"{hr.LEG_NAMES[k]} binds")
    mu = ax.axhline(d["mu"], color=MU_COLOR, ls="--", lw=1, label=f"scene mu = {d['mu']:g}")
    slips = d["slip"][:, k] == 1
    slip, = ax.plot(t[slips], req[slips], "x", ms=5, color=SLIP_COLOR,
                    label=f"slip ({int(slips.sum())})")
    ax.set_yscale("symlog", linthresh=0.1)
    ax.set_title(f"{hr.LEG_NAMES[k]}: {int(slips.sum())} slip sample(s)", fontsize=9)
    ax.grid(alpha=0.3)
    return {"spans": spans, "utilized": used, "required": needed, "binds": bind, "mu": mu,
            "slip": slip}


def draw(res):
    """The figure, its artists per leg and the data drawn."""
    d = grip_data(res)
    fig, axes = plt.subplots(3, 2, figsize=(11, 8), sharex=True, sharey=True)
    artists = [draw_leg(axes.flat[k], d, k) for k in range(6)]
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    for ax in axes[:, 0]:
        ax.set_ylabel("friction coefficient")
    axes[0, 1].legend(fontsize=7, loc="upper right")
    fit_suptitle(fig, "Grip per leg: utilised friction |F_t|/F_n, the sample's required "
                 "friction (dots: this leg binds), the scene's mu (dashed), touchdown "
                 "transients (shaded), slip samples (crosses)")
    fig.tight_layout()
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
