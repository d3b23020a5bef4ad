#!/usr/bin/python3
"""Pareto plot of a hexdyn-study/1 file (analysis/study.py): cost against error.

    /usr/bin/python3 analysis/plot_study.py STUDY.h5 OUTDIR [--markdown] [--check]

Writes OUTDIR/pareto.png: one panel per error metric (impact peak, impact impulse,
energy, peak |tau|, RMS torque), wall time on a log x axis against relative error on a
log y axis, points coloured by category, the Pareto front of each category (the runs no
cheaper run of the category beats) drawn as a line, the default configuration starred
and labelled (fronts are drawn for the series over a grid or tolerance; the fidelity,
friction and solver rows are single choices, labelled instead), the study's targets
dashed (peak 1 %, energy 0.1 %, 5 % of the converged reference's cost). Errors of
exactly 0 (the adaptive grid samples the exact peak instant) are drawn on a dotted line
at the bottom of the panel. Friction rows are
measured against the exact cone on the same grid (hollow markers), every other row
against the converged reference. The sixth panel is wall time against samples. The
figure is saved under a temporary name and renamed when complete.

Prints the table of runs to stdout (--markdown: as a Markdown table) and the verdict.

--check also verifies the file (the smoke test): every /runs column present with one
value per row and a `units` attribute; one default row; each reference's own row has
zero error; every error finite and >= 0; the converged reference's floor below 1e-4
(energy, RMS torque) and 1e-3 (impulse); a uniform 0.05 s grid, if present, misses
every impact peak (error 1) and a rigid contact, if present, misses it by > 50 %; the
default's impact peak and energy errors within the targets and the verdict's pass
flags consistent with its numbers. Wall times are not checked (they are timings).
Prints one line per failure and exits 1 on any.
"""

import argparse
import math
import os
import sys


import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fit_suptitle, fit_title, save_atomically  # first: Agg
import hexdyn
import matplotlib.pyplot as plt
import numpy as np


METRICS = (  # column, title, target key in /verdict (or None)
    ("err_peak", "impact peak (sampled)", "target_peak"),
    ("err_impulse", "impact impulse (sampled)", None),
    ("err_energy", "energy", "target_energy"),
    ("err_tau_peak", "peak |τ|", None),
    ("err_tau_rms", "RMS torque", None),
)

STYLE = {  # category -> (colour, marker)
    "reference": ("0.45", "D"),
    "grid-uniform": ("tab:blue", "o"),
    "grid-adaptive": ("tab:orange", "s"),
    "grid-event-step": ("tab:olive", "^"),
    "fidelity": ("tab:red", "P"),
    "friction": ("tab:purple", "o"),
    "solver": ("tab:brown", "X"),
    "tolerance-active-set": ("tab:green", "v"),
    "tolerance-ipopt": ("tab:cyan", "v"),
}
# Categories of distinct models rather than a refinement series: each point is labelled,
# no front is drawn.
ANNOTATED = ("fidelity", "friction", "solver")
EXTRA_COLOURS = ("tab:pink", "tab:gray", "gold", "navy")


def read_study(path):
    """(rows: dict of column -> numpy array or list of str, verdict attrs, references)."""
    try:
        st = hexdyn.open_study(path)
    except (OSError, ValueError) as e:
        raise SystemExit(f"plot_study: {e}")
    return st.rows, st.verdict, st.references


def pareto_front(x, y):
    """Indices of the points no cheaper point beats, by increasing x."""
    order = np.lexsort((y, x))
    front, best = [], math.inf
    for i in order:
        if y[i] < best:
            front.append(i)
            best = y[i]
    return front


def style_of(category, extra):
    if category not in STYLE:
        STYLE[category] = (EXTRA_COLOURS[len(extra) % len(EXTRA_COLOURS)], "o")
        extra.append(category)
    return STYLE[category]


def study_scene(path):
    """The scene file the study ran (/meta scene_file), or None."""
    value = hexdyn.open_study(path).meta.get("scene_file")
    return None if value is None else str(value)


