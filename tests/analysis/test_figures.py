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
    plots draw the limit and mark the same scenarios; the command writes its files. --metric
    takes any /scenarios column: on an actuated sweep the electrical cost of transport drawn
    is E_el/(m g d) recomputed from each kept run.
  - plot_actuators.draw with actuators (the paper scene with MX-64 servos, the femurs given
    a continuous rating): each joint's envelope, read off the drawn polyline at every
    sample's speed, is /joints/drive_torque_limit, and at its vertices the bound computed
    here from /meta actuators.joints; the no-load speed V/(G k_t); the continuous rating on
    the femurs only; the windowed RMS (no thermal_window: over the run) is
    sqrt(trapz(tau_drive², t) / duration); the relaxed samples marked are those above the
    per-sample bound.
  - plot_energy: on a two-scenario sweep with kept runs (regeneration 0 and 1), the bars
    are /scenarios' energies; the copper and friction bars equal trapz(sum R I²) and
    trapz(sum tau_c |omega| + b omega²) recomputed from each kept run's drive torques,
    speeds and /meta; the electrical marks differ between the two scenarios by exactly what
    the second regenerates; a sweep without actuators is refused in one line.

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
    names = raw["names"]
    for leg in (1, 2):
        fig, ax = plt.subplots()
        drawn = plot_paper.draw_torques(ax, res, leg)
        # The leg's joints, by the labels of the paper robot (L1_coxa, ...), in file order.
        leg_joints = [k for k, n in enumerate(names) if n.startswith(f"L{leg}_")]
        check(len(drawn) == len(leg_joints), f"paper leg {leg}: one torque line per joint")
        for j, dj in enumerate(drawn):
            k = leg_joints[j]
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
    check(len(artists) == len(names) and ok_lim,
          f"actuators (paper): ±torque limit on all {len(names)} joints")
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
    metric = plot_sweep.column_metric(sweep, "peak_torque")
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
    # The default peak figure is the gait's: its values are the largest peak_torque_gait
    # over the joints, its frames the scenarios above the limit by that column, told apart
    # by their relaxed samples outside touchdowns.
    with h5py.File(path, "r") as f:
        gait = f["scenarios/peak_torque_gait"][()]
        relaxed_gait = f["scenarios/relaxed_gait_samples"][()]
    gait_peak = np.array([np.nan if np.isnan(row).all() else np.nanmax(row) for row in gait])
    metric = [m for m in plot_sweep.METRICS if m[0] == "sweep_peak_torque_gait.png"][0]
    values = metric[3](sweep.table)
    check(np.array_equal(np.isnan(values), np.isnan(gait_peak))
          and np.array_equal(values[~np.isnan(values)], gait_peak[~np.isnan(gait_peak)]),
          "default figure: the gait's peak torque per scenario")
    fig, marks = plot_sweep.draw_heatmap(sweep, metric, rows, cols)
    over_gait = gait_peak > limit * (1 + REL) + ABS
    check(len(marks["relaxed"]) == int((over_gait & (relaxed_gait > 0)).sum())
          and len(marks["optimal"]) == int((over_gait & (relaxed_gait == 0)).sum()),
          "gait heatmap: the cells above the limit are framed, by relaxed gait samples")
    plt.close(fig)
    out = os.path.join(d, "sweepfigs")
    r = subprocess.run(["/usr/bin/python3", os.path.join(args.source, "analysis", "plot_sweep.py"),
                        path, out, "--x", "terrain.riser_height", "--hue", "gait.duty_factor"],
                       capture_output=True, text=True)
    want = [f"sweep_{m}_vs_terrain.riser_height.png"
            for m in ("energy", "cost_of_transport", "peak_torque_gait", "peak_torque_transient")]
    check(r.returncode == 0 and sorted(os.listdir(out)) == sorted(want),
          "plot_sweep.py --x --hue writes one line plot per metric", r.stderr + str(
              os.listdir(out) if os.path.isdir(out) else ""))
    r = subprocess.run(["/usr/bin/python3", os.path.join(args.source, "analysis", "plot_sweep.py"),
                        path, out, "--x", "terrain.riser_height", "--sel", "nokey=1"],
                       capture_output=True, text=True)
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1,
          "plot_sweep.py --sel with an unknown key: one line, non-zero exit", r.stderr)


