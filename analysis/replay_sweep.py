#!/usr/bin/python3
"""The slip-and-impact study's table (pipelines/replay.sh, docs/validation/replay.md): one line
per hexdyn-replay/3 file of a directory, read with h5py.

    /usr/bin/python3 analysis/replay_sweep.py REPLAY_DIR OUT.csv [--table]

Each line: the replayed scene's duty factor, peak speed and surface friction (its resolved
/meta config_yaml, the scene as replayed); from /replay: whether the replay ran to the plan's
end and reached the top, the slip distance (sum over the feet and the largest foot's), the
energy lost to slip and to normal contact damping (touchdowns and support, summed over the
feet), each also as a share of the replay's joint energy /replay/energy (the integral of
sum |tau qdot|), that energy against the inverse dynamics' over the same span, the joints'
signed work and the balance of energy's residual, the trunk's position and orientation drift
at the end (replayed minus planned at the replay's last sample), the largest joint tracking
error, the integrator's steps and forced steps, the replay's wall time (/replay/seconds) and
the planning run's (/meta wall_time_s of the replayed result, when it is still there), and
the plan's relaxed support samples (allocation status relaxed or failed with no foot in its
touchdown transient: where the stored torques do not make the plan exact).
--table prints the main columns as a Markdown table on stdout.
"""

import argparse
import glob
import math
import os

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import fraction_text, write_csv_atomically
import h5py
import numpy as np
import yaml

COLUMNS = (
    "duty_factor", "peak_speed_mps", "mu_static", "mu_dynamic", "completed", "reached_top",
    "end_time_s", "plan_end_s", "slip_distance_m", "slip_distance_max_foot_m", "slip_energy_J",
    "touchdown_energy_J", "energy_J", "energy_inverse_dynamics_J", "energy_ratio",
    "slip_share", "touchdown_share", "actuator_work_J", "energy_residual_J", "drift_x_m",
    "drift_y_m", "drift_z_m", "drift_m", "orientation_drift_rad", "max_tracking_error_rad",
    "steps", "forced_steps", "step_s", "tolerance", "replay_seconds", "run_seconds",
    "plan_relaxed_support_samples", "message", "file")


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def replayed_scene(f):
    """The scene as replayed: the resolved YAML of the replay file's /meta."""
    return yaml.safe_load(text(f["meta"].attrs["config_yaml"]))


def plan_facts(path):
    """(wall time of the run [s], relaxed support samples, last instant [s]) of the replayed
    result file, NaNs when it is gone."""
    if not path or not os.path.isfile(path):
        return math.nan, math.nan, math.nan
    with h5py.File(path, "r") as r:
        status = np.asarray(r["solver/status"])
        impact = (np.asarray(r["contacts/phase"]) == 1).any(axis=1)
        return (float(r["meta"].attrs["wall_time_s"]), int(((status != 0) & ~impact).sum()),
                float(r["time"][-1]))


