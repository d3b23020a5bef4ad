#!/usr/bin/python3
"""Speed against error of the output grid across a stair sweep (docs/validation/grid-accuracy.md).

    /usr/bin/python3 bench/grid_accuracy.py [--grid {check,stairs}] [--hexdyn build/hexdyn]
        [--tolerances 0 1e-2 1e-3 1e-4] [--ranks 2] [--out DIR] [--check] [--page FILE]

Runs the grid's scenarios once per output-grid setting and once on a converged grid, each as
a `hexdyn sweep` on the same base (configs/sweeps/stairs_base.yaml over three treads of
travel, as configs/sweeps/stairs.yaml), and compares every scenario's figures with the
converged run's: energy (and so the cost of transport, E / (m g d) with the same m and d),
peak joint torque (the largest over the joints), peak total power and peak contact force.
Cost is each scenario's wall time and sample count. The settings:

  - `output.tolerance: T` for each T given (0: the grid as built, which is the default grid
    of 2dbb8e9 and earlier, not refined);
  - converged: 0.5 ms steps, 0.1 ms next to events, 400 intervals per touchdown transient,
    refined to 1e-6.

Grids: `check` is the 32 scenarios of the error-control check (riser 0.02 and 0.08 m, peak
speed 0.05 ... 0.20 m/s, duty factor 1/2, 2/3, 3/4, 5/6; tread 0.25 m); `stairs` is the
stair study's 512 (configs/sweeps/stairs.yaml: riser x tread x speed x duty factor).

Writes, in --out (default results/grid_accuracy/GRID): each sweep file, a table per scenario
(scenarios.csv), the summary as Markdown (summary.txt, also printed) and the figure
error_vs_cost.png. --check exits 1 unless, at output.tolerance 1e-4 (one of --tolerances),
every scenario's energy is within 1e-4 and its peak torque within 1e-3 of the converged run,
with the same status. Sets the root
permissions Open MPI needs when run as root.
"""

import argparse
import csv
import os
import subprocess
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "configs", "sweeps", "stairs_base.yaml")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
DEFAULT_TOLERANCE = 1e-2  # output.tolerance's default (core/scene.hpp kDefaultOutputTolerance)
CHECK_TOLERANCE = 1e-4  # --check: at this tolerance, energies within 1e-4, peak torques 1e-3
CONVERGED = {"output.sample_step": 0.0005, "output.event_step": 0.0001,
             "output.impact_samples": 400, "output.tolerance": 1e-6}
GRIDS = {
    "check": [("terrain.riser_height", "[0.02, 0.08]"),
              ("motion.peak_speed", "[0.05, 0.10, 0.15, 0.20]"),
              ("gait.duty_factor", "[1/2, 2/3, 3/4, 5/6]")],
    "stairs": [("terrain.riser_height", "{from: 0.0, to: 0.14, count: 8}"),
               ("terrain.tread_depth", "[0.20, 0.25, 0.30, 0.35]"),
               ("motion.peak_speed", "{from: 0.05, to: 0.20, count: 4}"),
               ("gait.duty_factor", "[1/2, 2/3, 3/4, 5/6]")],
}
# (dataset under /scenarios, label, reduce over joints)
FIGURES = [("energy", "energy", False), ("peak_torque", "peak torque", True),
           ("peak_power", "peak power", False), ("peak_contact_force", "peak contact force", False)]


def sweep_text(name, grid, settings):
    # The grid's accuracy is that of the energies and peaks; the required friction, which
    # none of them reads, is left out of these many-sample runs.
    lines = [f"name: {name}", f"base: {BASE}", "set:", "  motion.cycles: null",
             "  motion.travel.treads: 3", "  output.required_friction: false"]
    lines += [f"  {k}: {v!r}" for k, v in settings.items()]
    lines.append("axes:")
    for key, values in GRIDS[grid]:
        kind = "range" if values.startswith("{") else "values"
        lines += [f"  - key: {key}", f"    {kind}: {values}"]
    return "\n".join(lines) + "\n"


