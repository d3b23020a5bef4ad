#!/usr/bin/python3
"""The slip-and-impact pipeline, reduced (pipelines/replay.sh --quick; docs/validation/replay.md),
and the speed-against-error script on two steps (analysis/replay_convergence.py), checked
against readings of their files made here with h5py and csv:

  - the pipeline writes its CSV, table and figure, one replay per plan and surface;
  - each CSV line's duty factor, speed and mu are the replayed scene's, and its mu the one the
    file was replayed on (contact.static_friction and dynamic_friction of the replay file);
  - its slip distance, slip energy, touchdown energy and joint energy are the last samples of
    the replay file's cumulative series, and the shares their ratios;
  - its inverse-dynamics energy is the trapezoid integral of sum |tau qdot| of the planned
    result over the replayed span, its drift the replayed minus the planned trunk position at
    the last sample, and reached_top the arrival rule of docs/theory/replay.md recomputed from
    the stored poses (half a tread, half a riser, 0.5 rad of tilt);
  - the balance of energy closes: the joints' work less the gains in kinetic, potential and
    contact-spring energy (K d^(e+1)/(e+1) of the stored penetrations) and the dissipated
    energies is the stored residual;
  - on each plan, the slipperier surface slips farther;
  - the convergence script's reference line has no error and the other line's drift error is
    the distance between the two files' drifts;
  - its --replay-set changes the replays and not the plan: a replay-only mu of 0.2 slips
    farther than the scene's 0.3, the plan file keeps 0.3 and the replay file records 0.2;
  - the two-binary comparison (analysis/replay_against_binary.py), given the same binary
    twice, prints equal columns, and its drift error is the distance between the final trunk
    positions of the convergence script's two replays.

usage: test_replay.py --hexdyn BUILD/hexdyn --source SOURCE_DIR   (PYTHONPATH=BUILD/python)
"""

import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml

failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def same(a, b, rel=1e-12, abs_tol=1e-15):
    return math.isclose(float(a), float(b), rel_tol=rel, abs_tol=abs_tol)


def rotation(wxyz):
    w, x, y, z = wxyz / np.linalg.norm(wxyz)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def check_line(row, path):
    """The CSV line `row` against the replay file `path` and its planned result."""
    name = os.path.basename(path)
    with h5py.File(path, "r") as f:
        scene = yaml.safe_load(f["meta"].attrs["config_yaml"])
        mu = float(name.rsplit("_mu", 1)[1][:-3])
        check(scene["contact"]["static_friction"] == mu == scene["contact"]["dynamic_friction"],
              f"{name} replayed on mu = {mu}")
        check(same(row["duty_factor"], scene["gait"]["duty_factor"]) and
              same(row["peak_speed_mps"], scene["motion"]["peak_speed"]) and
              same(row["mu_static"], mu), f"{name} axis values")
        last = {k: float(np.sum(f[k][-1])) for k in ("contacts/slip_distance", "energy/slip",
                                                     "energy/contact_damping", "energy/actuator")}
        for col, key in (("slip_distance_m", "contacts/slip_distance"),
                         ("slip_energy_J", "energy/slip"),
                         ("touchdown_energy_J", "energy/contact_damping"),
                         ("energy_J", "energy/actuator")):
            check(same(row[col], last[key], rel=1e-9), f"{name} {col} = last of /{key}",
                  f"{row[col]} vs {last[key]}")
        e = last["energy/actuator"]
        check(same(row["slip_share"], last["energy/slip"] / e, rel=1e-9) and
              same(row["touchdown_share"], last["energy/contact_damping"] / e, rel=1e-9),
              f"{name} shares of the joint energy")
        t = f["time"][()]
        with h5py.File(f["meta"].attrs["source_result"], "r") as r:
            n = len(t)
            check(np.array_equal(r["time"][:n], t), f"{name} samples at the plan's instants")
            p = np.abs(r["joints/torque"][:n] * r["joints/velocity"][:n]).sum(axis=1)
            e_id = float(np.sum(0.5 * np.diff(t) * (p[1:] + p[:-1])))
            check(same(row["energy_inverse_dynamics_J"], e_id, rel=1e-9),
                  f"{name} inverse-dynamics energy over the replayed span",
                  f"{row['energy_inverse_dynamics_J']} vs {e_id}")
            d = f["base/position"][-1] - r["base/position"][n - 1]
            check(np.allclose([float(row[f"drift_{a}_m"]) for a in "xyz"], d,
                              rtol=0, atol=1e-12), f"{name} drift at the end")
            up = rotation(f["base/orientation"][-1])[:, 2] @ rotation(
                r["base/orientation"][n - 1])[:, 2]
            terrain = scene["terrain"]
            reached = (n == len(r["time"]) and np.hypot(d[0], d[1]) <= 0.5 * terrain["tread_depth"]
                       and abs(d[2]) <= max(0.5 * terrain["riser_height"], 0.01) and
                       math.acos(min(1.0, max(-1.0, up))) <= 0.5)
            check(int(row["reached_top"]) == int(reached), f"{name} reached_top recomputed")
            check(same(row["run_seconds"], r["meta"].attrs["wall_time_s"]),
                  f"{name} run wall time")
        c = scene["contact"]
        pen = f["contacts/penetration"][()]
        spring = (c["stiffness"] * np.power(pen, c["exponent"] + 1) / (c["exponent"] + 1)).sum(1)
        ke, pe = f["energy/kinetic"][()], f["energy/potential"][()]
        residual = (f["replay/actuator_work"][()] - (ke[-1] - ke[0]) - (pe[-1] - pe[0]) -
                    (spring[-1] - spring[0]) - last["energy/slip"] -
                    last["energy/contact_damping"])
        check(same(residual, row["energy_residual_J"], rel=1e-6, abs_tol=1e-9),
              f"{name} balance of energy", f"{residual} vs {row['energy_residual_J']}")


