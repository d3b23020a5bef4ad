#!/usr/bin/python3
"""Heatmaps and line plots of a hexdyn-sweep file: energy, cost of transport and peak joint
torque over the swept keys, or any column of its scenario table (--metric).

    /usr/bin/python3 analysis/plot_sweep.py SWEEP.h5 OUTDIR [--rows KEY] [--cols KEY]
    /usr/bin/python3 analysis/plot_sweep.py SWEEP.h5 OUTDIR --x KEY [--hue KEY]
                                            [--sel KEY=VALUE ...] [--metric NAME ...]

Heatmaps (default): OUTDIR/sweep_energy.png, sweep_cost_of_transport.png,
sweep_peak_torque_gait.png (the largest peak |tau| over the joints outside touchdown
transients, /scenarios/peak_torque_gait) and sweep_peak_torque_transient.png (the touchdown
transients' peaks, where the prescribed impact of a landing foot acts). Rows and columns
default to the first two axes with more than one value; every other axis with more than
one value gives one panel per value combination (up to 12 panels; beyond that each cell
shows the minimum over those axes, and the title says so). Cells of scenarios that could
not be computed are hatched grey and labelled with their status (reach, config, ...).

Torque limits: the peak-torque figures (these two, and --metric peak_torque, the peak over
every sample) draw the torque limit (allocation.torque_limit of
the base scene, or of each scenario when it is a swept axis; `effort`: each joint's URDF
effort limit, read from a kept run's /model/urdf) and mark the scenarios whose peak exceeds
it: a red frame (heatmap) or a red cross (line plot) when the scenario has relaxed samples
(/scenarios/relaxed_samples > 0, relaxed_gait_samples for the gait's peaks: the allocation
keeps every optimal sample within the limit, so the excess comes from samples where it had
to relax a constraint), a purple one when it has none.

Line plots (--x KEY): OUTDIR/sweep_<metric>_vs_<KEY>.png, the metric against axis KEY, one
line per value of axis --hue (e.g. cost of transport against terrain.riser_height, one line
per gait.duty_factor). Every other axis with more than one value is fixed by
--sel KEY=VALUE (VALUE as in the sweep file, e.g. gait.duty_factor=3/4) or else gives one
panel per value combination (up to 12; more is an error naming the axes to fix).

--metric NAME (repeatable; heatmaps and line plots) draws those metrics instead of the four
above: any numeric column of the file's /scenarios table (energy_electrical,
cost_of_transport_electrical, peak_torque_gait, required_friction_support, ... as the file
has them), titled by its long_name and unit; a per-joint column (peak_torque) is its
largest value over the joints, and COLUMN[JOINT] (peak_torque[L2_femur]) one joint's, as in
Sweep.to_dataframe. The files are OUTDIR/sweep_<NAME>.png and sweep_<NAME>_vs_<KEY>.png
(COLUMN[JOINT]: COLUMN_JOINT). Each figure is saved under a temporary name in OUTDIR and
renamed when complete.
"""

import argparse
import itertools
from fractions import Fraction
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (OPTIMAL_OVER_COLOR, RELAXED_COLOR, exceeds, fit_suptitle,  # first: Agg
                     fit_title, limit_text, nanmax_rows, save_atomically, with_units,
                     sweep_axis_label, sweep_axis_units, torque_ratio)
from hexdyn import results as hr
from matplotlib.patches import Rectangle
import matplotlib.pyplot as plt
import numpy as np

MAX_PANELS = 12
# Columns of /scenarios that are no metric: the scenario's id, its error message and its
# place on the grid.
NOT_METRICS = ("id", "message", "axis_index")