def run_sweep(hexdyn, ranks, text, out, work):
    path = os.path.join(work, os.path.basename(out) + ".yaml")
    with open(path, "w") as f:
        f.write(text)
    for leftover in (out, out + ".checkpoint"):
        if os.path.exists(leftover):
            os.remove(leftover)
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks), hexdyn, "sweep", path, "-o", out]
    proc = subprocess.run(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True)
    if proc.returncode != 0:
        sys.exit(f"grid_accuracy: {' '.join(cmd)} failed:\n{proc.stderr}")


def read(path):
    with h5py.File(path, "r") as f:
        s = f["scenarios"]
        d = {k: s[k][()] for k in ("status", "samples", "wall_time_s", "energy", "peak_torque",
                                   "peak_power", "peak_contact_force", "grid_energy_error",
                                   "grid_peak_error")}
        d["axes"] = [(s[f"axis_{i}"].attrs["key"], s[f"axis_{i}"][()])
                     for i in range(s["axis_index"].shape[1])]
    d["peak_torque"] = d["peak_torque"].max(axis=1)
    return d


def errors(run, ref):
    """Relative errors against the converged run, per figure (NaN where a scenario failed)."""
    ok = (run["status"] == 0) & (ref["status"] == 0)
    out = {}
    for key, _, _ in FIGURES:
        with np.errstate(invalid="ignore", divide="ignore"):
            out[key] = np.where(ok, (run[key] - ref[key]) / ref[key], np.nan)
    return out


def describe(x):
    a = np.abs(x[np.isfinite(x)])
    if a.size == 0:
        return "–"
    return f"{np.median(a):.2g} / {np.percentile(a, 90):.2g} / {a.max():.2g}"


