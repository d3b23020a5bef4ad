#!/usr/bin/python3
"""Figures of a design study (docs/user/designs.md): a hexdyn sweep over robot designs,
read with the package's reader (hexdyn.open_sweep, Sweep.to_xarray).

    /usr/bin/python3 analysis/plot_designs.py SWEEP.h5 OUTDIR [--x KEY] [--y KEY]
                                              [--panel KEY] [--name NAME]
    /usr/bin/python3 analysis/plot_designs.py SWEEP.h5 OUTDIR --cases [--envelope ENV.h5]
    /usr/bin/python3 analysis/plot_designs.py SWEEP.h5 OUTDIR --servos

Grid (default; configs/designs/paper_femur_tibia.yaml): designs on two axes, --y (default
robot.femur.length, rows) and --x (robot.tibia.length, columns), one panel per value of
--panel (terrain.riser_height). Writes
  OUTDIR/NAME.png        three rows of heatmaps, one panel per riser: cost of transport
                         E/(m g d), energy E, and the peak joint torque max_k max_t |tau_k|.
                         Designs that were not computed are hatched grey and labelled with
                         their status (reach: no posture lets the legs climb that riser);
                         peak-torque cells above the torque limit are framed (red: with
                         relaxed samples, purple dashed: without); a black star marks the
                         base scene's design (the reference lengths of
                         robot.links_follow_length, else the base scene's lengths);
  OUTDIR/NAME_climb.png  per design the tallest swept riser it climbs (status ok), hatched
                         where it climbs none;
  OUTDIR/NAME.csv        the plotted values, one line per scenario: id, the three axis
                         values, status, cost_of_transport, energy [J], peak_torque [N m],
                         relaxed_samples, and required_friction: the least friction
                         coefficient the scenario's support samples need
                         (/scenarios/required_friction_support, docs/theory/grip.md; NaN
                         where none suffices, the scenario failed, or the sweep predates it).
NAME defaults to the sweep's name. Every other axis of the sweep must hold one value.

Cases (--cases; configs/designs/robots.yaml): one design per value of the `cases` axis
(robots from their URDF), against the riser axis: OUTDIR/NAME.png with cost of
transport, energy and peak |tau| / effort limit per robot against the riser, failed
scenarios marked by an x at the bottom with their status; with --envelope (files of
`hexdyn envelope`, one per robot or one with a cases axis) OUTDIR/NAME_envelope.png, the
tallest riser per robot and criterion, and OUTDIR/NAME_envelope.csv, per robot and criterion
the tallest riser and the required friction of the run there
(/envelope/riser_max_required_friction). OUTDIR/NAME.csv holds the plotted values and each
scenario's required friction.

Servos (--servos; configs/designs/paper_servos.yaml): one design per servo, the values of
a `cases` axis of scenes with actuators, over the duty factor and the riser, with kept runs:
OUTDIR/NAME.png (electrical and mechanical cost of transport per servo over riser x duty
factor), OUTDIR/NAME_climb.png (which combinations climb, and why not),
OUTDIR/NAME_energy.png (the energy breakdown per scenario) and OUTDIR/NAME.csv; the rule
that decides whether a combination climbs is in analysis/plot_design_servos.py.

Each figure is saved under a temporary name in OUTDIR and renamed when complete.
"""

import argparse
import os

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (OPTIMAL_OVER_COLOR, RELAXED_COLOR, exceeds, fit_suptitle,  # first: Agg
                     fit_title, save_atomically, sweep_axis_units, torque_ratio, with_units,
                     write_csv_atomically)
from hexdyn import results as hr
from matplotlib.patches import Rectangle
import matplotlib.pyplot as plt
import numpy as np

RISER = "terrain.riser_height"
# (variable, title, unit): the rows of the grid figure
METRICS = (
    ("cost_of_transport", "cost of transport E/(m g d)", "1"),
    ("energy", "energy E", "J"),
    ("peak_torque", "peak joint torque max_k max_t |τ_k|", "N m"),
)


# The least friction coefficient a scenario's support samples need (docs/theory/grip.md).
MU = "required_friction_support"


def status_word(code):
    code = int(code)
    return hr.SWEEP_STATUS[code] if 0 <= code < len(hr.SWEEP_STATUS) else str(code)


