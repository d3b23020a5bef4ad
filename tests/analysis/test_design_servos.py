"""The servos' part of the reduced design studies (pipelines/designs.sh --quick,
configs/designs/paper_servos_quick.yaml), checked by tests/analysis/test_designs.py --parts
all against readings made here with h5py, csv and yaml:

  - each combination's verdict, recomputed from the sweep file: status ok, no failed sample,
    no sample of the kept run relaxed (/solver/status 1) while no leg is in phase impact
    (/contacts/phase 1), and a thermal load of at most 1 when the servo has a continuous
    rating; the thermal load itself recomputed from the kept run, max over the joints of
    sqrt(trapz(tau_drive², t) / duration) / continuous_torque (the study sets no
    thermal_window) against /scenarios/thermal_load; the reduced study has a combination
    that climbs, one that does not, and a servo with a rating;
  - paper_servos_quick.csv holds, per scenario, the case label, riser, duty factor, status,
    that verdict and the /scenarios energies and costs of transport;
  - plot_design_servos: the electrical cost-of-transport panels hold
    /scenarios/cost_of_transport_electrical at their (riser, duty factor) cells and hatch
    exactly the combinations that do not climb; the verdict figure's reasons are the CSV's.
"""

import csv
import math
import os
import sys

import h5py
from hexdyn import decode_text
import numpy as np
import yaml

NAME = "paper_servos_quick"


def text(v):
    return str(decode_text(v))


def same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


def read(path):
    """Per scenario: id, servo, riser, duty label, status, the verdict's inputs, metrics."""
    with h5py.File(path, "r") as f:
        keys = [text(f["axes"][str(i)]["key"][()]) for i in range(len(f["axes"]))]
        labels = [[text(x) for x in f["axes"][str(i)]["labels"][()]] for i in range(len(keys))]
        sc = f["scenarios"]
        meanings = text(sc["status"].attrs["flag_meanings"]).split()
        flags = list(np.asarray(sc["status"].attrs["flag_values"]).astype(int))
        index = np.asarray(sc["axis_index"][()])
        rows = []
        for s, sid in enumerate(text(x) for x in sc["id"][()]):
            row = {"id": sid, "status": meanings[flags.index(int(sc["status"][s]))]}
            for a, key in enumerate(keys):
                row["servo" if a == 0 else key] = labels[a][index[s][a]]
            for name in ("cost_of_transport_electrical", "cost_of_transport", "energy",
                         "energy_electrical", "thermal_load", "failed_samples"):
                row[name] = float(sc[name][s])
            row["gait"], row["load"] = math.nan, math.nan
            if sid in f.get("runs", {}):
                run = f["runs"][sid]
                st = run["solver/status"][()]
                impact = (run["contacts/phase"][()] == 1).any(axis=1)
                row["gait"] = int(((st == 1) & ~impact).sum())
                t, tau = run["time"][()], run["joints/drive_torque"][()]
                joints = yaml.safe_load(run["meta"].attrs["config_yaml"])["actuators"]["joints"]
                names = [text(n) for n in run["model/joint_names"][()]]
                rated = np.array([float(joints[n].get("continuous_torque", np.inf))
                                  for n in names])
                rms = np.sqrt(np.trapz(tau ** 2, t, axis=0) / (t[-1] - t[0]))
                row["load"] = float(np.max(rms / rated)) if np.isfinite(rated).any() else math.nan
            rows.append(row)
    return rows


def verdict(row):
    if row["status"] != "ok" or row["failed_samples"] > 0 or row["gait"] > 0:
        return False
    return not (np.isfinite(row["load"]) and row["load"] > 1.0)


def check(args, out, check):
    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import matplotlib.pyplot as plt
    import plot_design_servos
    from hexdyn import open_sweep

    path = os.path.join(out, f"{NAME}.h5")
    for name in (f"{NAME}.png", f"{NAME}_climb.png", f"{NAME}_energy.png", f"{NAME}.csv"):
        p = os.path.join(out, name)
        check(os.path.isfile(p) and os.path.getsize(p) > 0, f"servos: wrote {name}")
    if not os.path.isfile(path):
        return
    rows = read(path)
    loads_ok = all(same(r["load"], r["thermal_load"]) or math.isclose(
        r["load"], r["thermal_load"], rel_tol=1e-9) for r in rows)
    check(loads_ok, "servos: /scenarios/thermal_load = max_k sqrt(trapz(τ_d², t)/T) / rating",
          str([(r["load"], r["thermal_load"]) for r in rows]))
    want = [verdict(r) for r in rows]
    check(any(want) and not all(want) and any(np.isfinite(r["load"]) for r in rows),
          "servos: the reduced study has a combination that climbs, one that does not, and a "
          "rated servo", str(want))
    with open(os.path.join(out, f"{NAME}.csv")) as f:
        table = {r["id"]: r for r in csv.DictReader(f)}
    check(sorted(table) == sorted(r["id"] for r in rows), "servos csv: one line per scenario")
    for r in rows:
        got = table.get(r["id"], {})
        ok = (got.get("servo") == r["servo"] and got.get("status") == r["status"]
              and float(got.get("terrain.riser_height", "nan")) == float(r["terrain.riser_height"])
              and got.get("gait.duty_factor") == r["gait.duty_factor"]
              and got.get("climbs") == str(int(want[rows.index(r)]))
              and all(same(float(got.get(k, "nan")), r[k]) for k in (
                  "cost_of_transport_electrical", "cost_of_transport", "energy",
                  "energy_electrical"))
              and same(float(got.get("relaxed_gait_samples", "nan")), float(r["gait"])))
        check(ok, f"servos csv: scenario {r['id']} ({r['servo']}, β {r['gait.duty_factor']}) "
              "as recomputed", f"{got} vs {r}")
    sweep = open_sweep(path)
    fig, drawn = plot_design_servos.draw_cot(sweep, plot_design_servos.servo_rows(sweep))
    duty = sweep.axes[[a.key for a in sweep.axes].index("gait.duty_factor")].labels
    riser = [float(v) for v in sweep.axes[[a.key for a in sweep.axes]
                                          .index("terrain.riser_height")].values]
    for servo in sweep.axes[0].labels:
        shown = np.ma.filled(np.ma.asarray(drawn["cells"][("cost_of_transport_electrical",
                                                           servo)].get_array(), dtype=float),
                             np.nan)
        mine = [r for r in rows if r["servo"] == servo]
        cells = {(riser.index(float(r["terrain.riser_height"])),
                  duty.index(r["gait.duty_factor"])): r for r in mine}
        ok = all(same(float(shown[i, j]), r["cost_of_transport_electrical"])
                 for (i, j), r in cells.items())
        hatched = sorted(ij for ij, r in cells.items() if not verdict(r) and r["status"] == "ok")
        got = sorted(drawn["hatched"][("cost_of_transport_electrical", servo)])
        check(ok and got == hatched,
              f"servos figure: {servo}'s electrical CoT cells, hatched where it does not climb",
              f"{shown} {got} vs {hatched}")
    plt.close(fig)
    fig, climb = plot_design_servos.draw_climb(sweep, plot_design_servos.servo_rows(sweep))
    ok = all(climb["reason"][r["servo"]][riser.index(float(r["terrain.riser_height"])),
                                         duty.index(r["gait.duty_factor"])]
             == table[r["id"]]["reason"] for r in rows)
    check(ok, "servos climb figure: each cell's reason is the csv's")
    plt.close(fig)
