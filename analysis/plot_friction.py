#!/usr/bin/python3
"""Figures of the grip study (pipelines/friction.sh, docs/validation/friction.md): a hexdyn
sweep over duty factor x peak speed x riser with kept runs, read with the package's reader.

    /usr/bin/python3 analysis/plot_friction.py SWEEP.h5 OUTDIR [--name NAME] [--table]

Writes
  OUTDIR/NAME_required.png   the required friction (/scenarios/required_friction_support and
                             _transient, docs/theory/grip.md) against peak speed, one row of
                             panels per riser, support samples left and touchdown transients
                             right, a line per duty factor, each point labelled with its
                             binding leg; the published reference values drawn as lines
                             (human stair ascent 0.3-0.5, towr 0.5, Crocoddyl 0.7, the scene's
                             mu);
  OUTDIR/NAME_transient_energy.png   the share of the energy spent in touchdown transients:
                             the energy (the joints' |power| integrated by the file's energy
                             rule, each interval halved between its ends) over the samples where
                             some leg is in phase 1, over the total, same axes;
  OUTDIR/NAME.csv            one line per scenario: the axis values, status, the required
                             friction (support, transient) with leg and time, the largest
                             support required friction per leg (from the kept run), the
                             samples where no mu suffices, the largest utilised friction, the
                             slip and relaxed support samples, the energy and its transient
                             share.
--table prints the CSV's main columns as a Markdown table.
"""

import argparse
import os

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, fraction_text, save_atomically, write_csv_atomically
from hexdyn import results as hr
import matplotlib.pyplot as plt
import numpy as np

DUTY, SPEED, RISER = "gait.duty_factor", "motion.peak_speed", "terrain.riser_height"
# Published friction coefficients (docs/validation/friction.md cites each): a band and lines.
HUMAN_STAIR_ASCENT = (0.3, 0.5)
REFERENCE_LINES = (("towr", 0.5, "tab:green"), ("Crocoddyl quadruped", 0.7, "tab:purple"))


def transient_energy_share(run):
    """(transient energy, total energy) of a kept run by the rule its /meta energy_rule names
    (hexdyn.results.energy_by_rule; a version-2 file's is the trapezoid): the integral of the
    joints' |power| over each interval [t_k, t_k+1], a half of it counted to each end, summed
    over the samples where some leg is in its touchdown transient (phase 1), and over all
    samples, so that the total is the run's /energy/total."""
    t = np.asarray(run["/time"], dtype=float)
    if len(t) < 2:
        return 0.0, 0.0
    rule = run.meta.get("energy_rule", hr.ENERGY_RULE_TRAPEZOID)
    kind = run["/sample_kind"] if "/sample_kind" in run else None
    interval = hr.energy_by_rule(t, run["/power/per_joint"], kind, rule,
                                 per_interval=True).sum(axis=1)
    phase = np.asarray(run["/contacts/phase"])
    transient = (phase == hr.PHASE_IMPACT).any(axis=1).astype(float)
    e_tr = 0.5 * np.sum(interval * (transient[:-1] + transient[1:]))
    return float(e_tr), float(np.sum(interval))


def per_leg_support_peaks(run):
    """The largest required friction over the support samples each leg binds (NaN where it
    binds none): the support peak by leg."""
    mu = np.asarray(run["/contacts/required_friction"], dtype=float)
    leg = np.asarray(run["/contacts/required_friction_leg"])
    support = ~(np.asarray(run["/contacts/phase"]) == hr.PHASE_IMPACT).any(axis=1)
    out = np.full(len(hr.leg_names(run)), np.nan)
    for k in range(len(out)):
        sel = support & (leg == k) & np.isfinite(mu)
        if sel.any():
            out[k] = mu[sel].max()
    return out


def leg_text(row, k):
    """The name of leg k (0-based) of a row's robot; "-" for none (-1)."""
    return row["legs"][int(k)] if 0 <= int(k) < len(row["legs"]) else "-"


def sweep_legs(sw):
    """The leg names of the sweep's robot (one robot per sweep), as its first kept run of a
    computed scenario stores them; () when it keeps none."""
    for i in range(sw.size):
        if sw.ok[i]:
            return hr.leg_names(sw.run(i))
    return ()


def study_rows(sw):
    """One dict per scenario: axis values, table metrics, the robot's leg names ("legs") and
    the kept runs' derived values."""
    t = sw.table
    legs = sweep_legs(sw)
    rows = []
    for i in range(sw.size):
        s = sw.scenario(i)
        row = {"id": t["id"][i], "duty_factor": s[DUTY], "peak_speed": s[SPEED],
               "riser": s[RISER], "status": sw.status_names[i], "legs": legs}
        for name in ("required_friction_support", "required_friction_support_leg",
                     "required_friction_support_time", "required_friction_transient",
                     "required_friction_transient_leg", "required_friction_transient_time",
                     "no_friction_samples", "peak_utilized_friction", "slip_samples",
                     "relaxed_gait_samples", "energy"):
            row[name] = t[name][i]
        row["leg_peaks"] = np.full(len(legs), np.nan)
        row["transient_share"] = np.nan
        if sw.ok[i]:
            run = sw.run(i)
            row["leg_peaks"] = per_leg_support_peaks(run)
            e_tr, e = transient_energy_share(run)
            row["transient_share"] = e_tr / e if e > 0 else np.nan
        rows.append(row)
    return rows


def axis_values(rows, key):
    return sorted({r[key] for r in rows})


def draw_references(ax, mu_scene):
    ax.axhspan(*HUMAN_STAIR_ASCENT, color="0.85", zorder=0, label="human stair ascent 0.3-0.5")
    for label, mu, color in REFERENCE_LINES:
        ax.axhline(mu, color=color, lw=1, ls=":", label=f"{label} mu = {mu}")
    ax.axhline(mu_scene, color="tab:red", lw=1, ls="--", label=f"scene mu = {mu_scene}")