def design_table(sweep):
    """The sweep as an xarray.Dataset with `peak_torque` reduced to its largest joint and
    `torque_ratio` (peak |tau_k| / limit_k, largest over the joints; NaN without a limit)."""
    ds = sweep.to_xarray()
    keys = [a.key for a in sweep.axes]
    with np.errstate(invalid="ignore"):
        peak = ds["peak_torque"].max("joint", skipna=True)
    ds = ds.drop_vars("peak_torque").assign(peak_torque=peak)
    ratio, limits, source = torque_ratio(sweep)
    ratio = np.full(sweep.size, np.nan) if ratio is None else ratio
    ds["torque_ratio"] = (keys, ratio.reshape(sweep.shape))
    ds.attrs["torque_limit_source"] = source
    ds.attrs["torque_limits"] = limits
    return ds


def edges(centres):
    """Cell edges around sorted centres (midpoints; the outer cells symmetric)."""
    c = np.asarray(centres, dtype=float)
    if c.size == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


def base_design(sweep, xkey, ykey):
    """(x, y) of the base scene's design: the reference length of a link when the base
    scene's links follow their length, else the key's own value; None where not a link."""
    robot = (sweep.config or {}).get("robot", {}) or {}
    out = []
    for key in (xkey, ykey):
        parts = key.split(".")
        if len(parts) != 3 or parts[0] != "robot" or parts[2] != "length":
            return None
        link = robot.get(parts[1], {}) or {}
        value = link.get("reference_length") if robot.get(
            "links_follow_length", "none") != "none" else link.get("length")
        if value is None:
            return None
        out.append(float(value))
    return tuple(out)


def mark_base(ax, base, xs, ys, xe, ye):
    """A star at the upper right of the base design's cell (at the point itself when it is
    not a grid point), clear of the cell's number."""
    if base is None:
        return None
    x, y = base
    i, j = np.flatnonzero(np.isclose(ys, y)), np.flatnonzero(np.isclose(xs, x))
    if i.size and j.size:
        i, j = int(i[0]), int(j[0])
        x = xe[j] + 0.82 * (xe[j + 1] - xe[j])
        y = ye[i] + 0.78 * (ye[i + 1] - ye[i])
    return ax.plot([x], [y], marker="*", ms=10, mfc="white", mec="black", mew=1.0)[0]


def key_units(sweep):
    """{axis key: its unit} (None for words and cases)."""
    return dict(zip((a.key for a in sweep.axes), sweep_axis_units(sweep)))


def grid_axes(sweep, xkey, ykey, pkey):
    keys = [a.key for a in sweep.axes]
    for k in (xkey, ykey, pkey):
        if k not in keys:
            raise SystemExit(f"plot_designs: {k!r} is not an axis of {sweep.path}; axes: {keys}")
    extra = [a.key for a in sweep.axes if a.key not in (xkey, ykey, pkey) and len(a) > 1]
    if extra:
        raise SystemExit(f"plot_designs: the axes {extra} of {sweep.path} hold several values; "
                         "a design grid has two design axes and one panel axis")


