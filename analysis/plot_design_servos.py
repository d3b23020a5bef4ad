"""Figures of a design study whose designs are servos (configs/designs/paper_servos.yaml): a
sweep of scenes with actuators over a `cases` axis of servos, the duty factor and the riser
height, kept runs included (--keep-runs); drawn by `analysis/plot_designs.py --servos`
(docs/user/designs.md#which-servo-climbs).

A combination (servo, duty factor, riser) climbs when
  1. its scenario was computed (/scenarios/status ok);
  2. no sample failed (/scenarios/failed_samples 0);
  3. no sample outside the touchdown transients was relaxed: no sample of its kept run has
     /solver/status 1 while no leg is in phase impact (/contacts/phase 1), so the drives'
     bounds (peak and voltage) and the trunk's equations hold over the whole gait; the
     transients are left out because their prescribed impact forces are relaxed in this
     scene with ideal joints too (docs/user/designs.md);
  4. its thermal load (/scenarios/thermal_load, the largest windowed RMS drive torque over
     the continuous rating) is at most 1, when the servo has a continuous rating. A servo
     with none (NaN in the servo table) is not judged on heat: the combination climbs
     "unrated", and the table gives its largest windowed RMS drive torque.

  NAME.png         per servo, riser x duty factor: the electrical cost of transport
                   E_el/(m g d) (top row, one colour scale) and the mechanical one E/(m g d)
                   (bottom row); combinations that do not climb are hatched, those not
                   computed grey with their status.
  NAME_climb.png   per servo, riser x duty factor: the verdict and its reason (the number
                   of relaxed gait samples, the thermal load, the status).
  NAME_energy.png  the energy breakdown of every scenario, one panel per servo
                   (analysis/plot_energy.py).
  NAME.csv         one line per scenario: id, servo, riser, duty factor, status, climbs
                   (1/0), reason, the electrical and mechanical cost of transport and
                   energy [J], copper loss, friction loss, regenerated [J], peak electrical
                   power [W], relaxed samples, relaxed gait samples, failed samples, thermal
                   load, largest windowed RMS drive torque [N m], and with a thermal model
                   the peak winding temperature [°C] and the first time a winding reaches
                   its limit [s] (inf: never) over the joints.
The answer (which servo climbs each riser, and at what electrical cost of transport) is
printed to stderr.
"""

import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (fit_suptitle, fit_title, save_atomically, sweep_axis_units,  # first: Agg
                     with_units, write_csv_atomically)
from matplotlib.colors import LogNorm
from matplotlib.patches import Patch, Rectangle
import matplotlib.pyplot as plt
import numpy as np
import plot_energy

RISER, DUTY = "terrain.riser_height", "gait.duty_factor"
VERDICT_COLORS = {"climbs": "#7fc97f", "climbs, unrated": "#c7e9c0", "relaxed gait": "#fb9a99",
                  "thermal": "#fdbf6f", "failed samples": "0.35", "not computed": "0.85"}
COLUMNS = ("id", "servo", RISER, DUTY, "status", "climbs", "reason",
           "cost_of_transport_electrical", "cost_of_transport", "energy_electrical", "energy",
           "energy_copper_loss", "energy_friction_loss", "energy_regenerated",
           "peak_electrical_power", "relaxed_samples", "relaxed_gait_samples", "failed_samples",
           "thermal_load", "window_rms_max", "peak_winding_temperature_max",
           "time_to_winding_limit_min")
# The thermal model's columns (sweep layout 5 on; NaN for servos without a thermal model).
THERMAL = ("peak_winding_temperature_max", "time_to_winding_limit_min")


def climb_verdict(status, failed, relaxed_gait, thermal_load):
    """(climbs, reason) of one combination by the rule of the module comment; reason one
    of VERDICT_COLORS' words."""
    if status != "ok":
        return False, "not computed"
    if failed > 0:
        return False, "failed samples"
    if relaxed_gait > 0:
        return False, "relaxed gait"
    if not np.isfinite(thermal_load):
        return True, "climbs, unrated"
    return (True, "climbs") if thermal_load <= 1.0 else (False, "thermal")


def relaxed_gait_samples(run):
    """Samples of a run relaxed (/solver/status 1) while no leg is in phase impact."""
    status = np.asarray(run["/solver/status"])
    transient = (np.asarray(run["/contacts/phase"]) == 1).any(axis=1)
    return int(((status == 1) & ~transient).sum())


def study_axes(sweep):
    """(servo axis, riser axis, duty axis) indices; SystemExit naming the axes otherwise."""
    keys = [a.key for a in sweep.axes]
    cases = [i for i, a in enumerate(sweep.axes) if a.cases is not None]
    if not cases or RISER not in keys or DUTY not in keys:
        raise SystemExit(f"plot_designs: --servos needs a cases axis of servos, {RISER} and "
                         f"{DUTY}; {sweep.path} has {keys}")
    extra = [k for i, k in enumerate(keys) if len(sweep.axes[i]) > 1
             and i not in (cases[0], keys.index(RISER), keys.index(DUTY))]
    if extra:
        raise SystemExit(f"plot_designs: the axes {extra} of {sweep.path} hold several values")
    if not sweep.has_runs:
        raise SystemExit(f"plot_designs: {sweep.path} keeps no runs; the relaxed gait samples "
                         "are counted on them: run the sweep with --keep-runs")
    return cases[0], keys.index(RISER), keys.index(DUTY)


