#!/usr/bin/python3
"""Tests of the torque figures (docs/user/animation.md#figures): the artists they return
against values computed here from the files with h5py, yaml and xml.etree.

  - plot_paper.draw_torques: the torque limit (allocation.torque_limit of /meta config_yaml)
    drawn at ±limit; the samples marked above it are exactly those with |tau| > limit, split
    by /solver/status; no optimal sample exceeds the limit.
  - plot_actuators.draw: per joint the ±torque limit, the ±time-weighted RMS torque
    (numpy.trapz of tau² over /time), and for a URDF robot (kraby) the ±velocity limits and
    effort limits of the original robots/kraby.urdf; none for the paper robot.
  - plot_sweep: the peak-torque heatmap draws the limit on its colour bar and frames exactly
    the scenarios whose peak exceeds it, red where they have relaxed samples; --x --hue line
    plots draw the limit and mark the same scenarios; the command writes its files.

usage: test_figures.py --hexdyn BUILD/hexdyn --source SOURCE_DIR   (PYTHONPATH=BUILD/python)
"""

import argparse
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
REL, ABS = 1e-6, 1e-9  # the allocation's tolerance on the torque limit


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def read(path, group="/"):
    with h5py.File(path, "r") as f:
        g = f[group]
        out = {k: g[k][()] for k in ("time", "joints/torque", "joints/velocity", "solver/status")}
        out["config"] = yaml.safe_load(g["meta"].attrs["config_yaml"])
        out["names"] = [str(decode_text(n)) for n in g["model/joint_names"][()]]
    return out


def hline_levels(lines):
    return sorted(float(np.asarray(a.get_ydata())[0]) for a in lines)


def vline_levels(lines):
    return sorted(float(np.asarray(a.get_xdata())[0]) for a in lines)


def test_paper(args, d):
    import matplotlib.pyplot as plt
    from hexdyn.results import open_result

    import plot_actuators
    import plot_paper

    path = os.path.join(d, "paper.h5")
    subprocess.run([args.hexdyn, "run", os.path.join(args.source, "configs", "paper.yaml"), "-o",
                    path], check=True, capture_output=True)
    raw = read(path)
    limit = float(raw["config"]["allocation"]["torque_limit"])
    tau, status, t = raw["joints/torque"], raw["solver/status"], raw["time"]
    over = np.abs(tau) > limit * (1 + REL) + ABS
    check(not (over & (status[:, None] == 0)).any(), "paper: no optimal sample above the limit")
    check((over & (status[:, None] == 1)).any(), "paper: relaxed samples above the limit exist "
          "(what the marks are for)")
    res = open_result(path)
    for leg in (1, 2):
        fig, ax = plt.subplots()
        drawn = plot_paper.draw_torques(ax, res, leg)
        for j, dj in enumerate(drawn):
            k = 3 * (leg - 1) + j
            check(hline_levels(dj["limit"]) == [-limit, limit],
                  f"paper leg {leg} joint {j}: limit lines at ±{limit:g}",
                  str(hline_levels(dj["limit"])))
            for key, code in (("relaxed", 1), ("failed", 2)):
                want = np.flatnonzero(over[:, k] & (status == code))
                got = dj[key].get_offsets() if dj[key] is not None else np.zeros((0, 2))
                ok = len(got) == want.size and np.allclose(got[:, 0], t[want]) and \
                    np.allclose(got[:, 1], tau[want, k])
                check(ok, f"paper leg {leg} joint {j}: {key} samples above the limit marked "
                      f"({want.size})", f"marked {len(got)}")
        plt.close(fig)

    fig, artists, _ = plot_actuators.draw(res)
    rms = np.sqrt(np.trapz(tau ** 2, t, axis=0) / (t[-1] - t[0]))
    ok_lim = all(hline_levels(a["limit"]) == [-limit, limit] for a in artists)
    ok_rms = all(np.allclose(hline_levels(a["rms"]), [-rms[k], rms[k]], rtol=1e-12)
                 for k, a in enumerate(artists))
    ok_marks = all(a["counts"]["relaxed"] == int((over[:, k] & (status == 1)).sum())
                   for k, a in enumerate(artists))
    check(len(artists) == 18 and ok_lim, "actuators (paper): ±torque limit on all 18 joints")
    check(ok_rms, "actuators (paper): ±RMS torque = sqrt(trapz(tau², t) / duration)")
    check(ok_marks, "actuators (paper): relaxed samples above the limit marked")
    check(all(not a["velocity"] for a in artists), "actuators (paper): no velocity limit drawn "
          "for a robot given by parameters")
    plt.close(fig)