def plot(rows, verdict, refs, outdir, scene=None):
    labels, cats = rows["label"], rows["category"]
    wall = np.asarray(rows["wall_time_s"], dtype=float)
    is_default = np.asarray(rows["is_default"]).astype(bool)
    categories = list(dict.fromkeys(c for c in cats if c != "default"))
    ref_wall = float(verdict["reference_wall_time_s"])
    cost_line = float(verdict["target_cost"]) * ref_wall
    extra = []

    fig, axes = plt.subplots(2, 3, figsize=(16, 9.5))
    for ax, (col, title, target) in zip(axes.flat, METRICS):
        err = np.asarray(rows[col], dtype=float)
        ok = np.isfinite(err) & np.isfinite(wall)
        positive = err[ok & (err > 0)]
        smallest = min(([positive.min()] if positive.size else [1e-11])
                       + ([float(verdict[target])] if target else []))
        floor = max(10.0 ** (math.floor(math.log10(smallest)) - 1), 1e-14)
        shown = np.where(err > 0, err, floor)
        for cat in categories:
            colour, marker = style_of(cat, extra)
            idx = [i for i in range(len(cats)) if cats[i] == cat and ok[i]]
            if not idx:
                continue
            hollow = cat == "friction"
            ax.scatter(wall[idx], shown[idx], s=30, marker=marker,
                       facecolors="none" if hollow else colour, edgecolors=colour,
                       linewidths=1.2, zorder=3,
                       label=cat + (" (vs exact cone, same grid)" if hollow else ""))
            if cat in ANNOTATED:
                for i in (i for i in idx if err[i] > 0):  # labels at 0 would pile up
                    ax.annotate(labels[i][len(cat) + 1:] if labels[i].startswith(cat + " ")
                                else labels[i], (wall[i], shown[i]), textcoords="offset points",
                                xytext=(4, -9), fontsize=6.5, color=colour)
            elif cat != "reference":
                front = pareto_front(wall[idx], shown[idx])
                ax.plot(wall[idx][front], shown[idx][front], "-", color=colour, lw=1.0,
                        alpha=0.8, zorder=2)
        d = np.where(is_default & ok)[0]
        if d.size:
            i = d[0]
            ax.scatter([wall[i]], [shown[i]], s=220, marker="*", color="gold",
                       edgecolors="black", linewidths=1.0, zorder=5, label="default")
            ax.annotate(f"default\n{err[i]:.1e}" if err[i] > 0 else "default\nexact",
                        (wall[i], shown[i]), textcoords="offset points", xytext=(10, 8),
                        fontsize=8, fontweight="bold")
        ax.axhline(floor, color="0.6", ls=":", lw=0.8)
        ax.text(0.01, floor, " 0 (exact)", transform=ax.get_yaxis_transform(), fontsize=7,
                va="bottom", color="0.4")
        if target:
            ax.axhline(float(verdict[target]), color="crimson", ls="--", lw=1.0)
            ax.text(0.99, float(verdict[target]), f"target {float(verdict[target]):g} ",
                    transform=ax.get_yaxis_transform(), ha="right", va="bottom", fontsize=8,
                    color="crimson")
        ax.axvline(cost_line, color="crimson", ls="--", lw=1.0)
        ax.axvline(ref_wall, color="0.5", ls="-.", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        fit_title(ax, f"{title}: relative error", fontsize=10)
        ax.set_xlabel("wall time [s] (min over repeats)")
        ax.set_ylabel("relative error [-]")
        ax.grid(True, which="major", alpha=0.3)
        ax.text(cost_line, 1.0, f"{float(verdict['target_cost']):.0%} of ref.",
                transform=ax.get_xaxis_transform(), fontsize=7, color="crimson", ha="right",
                va="top", rotation=90)
        ax.text(ref_wall, 1.0, "converged ref.", transform=ax.get_xaxis_transform(),
                fontsize=7, color="0.4", ha="right", va="top", rotation=90)

    ax = axes.flat[5]
    samples = np.asarray(rows["samples"], dtype=float)
    for cat in categories:
        colour, marker = style_of(cat, extra)
        idx = [i for i in range(len(cats)) if cats[i] == cat]
        ax.scatter(samples[idx], wall[idx], s=25, marker=marker, color=colour, zorder=3)
    d = np.where(is_default)[0]
    if d.size:
        ax.scatter(samples[d], wall[d], s=220, marker="*", color="gold", edgecolors="black",
                   zorder=5)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("output samples [-]")
    ax.set_ylabel("wall time [s]")
    ax.set_title("cost against output samples", fontsize=10)
    ax.grid(True, which="major", alpha=0.3)

    handles, names = axes.flat[0].get_legend_handles_labels()
    seen = {}
    for a in axes.flat[:5]:
        for h, n in zip(*a.get_legend_handles_labels()):
            seen.setdefault(n, h)
    fig.legend(list(seen.values()), list(seen.keys()), loc="lower center",
               ncol=min(6, len(seen)), fontsize=8, frameon=False)
    word = {1: "pass", 0: "FAIL"}
    fit_suptitle(
        fig,
        f"hexdyn speed against error ({scene or 'the study scene'}). Default adaptive grid vs "
        "converged "
        f"reference: peak {float(verdict['err_peak']):.1e} ({word[int(verdict['pass_peak'])]}), "
        f"energy {float(verdict['err_energy']):.1e} ({word[int(verdict['pass_energy'])]}), "
        f"cost {float(verdict['cost_ratio']):.1%} of the reference "
        f"({word[int(verdict['pass_cost'])]})", fontsize=11)
    fig.tight_layout(rect=(0, 0.04, 1, 0.95))
    return save_atomically(fig, outdir, "pareto.png")


def fmt(v, kind="e"):
    v = float(v)
    if math.isnan(v):
        return "—"
    if kind == "e":
        return "0" if v == 0 else f"{v:.2e}"
    return f"{v:.4g}"


def table(rows, verdict, refs, markdown=False):
    cols = ("label", "reference", "samples", "wall_time_s") + tuple(m[0] for m in METRICS)
    head = ("run", "vs", "samples", "wall [s]", "peak", "impulse", "energy", "τ peak", "τ RMS")
    lines = []
    data = []
    for i in range(len(rows["label"])):
        data.append((rows["label"][i], rows["reference"][i], str(int(rows["samples"][i])),
                     fmt(rows["wall_time_s"][i], "g"))
                    + tuple(fmt(rows[c][i]) for c in cols[4:]))
    if markdown:
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "|".join(["---"] * 2 + ["---:"] * (len(head) - 2)) + "|")
        lines += ["| " + " | ".join(r) + " |" for r in data]
    else:
        widths = [max(len(h), *(len(r[j]) for r in data)) for j, h in enumerate(head)]
        lines.append("  ".join(h.ljust(w) if j < 2 else h.rjust(w)
                               for j, (h, w) in enumerate(zip(head, widths))))
        for r in data:
            lines.append("  ".join(c.ljust(w) if j < 2 else c.rjust(w)
                                   for j, (c, w) in enumerate(zip(r, widths))))
    conv = refs.get("converged", {})
    if "floor_err_energy" in conv:
        lines.append("")
        lines.append("converged reference: " + str(conv.get("overrides", ""))
                     + f"; {conv['samples']} samples, {float(conv['wall_time_s']):.4g} s; "
                     f"floor (check run: {conv.get('check_overrides', '')}): " + ", ".join(
                         f"{m[0][4:]} {fmt(conv['floor_' + m[0]])}" for m in METRICS))
    word = {1: "PASS", 0: "FAIL"}
    lines.append(
        f"verdict (default vs converged reference): impact peak {fmt(verdict['err_peak'])} "
        f"<= {float(verdict['target_peak']):g} {word[int(verdict['pass_peak'])]}; energy "
        f"{fmt(verdict['err_energy'])} <= {float(verdict['target_energy']):g} "
        f"{word[int(verdict['pass_energy'])]}; cost {float(verdict['wall_time_s']):.4g} s / "
        f"{float(verdict['reference_wall_time_s']):.4g} s = {float(verdict['cost_ratio']):.1%} "
        f"<= {float(verdict['target_cost']):.0%} {word[int(verdict['pass_cost'])]} (samples "
        f"{int(verdict['samples'])}/{int(verdict['reference_samples'])} = "
        f"{float(verdict['samples_ratio']):.1%})")
    return "\n".join(lines)