def servo_rows(sweep):
    """One dict per scenario, in file order, with the columns of COLUMNS (numbers as float,
    NaN where not computed) and "case", "ir", "id_duty": the axis indices."""
    ci, ri, di = study_axes(sweep)
    t, index = sweep.table, np.asarray(sweep.table["axis_index"])
    window = np.asarray(t["drive_torque_window_rms"], dtype=float)
    rows = []
    for s in range(sweep.size):
        status = sweep.status_names[s]
        gait = relaxed_gait_samples(sweep.run(s)) if status == "ok" else np.nan
        row = {"id": t["id"][s], "case": int(index[s][ci]), "ir": int(index[s][ri]),
               "id_duty": int(index[s][di]), "servo": sweep.axes[ci].labels[int(index[s][ci])],
               RISER: float(sweep.axes[ri].values[index[s][ri]]),
               DUTY: sweep.axes[di].labels[int(index[s][di])], "status": status,
               "relaxed_gait_samples": float(gait),
               "window_rms_max": float(np.max(window[s])) if np.isfinite(window[s]).any()
               else np.nan}
        for name in COLUMNS[7:15] + ("relaxed_samples", "failed_samples", "thermal_load"):
            row[name] = float(t[name][s])
        for name in THERMAL:
            row[name] = float(t[name][s]) if name in t else np.nan
        row["climbs"], row["reason"] = climb_verdict(status, row["failed_samples"], gait,
                                                     row["thermal_load"])
        rows.append(row)
    return rows


def grid_of(rows, sweep, servo, key):
    """(riser x duty) array of `key` for one servo."""
    _, ri, di = study_axes(sweep)
    out = np.full((len(sweep.axes[ri]), len(sweep.axes[di])), np.nan, dtype=object)
    for r in rows:
        if r["case"] == servo:
            out[r["ir"], r["id_duty"]] = r[key]
    return out


def label_grid(ax, sweep, units):
    _, ri, di = study_axes(sweep)
    ax.set_xticks(range(len(sweep.axes[di])), sweep.axes[di].labels, fontsize=8)
    ax.set_yticks(range(len(sweep.axes[ri])), sweep.axes[ri].labels, fontsize=8)
    ax.set_xlabel(with_units("duty factor β", units[di]), fontsize=8)
    ax.set_ylabel(with_units("riser h_s", units[ri]), fontsize=8)


def draw_cot(sweep, rows):
    """The cost-of-transport figure and {"cells": {(column, servo label): AxesImage},
    "hatched": {(column, servo label): [(riser index, duty index)]}, "grey": {(column, servo
    label): [...]}}: hatched, computed but not climbing; grey, not computed."""
    ci, _, _ = study_axes(sweep)
    labels, units = sweep.axes[ci].labels, sweep_axis_units(sweep)
    metrics = (("cost_of_transport_electrical", "electrical E_el/(m g d)"),
               ("cost_of_transport", "mechanical E/(m g d)"))
    fig, axs = plt.subplots(2, len(labels), squeeze=False, constrained_layout=True,
                            figsize=(1.5 + 3.3 * len(labels), 7.4))
    out = {"cells": {}, "hatched": {}, "grey": {}}
    for m, (name, title) in enumerate(metrics):
        allv = np.array([r[name] for r in rows], dtype=float)
        finite = allv[np.isfinite(allv) & (allv > 0)]
        norm = LogNorm(*(finite.min(), finite.max()) if finite.size else (0.1, 1.0))
        for c, servo in enumerate(labels):
            ax = axs[m][c]
            v = grid_of(rows, sweep, c, name).astype(float)
            climbs = grid_of(rows, sweep, c, "climbs")
            image = ax.imshow(np.ma.masked_invalid(v), origin="lower", aspect="auto",
                              cmap="viridis", norm=norm)
            out["cells"][(name, servo)] = image
            hatched, grey = out["hatched"].setdefault((name, servo), []), \
                out["grey"].setdefault((name, servo), [])
            for (i, j), x in np.ndenumerate(v):
                if not np.isfinite(x):
                    grey.append((i, j))
                    ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="0.85",
                                           edgecolor="0.5", hatch="//", lw=0.5))
                    ax.text(j, i, grid_of(rows, sweep, c, "status")[i, j], ha="center",
                            va="center", fontsize=7)
                    continue
                if not climbs[i, j]:
                    hatched.append((i, j))
                    ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False,
                                           edgecolor="white", hatch="xx", lw=0.0))
                ax.text(j, i, f"{x:.3g}", ha="center", va="center", fontsize=8,
                        color="black" if norm(x) > 0.6 else "white",
                        bbox=dict(boxstyle="round,pad=0.1", fc="0.3", ec="none", alpha=0.6)
                        if not climbs[i, j] else None)
            label_grid(ax, sweep, units)
            fit_title(ax, f"{servo}: {title}", fontsize=9)
        fig.colorbar(image, ax=list(axs[m]), label=with_units(f"cost of transport, {title}",
                                                              "1"), shrink=0.9)
    fit_suptitle(fig, f"{sweep.meta.get('name', 'sweep')}: cost of transport per servo at "
                 "equal travel; hatched: the combination does not climb (relaxed gait "
                 "samples, failed samples or thermal load above 1; NAME_climb.png gives the "
                 "reason), its cost computed on bounds that gave way; grey: not computed",
                 fontsize=9)
    return fig, out


