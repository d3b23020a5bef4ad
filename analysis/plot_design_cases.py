"""Figures of a design study whose designs are the values of a `cases` axis (robots from
their URDF, configs/designs/robots.yaml); drawn by `analysis/plot_designs.py --cases`
(docs/user/designs.md#robots-from-urdf-as-cases).

  NAME.png           per case (robot) against the riser: cost of transport, energy, and the
                     peak joint torque over the effort limit, max_k max_t |tau_k| / limit_k
                     (limits from each case's kept run /model/urdf; the peak in N m when the
                     sweep kept no run of the case). Scenarios not computed: an x on the
                     bottom of each panel with the status word.
  NAME_envelope.png  from `hexdyn envelope` files: the tallest riser per case and criterion
                     (grouped bars; a file per case, matched to the case by its /meta name,
                     or one file with the cases as a dimension).
  NAME_envelope.csv  one line per case and criterion: case, criterion, riser_max [m] and
                     required_friction, the least friction coefficient of the support
                     samples of the run at riser_max (/envelope/riser_max_required_friction;
                     NaN for the kinematic criterion, where none suffices, or in a file
                     written before it).
  NAME.csv           the plotted values, one line per scenario: id, case, riser, status,
                     cost_of_transport, energy, peak_torque [N m], torque_ratio,
                     required_friction (/scenarios/required_friction_support).
"""

import os

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (fit_suptitle, fit_title, fraction_text, with_units,  # first: Agg
                     save_atomically, sweep_axis_label, torque_limits, write_csv_atomically)
from hexdyn import results as hr
import matplotlib.pyplot as plt
import numpy as np
import yaml

RISER = "terrain.riser_height"
ENVELOPE_GRID = ("tread_depth", "duty_factor", "peak_speed", "criterion")


def cases_axis(sweep):
    """Index of the sweep's cases axis (SystemExit naming the axes when it has none)."""
    for i, a in enumerate(sweep.axes):
        if getattr(a, "cases", None) is not None:
            return i
    raise SystemExit(f"plot_designs: {sweep.path} has no cases axis; axes: "
                     f"{[a.key for a in sweep.axes]}")


def case_limits(sweep, ci):
    """{case index: per-joint torque limits (J,) N m} from a kept run of each case."""
    import h5py

    out = {}
    if not sweep.has_runs:
        return out
    index = np.asarray(sweep.table["axis_index"])
    with h5py.File(sweep.path, "r") as f:
        for s, sid in enumerate(sweep.table["id"]):
            c = int(index[s][ci])
            if c in out or sid not in sweep.run_ids:
                continue
            g = f["runs"][sid]
            config = yaml.safe_load(hr.decode_text(g["meta"].attrs["config_yaml"]))
            urdf = hr.decode_text(g["model"]["urdf"][()])
            # /model/urdf names the joints as the description does: /model/joint_names
            # holds those names in hexdyn's joint order.
            names = [hr.decode_text(n) for n in g["model"]["joint_names"][()]]
            limits, _ = torque_limits(config, urdf, names)
            if limits is not None:
                out[c] = limits
    return out


def case_table(sweep):
    """(cases axis, riser axis, rows): rows one dict per scenario in file order."""
    ci = cases_axis(sweep)
    keys = [a.key for a in sweep.axes]
    if RISER not in keys:
        raise SystemExit(f"plot_designs: {sweep.path} has no {RISER} axis; axes: {keys}")
    ri = keys.index(RISER)
    extra = [a.key for i, a in enumerate(sweep.axes) if i not in (ci, ri) and len(a) > 1]
    if extra:
        raise SystemExit(f"plot_designs: the axes {extra} of {sweep.path} hold several values; "
                         "a cases study has the cases and the riser")
    limits = case_limits(sweep, ci)
    index = np.asarray(sweep.table["axis_index"])
    try:
        mu = np.asarray(sweep.table["required_friction_support"], dtype=float)
    except KeyError:  # a sweep written before the required friction
        mu = np.full(sweep.size, np.nan)
    peak = np.asarray(sweep.table["peak_torque"], dtype=float)
    rows = []
    for s in range(sweep.size):
        c, r = int(index[s][ci]), int(index[s][ri])
        finite = np.isfinite(peak[s])
        ratio = np.nan
        if c in limits and finite.any():
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = float(np.nanmax(peak[s] / limits[c]))
        rows.append({
            "id": sweep.table["id"][s], "case": c, "label": sweep.axes[ci].labels[c],
            "riser": float(sweep.axes[ri].values[r]), "status": sweep.status_names[s],
            "cost_of_transport": float(sweep.table["cost_of_transport"][s]),
            "energy": float(sweep.table["energy"][s]),
            "peak_torque": float(np.nanmax(peak[s])) if finite.any() else np.nan,
            "torque_ratio": ratio, "required_friction": float(mu[s])})
    return ci, ri, rows, limits