def plot_grid(rows, outdir, name, title, panels, ylabel, references=None):
    """A row of panels per riser, one column per (metric, leg metric, column title) of
    `panels`, x the peak speed, one line per duty factor."""
    risers, duties = axis_values(rows, "riser"), axis_values(rows, "duty_factor")
    fig, axes = plt.subplots(len(risers), len(panels), figsize=(5.2 * len(panels),
                             2.9 * len(risers)), squeeze=False, sharex=True)
    colors = plt.get_cmap("viridis")(np.linspace(0, 0.9, len(duties)))
    for r_i, riser in enumerate(risers):
        for c_i, (metric, leg_metric, column) in enumerate(panels):
            ax = axes[r_i, c_i]
            if references is not None:
                draw_references(ax, references)
            for d_i, duty in enumerate(duties):
                sel = sorted((r for r in rows if r["riser"] == riser and r["duty_factor"] == duty),
                             key=lambda r: r["peak_speed"])
                x = np.array([r["peak_speed"] for r in sel])
                y = np.array([r[metric] for r in sel], dtype=float)
                ax.plot(x, y, "o-", color=colors[d_i], label=f"duty {fraction_text(duty)}")
                if leg_metric:
                    for r, xv, yv in zip(sel, x, y):
                        if np.isfinite(yv):
                            ax.annotate(leg_text(r, r[leg_metric]), (xv, yv), fontsize=6,
                                        xytext=(2, 2), textcoords="offset points")
            ax.set_title(f"riser {riser * 100:.0f} cm: {column}", fontsize=9)
            ax.set_ylabel(ylabel)
            if references is not None:  # mu spans 0 to hundreds: linear below 0.1
                ax.set_yscale("symlog", linthresh=0.1)
            ax.grid(alpha=0.3)
            if r_i == len(risers) - 1:
                ax.set_xlabel("peak speed [m/s]")
    axes[0, -1].legend(fontsize=6, loc="upper left")
    fit_suptitle(fig, title)
    fig.tight_layout()
    return save_atomically(fig, outdir, name)


def write_csv(rows, path):
    header = ["id", "duty_factor", "peak_speed", "riser", "status", "mu_support", "leg_support",
              "t_support", "mu_transient", "leg_transient", "t_transient",
              *[f"mu_support_{leg}" for leg in (rows[0]["legs"] if rows else ())],
              "no_friction_samples",
              "peak_utilized_friction", "slip_samples", "relaxed_gait_samples", "energy",
              "transient_energy_share"]
    out = []
    for r in rows:
        out.append([r["id"], r["duty_factor"], r["peak_speed"], r["riser"], r["status"],
                    r["required_friction_support"], leg_text(r, r["required_friction_support_leg"]),
                    r["required_friction_support_time"], r["required_friction_transient"],
                    leg_text(r, r["required_friction_transient_leg"]),
                    r["required_friction_transient_time"], *r["leg_peaks"],
                    r["no_friction_samples"], r["peak_utilized_friction"], r["slip_samples"],
                    r["relaxed_gait_samples"], r["energy"], r["transient_share"]])
    write_csv_atomically(path, header, out)


def print_table(rows):
    print("| riser [m] | duty | speed [m/s] | mu* support (leg) | mu* transient (leg) "
          "| no-mu samples | transient energy share |")
    print("|---|---|---|---|---|---|---|")
    for r in sorted(rows, key=lambda r: (r["riser"], r["duty_factor"], r["peak_speed"])):
        print(f"| {r['riser']:.2f} | {fraction_text(r['duty_factor'])} | {r['peak_speed']:.2f} "
              f"| {r['required_friction_support']:.3f} "
              f"({leg_text(r, r['required_friction_support_leg'])}) "
              f"| {r['required_friction_transient']:.3f} "
              f"({leg_text(r, r['required_friction_transient_leg'])}) "
              f"| {r['no_friction_samples']} | {100 * r['transient_share']:.1f} % |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("sweep")
    ap.add_argument("outdir")
    ap.add_argument("--name", default=None)
    ap.add_argument("--table", action="store_true")
    args = ap.parse_args()
    sw = hr.open_sweep(args.sweep)
    keys = [a.key for a in sw.axes]
    for key in (DUTY, SPEED, RISER):
        if key not in keys:
            ap.error(f"{args.sweep}: no axis {key} (axes: {', '.join(keys)})")
    name = args.name or sw.meta.get("name", "friction")
    os.makedirs(args.outdir, exist_ok=True)
    rows = study_rows(sw)
    mu_scene = float(sw.config.get("contact", {}).get("friction_coefficient", np.nan))
    plot_grid(rows, args.outdir, f"{name}_required.png",
              "Required friction: the least mu for which the rows admit a force distribution "
              "(largest over support samples, left, and touchdown transients, right; label: "
              "binding leg)",
              (("required_friction_support", "required_friction_support_leg", "support"),
               ("required_friction_transient", "required_friction_transient_leg",
                "touchdown transients")), "required mu", references=mu_scene)
    for r in rows:
        r["transient_percent"] = 100 * r["transient_share"]
    plot_grid(rows, args.outdir, f"{name}_transient_energy.png",
              "Share of the energy spent in touchdown transients (samples with a leg in phase "
              "impact)", (("transient_percent", None, "transient energy / total"),), "share [%]")
    write_csv(rows, os.path.join(args.outdir, f"{name}.csv"))
    if args.table:
        print_table(rows)


if __name__ == "__main__":
    main()