# (file name, title, unit, per-scenario value from the table): the default figures. The
# peak torque is the gait's, outside touchdown transients; the transients' peaks (the
# prescribed impact of a landing foot, docs/theory/contact.md) are a figure of their own.
METRICS = (
    ("sweep_energy.png", "energy E", "J", lambda t: np.asarray(t["energy"], dtype=float)),
    ("sweep_cost_of_transport.png", "cost of transport E/(m g d)", "1",
     lambda t: np.asarray(t["cost_of_transport"], dtype=float)),
    ("sweep_peak_torque_gait.png", "peak joint torque outside touchdowns",
     "N m", lambda t: nanmax_rows(np.asarray(t["peak_torque_gait"], dtype=float))),
    ("sweep_peak_torque_transient.png", "peak joint torque in touchdown transients", "N m",
     lambda t: nanmax_rows(np.asarray(t["peak_torque_transient"], dtype=float))),
)

# The figures of a per-joint peak-torque column, drawn against the torque limit: file name
# -> (column, the /scenarios column counting the relaxed samples that may explain an excess).
TORQUE_FIGURES = {
    "sweep_peak_torque.png": ("peak_torque", "relaxed_samples"),
    "sweep_peak_torque_gait.png": ("peak_torque_gait", "relaxed_gait_samples"),
    "sweep_peak_torque_transient.png": ("peak_torque_transient", "relaxed_samples"),
}


def torque_marks(sweep, name):
    """(ratio, limits, source, relaxed counts) of a peak-torque figure against the torque
    limit, or (None, None, None, None) for another figure."""
    if name not in TORQUE_FIGURES:
        return None, None, None, None
    column, relaxed_column = TORQUE_FIGURES[name]
    ratio, limits, source = torque_ratio(sweep, column)
    relaxed = np.asarray(sweep.table[relaxed_column], dtype=float)
    return ratio, limits, source, relaxed


def metric_columns(sweep):
    """The columns --metric takes for this sweep, {name: per joint (bool)}: every numeric
    column of /scenarios but the id, the message and the grid's indices."""
    out = {}
    for name, column in sweep.table.items():
        values = np.asarray(column)
        if name in NOT_METRICS or name.startswith("axis_") or values.dtype.kind not in "fiub":
            continue
        out[name] = values.ndim == 2
    return out


def column_metric(sweep, name):
    """The metric tuple (file name, title, unit, value) of the /scenarios column `name` or
    COLUMN[JOINT]; one of METRICS when it is one of the default three. SystemExit naming the
    metrics the file has for any other name."""
    columns = metric_columns(sweep)
    column, _, joint = name.partition("[")
    joint = joint[:-1] if joint.endswith("]") else None if not joint else ""
    if column not in columns or (joint is not None and (
            not columns[column] or joint not in sweep.joint_names)):
        per_joint = [c for c, j in columns.items() if j]
        raise SystemExit(f"plot_sweep: --metric {name!r} is not a metric of {sweep.path}; its "
                         f"metrics: {', '.join(columns)}; one joint's as COLUMN[JOINT] of "
                         f"{', '.join(per_joint)} (joints {', '.join(sweep.joint_names)})")
    for m in METRICS:
        if m[0] == f"sweep_{name}.png":
            return m
    spec = hr.SPECS.get(f"{hr.SCENARIOS_GROUP}/{column}")
    title = spec.long_name if spec is not None and spec.long_name else column
    unit = sweep.units.get(column, "")
    if joint:
        j = list(sweep.joint_names).index(joint)
        return (f"sweep_{column}_{joint}.png", f"{title}, {joint}", unit,
                lambda t: np.asarray(t[column], dtype=float)[:, j])
    if np.ndim(sweep.table[column]) == 2:
        return (f"sweep_{column}.png", f"{title}, largest over the joints", unit,
                lambda t: nanmax_rows(np.asarray(t[column], dtype=float)))
    return (f"sweep_{column}.png", title, unit, lambda t: np.asarray(t[column], dtype=float))


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


def setting(sweep, i, j, units):
    """ "key = value unit" for value j of axis i (no unit for dimensionless keys or words)."""
    unit = units[i]
    return f"{sweep.axes[i].key} = {sweep.axes[i].labels[j]}" + (
        f" {unit}" if unit and unit != "1" else "")