def draw_cases(sweep):
    """The figure and {"lines": {(panel name, case label): (x, y)}, "failed": [(case label,
    riser, status)]}."""
    ci, ri, rows, limits = case_table(sweep)
    labels = sweep.axes[ci].labels
    all_limits = len(limits) == len(labels)
    panels = [("cost_of_transport", with_units("cost of transport E/(m g d)", "1")),
              ("energy", with_units("energy E", "J")),
              ("torque_ratio", with_units("peak |τ_k| / effort limit_k", "1")) if all_limits
              else ("peak_torque", with_units("peak joint torque", "N m"))]
    fig, axs = plt.subplots(1, len(panels), figsize=(5.0 * len(panels), 4.3),
                            constrained_layout=True)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    out = {"lines": {}, "failed": []}
    for p, (name, title) in enumerate(panels):
        ax = axs[p]
        for c, case in enumerate(labels):
            mine = [r for r in rows if r["case"] == c]
            x = np.array([r["riser"] for r in mine])
            y = np.array([r[name] for r in mine])
            ok = np.array([r["status"] == "ok" for r in mine])
            ax.plot(x[ok], y[ok], "-o", ms=4, color=colors[c % len(colors)], label=case)
            out["lines"][(name, case)] = (x[ok], y[ok])
            for r in mine:
                if r["status"] != "ok":
                    ax.plot([r["riser"]], [0.04 + 0.06 * c], "x", ms=8, mew=2,
                            color=colors[c % len(colors)], transform=ax.get_xaxis_transform())
                    if p == 0:
                        out["failed"].append((case, r["riser"], r["status"]))
        if name == "torque_ratio":
            ax.axhline(1.0, color="#d62728", lw=1.5, label="effort limit")
            ax.legend(fontsize=8)
        if name in ("torque_ratio", "peak_torque"):
            fit_title(ax, "peaks include the touchdown transients (relaxed samples)", fontsize=8)
        ax.set_xlabel(sweep_axis_label(sweep, ri))
        ax.set_ylabel(title)
        ax.grid(alpha=0.3)
    axs[0].legend(fontsize=8)
    failed = sorted({(lab, st) for lab, _, st in out["failed"]})
    note = "; ".join(f"{lab}: {st} from {min(r for l2, r, s2 in out['failed'] if l2 == lab):g} m"
                     for lab, st in failed)
    fit_suptitle(fig, f"{sweep.meta.get('name', 'sweep')}: {sweep.size} scenarios, "
                 f"{int(sweep.ok.sum())} computed"
                 + (f"; x: not computed ({note})" if note else ""), fontsize=9)
    return fig, out


def read_envelope(path):
    """{"name": /meta name, "ds": the /envelope group with its coordinates}."""
    import h5py
    from hexdyn.xr import open_envelope

    with h5py.File(path, "r") as f:
        name = hr.decode_text(f["meta"].attrs.get("name", os.path.basename(path)))
    return {"name": name, "ds": open_envelope(path)}