def verdict_text(row):
    if row["reason"] == "not computed":
        return row["status"]
    if row["reason"] == "relaxed gait":
        return f"no\n{int(row['relaxed_gait_samples'])} gait"
    if row["reason"] == "failed samples":
        return f"no\n{int(row['failed_samples'])} failed"
    load = row["thermal_load"]
    heat = f"\nthermal {load:.2f}" if np.isfinite(load) else "\nunrated"
    return ("yes" if row["climbs"] else "no") + heat


def draw_climb(sweep, rows):
    """The verdict figure and {"reason": {servo label: (riser x duty) array of reasons},
    "text": {servo label: array of the cell texts}}."""
    ci, _, _ = study_axes(sweep)
    labels, units = sweep.axes[ci].labels, sweep_axis_units(sweep)
    fig, axs = plt.subplots(1, len(labels), squeeze=False, constrained_layout=True,
                            figsize=(1.5 + 3.0 * len(labels), 4.0))
    out = {"reason": {}, "text": {}}
    for c, servo in enumerate(labels):
        ax = axs[0][c]
        reason = grid_of(rows, sweep, c, "reason")
        text = np.empty(reason.shape, dtype=object)
        for (i, j), word in np.ndenumerate(reason):
            ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor=VERDICT_COLORS[word],
                                   edgecolor="white", lw=1.5))
            row = next(r for r in rows if r["case"] == c and r["ir"] == i and r["id_duty"] == j)
            text[i, j] = verdict_text(row)
            ax.text(j, i, text[i, j], ha="center", va="center", fontsize=7)
        ax.set_xlim(-0.5, reason.shape[1] - 0.5)
        ax.set_ylim(-0.5, reason.shape[0] - 0.5)
        label_grid(ax, sweep, units)
        fit_title(ax, servo, fontsize=9)
        out["reason"][servo], out["text"][servo] = reason, text
    handles = [Patch(facecolor=col, label=word) for word, col in VERDICT_COLORS.items()]
    axs[0][-1].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.03, 1.0), fontsize=8)
    fit_suptitle(fig, f"{sweep.meta.get('name', 'sweep')}: which combinations climb: computed, "
                 "no failed sample, no relaxed sample outside touchdown transients ('gait': "
                 "their number) and thermal load ≤ 1 where the servo has a continuous "
                 "rating ('unrated': none in the servo table, not judged on heat)", fontsize=9)
    return fig, out


def answer(sweep, rows):
    """Lines: per riser, the servos that climb it (their duty factors) and the cheapest
    climbing combination by electrical cost of transport."""
    _, ri, _ = study_axes(sweep)
    unit = sweep_axis_units(sweep)[ri] or ""
    lines = []
    for ir, riser in enumerate(sweep.axes[ri].labels):
        mine = [r for r in rows if r["ir"] == ir and r["climbs"]]
        servos = []
        for servo in dict.fromkeys(r["servo"] for r in mine):
            duties = [r[DUTY] for r in mine if r["servo"] == servo]
            servos.append(f"{servo} ({', '.join(duties)})")
        if not mine:
            lines.append(f"riser {riser} {unit}: no servo climbs")
            continue
        best = min(mine, key=lambda r: r["cost_of_transport_electrical"])
        lines.append(f"riser {riser} {unit}: climbs with {'; '.join(servos)}; cheapest "
                     f"{best['servo']} at duty factor {best[DUTY]}, electrical CoT "
                     f"{best['cost_of_transport_electrical']:.3g} (mechanical "
                     f"{best['cost_of_transport']:.3g})")
    return lines


def cell(value):
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, float):
        return repr(value)
    return value


def write_csv(rows, path):
    return write_csv_atomically(path, list(COLUMNS),
                                ([cell(r[c]) for c in COLUMNS] for r in rows))


def draw_all(sweep, outdir, name):
    rows = servo_rows(sweep)
    written = []
    fig, _ = draw_cot(sweep, rows)
    written.append(save_atomically(fig, outdir, f"{name}.png"))
    fig, _ = draw_climb(sweep, rows)
    written.append(save_atomically(fig, outdir, f"{name}_climb.png"))
    fig, _ = plot_energy.draw_energy(sweep, sweep.axes[study_axes(sweep)[0]].key)
    written.append(save_atomically(fig, outdir, f"{name}_energy.png"))
    written.append(write_csv(rows, os.path.join(outdir, f"{name}.csv")))
    for line in answer(sweep, rows):
        print(f"{name}: {line}", file=sys.stderr)
    return written