def read_replay_report(path):
    """The line of the table for one replay file (a dict keyed by COLUMNS)."""
    with h5py.File(path, "r") as f:
        scene = replayed_scene(f)
        rp = f["replay"]
        energy = float(rp["energy"][()])
        slip_e = float(np.sum(rp["slip_energy"][()]))
        touch_e = float(np.sum(rp["touchdown_energy"][()]))
        slip = np.asarray(rp["slip_distance"][()], dtype=float)
        drift = np.asarray(rp["final_position_error"][()], dtype=float)
        orient = np.asarray(rp["orientation_drift"][()], dtype=float)
        message = text(rp["message"][()])
        run_s, relaxed, plan_end = plan_facts(text(f["meta"].attrs["source_result"]))
        row = {
            "duty_factor": float(scene["gait"]["duty_factor"]),
            "peak_speed_mps": float(scene["motion"].get("peak_speed", math.nan)),
            "mu_static": float(scene["contact"]["static_friction"]),
            "mu_dynamic": float(scene["contact"]["dynamic_friction"]),
            "completed": int(message == ""),
            "reached_top": int(rp["reached_top"][()]),
            "end_time_s": float(f["time"][-1]),
            "plan_end_s": plan_end,
            "slip_distance_m": float(slip.sum()),
            "slip_distance_max_foot_m": float(slip.max()),
            "slip_energy_J": slip_e,
            "touchdown_energy_J": touch_e,
            "energy_J": energy,
            "energy_inverse_dynamics_J": float(rp["energy_inverse_dynamics"][()]),
            "slip_share": slip_e / energy if energy > 0 else math.nan,
            "touchdown_share": touch_e / energy if energy > 0 else math.nan,
            "actuator_work_J": float(rp["actuator_work"][()]),
            "energy_residual_J": float(rp["energy_residual"][()]),
            "drift_x_m": drift[0], "drift_y_m": drift[1], "drift_z_m": drift[2],
            "drift_m": float(np.linalg.norm(drift)),
            "orientation_drift_rad": float(np.linalg.norm(orient[-1])) if len(orient) else
            math.nan,
            "max_tracking_error_rad": float(rp["max_tracking_error"][()]),
            "steps": int(rp["steps"][()]),
            "forced_steps": int(rp["forced_steps"][()]),
            "step_s": float(scene["replay"]["step"]),
            "tolerance": float(scene["replay"]["tolerance"]),
            "replay_seconds": float(rp["seconds"][()]),
            "run_seconds": run_s,
            "plan_relaxed_support_samples": relaxed,
            "message": message,
            "file": os.path.basename(path),
        }
        row["energy_ratio"] = (energy / row["energy_inverse_dynamics_J"]
                               if row["energy_inverse_dynamics_J"] > 0 else math.nan)
        return row


def cell(value):
    if isinstance(value, float):
        return repr(value)
    return str(value)


def read_rows(directory):
    """Every replay file of `directory`, ordered by duty factor, speed and friction."""
    rows = [read_replay_report(p) for p in sorted(glob.glob(os.path.join(directory, "*.h5")))]
    rows.sort(key=lambda r: (r["duty_factor"], r["peak_speed_mps"], r["mu_static"]))
    return rows


def markdown_table(rows):
    head = ("| duty | speed [m/s] | μ | reached top | slip [m] | slip [J] | touchdown [J] | "
            "slip share | touchdown share | joint energy [J] (ID) | drift [mm] | "
            "residual / work | relaxed plan samples |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        top = "yes" if r["reached_top"] else ("no" if r["completed"] else "no (ended early)")
        lines.append(
            f"| {fraction_text(r['duty_factor'])} | {r['peak_speed_mps']:.2f} | "
            f"{r['mu_static']:.1f} | {top} | {r['slip_distance_m']:.3f} | "
            f"{r['slip_energy_J']:.3f} | {r['touchdown_energy_J']:.3f} | "
            f"{100 * r['slip_share']:.2f} % | {100 * r['touchdown_share']:.2f} % | "
            f"{r['energy_J']:.1f} ({r['energy_inverse_dynamics_J']:.1f}) | "
            f"{1e3 * r['drift_m']:.1f} | "
            f"{100 * abs(r['energy_residual_J'] / r['actuator_work_J']):.2f} % | "
            f"{r['plan_relaxed_support_samples']} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("replays", help="directory of hexdyn-replay/3 files")
    ap.add_argument("csv", help="the CSV to write")
    ap.add_argument("--table", action="store_true", help="print a Markdown table")
    args = ap.parse_args()
    rows = read_rows(args.replays)
    if not rows:
        raise SystemExit(f"replay_sweep.py: error: no .h5 file in {args.replays}")
    write_csv_atomically(args.csv, COLUMNS, [[cell(r[c]) for c in COLUMNS] for r in rows])
    if args.table:
        print(markdown_table(rows))


if __name__ == "__main__":
    main()
