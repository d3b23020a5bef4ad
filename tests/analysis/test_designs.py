#!/usr/bin/python3
"""The design-study pipeline, reduced (pipelines/designs.sh --quick; docs/user/designs.md),
checked against readings of its files made here with h5py, csv, yaml and xml.etree:

  - the pipeline writes the figures and the table of the paper study (and, with --parts all,
    of the URDF robots' study and of the servos' study, whose checks are in
    test_design_cases.py and test_design_servos.py);
  - paper_femur_tibia_quick.csv holds, for every scenario, the axis values, the status word
    (the CF flag_meanings of /scenarios/status) and the cost of transport, energy, largest
    peak |tau|, relaxed-sample count and support required friction of the sweep file's
    /scenarios table;
  - plot_designs.draw_grid draws those numbers: each panel's colour mesh holds the table's
    values at its (femur, tibia) cells, and the cells it hatches and labels are exactly the
    scenarios not computed, with their status; the tallest riser per design is the largest
    riser with status ok;
  - robot.links_follow_length: uniform_density in a result file: /model/total_mass is the
    trunk, payload and six legs of links whose masses scale with length (numbers of
    configs/paper.yaml), and every femur and tibia inertial of /model/urdf equals that of the
    paper's link, modelled as point masses with its stated moments, stretched along the
    link by the length ratio and integrated here.

usage: test_designs.py --hexdyn BUILD/hexdyn --source SOURCE_DIR [--parts paper|all]
       (PYTHONPATH=BUILD/python)
"""

import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
from hexdyn import decode_text
import numpy as np
import yaml

failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def text(v):
    return str(decode_text(v))


def read_sweep(path):
    """{"keys": [...], "values": [arrays], "index": (N, axes), "status": words, metrics}."""
    with h5py.File(path, "r") as f:
        n_axes = len(f["axes"])
        keys = [text(f["axes"][str(i)]["key"][()]) for i in range(n_axes)]
        values = [np.asarray(f["axes"][str(i)]["values"][()], dtype=float) for i in range(n_axes)]
        sc = f["scenarios"]
        meanings = text(sc["status"].attrs["flag_meanings"]).split()
        flags = list(np.asarray(sc["status"].attrs["flag_values"]).astype(int))
        status = [meanings[flags.index(int(c))] for c in sc["status"][()]]
        out = {"keys": keys, "values": values, "index": np.asarray(sc["axis_index"][()]),
               "status": status, "id": [text(x) for x in sc["id"][()]]}
        for name in ("cost_of_transport", "energy", "relaxed_samples",
                     "required_friction_support"):
            out[name] = np.asarray(sc[name][()], dtype=float)
        peak = np.asarray(sc["peak_torque"][()], dtype=float)
        out["peak_torque"] = np.array([np.nanmax(row) if np.isfinite(row).any() else np.nan
                                       for row in peak])
    return out


def same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


def check_csv(csv_path, sw):
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == len(sw["id"]), "csv: one line per scenario")
    for i, row in enumerate(rows):
        s = sw["id"].index(row["id"])
        axes_ok = all(float(row[k]) == sw["values"][a][sw["index"][s][a]]
                      for a, k in enumerate(sw["keys"]))
        metrics_ok = all(same(float(row[m]), float(sw[m][s]))
                         for m in ("cost_of_transport", "energy", "peak_torque", "relaxed_samples"))
        metrics_ok = metrics_ok and same(float(row["required_friction"]),
                                         float(sw["required_friction_support"][s]))
        check(axes_ok and metrics_ok and row["status"] == sw["status"][s],
              f"csv: scenario {row['id']} as in /scenarios", str(row))


def check_figure(sweep_path, sw):
    sys.path.insert(0, os.path.join(ARGS.source, "analysis"))
    import matplotlib.pyplot as plt
    import plot_designs
    from hexdyn import open_sweep

    sweep = open_sweep(sweep_path)
    fig, drawn = plot_designs.draw_grid(sweep)
    kr, kf, kt = (sw["keys"].index(k) for k in
                  ("terrain.riser_height", "robot.femur.length", "robot.tibia.length"))
    for (metric, p), mesh in drawn["cells"].items():
        shown = np.ma.filled(np.ma.asarray(mesh.get_array(), dtype=float), np.nan)
        shown = shown.reshape(len(sw["values"][kf]), len(sw["values"][kt]))
        want = np.full_like(shown, np.nan)
        for s in range(len(sw["id"])):
            ix = sw["index"][s]
            if ix[kr] == p:
                want[ix[kf], ix[kt]] = sw[metric][s]
        check(np.array_equal(np.isnan(shown), np.isnan(want))
              and np.array_equal(shown[~np.isnan(shown)], want[~np.isnan(want)]),
              f"figure: {metric} at riser {sw['values'][kr][p]:g} as in /scenarios",
              f"{shown} != {want}")
    for p, failed in drawn["failed"].items():
        want = sorted((int(sw["index"][s][kf]), int(sw["index"][s][kt]), sw["status"][s])
                      for s in range(len(sw["id"]))
                      if sw["index"][s][kr] == p and sw["status"][s] != "ok")
        check(sorted(failed) == want, f"figure: hatched cells at riser {p} are the failed "
              "scenarios with their status", f"{sorted(failed)} != {want}")
    check(any(drawn["failed"].values()), "figure: the reduced study has a failed design "
          "(what the hatching is for)")
    plt.close(fig)
    tallest, _, _ = plot_designs.climb_grid(sweep)
    for f_i in range(len(sw["values"][kf])):
        for t_i in range(len(sw["values"][kt])):
            ok = [sw["values"][kr][sw["index"][s][kr]] for s in range(len(sw["id"]))
                  if sw["index"][s][kf] == f_i and sw["index"][s][kt] == t_i
                  and sw["status"][s] == "ok"]
            check(same(float(tallest[f_i, t_i]), max(ok) if ok else math.nan),
                  f"climb: design ({f_i}, {t_i}) tallest riser ok")