def panels(sweep, rows, cols):
    """[(title, {axis: index})...] for the other varied axes, and whether the other
    axes had to be aggregated (too many combinations)."""
    others = [i for i, a in enumerate(sweep.axes) if len(a) > 1 and i not in (rows, cols)]
    combos = list(itertools.product(*[range(len(sweep.axes[i])) for i in others]))
    if len(combos) > MAX_PANELS:
        return [("minimum over " + ", ".join(sweep.axes[i].key for i in others), None)], others
    out = []
    units = sweep_axis_units(sweep)
    for combo in combos:
        title = ", ".join(setting(sweep, i, j, units) for i, j in zip(others, combo))
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
    """Draws and saves one heatmap figure; returns its path."""
    fig, _ = draw_heatmap(sweep, metric, rows, cols)
    return save_atomically(fig, outdir, metric[0])


def draw_heatmap(sweep, metric, rows, cols):
    """The heatmap figure of `metric` and the artists of the torque limit: {"limit": [lines
    on the colour bar], "relaxed": [cell frames], "optimal": [cell frames]}."""
    name, title, unit, getter = metric
    marks = {"limit": [], "relaxed": [], "optimal": []}
    limit_note = None
    ratio, limits, source, relaxed = torque_marks(sweep, name)
    values = getter(sweep.table)
    plist, others = panels(sweep, rows, cols)
    n = len(plist)
    ncols = min(n, 4)
    nrows = (n + ncols - 1) // ncols
    row_axis = sweep.axes[rows]
    col_axis = sweep.axes[cols] if cols is not None else None
    units = sweep_axis_units(sweep)
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
        if ratio is not None:
            # Cells above the limit (the shown value, a minimum over hidden axes, included).
            r, _ = panel_values(sweep, ratio, rows, cols, fixed, others)
            nr, _ = panel_values(sweep, relaxed, rows, cols, fixed, others)
            for (i, j), x in np.ndenumerate(r):
                if np.isfinite(x) and exceeds(x, 1.0):
                    key = "relaxed" if nr[i, j] > 0 else "optimal"
                    marks[key].append(ax.add_patch(Rectangle(
                        (j - 0.46, i - 0.46), 0.92, 0.92, fill=False, lw=2.2,
                        edgecolor=RELAXED_COLOR if key == "relaxed" else OPTIMAL_OVER_COLOR,
                        ls="-" if key == "relaxed" else "--")))
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
        ax.set_ylabel(sweep_axis_label(sweep, rows, units))
        if col_axis is not None:
            ax.set_xticks(range(len(col_axis)), col_axis.labels)
            ax.set_xlabel(sweep_axis_label(sweep, cols, units))
        else:
            ax.set_xticks([])
        if ptitle:
            fit_title(ax, ptitle, fontsize=9)
    for k in range(n, nrows * ncols):
        axs[k // ncols][k % ncols].set_visible(False)
    if image is not None:
        bar = fig.colorbar(image, ax=axs, label=with_units(title, unit), shrink=0.9)
        if limits is not None:
            for lim in np.unique(limits[np.isfinite(limits)]):
                marks["limit"].append(bar.ax.axhline(lim, color=RELAXED_COLOR, lw=2.0))
    notes = [setting(sweep, i, 0, units) for i, a in enumerate(sweep.axes) if len(a) == 1]
    if limits is not None:
        limit_note = (f"red line: {limit_text(limits, source)}; red frame: above it, with "
                      "relaxed samples; purple dashed: above it, none relaxed")
    elif ratio is None and name in TORQUE_FIGURES:
        limit_note = f"no torque limit drawn ({source})"
    failed = int((~sweep.ok).sum())
    if failed:
        notes.append(f"{failed} of {sweep.size} scenarios not computed: hatched, with their status")
    sup = f"{sweep.meta.get('name', 'sweep')}: {title}"
    if notes:
        sup += "\n" + "; ".join(notes)
    if limit_note:
        sup += "\n" + limit_note
    fit_suptitle(fig, sup, fontsize=9)
    return fig, marks


def parse_sel(sweep, items):
    """--sel KEY=VALUE ... -> {axis index: value index}; SystemExit naming a bad item."""
    keys = [a.key for a in sweep.axes]
    fixed = {}
    for item in items or []:
        key, sep, value = item.partition("=")
        if not sep or key not in keys:
            raise SystemExit(f"plot_sweep: --sel {item!r}: expected KEY=VALUE with KEY one of "
                             f"{keys}")
        axis = sweep.axes[keys.index(key)]
        match = [k for k, label in enumerate(axis.labels) if label == value]
        if not match and axis.numeric:
            try:
                v = float(Fraction(value))
            except (ValueError, ZeroDivisionError):
                v = None
            match = [k for k, x in enumerate(axis.values) if v is not None and np.isclose(x, v)]
        if not match:
            raise SystemExit(f"plot_sweep: --sel {item!r}: {key} has no value {value!r} "
                             f"(values: {', '.join(axis.labels)})")
        fixed[keys.index(key)] = match[0]
    return fixed


def draw_lines(sweep, metric, x, hue, fixed):
    """The figure of `metric` against axis `x`, one line per value of axis `hue` (or one
    line), a panel per combination of the other varied axes not in `fixed`. Returns (fig,
    marks) with marks {"limit": [Line2D], "relaxed": [PathCollection], "optimal": [...]}."""
    name, title, unit, getter = metric
    values = getter(sweep.table)
    grid = values.reshape(sweep.shape)
    ratio, limits, source, relaxed = torque_marks(sweep, name)
    if relaxed is not None:
        relaxed = relaxed.reshape(sweep.shape)
    others = [i for i, a in enumerate(sweep.axes)
              if len(a) > 1 and i not in (x, hue) and i not in fixed]
    combos = list(itertools.product(*[range(len(sweep.axes[i])) for i in others]))
    if len(combos) > MAX_PANELS:
        raise SystemExit(f"plot_sweep: {len(combos)} panels for the axes "
                         f"{[sweep.axes[i].key for i in others]}; fix some with --sel KEY=VALUE")
    ncols = min(len(combos), 3)
    nrows = (len(combos) + ncols - 1) // ncols
    fig, axs = plt.subplots(nrows, ncols, figsize=(1.5 + 4.5 * ncols, 1.3 + 3.4 * nrows),
                            squeeze=False, constrained_layout=True, sharey=True)
    xa = sweep.axes[x]
    units = sweep_axis_units(sweep)
    xs = np.asarray(xa.values, dtype=float) if xa.numeric else np.arange(len(xa))
    marks = {"limit": [], "relaxed": [], "optimal": []}
    hue_values = range(len(sweep.axes[hue])) if hue is not None else [None]
    for p, combo in enumerate(combos):
        ax = axs[p // ncols][p % ncols]
        where = dict(fixed)
        where.update(zip(others, combo))
        for h in hue_values:
            index = [slice(None) if i == x else (h if i == hue else where.get(i, 0))
                     for i in range(len(sweep.axes))]
            name = setting(sweep, hue, h, units) if hue is not None else None
            ys = grid[tuple(index)]
            ax.plot(xs, ys, "o-", ms=4, lw=1.2, label=name)
            if ratio is not None:
                r = ratio.reshape(sweep.shape)[tuple(index)]
                nr = relaxed[tuple(index)]
                over = np.isfinite(r) & exceeds(np.nan_to_num(r), 1.0)
                for key, sel, color in (("relaxed", over & (nr > 0), RELAXED_COLOR),
                                        ("optimal", over & (nr == 0), OPTIMAL_OVER_COLOR)):
                    if sel.any():
                        marks[key].append(ax.scatter(xs[sel], ys[sel], marker="x", s=70, lw=2,
                                                     color=color, zorder=5))
        if limits is not None:
            finite = np.unique(limits[np.isfinite(limits)])
            for lim in finite[:4]:
                marks["limit"].append(ax.axhline(lim, color=RELAXED_COLOR, ls=":", lw=1.2))
        ax.set_xlabel(sweep_axis_label(sweep, x, units))
        if not xa.numeric:
            ax.set_xticks(xs, xa.labels)
        if p % ncols == 0:
            ax.set_ylabel(with_units(title, unit))
        ax.grid(alpha=0.3)
        ptitle = ", ".join(setting(sweep, i, j, units) for i, j in zip(others, combo))
        if ptitle:
            fit_title(ax, ptitle, fontsize=9)
        if hue is not None and p == 0:
            ax.legend(fontsize=8)
    for k in range(len(combos), nrows * ncols):
        axs[k // ncols][k % ncols].set_visible(False)
    notes = [setting(sweep, i, j, units) for i, j in fixed.items()]
    notes += [setting(sweep, i, 0, units) for i, a in enumerate(sweep.axes)
              if len(a) == 1 and i not in fixed and i not in (x, hue)]
    if limits is not None:
        limit_note = (f"red dotted: {limit_text(limits, source)}; red cross: above it, with "
                      "relaxed samples; purple: above it, none relaxed")
    failed = int((~sweep.ok).sum())
    if failed:
        notes.append(f"{failed} scenario(s) not computed: gaps")
    sup = f"{sweep.meta.get('name', 'sweep')}: {title} against {xa.key}"
    if notes:
        sup += "\n" + "; ".join(notes)
    if limits is not None:
        sup += "\n" + limit_note
    fit_suptitle(fig, sup, fontsize=9)
    return fig, marks


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="plot_sweep.py", description=__doc__.strip().split("\n\n")[0],
        epilog=__doc__.strip().split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep", help="a hexdyn-sweep file")
    ap.add_argument("outdir")
    ap.add_argument("--rows", help="heatmaps: axis key for the rows")
    ap.add_argument("--cols", help="heatmaps: axis key for the columns")
    ap.add_argument("--x", help="line plots: axis key along x")
    ap.add_argument("--hue", help="line plots: axis key with one line per value")
    ap.add_argument("--sel", action="append", metavar="KEY=VALUE",
                    help="line plots: fix an axis to one value (repeatable)")
    ap.add_argument("--metric", action="append", metavar="NAME",
                    help="a /scenarios column to draw, COLUMN[JOINT] for one joint "
                         "(repeatable; default energy, cost_of_transport, peak_torque_gait, "
                         "peak_torque_transient)")
    args = ap.parse_args(argv)
    sweep = hr.open_sweep(args.sweep)
    if args.metric:
        chosen = [column_metric(sweep, name) for name in args.metric]
    else:  # the defaults the file has values of (no transients: no transient figure)
        chosen = [m for m in METRICS if np.isfinite(m[3](sweep.table)).any()]
        for m in METRICS:
            if m not in chosen:
                print(f"plot_sweep: no {m[0]}: no scenario has a value of {m[1]}",
                      file=sys.stderr)
    os.makedirs(args.outdir, exist_ok=True)
    if args.x is None:
        if args.hue or args.sel:
            raise SystemExit("plot_sweep: --hue and --sel go with --x KEY")
        rows, cols = choose_axes(sweep, args.rows, args.cols)
        written = [draw(sweep, m, rows, cols, args.outdir) for m in chosen]
    else:
        keys = [a.key for a in sweep.axes]
        for k in (args.x, args.hue):
            if k is not None and k not in keys:
                raise SystemExit(f"plot_sweep: {k!r} is not an axis of {sweep.path}; axes: {keys}")
        x = keys.index(args.x)
        hue = keys.index(args.hue) if args.hue else None
        if hue == x:
            raise SystemExit("plot_sweep: --x and --hue must be different axes")
        fixed = parse_sel(sweep, args.sel)
        if x in fixed or (hue is not None and hue in fixed):
            raise SystemExit("plot_sweep: --sel fixes an axis given as --x or --hue")
        written = []
        for m in chosen:
            fig, _ = draw_lines(sweep, m, x, hue, fixed)
            written.append(save_atomically(fig, args.outdir,
                                           f"{m[0][:-4]}_vs_{args.x}.png"))
    for path in written:
        print(f"plot_sweep: wrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
