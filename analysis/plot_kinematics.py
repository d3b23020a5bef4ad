#!/usr/bin/python3
"""Kinematic figures of a hexdyn-result file.

    /usr/bin/python3 analysis/plot_kinematics.py RESULT.h5 OUTDIR

Writes OUTDIR/gait_diagram.png (support and impact phases of every leg, /model/leg_names,
against time, from /contacts/phase) and OUTDIR/feet_heights.png (foot height z against forward
position y for every leg over the terrain profile of the resolved configuration).
Each figure is saved under a temporary name in OUTDIR and renamed when complete.
"""

import argparse
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (IMPACT_COLOR, SUPPORT_COLOR, leg_color, leg_side,  # first: Agg
                     save_atomically)
from hexdyn import results as hr
from matplotlib.patches import Patch
import matplotlib.pyplot as plt
import numpy as np


def _get(terrain, key, default=None):
    """terrain[key], also accepting the key with an SI suffix (_m, _rad)."""
    for k in (key, key + "_m", key + "_rad"):
        if k in terrain:
            return terrain[k]
    if default is None:
        raise KeyError(f"terrain: missing key {key!r}")
    return default


def terrain_height(terrain, y):
    """Terrain height z [m] at forward positions y [m] for config['terrain']."""
    y = np.asarray(y, dtype=float)
    kind = terrain.get("type", "stairs")
    if kind == "flat":
        return np.full_like(y, float(_get(terrain, "height", 0.0)))
    if kind == "slope":
        ground = float(_get(terrain, "ground_height", 0.0))
        angle = float(_get(terrain, "angle", 0.0))
        origin = float(_get(terrain, "origin_y", 0.0))
        return ground + np.maximum(0.0, y - origin) * np.tan(angle)
    if kind == "stairs":
        ground = float(_get(terrain, "ground_height", 0.0))
        riser = float(_get(terrain, "riser_height"))
        tread = float(_get(terrain, "tread_depth"))
        steps = int(_get(terrain, "steps"))
        first = float(_get(terrain, "first_riser_y"))
        # Riser k (1-based) stands at y = first + (k - 1) tread.
        risers = first + tread * np.arange(steps)
        k = np.sum(y[..., None] >= risers, axis=-1)
        return ground + riser * k
    raise ValueError(f"terrain: unknown type {kind!r}")


def terrain_polyline(terrain, y_min, y_max):
    """Vertices (y, z) of the terrain profile between y_min and y_max, with vertical
    risers drawn exactly."""
    ys = [y_min, y_max]
    if terrain.get("type", "stairs") == "stairs":
        first = float(_get(terrain, "first_riser_y"))
        tread = float(_get(terrain, "tread_depth"))
        for k in range(int(_get(terrain, "steps"))):
            y_k = first + k * tread
            if y_min < y_k < y_max:
                ys += [np.nextafter(y_k, -np.inf), y_k]
    elif terrain.get("type") == "slope":
        origin = float(_get(terrain, "origin_y", 0.0))
        if y_min < origin < y_max:
            ys.append(origin)
    ys = np.array(sorted(ys))
    return ys, terrain_height(terrain, ys)


def _runs(mask):
    """(start, stop) index pairs of consecutive True values."""
    padded = np.concatenate(([False], mask, [False]))
    edges = np.flatnonzero(np.diff(padded.astype(np.int8)))
    return list(zip(edges[0::2], edges[1::2]))


def plot_gait_diagram(res, outdir):
    t = np.asarray(res["/time"], dtype=float)
    phase = np.asarray(res["/contacts/phase"])
    dt_last = np.median(np.diff(t)) if len(t) > 1 else 0.05
    t_end = np.append(t[1:], t[-1] + dt_last) if len(t) else t
    names = hr.leg_names(res)
    n = len(names)
    fig, ax = plt.subplots(figsize=(10, 4))
    for leg in range(n):
        row = n - 1 - leg  # L1 on top
        for value, color in ((hr.PHASE_SUPPORT, SUPPORT_COLOR), (hr.PHASE_IMPACT, IMPACT_COLOR)):
            bars = [(t[a], t_end[b - 1] - t[a]) for a, b in _runs(phase[:, leg] == value)]
            ax.broken_barh(bars, (row - 0.4, 0.8), facecolors=color, edgecolor="none")
    ax.set_yticks(range(n))
    ax.set_yticklabels(names[::-1])
    ax.set_ylim(-0.6, n - 0.4)
    if len(t):
        ax.set_xlim(t[0], t_end[-1])
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("leg")
    ax.set_title("Gait diagram (blank: swing)")
    ax.grid(axis="x", alpha=0.3)
    ax.legend(handles=[Patch(color=SUPPORT_COLOR, label="support"),
                       Patch(color=IMPACT_COLOR, label="impact")],
              loc="upper right", bbox_to_anchor=(1.0, 1.15), ncol=2, frameon=False)
    fig.tight_layout()
    return save_atomically(fig, outdir, "gait_diagram.png")


def plot_feet_heights(res, outdir):
    feet = np.asarray(res["/feet/position"], dtype=float)  # (T, L, 3)
    fig, ax = plt.subplots(figsize=(10, 5))
    y_min, y_max = float(feet[:, :, 1].min()), float(feet[:, :, 1].max())
    pad = 0.05 * max(y_max - y_min, 0.1)
    try:
        terrain = res.config.get("terrain") if isinstance(res.config, dict) else None
    except ValueError as e:
        print(f"plot_kinematics: {e}", file=sys.stderr)
        terrain = None
    if isinstance(terrain, dict):
        ty, tz = terrain_polyline(terrain, y_min - pad, y_max + pad)
        ax.fill_between(ty, tz, tz.min() - 0.02, color="0.85", step=None, zorder=0)
        ax.plot(ty, tz, color="black", linewidth=1.2, label="terrain", zorder=1)
    else:
        print("plot_kinematics: no terrain in the configuration; profile not drawn",
              file=sys.stderr)
    for leg, name in enumerate(hr.leg_names(res)):
        side = leg_side(leg)
        style = "-" if side == "left" else "--"  # left legs solid; right dashed
        ax.plot(feet[:, leg, 1], feet[:, leg, 2], style, color=leg_color(leg),
                linewidth=1.2, label=f"{name} ({side})", zorder=2)
    ax.set_xlim(y_min - pad, y_max + pad)
    ax.set_xlabel("foot position y (forward) [m]")
    ax.set_ylabel("foot height z [m]")
    ax.set_title("Foot paths over the terrain (world frame)")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize="small", ncol=2)
    fig.tight_layout()
    return save_atomically(fig, outdir, "feet_heights.png")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("result", help="hexdyn-result HDF5 file")
    parser.add_argument("outdir", help="directory for the PNG files (created if missing)")
    args = parser.parse_args(argv)
    try:
        res = hr.open_result(args.result)
    except (OSError, ValueError) as e:
        print(f"plot_kinematics: {e}", file=sys.stderr)
        return 2
    os.makedirs(args.outdir, exist_ok=True)
    for path in (plot_gait_diagram(res, args.outdir), plot_feet_heights(res, args.outdir)):
        print(f"plot_kinematics: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
