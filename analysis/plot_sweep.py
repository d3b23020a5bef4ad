#!/usr/bin/python3
"""Heatmaps of a hexdyn-sweep/2 file: energy, cost of transport and peak joint torque
over two swept keys.

    /usr/bin/python3 analysis/plot_sweep.py SWEEP.h5 OUTDIR [--rows KEY] [--cols KEY]

Writes OUTDIR/sweep_energy.png, sweep_cost_of_transport.png and sweep_peak_torque.png
(the largest peak |tau| over the 18 joints). Rows and columns default to the first two
axes with more than one value; every other axis with more than one value gives one
panel per value combination (up to 12 panels; beyond that each cell shows the minimum
over those axes, and the title says so). Cells of scenarios that could not be computed
are hatched grey and labelled with their status (reach, config, ...). Each figure is
saved under a temporary name in OUTDIR and renamed when complete.
"""

import argparse
import itertools
import os
import sys


import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402
import numpy as np  # noqa: E402

from hexdyn import results as hr  # noqa: E402
from plot_kinematics import save_atomically  # noqa: E402

MAX_PANELS = 12

# (file name, title, unit, per-scenario value from the table)
METRICS = (
    ("sweep_energy.png", "energy E", "J", lambda t: np.asarray(t["energy"], dtype=float)),
    ("sweep_cost_of_transport.png", "cost of transport E/(m g d)", "1",
     lambda t: np.asarray(t["cost_of_transport"], dtype=float)),
    ("sweep_peak_torque.png", "peak joint torque max_k max_t |τ_k|", "N m",
     lambda t: _nanmax_rows(np.asarray(t["peak_torque"], dtype=float))),
)


def _nanmax_rows(a):
    out = np.full(a.shape[0], np.nan)
    finite = np.isfinite(a).any(axis=1)
    out[finite] = np.nanmax(a[finite], axis=1)
    return out


def choose_axes(sweep, rows_key=None, cols_key=None):
    """Indices of the row and column axes (cols may be None for a single swept axis)."""
    keys = [a.key for a in sweep.axes]
    for k in (rows_key, cols_key):
        if k is not None and k not in keys:
            raise SystemExit(f"plot_sweep: {k!r} is not an axis of {sweep.path}; axes: {keys}")
    varied = [i for i, a in enumerate(sweep.axes) if len(a) > 1]
    rows = keys.index(rows_key) if rows_key else None
    cols = keys.index(cols_key) if cols_key else None
    free = [i for i in varied if i not in (rows, cols)]
    if rows is None and free:
        rows = free.pop(0)
    if cols is None and free:
        cols = free.pop(0)
    if rows is None:
        rows = 0
    if rows == cols:
        raise SystemExit("plot_sweep: rows and columns must be different axes")
    return rows, cols


def panels(sweep, rows, cols):
    """[(title, {axis: index})...] for the other varied axes, and whether the other
    axes had to be aggregated (too many combinations)."""
    others = [i for i, a in enumerate(sweep.axes) if len(a) > 1 and i not in (rows, cols)]
    combos = list(itertools.product(*[range(len(sweep.axes[i])) for i in others]))
    if len(combos) > MAX_PANELS:
        return [("minimum over " + ", ".join(sweep.axes[i].key for i in others), None)], others
    out = []
    for combo in combos:
        title = ", ".join(f"{sweep.axes[i].key} = {sweep.axes[i].labels[j]}"
                          for i, j in zip(others, combo))
        out.append((title, dict(zip(others, combo))))
    return out, others


