#!/usr/bin/python3
"""Figures and table of the quadruped study (pipelines/quadrupeds.sh,
docs/validation/quadrupeds.md): hexdyn sweeps of Solo-12 and ANYmal C, crawl and trot, on flat
ground over speed and on stairs over riser x speed, read with the package's reader.

    /usr/bin/python3 analysis/plot_quadrupeds.py OUTDIR SWEEP.h5 [SWEEP.h5 ...]

Each sweep file is one robot, gait and terrain: the robot from its base scene's robot.urdf, the
gait from gait.pattern (wave on four legs: the crawl) and gait.duty_factor, the terrain from
terrain.type; its axes are motion.peak_speed and, on stairs, terrain.riser_height (flat ground:
riser 0). Each scenario is one of three verdicts:
  climbs    computed (status ok) with no relaxed sample outside touchdowns
            (/scenarios/relaxed_gait_samples 0): within the drives' torque bounds and the
            scene's friction on every sample outside touchdown transients;
  relaxed   computed, but some sample outside touchdowns relaxed (the count is drawn);
  failed    not computed (status reach, planning, ...; its message is in the table).
Writes
  OUTDIR/quadrupeds_cot_speed.png   /scenarios/cost_of_transport (mechanical, solid) and
                                    cost_of_transport_electrical (dashed) against speed on flat
                                    ground, a panel per robot, a colour per gait;
  OUTDIR/quadrupeds_cot_riser.png   the same against riser height on stairs, a panel per robot
                                    and gait, a colour per speed;
  OUTDIR/quadrupeds_envelope.png    the climbable envelope: every stairs scenario at its riser
                                    and speed, coloured by its verdict, a panel per robot and
                                    gait;
  OUTDIR/quadrupeds_friction.png    /scenarios/required_friction_support (the largest required
                                    friction outside touchdowns) against speed (flat) and riser
                                    (stairs), with the scenes' mu;
  OUTDIR/quadrupeds_thermal.png     /scenarios/peak_winding_temperature_max, same axes, with the
                                    winding limit;
  OUTDIR/quadrupeds.csv             one line per scenario of every file: robot, gait, terrain,
                                    riser, speed, status, verdict, relaxed and failed counts,
                                    distance, energies, both costs of transport, required
                                    friction and its leg, peak winding temperature, time to the
                                    winding limit, the sweep and scenario id, the message;
  OUTDIR/quadrupeds_table.txt        the CSV's main columns as a Markdown table.
Filled markers climb; hollow markers relax; failed scenarios have no value and are listed in
the panel.
"""

import argparse
import math
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, fraction_text, save_atomically, write_csv_atomically
from hexdyn import open_sweep
from matplotlib.patches import Rectangle
import matplotlib.pyplot as plt
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
import numpy as np

SPEED, RISER = "motion.peak_speed", "terrain.riser_height"
ROBOT_NAMES = {"solo12": "Solo-12", "anymal_c": "ANYmal C"}
GAIT_COLORS = {"crawl": "tab:blue", "trot": "tab:orange"}
VERDICT_COLORS = {"climbs": "tab:green", "relaxed": "tab:orange", "failed": "tab:red"}
COLUMNS = ["robot", "gait", "duty_factor", "terrain", "riser_height", "peak_speed", "status",
           "verdict", "relaxed_gait_samples", "relaxed_samples", "failed_samples", "distance",
           "energy", "energy_electrical", "cost_of_transport", "cost_of_transport_electrical",
           "required_friction_support", "required_friction_support_leg",
           "peak_winding_temperature_max", "time_to_winding_limit_min", "sweep", "id", "message"]


def robot_name(config):
    """Solo-12, ANYmal C, or the URDF's file stem."""
    stem = os.path.splitext(os.path.basename(config["robot"]["urdf"]))[0]
    return ROBOT_NAMES.get(stem, stem)


def gait_name(config):
    """crawl for the wave gait (docs/theory/stages.md#gait-patterns), else the pattern's name."""
    pattern = config["gait"].get("pattern", "wave")
    return "crawl" if pattern == "wave" else pattern


def verdict(status, relaxed_gait):
    if status != "ok":
        return "failed"
    return "climbs" if relaxed_gait == 0 else "relaxed"