def draw_grid(sweep, xkey="robot.tibia.length", ykey="robot.femur.length", pkey=RISER):
    """The grid figure and its artists: {"cells": {(metric, panel index): QuadMesh},
    "values": {(metric, panel index): 2-D array (y, x)}, "failed": {panel index: [(iy, ix,
    status word)]}, "relaxed"/"optimal": [(panel index, iy, ix)], "base": (x, y) or None}."""
    grid_axes(sweep, xkey, ykey, pkey)
    ds = design_table(sweep)
    others = {a.key: 0 for a in sweep.axes if a.key not in (xkey, ykey, pkey)}
    ds = ds.isel(others)
    panels = ds[pkey].values
    xs, ys = ds[xkey].values.astype(float), ds[ykey].values.astype(float)
    xe, ye = edges(xs), edges(ys)
    base = base_design(sweep, xkey, ykey)
    units = key_units(sweep)
    punit = f" {units[pkey]}" if units[pkey] not in (None, "", "1") else ""
    fig, axs = plt.subplots(len(METRICS), len(panels), squeeze=False, constrained_layout=True,
                            figsize=(max(8.5, 1.5 + 3.6 * len(panels)), 1.2 + 3.1 * len(METRICS)))
    out = {"cells": {}, "values": {}, "failed": {}, "relaxed": [], "optimal": [], "base": base}
    for m, (name, title, unit) in enumerate(METRICS):
        allv = ds[name].values
        finite = allv[np.isfinite(allv)]
        vmin, vmax = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
        if vmin == vmax:
            vmin, vmax = vmin - 0.5, vmax + 0.5
        mesh = None
        for p in range(len(panels)):
            ax = axs[m][p]
            cell = ds.isel({pkey: p}).transpose(ykey, xkey, ...)
            v = cell[name].values.astype(float)
            st = cell["status"].values
            mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(v), cmap="viridis", vmin=vmin,
                                 vmax=vmax)
            out["cells"][(name, p)] = mesh
            out["values"][(name, p)] = v
            failed = []
            for (i, j), x in np.ndenumerate(v):
                box = (xe[j], ye[i]), xe[j + 1] - xe[j], ye[i + 1] - ye[i]
                if np.isfinite(x):
                    shade = (x - vmin) / (vmax - vmin)
                    ax.text(xs[j], ys[i], f"{x:.3g}", ha="center", va="center", fontsize=7,
                            color="black" if shade > 0.6 else "white")
                else:
                    ax.add_patch(Rectangle(*box, facecolor="0.85", edgecolor="0.5", hatch="//",
                                           linewidth=0.5))
                    word = status_word(st[i, j])
                    failed.append((i, j, word))
                    ax.text(xs[j], ys[i], word, ha="center", va="center", fontsize=7,
                            color="0.2")
            out["failed"][p] = failed
            if name == "peak_torque":
                r = cell["torque_ratio"].values
                nr = cell["relaxed_samples"].values
                for (i, j), x in np.ndenumerate(r):
                    if np.isfinite(x) and exceeds(x, 1.0):
                        kind = "relaxed" if nr[i, j] > 0 else "optimal"
                        out[kind].append((p, i, j))
                        (x0, y0), w, h = (xe[j], ye[i]), xe[j + 1] - xe[j], ye[i + 1] - ye[i]
                        ax.add_patch(Rectangle((x0 + 0.04 * w, y0 + 0.04 * h), 0.92 * w, 0.92 * h,
                                               fill=False, lw=2.0,
                                               edgecolor=RELAXED_COLOR if kind == "relaxed"
                                               else OPTIMAL_OVER_COLOR,
                                               ls="-" if kind == "relaxed" else "--"))
            mark_base(ax, base, xs, ys, xe, ye)
            ax.set_xticks(xs, [f"{x:g}" for x in xs], fontsize=7)
            ax.set_yticks(ys, [f"{y:g}" for y in ys], fontsize=7)
            ax.set_xlabel(with_units(xkey, units[xkey]), fontsize=8)
            if p == 0:
                ax.set_ylabel(with_units(ykey, units[ykey]), fontsize=8)
            if m == 0:
                fit_title(ax, f"{pkey} = {panels[p]:g}{punit}", fontsize=9)
        fig.colorbar(mesh, ax=list(axs[m]), label=with_units(title, unit), shrink=0.9)
    notes = [f"{sweep.meta.get('name', 'sweep')}: {sweep.size} scenarios, "
             f"{int(sweep.ok.sum())} computed; hatched: not computed, with the status"]
    limits = ds.attrs.get("torque_limits")
    if limits is not None:
        finite = limits[np.isfinite(limits)]
        lim = f"{finite[0]:g} N m" if finite.size and np.allclose(finite, finite[0]) else "limits"
        notes.append(f"peak torque framed above the torque limit ({lim}): red with relaxed "
                     "samples, purple dashed without")
    if base is not None:
        notes.append(f"star: the base scene's design ({xkey} {base[0]:g} {units[xkey] or ''}, "
                     f"{ykey} {base[1]:g} {units[ykey] or ''})")
    if others:
        notes.append(", ".join(f"{k} = {sweep.axes[[a.key for a in sweep.axes].index(k)].labels[0]}"
                               for k in others))
    fit_suptitle(fig, "\n".join(notes), fontsize=9)
    return fig, out


def climb_grid(sweep, xkey="robot.tibia.length", ykey="robot.femur.length", pkey=RISER):
    """2-D array (y, x): the tallest value of the panel axis each design computes (status
    ok), NaN where none; and the axis values (xs, ys)."""
    ds = design_table(sweep)
    others = {a.key: 0 for a in sweep.axes if a.key not in (xkey, ykey, pkey)}
    ds = ds.isel(others).transpose(ykey, xkey, pkey, ...)
    ok = ds["status"].values == 0
    risers = ds[pkey].values.astype(float)
    tallest = np.where(ok, risers[None, None, :], -np.inf).max(axis=-1)
    tallest[~np.isfinite(tallest)] = np.nan
    return tallest, ds[xkey].values.astype(float), ds[ykey].values.astype(float)