def test_kraby(args, d):
    import matplotlib.pyplot as plt
    from hexdyn.results import open_result

    import plot_actuators

    path = os.path.join(d, "kraby.h5")
    subprocess.run([args.hexdyn, "run", os.path.join(args.source, "configs", "robots",
                                                     "kraby_stairs.yaml"), "-o", path],
                   check=True, capture_output=True)
    raw = read(path)
    root = ET.parse(os.path.join(args.source, "robots", "kraby.urdf")).getroot()
    lim = {j.get("name"): j.find("limit") for j in root.findall("joint")}
    effort = np.array([float(lim[n].get("effort")) for n in raw["names"]])
    velocity = np.array([float(lim[n].get("velocity")) for n in raw["names"]])
    fig, artists, _ = plot_actuators.draw(open_result(path))
    check(all(np.allclose(hline_levels(a["limit"]), [-effort[k], effort[k]], rtol=1e-12)
              for k, a in enumerate(artists)), "actuators (kraby): ±URDF effort limits")
    check(all(np.allclose(vline_levels(a["velocity"]), [-velocity[k], velocity[k]], rtol=1e-12)
              for k, a in enumerate(artists)), "actuators (kraby): ±URDF velocity limits")
    plt.close(fig)
    out = os.path.join(d, "figs")
    r = subprocess.run(["/usr/bin/python3", os.path.join(args.source, "analysis",
                                                         "plot_actuators.py"), path, out],
                       capture_output=True, text=True)
    check(r.returncode == 0 and os.path.getsize(os.path.join(out, "actuators.png")) > 0,
          "plot_actuators.py writes actuators.png", r.stderr)


def test_sweep(args, d):
    import matplotlib.pyplot as plt
    from hexdyn import results as hr

    import plot_sweep

    path = os.path.join(d, "smoke.h5")
    subprocess.run([args.hexdyn, "sweep", os.path.join(args.source, "configs", "sweeps",
                                                       "smoke.yaml"), "-o", path],
                   check=True, capture_output=True)
    with h5py.File(path, "r") as f:
        peak = f["scenarios/peak_torque"][()].max(axis=1)
        relaxed = f["scenarios/relaxed_samples"][()]
        limit = float(yaml.safe_load(f["meta"].attrs["base_config_yaml"])["allocation"]
                      ["torque_limit"])
    over = peak > limit * (1 + REL) + ABS
    check(over.any(), "smoke sweep: some peaks exceed the limit (what the marks are for)")
    sweep = hr.open_sweep(path)
    metric = [m for m in plot_sweep.METRICS if m[0] == "sweep_peak_torque.png"][0]
    rows, cols = plot_sweep.choose_axes(sweep)
    fig, marks = plot_sweep.draw_heatmap(sweep, metric, rows, cols)
    check([float(np.asarray(a.get_ydata())[0]) for a in marks["limit"]] == [limit],
          f"heatmap: the limit {limit:g} N m on the colour bar")
    check(len(marks["relaxed"]) == int((over & (relaxed > 0)).sum())
          and len(marks["optimal"]) == int((over & (relaxed == 0)).sum()),
          "heatmap: the cells above the limit are framed, by relaxed samples",
          f"{len(marks['relaxed'])} + {len(marks['optimal'])} frames, want "
          f"{int((over & (relaxed > 0)).sum())} + {int((over & (relaxed == 0)).sum())}")
    plt.close(fig)
    keys = [a.key for a in sweep.axes]
    fig, marks = plot_sweep.draw_lines(sweep, metric, keys.index("terrain.riser_height"),
                                       keys.index("gait.duty_factor"), {})
    check(marks["limit"] and all(hline_levels([a]) == [limit] for a in marks["limit"]),
          "line plot: the limit line drawn")
    n_marked = sum(len(c.get_offsets()) for c in marks["relaxed"] + marks["optimal"])
    check(n_marked == int(over.sum()), "line plot: the scenarios above the limit marked",
          f"{n_marked} vs {int(over.sum())}")
    plt.close(fig)
    out = os.path.join(d, "sweepfigs")
    r = subprocess.run(["/usr/bin/python3", os.path.join(args.source, "analysis", "plot_sweep.py"),
                        path, out, "--x", "terrain.riser_height", "--hue", "gait.duty_factor"],
                       capture_output=True, text=True)
    want = [f"sweep_{m}_vs_terrain.riser_height.png" for m in ("energy", "cost_of_transport",
                                                               "peak_torque")]
    check(r.returncode == 0 and sorted(os.listdir(out)) == sorted(want),
          "plot_sweep.py --x --hue writes one line plot per metric", r.stderr + str(
              os.listdir(out) if os.path.isdir(out) else ""))
    r = subprocess.run(["/usr/bin/python3", os.path.join(args.source, "analysis", "plot_sweep.py"),
                        path, out, "--x", "terrain.riser_height", "--sel", "nokey=1"],
                       capture_output=True, text=True)
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1,
          "plot_sweep.py --sel with an unknown key: one line, non-zero exit", r.stderr)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import matplotlib

    matplotlib.use("Agg")
    with tempfile.TemporaryDirectory() as d:
        test_paper(args, d)
        test_kraby(args, d)
        test_sweep(args, d)
    if failures:
        print(f"{len(failures)} check(s) failed: {'; '.join(failures)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