def read_study(path):
    """One sweep file as a dict: robot, gait, beta, terrain, mu, winding limit and its rows."""
    sw = open_sweep(path)
    cfg = sw.config
    limits = [j.get("winding_temperature_limit", math.nan)
              for j in cfg.get("actuators", {}).get("joints", {}).values()]
    study = {"robot": robot_name(cfg), "gait": gait_name(cfg),
             "beta": float(cfg["gait"]["duty_factor"]), "terrain": cfg["terrain"]["type"],
             "mu": float(cfg["contact"]["friction_coefficient"]),
             "winding_limit": min(limits) if limits else math.nan,
             "sweep": sw.meta.get("name", os.path.basename(path)), "rows": []}
    t = sw.table
    for i in range(sw.size):
        sc = sw.scenario(i)
        stairs = study["terrain"] == "stairs"
        riser = sc.get(RISER, cfg["terrain"].get("riser_height", 0.0)) if stairs else 0.0
        speed = sc.get(SPEED, cfg["motion"]["peak_speed"])
        row = {"riser_height": float(riser), "peak_speed": float(speed),
               "status": sw.status_names[i], "id": t["id"][i], "message": t["message"][i]}
        for key in COLUMNS:
            if key not in row and key in t:
                row[key] = t[key][i]
        row["verdict"] = verdict(row["status"], int(row["relaxed_gait_samples"]))
        study["rows"].append(row)
    return study


def cell(value):
    """A CSV cell: floats with every digit (repr), strings as they are."""
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, (np.integer,)):
        return str(int(value))
    return str(value)


def table_rows(studies):
    out = []
    for s in studies:
        for r in s["rows"]:
            full = dict(r, robot=s["robot"], gait=s["gait"], duty_factor=s["beta"],
                        terrain=s["terrain"], sweep=s["sweep"])
            out.append([cell(full.get(k, "")) for k in COLUMNS])
    return out


def short(value, digits=3):
    v = float(value)
    return "-" if not math.isfinite(v) else f"{v:.{digits}g}"


def markdown_table(studies):
    lines = ["| robot | gait | terrain | riser [m] | speed [m/s] | verdict (status) | relaxed "
             "outside touchdowns / all | CoT | CoT el. | μ required | T_w peak [°C] | message |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in studies:
        for r in s["rows"]:
            msg = str(r["message"]).replace("|", "/")
            msg = msg if len(msg) <= 90 else msg[:87] + "..."
            gait = f"{s['gait']} β={fraction_text(s['beta'])}"
            lines.append(
                f"| {s['robot']} | {gait} | {s['terrain']} | {r['riser_height']:g} | "
                f"{r['peak_speed']:g} | {r['verdict']} ({r['status']}) | "
                f"{int(r['relaxed_gait_samples'])} / {int(r['relaxed_samples'])} | "
                f"{short(r['cost_of_transport'])} | {short(r['cost_of_transport_electrical'])} | "
                f"{short(r['required_friction_support'])} | "
                f"{short(r['peak_winding_temperature_max'], 4)} | {msg} |")
    return "\n".join(lines) + "\n"


def draw_series(ax, rows, x_key, y_key, color, style="-", label=None):
    """A line through the computed rows (failed ones have no value), filled markers where the
    scenario climbs, hollow where it relaxes; returns the failed rows."""
    rows = sorted(rows, key=lambda r: r[x_key])
    done = [r for r in rows if r["verdict"] != "failed"]
    x = np.array([r[x_key] for r in done])
    y = np.array([float(r[y_key]) for r in done])
    ax.plot(x, y, style, color=color, label=label, lw=1.2)
    for climbs in (True, False):
        sel = np.array([(r["verdict"] == "climbs") == climbs for r in done], dtype=bool)
        if sel.any():
            ax.plot(x[sel], y[sel], "o", ms=5, color=color,
                    markerfacecolor=color if climbs else "white")
    return [r for r in rows if r["verdict"] == "failed"]


def note_failed(ax, failed, x_key, unit, name="", color="tab:red"):
    """Marks the failed scenarios with crosses at the panel's foot, at their x, and returns a
    line naming their x values by status (for the axis label)."""
    if not failed:
        return ""
    xs = sorted({r[x_key] for r in failed})
    ax.plot(xs, [0.03] * len(xs), "x", color=color, ms=6, mew=1.5, clip_on=False,
            transform=ax.get_xaxis_transform())
    parts = []
    for st in sorted({r["status"] for r in failed}):
        values = sorted({r[x_key] for r in failed if r["status"] == st})
        parts.append(", ".join(f"{x:g}" for x in values) + f" {unit} ({st})")
    return (f"{name} " if name else "") + "failed (×): " + "; ".join(parts)


def label_with_notes(ax, label, notes):
    """The x axis label, the failed scenarios' lines under it."""
    notes = [n for n in notes if n]
    ax.set_xlabel("\n".join([label] + notes), fontsize=8 if notes else None)


def failed_counts(failed, total):
    """A line counting a stairs panel's failed scenarios by status (the envelope figure places
    them), for the axis label."""
    if not failed:
        return ""
    counts = {}
    for r in failed:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    return (f"failed: {len(failed)} of {total} scenarios ("
            + ", ".join(f"{n} {st}" for st, n in sorted(counts.items())) + ")")


def panel_grid(n_rows, n_cols, width=6.4, height=3.4):
    fig, axes = plt.subplots(n_rows, n_cols, figsize=(width * n_cols, height * n_rows),
                             squeeze=False)
    return fig, axes


def by_terrain(studies, terrain):
    return [s for s in studies if s["terrain"] == terrain]


def robots_of(studies):
    out = []
    for s in studies:
        if s["robot"] not in out:
            out.append(s["robot"])
    return out


def log_axis(ax):
    """A logarithmic y axis labelled with plain numbers."""
    ax.set_yscale("log")
    ax.yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(NullFormatter())


def outside_legend(ax):
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))