COLUMNS = ("label", "category", "reference", "overrides", "grid", "sample_step", "event_step",
           "impact_samples", "tolerance", "solver", "friction", "leg_inertia", "contact_model",
           "samples", "relaxed_samples", "failed_samples", "repeats", "wall_time_s", "energy_J",
           "tau_peak_Nm", "tau_rms_Nm", "err_peak", "err_impulse", "err_energy", "err_tau_peak",
           "err_tau_rms", "impacts_match", "is_default")


def check(path, rows, verdict, refs):
    """Failures (list of str) of the study file's invariants."""
    bad = []
    n = len(rows.get("label", []))
    units = hexdyn.open_study(path).units
    for c in COLUMNS:
        if c not in rows:
            bad.append(f"/runs/{c} missing")
        elif len(rows[c]) != n:
            bad.append(f"/runs/{c} has {len(rows[c])} values for {n} rows")
        elif c not in units:
            bad.append(f"/runs/{c} has no units attribute")
    if bad or n == 0:
        return bad or ["no rows"]
    labels = list(rows["label"])
    if int(np.sum(np.asarray(rows["is_default"]) == 1)) != 1 or labels.count("default") != 1:
        bad.append("not exactly one default row")
    for name in refs:
        if f"reference {name}" not in labels:
            bad.append(f"no row for reference {name}")
            continue
        i = labels.index(f"reference {name}")
        for m, _, _ in METRICS:
            if float(rows[m][i]) != 0.0:
                bad.append(f"reference {name} against itself: {m} = {float(rows[m][i])}")
    for m, _, _ in METRICS:
        e = np.asarray(rows[m], dtype=float)
        for i in np.where(~(np.isfinite(e) & (e >= 0)))[0]:
            bad.append(f"{labels[i]}: {m} = {e[i]} (expected finite and >= 0)")
    conv = refs.get("converged", {})
    for key, limit in (("floor_err_energy", 1e-4), ("floor_err_tau_rms", 1e-4),
                       ("floor_err_impulse", 1e-3)):
        if key not in conv:
            bad.append(f"/references/converged: no {key}")
        elif not float(conv[key]) <= limit:
            bad.append(f"converged reference not converged: {key} = {float(conv[key]):.3g} "
                       f"> {limit:g}")
    for i, lab in enumerate(labels):
        if (rows["grid"][i] == "uniform" and abs(float(rows["sample_step"][i]) - 0.05) < 1e-12
                and float(rows["err_peak"][i]) != 1.0):
            bad.append(f"{lab}: a uniform 0.05 s grid samples an impact peak "
                       f"(err_peak {float(rows['err_peak'][i]):.3g}, expected 1)")
        if rows["contact_model"][i] == "rigid" and not float(rows["err_peak"][i]) > 0.5:
            bad.append(f"{lab}: rigid contact err_peak {float(rows['err_peak'][i]):.3g}, "
                       f"expected > 0.5 (no transient)")
    v = {k: float(verdict[k]) for k in ("err_peak", "err_energy", "cost_ratio", "target_peak",
                                       "target_energy", "target_cost")}
    for flag, ok in (("pass_peak", v["err_peak"] <= v["target_peak"]),
                     ("pass_energy", v["err_energy"] <= v["target_energy"]),
                     ("pass_cost", v["cost_ratio"] <= v["target_cost"])):
        if int(verdict[flag]) != int(ok):
            bad.append(f"/verdict {flag} = {verdict[flag]} contradicts its numbers")
    if v["err_peak"] > v["target_peak"]:
        bad.append(f"default impact peak error {v['err_peak']:.3g} > {v['target_peak']:g}")
    if v["err_energy"] > v["target_energy"]:
        bad.append(f"default energy error {v['err_energy']:.3g} > {v['target_energy']:g}")
    return bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study", help="hexdyn-study/1 file")
    ap.add_argument("outdir", help="directory for pareto.png")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--check", action="store_true", help="also verify the file (exit 1 on failure)")
    args = ap.parse_args(argv)
    rows, verdict, refs = read_study(args.study)
    if not os.path.isdir(args.outdir):
        raise SystemExit(f"plot_study: output directory {args.outdir} does not exist")
    failures = check(args.study, rows, verdict, refs) if args.check else []
    path = plot(rows, verdict, refs, args.outdir, study_scene(args.study))
    print(table(rows, verdict, refs, args.markdown))
    print(f"plot_study: wrote {path}", file=sys.stderr)
    if args.check:
        for msg in failures:
            print(f"plot_study: check FAILED: {msg}", file=sys.stderr)
        print(f"plot_study: check: {'ok' if not failures else f'{len(failures)} failure(s)'}",
              file=sys.stderr)
        return 1 if failures else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