def label(tol):
    return "as built (0)" if tol == 0 else f"{tol:g}" + (" (default)" if tol == DEFAULT_TOLERANCE
                                                        else "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", choices=sorted(GRIDS), default="check")
    ap.add_argument("--hexdyn", default=os.path.join(ROOT, "build", "hexdyn"))
    ap.add_argument("--tolerances", type=float, nargs="+", default=[0.0, 1e-2, 1e-3, 1e-4])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--out", help="output folder (default results/grid_accuracy/GRID)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless tolerance 1e-4 meets 1e-4 (energy), 1e-3 (peak torque)")
    args = ap.parse_args()
    out = args.out or os.path.join(ROOT, "results", "grid_accuracy", args.grid)
    os.makedirs(out, exist_ok=True)
    runs = {}
    with tempfile.TemporaryDirectory(prefix="hexdyn_grid_") as work:
        ref_path = os.path.join(out, "converged.h5")
        run_sweep(args.hexdyn, args.ranks, sweep_text("converged", args.grid, CONVERGED), ref_path,
                  work)
        ref = read(ref_path)
        for tol in args.tolerances:
            path = os.path.join(out, f"tolerance_{tol:g}.h5")
            run_sweep(args.hexdyn, args.ranks,
                      sweep_text(f"tolerance_{tol:g}", args.grid, {"output.tolerance": tol}), path,
                      work)
            runs[tol] = read(path)

    n = len(ref["status"])
    computed = int(((ref["status"] == 0)).sum())
    lines = [f"Grid `{args.grid}`: {n} scenarios ({computed} computed on the converged grid), "
             f"{args.ranks} ranks. Errors are relative to the converged run (0.5 ms steps, 0.1 ms "
             f"next to events, 400 intervals per transient, refined to 1e-6), as median / 90th "
             f"percentile / largest over the scenarios; cost is the scenarios' summed wall time "
             f"and samples.", "",
             "| output.tolerance | energy (and CoT) | peak torque | peak power | peak contact "
             "force | samples | wall [s] | largest estimate, energy / peak |",
             "|---|---|---|---|---|---:|---:|---|"]
    errs = {tol: errors(r, ref) for tol, r in runs.items()}
    for tol, r in runs.items():
        e = errs[tol]
        ok = r["status"] == 0
        lines.append(f"| {label(tol)} | " + " | ".join(describe(e[k]) for k, _, _ in FIGURES) +
                     f" | {int(r['samples'][ok].sum())} | {r['wall_time_s'][ok].sum():.1f} | "
                     f"{np.nanmax(r['grid_energy_error']):.2g} / "
                     f"{np.nanmax(r['grid_peak_error']):.2g} |")
    ok = ref["status"] == 0
    lines.append(f"| converged | – | – | – | – | {int(ref['samples'][ok].sum())} | "
                 f"{ref['wall_time_s'][ok].sum():.1f} | – |")
    failures = []
    if args.check and CHECK_TOLERANCE not in errs:
        sys.exit("grid_accuracy: --check needs 1e-4 among --tolerances")
    if CHECK_TOLERANCE in errs:
        e = errs[CHECK_TOLERANCE]
        bad_e = np.abs(np.nan_to_num(e["energy"])) > 1e-4
        bad_t = np.abs(np.nan_to_num(e["peak_torque"])) > 1e-3
        lines += ["", f"At output.tolerance 1e-4: {int(bad_e.sum())} of {computed} scenarios with "
                  f"an energy error over 1e-4, {int(bad_t.sum())} with a peak-torque error over "
                  f"1e-3."]
        failures = [i for i in range(n) if bad_e[i] or bad_t[i]]
        stat_same = (runs[CHECK_TOLERANCE]["status"] == ref["status"]).all()
        if not stat_same:
            lines.append("Statuses differ from the converged run's.")
            failures.append(-1)
    summary = "\n".join(lines)
    print(summary)
    with open(os.path.join(out, "summary.txt"), "w") as f:
        f.write(summary + "\n")

    with open(os.path.join(out, "scenarios.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([k for k, _ in ref["axes"]] + ["tolerance", "samples", "wall_time_s"] +
                   [f"{k}_error" for k, _, _ in FIGURES] + ["energy_estimate", "peak_estimate"])
        for tol, r in runs.items():
            for i in range(n):
                w.writerow([v[i] for _, v in ref["axes"]] + [tol, r["samples"][i],
                                                              r["wall_time_s"][i]] +
                           [errs[tol][k][i] for k, _, _ in FIGURES] +
                           [r["grid_energy_error"][i], r["grid_peak_error"][i]])

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    markers = "os^vDP"
    base = runs.get(0.0, ref)  # cost against the grid as built when it ran
    base_name = "the grid as built" if 0.0 in runs else "the converged grid"
    for (tol, r), m in zip(runs.items(), markers):
        ok = (r["status"] == 0) & (base["status"] == 0)
        cost = r["wall_time_s"][ok] / base["wall_time_s"][ok]
        for ax, key in zip(axes, ("energy", "peak_torque")):
            err = np.maximum(np.abs(errs[tol][key][ok]), 1e-9)  # exact ones drawn at 1e-9
            ax.loglog(cost, err, m, ms=4, alpha=0.7, label=f"output.tolerance {label(tol)}")
    for ax, key, limit in zip(axes, ("energy", "peak torque"), (1e-4, 1e-3)):
        ax.axhline(limit, color="k", lw=0.8, ls="--")
        ax.set_xlabel(f"scenario wall time relative to {base_name} [1]")
        ax.set_ylabel(f"|relative {key} error| [1]")
        ax.set_title(f"{key}: each scenario against the converged grid", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    final = os.path.join(out, "error_vs_cost.png")
    tmp = os.path.join(out, f".error_vs_cost.png.tmp.{os.getpid()}")
    fig.savefig(tmp, format="png", dpi=130)
    os.replace(tmp, final)
    print(f"\ngrid_accuracy: wrote {out}/summary.txt, scenarios.csv, error_vs_cost.png",
          file=sys.stderr)
    if args.check and failures:
        print("grid_accuracy: check FAILED", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