def envelope_table(paths, labels, variable="riser_max"):
    """{case label: {criterion: tallest riser [m] (NaN: fails at the lowest)}} over the
    files, at their first tread depth, duty factor and speed, and that cell as (tread depth,
    duty factor, speed) of the first file. `variable` another (case,) cell, criterion grid of
    the /envelope group ("riser_max_required_friction": NaN for a file without it)."""
    out = {}
    cell = None
    for path in paths:
        env = read_envelope(path)
        ds = env["ds"]
        if variable not in ds:
            ds = ds.assign({variable: ds["riser_max"] * np.nan})
        case_dims = [d for d in ds["riser_max"].dims if d not in ENVELOPE_GRID]
        first = {d: 0 for d in ENVELOPE_GRID[:3] if d in ds.dims}
        ds = ds.isel(first)
        if cell is None:
            cell = tuple(float(ds[d].values) for d in ENVELOPE_GRID[:3] if d in ds.coords)
        crits = [str(c) for c in ds["criterion"].values]
        if case_dims:  # one file, the cases as a dimension
            d = case_dims[0]
            for k, label in enumerate(ds[d].values):
                out[str(label)] = {c: float(ds[variable].isel({d: k}).values[j])
                                   for j, c in enumerate(crits)}
        else:
            label = env["name"] if env["name"] in labels else os.path.splitext(
                os.path.basename(path))[0]
            out[label] = {c: float(ds[variable].values[j]) for j, c in enumerate(crits)}
    return out, cell


def draw_envelope(table, name, cell=None):
    labels = list(table)
    crits = sorted({c for v in table.values() for c in v},
                   key=lambda c: ("kinematic", "torque", "friction").index(c)
                   if c in ("kinematic", "torque", "friction") else 9)
    fig, ax = plt.subplots(figsize=(1.8 + 1.6 * len(labels) * max(1, len(crits)) / 2, 4.2),
                           constrained_layout=True)
    width = 0.8 / max(1, len(crits))
    bars = {}
    for j, c in enumerate(crits):
        y = [table[lab].get(c, np.nan) for lab in labels]
        x = np.arange(len(labels)) + (j - (len(crits) - 1) / 2) * width
        bars[c] = ax.bar(x, np.nan_to_num(y), width, label=c)
        for xi, yi in zip(x, y):
            ax.text(xi, 0 if not np.isfinite(yi) else yi, "none" if not np.isfinite(yi) else
                    f"{1000 * yi:.0f} mm", ha="center", va="bottom", fontsize=7)
    ax.set_xticks(np.arange(len(labels)), labels)
    ax.set_ylabel("tallest riser climbed [m]")
    top = max([v for t in table.values() for v in t.values() if np.isfinite(v)] or [0.01])
    ax.set_ylim(0, 1.3 * top)
    ax.legend(fontsize=8, title="criterion", ncols=len(crits), loc="upper center")
    where = (f" (tread {cell[0]:g} m, duty factor {fraction_text(cell[1])}, peak speed "
             f"{cell[2]:g} m/s)" if cell and len(cell) == 3 else "")
    fit_title(ax, f"{name}: climbable envelope per robot{where}", fontsize=9)
    return fig, bars


def write_csv(rows, path):
    return write_csv_atomically(
        path, ["id", "case", RISER, "status", "cost_of_transport", "energy", "peak_torque",
               "torque_ratio", "required_friction"],
        ([r["id"], r["label"], repr(r["riser"]), r["status"]]
         + [repr(r[k]) for k in ("cost_of_transport", "energy", "peak_torque", "torque_ratio",
                                 "required_friction")]
         for r in rows))


def write_envelope_csv(risers, mus, path):
    """One line per case and criterion: the tallest riser and the required friction there."""
    return write_csv_atomically(
        path, ["case", "criterion", "riser_max", "required_friction"],
        ([label, c, repr(risers[label][c]), repr(mus[label][c])]
         for label in risers for c in risers[label]))


def draw_all(sweep, outdir, name, envelopes, panel=RISER):
    if panel != RISER:
        raise SystemExit(f"plot_designs: --cases plots against {RISER}, got --panel {panel}")
    written = []
    fig, _ = draw_cases(sweep)
    written.append(save_atomically(fig, outdir, f"{name}.png"))
    if envelopes:
        labels = sweep.axes[cases_axis(sweep)].labels
        table, cell = envelope_table(envelopes, labels)
        fig, _ = draw_envelope(table, name, cell)
        written.append(save_atomically(fig, outdir, f"{name}_envelope.png"))
        mus, _ = envelope_table(envelopes, labels, "riser_max_required_friction")
        written.append(write_envelope_csv(table, mus, os.path.join(outdir,
                                                                   f"{name}_envelope.csv")))
    _, _, rows, _ = case_table(sweep)
    written.append(write_csv(rows, os.path.join(outdir, f"{name}.csv")))
    return written