def drive_specs(config, names):
    """{key: (J,) array} of /meta actuators.joints (absent voltage and ratings: +inf)."""
    joints = config["actuators"]["joints"]
    keys = {"gear_ratio": None, "torque_constant": None, "resistance": None,
            "gear_efficiency": 1.0, "voltage": np.inf, "peak_torque": np.inf,
            "continuous_torque": np.inf, "coulomb_friction": 0.0, "viscous_friction": 0.0,
            "regeneration": 0.0}
    return {k: np.array([float(joints[n].get(k, v)) for n in names]) for k, v in keys.items()}


def bound(sp, k, w):
    gk = sp["gear_ratio"][k] * sp["torque_constant"][k]
    line = gk * sp["gear_efficiency"][k] * (sp["voltage"][k] - gk * np.abs(w)) / sp["resistance"][k]
    return np.clip(np.minimum(sp["peak_torque"][k], line), 0.0, None)


def test_drive(args, d):
    import matplotlib.pyplot as plt
    from hexdyn.results import open_result

    import plot_actuators

    scene = os.path.join(d, "paper_mx64.yaml")
    with open(scene, "w") as f:
        f.write(f"inherit: {os.path.join(args.source, 'configs', 'paper.yaml')}\n"
                "actuators:\n  default: {model: dynamixel_mx64}\n"
                "  femur: {continuous_torque: 1.5}\n")
    path = os.path.join(d, "paper_mx64.h5")
    subprocess.run([args.hexdyn, "run", scene, "-o", path], check=True, capture_output=True)
    with h5py.File(path, "r") as f:
        t, w = f["time"][()], f["joints/velocity"][()]
        tau_d, limit = f["joints/drive_torque"][()], f["joints/drive_torque_limit"][()]
        status = f["solver/status"][()]
        config = yaml.safe_load(f["meta"].attrs["config_yaml"])
        names = [str(decode_text(n)) for n in f["model/joint_names"][()]]
    sp = drive_specs(config, names)
    fig, artists, _ = plot_actuators.draw(open_result(path))
    ok_read, ok_vertex, ok_noload, ok_rated, ok_rms, ok_marks = (True,) * 6
    rms = np.sqrt(np.trapz(tau_d ** 2, t, axis=0) / (t[-1] - t[0]))
    over = np.abs(tau_d) > limit * (1 + REL) + ABS
    for k, a in enumerate(artists):
        upper, lower = a["envelope"]
        x, y = np.asarray(upper.get_xdata()), np.asarray(upper.get_ydata())
        ok_read &= bool(np.allclose(np.interp(w[:, k], x, y), limit[:, k], rtol=0, atol=1e-9))
        ok_read &= bool(np.allclose(np.asarray(lower.get_ydata()), -y, rtol=0, atol=0))
        ok_vertex &= bool(np.allclose(y, bound(sp, k, x), rtol=1e-12, atol=1e-12))
        w0 = sp["voltage"][k] / (sp["gear_ratio"][k] * sp["torque_constant"][k])
        ok_noload &= bool(a["no_load"] and np.allclose(sorted(a["no_load"][0].get_xdata()),
                                                       [-w0, w0], rtol=1e-12))
        want = [-1.5, 1.5] if names[k].endswith("femur") else []
        ok_rated &= hline_levels(a["continuous"]) == want
        ok_rms &= bool(np.allclose(hline_levels(a["window_rms"]), [-rms[k], rms[k]], rtol=1e-9))
        ok_marks &= a["counts"]["relaxed"] == int((over[:, k] & (status == 1)).sum())
    check(len(artists) == len(names) and ok_read, "actuators (MX-64): the envelope at each sample's "
          "speed is /joints/drive_torque_limit (1e-9 N m)")
    check(ok_vertex, "actuators (MX-64): the envelope's vertices on min(peak, G k_t η (V − "
          "G k_t|ω|)/R) of /meta")
    check(ok_noload, "actuators (MX-64): the no-load speed ±V/(G k_t) marked")
    check(ok_rated, "actuators (MX-64): the continuous rating ±1.5 N m on the femurs only")
    check(ok_rms, "actuators (MX-64): windowed RMS = sqrt(trapz(τ_drive², t) / duration)")
    check(ok_marks and over[status == 1].any(), "actuators (MX-64): the relaxed samples "
          "above the per-sample bound marked (some exist)")
    plt.close(fig)
    out = os.path.join(d, "drivefigs")
    r = subprocess.run(["/usr/bin/python3", os.path.join(args.source, "analysis",
                                                         "plot_actuators.py"), path, out],
                       capture_output=True, text=True)
    check(r.returncode == 0 and os.listdir(out) == ["actuators.png"],
          "plot_actuators.py with actuators writes actuators.png alone", r.stderr)