def legend_notes(ax):
    ax.plot([], [], "ko", ms=5, label="climbs")
    ax.plot([], [], "o", ms=5, color="k", markerfacecolor="white", label="relaxes outside\ntouchdowns")
    outside_legend(ax)


def plot_cot_speed(studies, outdir):
    flat = by_terrain(studies, "flat")
    robots = robots_of(flat)
    fig, axes = panel_grid(1, max(len(robots), 1), height=4.4)
    for ax, robot in zip(axes[0], robots):
        notes = []
        for s in (s for s in flat if s["robot"] == robot):
            c = GAIT_COLORS.get(s["gait"], "tab:gray")
            name = f"{s['gait']} β={fraction_text(s['beta'])}"
            failed = draw_series(ax, s["rows"], "peak_speed", "cost_of_transport", c, "-",
                                 f"{name}, mechanical")
            draw_series(ax, s["rows"], "peak_speed", "cost_of_transport_electrical", c, "--",
                        f"{name}, electrical")
            notes.append(note_failed(ax, failed, "peak_speed", "m/s", s["gait"], c))
        log_axis(ax)
        label_with_notes(ax, "peak speed [m/s]", notes)
        ax.set_ylabel("cost of transport E/(m g d)")
        ax.set_title(f"{robot}, flat ground", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        legend_notes(ax)
    fit_suptitle(fig, "Cost of transport against speed (balanced trunk; solid: joints' |τω|, "
                 "dashed: electrical, drives only)")
    fig.tight_layout()
    return save_atomically(fig, outdir, "quadrupeds_cot_speed.png")


def speeds_of(study):
    return sorted({r["peak_speed"] for r in study["rows"]})


def stairs_panels(studies, height=3.4):
    """(fig, [(ax, study)]) a row per robot and a column per gait of the stairs studies."""
    stairs = by_terrain(studies, "stairs")
    robots = robots_of(stairs)
    gaits = []
    for s in stairs:
        if s["gait"] not in gaits:
            gaits.append(s["gait"])
    fig, axes = panel_grid(max(len(robots), 1), max(len(gaits), 1), height=height)
    cells = []
    for s in stairs:
        ax = axes[robots.index(s["robot"])][gaits.index(s["gait"])]
        ax.set_title(f"{s['robot']}, {s['gait']} β={fraction_text(s['beta'])}, stairs",
                     fontsize=10)
        cells.append((ax, s))
    return fig, cells


def plot_cot_riser(studies, outdir):
    fig, cells = stairs_panels(studies)
    for ax, s in cells:
        colors = plt.cm.viridis(np.linspace(0.0, 0.85, max(len(speeds_of(s)), 1)))
        failed = []
        for v, c in zip(speeds_of(s), colors):
            rows = [r for r in s["rows"] if r["peak_speed"] == v]
            failed += draw_series(ax, rows, "riser_height", "cost_of_transport", c, "-",
                                  f"{v:g} m/s")
            draw_series(ax, rows, "riser_height", "cost_of_transport_electrical", c, "--")
        log_axis(ax)
        label_with_notes(ax, "riser height [m]", [failed_counts(failed, len(s["rows"]))])
        ax.set_ylabel("cost of transport")
        ax.grid(True, which="both", alpha=0.3)
        legend_notes(ax)
    fit_suptitle(fig, "Cost of transport against riser height (solid: mechanical, dashed: "
                 "electrical; filled: climbs, hollow: relaxes)")
    fig.tight_layout()
    return save_atomically(fig, outdir, "quadrupeds_cot_riser.png")


def plot_envelope(studies, outdir):
    fig, cells = stairs_panels(studies, height=4.6)
    for ax, s in cells:
        speeds = speeds_of(s)
        risers = sorted({r["riser_height"] for r in s["rows"]})
        for r in s["rows"]:
            x, y = speeds.index(r["peak_speed"]), risers.index(r["riser_height"])
            ax.add_patch(Rectangle((x - 0.5, y - 0.5), 1.0, 1.0, lw=0.5, edgecolor="w",
                                   facecolor=VERDICT_COLORS[r["verdict"]]))
            label = {"climbs": "", "relaxed": str(int(r["relaxed_gait_samples"])),
                     "failed": r["status"]}[r["verdict"]]
            ax.annotate(label, (x, y), ha="center", va="center", fontsize=6)
        ax.set_xticks(range(len(speeds)), [f"{v:g}" for v in speeds])
        ax.set_yticks(range(len(risers)), [f"{v:g}" for v in risers], fontsize=7)
        ax.set_xlim(-0.5, len(speeds) - 0.5)
        ax.set_ylim(-0.5, len(risers) - 0.5)
        ax.set_xlabel("peak speed [m/s]")
        ax.set_ylabel("riser height [m]")
        for name, color in VERDICT_COLORS.items():
            ax.add_patch(Rectangle((0, 0), 0, 0, facecolor=color, label=name))
        outside_legend(ax)
    fit_suptitle(fig, "Climbable envelope: climbs = computed with no relaxed sample outside "
                 "touchdowns (torque bounds and μ met); relaxed: the count of such samples; "
                 "failed: the status")
    fig.tight_layout()
    return save_atomically(fig, outdir, "quadrupeds_envelope.png")


def plot_metric(studies, outdir, key, ylabel, title, name, reference, log=False):
    """A row per robot: flat ground against speed (a line per gait) and stairs against riser
    (a line per gait and speed); `reference(study)` a horizontal line's (value, label)."""
    robots = robots_of(studies)
    fig, axes = panel_grid(max(len(robots), 1), 2)
    notes = {}
    for s in studies:
        flat = s["terrain"] == "flat"
        ax = axes[robots.index(s["robot"])][0 if flat else 1]
        c = GAIT_COLORS.get(s["gait"], "tab:gray")
        gait = f"{s['gait']} β={fraction_text(s['beta'])}"
        if flat:
            failed = draw_series(ax, s["rows"], "peak_speed", key, c, "-", gait)
            notes.setdefault(ax, []).append(
                note_failed(ax, failed, "peak_speed", "m/s", s["gait"], c))
        else:
            for v, style in zip(speeds_of(s), ("-", "--", ":", "-.") * 4):
                rows = [r for r in s["rows"] if r["peak_speed"] == v]
                draw_series(ax, rows, "riser_height", key, c, style, f"{gait}, {v:g} m/s")
        value, label = reference(s)
        if math.isfinite(value):
            ax.axhline(value, color="k", lw=0.8, ls=":")
            ax.annotate(label, (0.98, value), xycoords=("axes fraction", "data"), ha="right",
                        va="bottom", fontsize=7)
        label_with_notes(ax, "peak speed [m/s]" if flat else "riser height [m]",
                         notes.get(ax, []))
        ax.set_ylabel(ylabel)
        ax.set_title(f"{s['robot']}, {'flat ground' if flat else 'stairs'}", fontsize=10)
        if log:
            log_axis(ax)
        ax.grid(True, which="both", alpha=0.3)
        outside_legend(ax)
    fit_suptitle(fig, title)
    fig.tight_layout()
    return save_atomically(fig, outdir, name)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("sweeps", nargs="+")
    args = ap.parse_args()
    if not os.path.isdir(args.outdir):
        sys.exit(f"plot_quadrupeds.py: error: OUTDIR: got '{args.outdir}', expected a folder")
    studies = [read_study(p) for p in args.sweeps]
    write_csv_atomically(os.path.join(args.outdir, "quadrupeds.csv"), COLUMNS,
                         table_rows(studies))
    tmp = os.path.join(args.outdir, f".quadrupeds_table.txt.tmp.{os.getpid()}")
    with open(tmp, "w") as f:
        f.write(markdown_table(studies))
    os.replace(tmp, os.path.join(args.outdir, "quadrupeds_table.txt"))
    plot_cot_speed(studies, args.outdir)
    plot_cot_riser(studies, args.outdir)
    plot_envelope(studies, args.outdir)
    plot_metric(studies, args.outdir, "required_friction_support",
                "required friction",
                "Required friction (/contacts/required_friction, the largest outside touchdowns)",
                "quadrupeds_friction.png", lambda s: (s["mu"], f"scene μ = {s['mu']:g}"),
                log=True)
    plot_metric(studies, args.outdir, "peak_winding_temperature_max",
                "peak winding temperature [°C]",
                "Peak winding temperature over the joints (two-node thermal model, from ambient)",
                "quadrupeds_thermal.png",
                lambda s: (s["winding_limit"], f"winding limit {s['winding_limit']:g} °C"))
    counts = {}
    for s in studies:
        for r in s["rows"]:
            counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
    print("quadrupeds: " + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())),
          file=sys.stderr)


if __name__ == "__main__":
    main()