def draw_climb(sweep, xkey="robot.tibia.length", ykey="robot.femur.length", pkey=RISER):
    tallest, xs, ys = climb_grid(sweep, xkey, ykey, pkey)
    xe, ye = edges(xs), edges(ys)
    units = key_units(sweep)
    fig, ax = plt.subplots(figsize=(6.4, 5.0), constrained_layout=True)
    mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(tallest), cmap="cividis")
    for (i, j), x in np.ndenumerate(tallest):
        if np.isfinite(x):
            ax.text(xs[j], ys[i], f"{x:g}", ha="center", va="center", fontsize=8, color="white"
                    if x < np.nanmax(tallest) else "black")
        else:
            ax.add_patch(Rectangle((xe[j], ye[i]), xe[j + 1] - xe[j], ye[i + 1] - ye[i],
                                   facecolor="0.85", edgecolor="0.5", hatch="//", linewidth=0.5))
            ax.text(xs[j], ys[i], "none", ha="center", va="center", fontsize=8, color="0.2")
    mark_base(ax, base_design(sweep, xkey, ykey), xs, ys, xe, ye)
    ax.set_xticks(xs, [f"{x:g}" for x in xs], fontsize=8)
    ax.set_yticks(ys, [f"{y:g}" for y in ys], fontsize=8)
    ax.set_xlabel(with_units(xkey, units[xkey]))
    ax.set_ylabel(with_units(ykey, units[ykey]))
    fig.colorbar(mesh, ax=ax, label=with_units(f"tallest {pkey} climbed", units[pkey]))
    fit_title(ax, f"{sweep.meta.get('name', 'sweep')}: tallest swept {pkey} each design climbs "
              f"(of {', '.join(f'{v:g}' for v in sweep.to_xarray()[pkey].values)}"
              f"{' ' + units[pkey] if units[pkey] else ''})", fontsize=9)
    return fig, tallest


def write_csv(sweep, path, keys):
    """The plotted values, one line per scenario (module comment), via a temporary file."""
    ds = design_table(sweep)
    if MU not in ds:  # a sweep written before the required friction
        ds[MU] = ds["energy"] * np.nan
    df = ds[["status", "cost_of_transport", "energy", "peak_torque", "relaxed_samples", MU]] \
        .to_dataframe().reset_index()
    ids = ds["id"].to_dataframe().reset_index()
    rows = ([idrow["id"]] + [repr(float(row[k])) if not isinstance(row[k], str) else row[k]
                             for k in keys]
            + [status_word(row["status"])]
            + [repr(float(row[k])) for k in ("cost_of_transport", "energy", "peak_torque")]
            + [int(row["relaxed_samples"]), repr(float(row[MU]))]
            for (_, row), (_, idrow) in zip(df.iterrows(), ids.iterrows()))
    return write_csv_atomically(
        path, ["id"] + keys + ["status", "cost_of_transport", "energy", "peak_torque",
                               "relaxed_samples", "required_friction"], rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("sweep")
    ap.add_argument("outdir")
    ap.add_argument("--x", default="robot.tibia.length", help="design axis along x")
    ap.add_argument("--y", default="robot.femur.length", help="design axis along y")
    ap.add_argument("--panel", default=RISER, help="one panel per value of this axis")
    ap.add_argument("--name", help="file stem (default: the sweep's name)")
    ap.add_argument("--cases", action="store_true", help="designs on a cases axis")
    ap.add_argument("--envelope", nargs="*", default=[], help="envelope files (--cases)")
    ap.add_argument("--servos", action="store_true",
                    help="servos on a cases axis, over duty factor and riser (kept runs)")
    args = ap.parse_args(argv)
    if args.cases and args.servos:
        ap.error("--cases and --servos: expected one of them")
    sweep = hr.open_sweep(args.sweep)
    name = args.name or str(sweep.meta.get("name") or "designs")
    os.makedirs(args.outdir, exist_ok=True)
    written = []
    if args.servos:
        import plot_design_servos
        written += plot_design_servos.draw_all(sweep, args.outdir, name)
    elif args.cases:
        import plot_design_cases
        written += plot_design_cases.draw_all(sweep, args.outdir, name, args.envelope,
                                              args.panel)
    else:
        fig, _ = draw_grid(sweep, args.x, args.y, args.panel)
        written.append(save_atomically(fig, args.outdir, f"{name}.png"))
        fig, _ = draw_climb(sweep, args.x, args.y, args.panel)
        written.append(save_atomically(fig, args.outdir, f"{name}_climb.png"))
        written.append(write_csv(sweep, os.path.join(args.outdir, f"{name}.csv"),
                                 [args.panel, args.y, args.x]))
    for path in written:
        print(path)


if __name__ == "__main__":
    main()