def recomputed_losses(run):
    """(copper, friction) [J] of a kept run from its drive torques, speeds and /meta."""
    t, w = run["time"][()], run["joints/velocity"][()]
    tau_d = run["joints/drive_torque"][()]
    names = [str(decode_text(n)) for n in run["model/joint_names"][()]]
    sp = drive_specs(yaml.safe_load(run["meta"].attrs["config_yaml"]), names)
    gk, eta = sp["gear_ratio"] * sp["torque_constant"], sp["gear_efficiency"]
    current = np.where(tau_d * w >= 0, tau_d / (gk * eta), tau_d * eta / gk)
    copper = np.trapz((sp["resistance"] * current ** 2).sum(axis=1), t)
    friction = np.trapz((sp["coulomb_friction"] * np.abs(w) + sp["viscous_friction"] * w ** 2)
                        .sum(axis=1), t)
    return copper, friction


def bar_heights(container):
    return np.array([p.get_height() for p in container.patches])


def test_energy(args, d):
    import matplotlib.pyplot as plt
    from hexdyn import results as hr

    import plot_energy

    spec = os.path.join(d, "energy_check.yaml")
    base = os.path.join(args.source, "configs", "sweeps", "stairs_base.yaml")
    with open(spec, "w") as f:
        f.write(f"name: energy_check\nbase: {base}\nset: {{output.grid: uniform, "
                "motion.cycles: 1, actuators.default.model: dynamixel_mx64}\n"
                "axes:\n  - name: drive\n    cases:\n"
                "      - {label: burnt, actuators.default.regeneration: 0}\n"
                "      - {label: returned, actuators.default.regeneration: 1}\n")
    path = os.path.join(d, "energy_check.h5")
    r = subprocess.run([args.hexdyn, "sweep", spec, "-o", path, "--keep-runs"],
                       capture_output=True, text=True)
    check(r.returncode == 0, "energy: the two-scenario sweep runs", r.stderr[-500:])
    if r.returncode != 0:
        return
    with h5py.File(path, "r") as f:
        sc = {k: f["scenarios"][k][()] for k in ("energy", "energy_copper_loss",
                                                  "energy_friction_loss", "energy_regenerated",
                                                  "energy_electrical")}
        ids = [str(decode_text(i)) for i in f["scenarios/id"][()]]
        losses = [recomputed_losses(f["runs"][i]) for i in ids]
    fig, out = plot_energy.draw_energy(hr.open_sweep(path))
    bars = {label: out["panels"][label] for label in ("burnt", "returned")}
    got = {key: np.array([bar_heights(bars[lab][key])[0] for lab in bars])
           for key in ("mechanical", "copper", "friction", "regenerated")}
    got["electrical"] = np.array([bars[lab]["electrical"].get_segments()[0][0][1] for lab in bars])
    bottoms = np.array([[p.get_y() for p in bars[lab][key].patches][0] for lab in bars
                        for key in ("copper", "friction")])
    # A stacked patch keeps its bottom and top: its height is exact to the last bits only.
    check(np.array_equal(got["mechanical"], sc["energy"])
          and np.allclose(got["copper"], sc["energy_copper_loss"], rtol=1e-12, atol=0)
          and np.allclose(got["friction"], sc["energy_friction_loss"], rtol=1e-12, atol=0)
          and np.array_equal(got["regenerated"], -sc["energy_regenerated"])
          and np.array_equal(got["electrical"], sc["energy_electrical"]),
          "energy: the bars and marks are /scenarios' energies (regenerated below 0)",
          f"{got} vs {sc}")
    check(np.allclose(bottoms, [sc["energy"][0], sc["energy"][0] + sc["energy_copper_loss"][0],
                                sc["energy"][1], sc["energy"][1] + sc["energy_copper_loss"][1]],
                      rtol=1e-15), "energy: mechanical, copper, friction stacked")
    check(all(np.isclose(got["copper"][i], losses[i][0], rtol=1e-9)
              and np.isclose(got["friction"][i], losses[i][1], rtol=1e-9) for i in range(2)),
          "energy: copper and friction bars = trapz(Σ R I²), trapz(Σ τ_c|ω| + b ω²) of the "
          "kept runs", f"{got['copper']} {got['friction']} vs {losses}")
    check(got["regenerated"][0] == 0 and got["regenerated"][1] < 0
          and np.isclose(got["electrical"][0] - got["electrical"][1], -got["regenerated"][1],
                         rtol=1e-9),
          "energy: E_el(r = 0) − E_el(r = 1) = the energy regenerated at r = 1",
          f"{got['electrical']} {got['regenerated']}")
    plt.close(fig)
    script = os.path.join(args.source, "analysis", "plot_energy.py")
    out_dir = os.path.join(d, "energyfigs")
    r = subprocess.run(["/usr/bin/python3", script, path, out_dir], capture_output=True, text=True)
    check(r.returncode == 0 and os.listdir(out_dir) == ["energy.png"],
          "plot_energy.py writes energy.png", r.stderr)
    r = subprocess.run(["/usr/bin/python3", script, os.path.join(d, "smoke.h5"), out_dir],
                       capture_output=True, text=True)
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1
          and "electrical" in r.stderr, "plot_energy.py on a sweep without actuators: one "
          "line, non-zero exit", r.stderr)
    test_sweep_metric(args, d, path, ids)