def check_pipeline(args, d):
    subprocess.run(["bash", os.path.join(args.source, "pipelines", "replay.sh"), "--quick",
                    "--hexdyn", args.hexdyn, "--out", d], check=True)
    for name in ("replay.csv", "replay_table.txt", "replay_shares.png"):
        check(os.path.getsize(os.path.join(d, name)) > 0, f"pipeline writes {name}")
    with open(os.path.join(d, "replay.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    files = sorted(os.listdir(os.path.join(d, "replays")))
    check(len(rows) == len(files) == 4 and len(os.listdir(os.path.join(d, "runs"))) == 2,
          "two plans, each replayed on two surfaces, one CSV line each")
    for row in rows:
        check_line(row, os.path.join(d, "replays", row["file"]))
    by_plan = {}
    for row in rows:
        by_plan.setdefault((row["duty_factor"], row["peak_speed_mps"]), []).append(
            (float(row["mu_static"]), float(row["slip_distance_m"])))
    for plan, slips in by_plan.items():
        (mu_lo, s_lo), (mu_hi, s_hi) = sorted(slips)
        check(s_lo > s_hi, f"plan {plan}: slips farther at mu {mu_lo} than at {mu_hi}",
              f"{s_lo} vs {s_hi}")


def check_convergence(args, d):
    subprocess.run([sys.executable, os.path.join(args.source, "analysis",
                                                 "replay_convergence.py"), d, "--hexdyn",
                    args.hexdyn, "--steps", "2e-3", "1e-3", "--tolerances", "0.05"], check=True)
    with open(os.path.join(d, "replay_convergence.csv"), newline="") as f:
        rows = {float(r["step_s"]): r for r in csv.DictReader(f)}
    check(os.path.getsize(os.path.join(d, "replay_convergence.png")) > 0,
          "convergence figure written")
    check(float(rows[1e-3]["drift_error_m"]) == 0.0 and float(rows[1e-3]["energy_error"]) == 0.0,
          "the reference has no error")
    drift = {}
    for step in (2e-3, 1e-3):
        with h5py.File(os.path.join(d, "replays", f"step{step:g}_tol0.05.h5"), "r") as f:
            drift[step] = f["replay/final_position_error"][()]
            check(same(f["replay/step"][()], step), f"replayed at step {step:g}")
    check(same(rows[2e-3]["drift_error_m"], np.linalg.norm(drift[2e-3] - drift[1e-3])),
          "drift error is the distance between the drifts")
    return rows


def check_replay_set(args, d, plain):
    """--replay-set reaches every replay and not the plan: at μ 0.2 the same plan slips
    farther than at the scene's 0.3, and the stored plan keeps the scene's μ."""
    subprocess.run([sys.executable, os.path.join(args.source, "analysis",
                                                 "replay_convergence.py"), d, "--hexdyn",
                    args.hexdyn, "--steps", "2e-3", "--tolerances", "0.05",
                    "--replay-set", "contact.static_friction=0.2",
                    "--replay-set", "contact.dynamic_friction=0.2"], check=True)
    with open(os.path.join(d, "replay_convergence.csv"), newline="") as f:
        row = next(csv.DictReader(f))
    check(float(row["slip_energy_J"]) > 2.0 * float(plain[2e-3]["slip_energy_J"]),
          "a replay-only lower mu slips farther",
          f"{row['slip_energy_J']} vs {plain[2e-3]['slip_energy_J']}")
    for name, mu in (("result.h5", 0.3), (os.path.join("replays", "step0.002_tol0.05.h5"), 0.2)):
        with h5py.File(os.path.join(d, name), "r") as f:
            config = f["meta"].attrs["config_yaml"]
        found = yaml.safe_load(config)["contact"]["static_friction"]
        check(same(found, mu), f"{name} records mu {mu}", str(found))


def check_against_binary(args, conv, d):
    """analysis/replay_against_binary.py on the convergence script's plan: 2e-3 s against a
    reference at 1e-3 s, the same binary as old and new."""
    out = subprocess.run([sys.executable, os.path.join(args.source, "analysis",
                                                       "replay_against_binary.py"),
                          "--old", args.hexdyn, "--new", args.hexdyn,
                          "--plan", f"paper={os.path.join(conv, 'result.h5')}",
                          "--settings", "2e-3:0.05", "--reference", "1e-3:0.05", "--work", d],
                         check=True, capture_output=True, text=True).stdout
    rows = [[c.strip().strip("*") for c in line.strip("|").split("|")]
            for line in out.splitlines()[2:]]
    check(len(rows) == 2, "a reference row and a row per setting", out)
    for r in rows:
        check(r[2] == r[3] and r[4] == r[5] and r[6] == r[7] and r[8] == r[9],
              "the same binary twice gives equal columns", " ".join(r))
    check(float(rows[0][3]) == 0.0, "the reference has no drift error", rows[0][3])
    pos = {}
    for step in (2e-3, 1e-3):
        with h5py.File(os.path.join(conv, "replays", f"step{step:g}_tol0.05.h5"), "r") as f:
            pos[step] = f["base/position"][-1]
    expected = np.linalg.norm(pos[2e-3] - pos[1e-3]) * 1e3
    check(abs(float(rows[1][3]) - expected) <= 0.006, "drift error is the distance between the "
          "final trunk positions", f"{rows[1][3]} mm against {expected:.4f} mm")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        check_pipeline(args, os.path.join(d, "sweep"))
        plain = check_convergence(args, os.path.join(d, "convergence"))
        check_replay_set(args, os.path.join(d, "replay_set"), plain)
        check_against_binary(args, os.path.join(d, "convergence"), os.path.join(d, "binaries"))
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
