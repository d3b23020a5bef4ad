"""The URDF robots' part of the reduced design studies (pipelines/designs.sh --quick,
configs/designs/robots_quick.yaml), checked by tests/analysis/test_designs.py --parts all
against readings made here with h5py, csv and xml.etree:

  - robots_quick.csv holds, per scenario, the case label and riser of /axes, the status word
    (CF flag_meanings), cost of transport, energy and largest peak |tau| of /scenarios, and
    the peak over the robot's effort limit read from its original URDF file (every joint of
    each robot has the same effort limit, so the ratio is the largest peak over it);
  - plot_design_cases.draw_cases draws, per case, exactly the computed scenarios' values
    against the riser; the envelope figure's numbers are /envelope/riser_max of each case of
    robots_envelope_quick.h5, and robots_quick_envelope.csv holds, per case and criterion,
    /envelope/riser_max and /envelope/riser_max_required_friction;
  - the sweep and the envelope (the same cases and travel) agree: every riser up to a
    robot's kinematic boundary is computed, every riser from its failing riser is `reach`.
"""

import csv
import math
import os
import sys
import xml.etree.ElementTree as ET

import h5py
from hexdyn import decode_text
import numpy as np


def text(v):
    return str(decode_text(v))


def same(a, b, rel=0.0):
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return abs(a - b) <= rel * abs(b)


def effort_limit(urdf_path):
    """The one effort limit of every revolute joint of the file (None if they differ)."""
    efforts = {float(j.find("limit").get("effort")) for j in ET.parse(urdf_path).getroot()
               .findall("joint") if j.get("type") == "revolute"}
    return efforts.pop() if len(efforts) == 1 else None


def read(path):
    with h5py.File(path, "r") as f:
        labels = [text(x) for x in f["axes"]["0"]["labels"][()]]
        risers = np.asarray(f["axes"]["1"]["values"][()], dtype=float)
        sc = f["scenarios"]
        meanings = text(sc["status"].attrs["flag_meanings"]).split()
        flags = list(np.asarray(sc["status"].attrs["flag_values"]).astype(int))
        peak = np.asarray(sc["peak_torque"][()], dtype=float)
        return {
            "labels": labels, "risers": risers, "index": np.asarray(sc["axis_index"][()]),
            "id": [text(x) for x in sc["id"][()]],
            "status": [meanings[flags.index(int(c))] for c in sc["status"][()]],
            "cost_of_transport": np.asarray(sc["cost_of_transport"][()], dtype=float),
            "energy": np.asarray(sc["energy"][()], dtype=float),
            "peak_torque": np.array([np.nanmax(p) if np.isfinite(p).any() else np.nan
                                     for p in peak])}


def check(args, out, check):
    path = os.path.join(out, "robots_quick.h5")
    sw = read(path)
    limit = {lab: effort_limit(os.path.join(args.source, "robots", f"{lab}.urdf"))
             for lab in sw["labels"]}
    check(all(v is not None for v in limit.values()), "cases: one effort limit per robot URDF")
    check(len(set(sw["labels"])) == 2 and "ok" in sw["status"],
          "cases: two robots, scenarios computed")
    with open(os.path.join(out, "robots_quick.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == len(sw["id"]), "cases csv: one line per scenario")
    for row in rows:
        s = sw["id"].index(row["id"])
        c, r = sw["index"][s]
        ok = (row["case"] == sw["labels"][c]
              and float(row["terrain.riser_height"]) == sw["risers"][r]
              and row["status"] == sw["status"][s]
              and all(same(float(row[m]), float(sw[m][s]))
                      for m in ("cost_of_transport", "energy", "peak_torque"))
              and same(float(row["torque_ratio"]), sw["peak_torque"][s] / limit[sw["labels"][c]],
                       1e-12))
        check(ok, f"cases csv: scenario {row['id']} as in /scenarios and the URDF", str(row))

    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import matplotlib.pyplot as plt
    import plot_design_cases
    from hexdyn import open_sweep

    fig, drawn = plot_design_cases.draw_cases(open_sweep(path))
    plt.close(fig)
    for c, lab in enumerate(sw["labels"]):
        mine = [s for s in range(len(sw["id"]))
                if sw["index"][s][0] == c and sw["status"][s] == "ok"]
        for m in ("cost_of_transport", "energy"):
            x, y = drawn["lines"][(m, lab)]
            check(list(x) == [sw["risers"][sw["index"][s][1]] for s in mine]
                  and list(y) == [sw[m][s] for s in mine],
                  f"cases figure: {lab} {m} line = the computed scenarios")
    want_failed = sorted((sw["labels"][sw["index"][s][0]], sw["risers"][sw["index"][s][1]],
                          sw["status"][s]) for s in range(len(sw["id"])) if sw["status"][s] != "ok")
    check(sorted(drawn["failed"]) == want_failed, "cases figure: marked scenarios = not computed")

    env_path = os.path.join(out, "robots_envelope_quick.h5")
    table, _ = plot_design_cases.envelope_table([env_path], sw["labels"])
    with h5py.File(env_path, "r") as f:
        cases = [text(x) for x in f["case"][()]]
        crits = [text(x) for x in f["criterion"][()]]
        riser_max = np.asarray(f["envelope"]["riser_max"][()], dtype=float)[:, 0, 0, 0, :]
        riser_fail = np.asarray(f["envelope"]["riser_fail"][()], dtype=float)[:, 0, 0, 0, :]
        mu = np.asarray(f["envelope"]["riser_max_required_friction"][()],
                        dtype=float)[:, 0, 0, 0, :]
    with open(os.path.join(out, "robots_quick_envelope.csv")) as f:
        env_rows = {(r["case"], r["criterion"]): r for r in csv.DictReader(f)}
    check(len(env_rows) == len(cases) * len(crits), "envelope csv: one line per case and criterion")
    for c, lab in enumerate(cases):
        for j, cr in enumerate(crits):
            r = env_rows.get((lab, cr))
            check(r is not None and same(float(r["riser_max"]), float(riser_max[c, j]))
                  and same(float(r["required_friction"]), float(mu[c, j])),
                  f"envelope csv: {lab} {cr} = /envelope/riser_max and its required friction",
                  str(r))
    check(cases == sw["labels"], "envelope: the sweep's cases, in order")
    for c, lab in enumerate(cases):
        want = {cr: float(riser_max[c, j]) for j, cr in enumerate(crits)}
        got = table.get(lab)
        check(got is not None and all(same(got[k], v) for k, v in want.items()),
              f"envelope figure: {lab} tallest risers = /envelope/riser_max", f"{got} vs {want}")
        # The two drivers agree on the same scenes: the sweep computes every riser up to the
        # envelope's kinematic boundary and none from the riser where the envelope fails.
        k = crits.index("kinematic")
        for s in range(len(sw["id"])):
            if sw["index"][s][0] != c:
                continue
            h = sw["risers"][sw["index"][s][1]]
            if h <= riser_max[c, k]:
                check(sw["status"][s] == "ok", f"sweep and envelope: {lab} climbs {h:g} m")
            elif np.isfinite(riser_fail[c, k]) and h >= riser_fail[c, k]:
                check(sw["status"][s] == "reach", f"sweep and envelope: {lab} fails {h:g} m")