def cloud_inertia(mass, com, moments, ratio):
    """A link of `mass`, `com` and principal `moments` (link axes, about the COM) as six
    point masses, stretched x -> ratio x about the joint at the same density (each point's
    mass times ratio); returns (mass, com, inertia tensor about the new COM)."""
    I = np.asarray(moments, dtype=float)
    sigma = 0.5 * np.array([I[1] + I[2] - I[0], I[0] + I[2] - I[1], I[0] + I[1] - I[2]])
    pts, ms = [], []
    for axis in range(3):
        d = math.sqrt(3.0 * sigma[axis] / mass)  # two points of mass/6 each: 2 (m/6) d² = Σ
        for sign in (1.0, -1.0):
            p = np.array(com, dtype=float)
            p[axis] += sign * d
            pts.append(p)
            ms.append(mass / 6.0)
    pts = np.array(pts) * np.array([ratio, 1.0, 1.0])
    ms = np.array(ms) * ratio
    m = ms.sum()
    c = (ms[:, None] * pts).sum(axis=0) / m
    tensor = np.zeros((3, 3))
    for mi, p in zip(ms, pts - c):
        tensor += mi * (p @ p * np.eye(3) - np.outer(p, p))
    return m, c, tensor


def check_mass_rule(d):
    paper = yaml.safe_load(open(os.path.join(ARGS.source, "configs", "paper.yaml")))["robot"]
    lengths = {"femur": 0.15, "tibia": 0.08}
    path = os.path.join(d, "design.h5")
    cmd = [ARGS.hexdyn, "run", os.path.join(ARGS.source, "configs", "designs", "paper_base.yaml"),
           "-o", path, "--set", "motion.cycles=1", "--set", "output.grid=uniform"]
    for link, L in lengths.items():
        cmd += ["--set", f"robot.{link}.length={L}"]
    subprocess.run(cmd, check=True, capture_output=True)
    with h5py.File(path, "r") as f:
        total = float(f["model/total_mass"][()])
        urdf = ET.fromstring(text(f["model/urdf"][()]))
        legs = [text(n) for n in f["model/leg_names"][()]]  # the robot's legs, L1 ...
    ratio = {"coxa": 1.0, **{k: v / paper[k]["length"] for k, v in lengths.items()}}
    want = paper["trunk"]["mass"] + paper["payload"]["mass"] + len(legs) * sum(
        paper[k]["mass"] * ratio[k] for k in ("coxa", "femur", "tibia"))
    check(abs(total - want) <= 1e-12 * want, "mass rule: /model/total_mass is the hand sum",
          f"{total} != {want}")
    links = {l.get("name"): l for l in urdf.findall("link")}
    for leg in legs:
        for link in ("femur", "tibia"):
            el = links[f"{leg}_{link}_link"].find("inertial")
            m = float(el.find("mass").get("value"))
            c = np.array([float(x) for x in el.find("origin").get("xyz").split()])
            it = el.find("inertia")
            got = np.array([[float(it.get("ixx")), float(it.get("ixy")), float(it.get("ixz"))],
                            [float(it.get("ixy")), float(it.get("iyy")), float(it.get("iyz"))],
                            [float(it.get("ixz")), float(it.get("iyz")), float(it.get("izz"))]])
            wm, wc, wI = cloud_inertia(paper[link]["mass"], paper[link]["com"],
                                       paper[link]["inertia"], ratio[link])
            ok = (abs(m - wm) <= 1e-12 * wm and np.allclose(c, wc, rtol=1e-12, atol=1e-15)
                  and np.allclose(got, wI, rtol=1e-9, atol=1e-15))
            check(ok, f"mass rule: {leg}_{link} inertial = the stretched point cloud",
                  f"{m} {c} {got.diagonal()} vs {wm} {wc} {wI.diagonal()}")


def main():
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "designs")
        cmd = ["bash", os.path.join(ARGS.source, "pipelines", "designs.sh"), "--quick",
               "--hexdyn", ARGS.hexdyn, "--out", out]
        if ARGS.parts == "paper":
            cmd += ["--only", "paper"]
        run = subprocess.run(cmd, capture_output=True, text=True)
        check(run.returncode == 0, "pipeline: designs.sh --quick exits 0", run.stderr[-2000:])
        names = ["paper_femur_tibia_quick.png", "paper_femur_tibia_quick_climb.png",
                 "paper_femur_tibia_quick.csv", "paper_femur_tibia_quick.h5"]
        if ARGS.parts == "all":
            names += ["robots_quick.png", "robots_quick_envelope.png", "robots_quick.csv",
                      "robots_quick_envelope.csv"]
        for name in names:
            p = os.path.join(out, name)
            check(os.path.isfile(p) and os.path.getsize(p) > 0, f"pipeline: wrote {name}")
        sweep_path = os.path.join(out, "paper_femur_tibia_quick.h5")
        if os.path.isfile(sweep_path):
            sw = read_sweep(sweep_path)
            check_csv(os.path.join(out, "paper_femur_tibia_quick.csv"), sw)
            check_figure(sweep_path, sw)
        if ARGS.parts == "all" and os.path.isfile(os.path.join(out, "robots_quick.h5")):
            import test_design_cases
            test_design_cases.check(ARGS, out, check)
        if ARGS.parts == "all":
            import test_design_servos
            test_design_servos.check(ARGS, out, check)
        check_mass_rule(d)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--parts", choices=("paper", "all"), default="paper")
    ARGS = ap.parse_args()
    sys.exit(main())