def panel_values(sweep, values, rows, cols, fixed, others):
    """2-D arrays (value, status) with shape (len rows, len cols) for one panel."""
    grid = values.reshape(sweep.shape)
    status = np.asarray(sweep.table["status"]).reshape(sweep.shape)
    index = []
    for i, axis in enumerate(sweep.axes):
        if i in (rows, cols):
            index.append(slice(None))
        elif fixed is not None and i in fixed:
            index.append(fixed[i])
        elif fixed is None and i in others:
            index.append(slice(None))
        else:
            index.append(0)  # an axis with one value
    v, st = grid[tuple(index)], status[tuple(index)]
    kept = [i for i, ix in enumerate(index) if isinstance(ix, slice)]
    # Bring the (rows, cols) axes to the front, aggregate the rest.
    order = [kept.index(rows)] + ([kept.index(cols)] if cols is not None else [])
    rest = [k for k in range(len(kept)) if k not in order]
    v = np.transpose(v, order + rest)
    st = np.transpose(st, order + rest)
    if rest:
        flat_v = v.reshape(v.shape[:len(order)] + (-1,))
        flat_s = st.reshape(st.shape[:len(order)] + (-1,))
        with np.errstate(all="ignore"):
            finite = np.isfinite(flat_v).any(axis=-1)
            v = np.where(finite, np.nanmin(np.where(np.isfinite(flat_v), flat_v, np.inf), axis=-1),
                         np.nan)
        st = np.where(finite, 0, flat_s.max(axis=-1))
    if cols is None:
        v, st = v[:, None], st[:, None]
    return v, st


def draw(sweep, metric, rows, cols, outdir):
    name, title, unit, getter = metric
    values = getter(sweep.table)
    plist, others = panels(sweep, rows, cols)
    n = len(plist)
    ncols = min(n, 4)
    nrows = (n + ncols - 1) // ncols
    row_axis = sweep.axes[rows]
    col_axis = sweep.axes[cols] if cols is not None else None
    fig, axs = plt.subplots(nrows, ncols, figsize=(max(6.5, 1.2 + 3.6 * ncols), 1.2 + 3.0 * nrows),
                            squeeze=False, constrained_layout=True)
    finite = values[np.isfinite(values)]
    vmin, vmax = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if vmin == vmax:
        vmin, vmax = vmin - 0.5, vmax + 0.5
    image = None
    for k, (ptitle, fixed) in enumerate(plist):
        ax = axs[k // ncols][k % ncols]
        v, st = panel_values(sweep, values, rows, cols, fixed, others)
        image = ax.imshow(np.ma.masked_invalid(v), origin="lower", aspect="auto",
                          cmap="viridis", vmin=vmin, vmax=vmax)
        for (i, j), x in np.ndenumerate(v):
            if np.isfinite(x):
                shade = (x - vmin) / (vmax - vmin)
                ax.text(j, i, f"{x:.3g}", ha="center", va="center", fontsize=8,
                        color="black" if shade > 0.6 else "white")
            else:
                ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="0.85",
                                       edgecolor="0.5", hatch="//", linewidth=0.5))
                code = int(st[i, j])
                word = hr.SWEEP_STATUS[code] if 0 <= code < len(hr.SWEEP_STATUS) else "?"
                ax.text(j, i, word, ha="center", va="center", fontsize=8, color="0.2")
        ax.set_yticks(range(len(row_axis)), row_axis.labels)
        ax.set_ylabel(row_axis.key)
        if col_axis is not None:
            ax.set_xticks(range(len(col_axis)), col_axis.labels)
            ax.set_xlabel(col_axis.key)
        else:
            ax.set_xticks([])
        if ptitle:
            ax.set_title(ptitle, fontsize=9)
    for k in range(n, nrows * ncols):
        axs[k // ncols][k % ncols].set_visible(False)
    if image is not None:
        fig.colorbar(image, ax=axs, label=f"{title} [{unit}]", shrink=0.9)
    notes = [f"{a.key} = {a.labels[0]}" for a in sweep.axes if len(a) == 1]
    failed = int((~sweep.ok).sum())
    if failed:
        notes.append(f"{failed} of {sweep.size} scenarios not computed: hatched, with their status")
    sup = f"{sweep.meta.get('name', 'sweep')}: {title}"
    if notes:
        sup += "\n" + "; ".join(notes)
    fig.suptitle(sup, fontsize=10)
    return save_atomically(fig, outdir, name)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep", help="a hexdyn-sweep/2 file")
    ap.add_argument("outdir")
    ap.add_argument("--rows", help="axis key for the heatmap rows")
    ap.add_argument("--cols", help="axis key for the heatmap columns")
    args = ap.parse_args(argv)
    sweep = hr.open_sweep(args.sweep)
    os.makedirs(args.outdir, exist_ok=True)
    rows, cols = choose_axes(sweep, args.rows, args.cols)
    written = [draw(sweep, m, rows, cols, args.outdir) for m in METRICS]
    for path in written:
        print(f"plot_sweep: wrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