def test_sweep_metric(args, d, path, ids):
    """plot_sweep --metric on the actuated sweep: the electrical cost of transport drawn is
    E_el/(m g d) recomputed from each kept run; one joint's column is the data frame's."""
    import matplotlib.pyplot as plt
    from hexdyn import results as hr

    import plot_sweep

    sweep = hr.open_sweep(path)
    with h5py.File(path, "r") as f:
        want = np.array([f["runs"][i]["energy/electrical"][()] / (
            f["runs"][i]["model/total_mass"][()] * 9.81 * f["runs"][i]["energy/distance"][()])
            for i in ids])
    fig, _ = plot_sweep.draw_heatmap(
        sweep, plot_sweep.column_metric(sweep, "cost_of_transport_electrical"), 0, None)
    drawn = np.ma.filled(fig.axes[0].images[0].get_array(), np.nan).ravel()
    check(np.all(np.isfinite(want)) and np.allclose(drawn, want, rtol=1e-12, atol=0),
          "plot_sweep --metric cost_of_transport_electrical: E_el/(m g d) of the kept runs",
          f"{drawn} vs {want}")
    plt.close(fig)
    one = plot_sweep.column_metric(sweep, "peak_torque[L2_femur]")
    check(np.array_equal(one[3](sweep.table), sweep.to_dataframe()["peak_torque[L2_femur]"]),
          "plot_sweep --metric peak_torque[L2_femur]: the data frame's column")
    script = os.path.join(args.source, "analysis", "plot_sweep.py")
    out = os.path.join(d, "metricfigs")
    r = subprocess.run(["/usr/bin/python3", script, path, out, "--metric",
                        "cost_of_transport_electrical", "--metric", "peak_torque[L2_femur]"],
                       capture_output=True, text=True)
    check(r.returncode == 0 and sorted(os.listdir(out)) == [
        "sweep_cost_of_transport_electrical.png", "sweep_peak_torque_L2_femur.png"],
        "plot_sweep.py --metric writes one heatmap per metric", r.stderr)
    r = subprocess.run(["/usr/bin/python3", script, path, out, "--metric", "nosuch"],
                       capture_output=True, text=True)
    check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1
          and "cost_of_transport_electrical" in r.stderr,
          "plot_sweep.py --metric of no column: one line naming the columns, non-zero exit",
          r.stderr)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    args.source = os.path.abspath(args.source)  # the scenes written here inherit from it
    sys.path.insert(0, os.path.join(args.source, "analysis"))
    import matplotlib

    matplotlib.use("Agg")
    with tempfile.TemporaryDirectory() as d:
        test_paper(args, d)
        test_kraby(args, d)
        test_sweep(args, d)
        test_drive(args, d)
        test_energy(args, d)  # after test_sweep: reads its smoke.h5
    if failures:
        print(f"{len(failures)} check(s) failed: {'; '.join(failures)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
