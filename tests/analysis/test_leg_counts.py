#!/usr/bin/python3
"""The analysis scripts and figures on a robot that is not a hexapod: every script that takes
a result runs on the paper result and on a four-legged copy of it, and each per-leg figure has
one panel (or row, or line) per leg of the file, laid out from the leg count.

The four-legged file is the paper result cut with h5py to its legs L1 ... L4 and their twelve
joints in every leg and joint dataset, /model/leg_names and /model/joint_names set
accordingly, its /model/urdf cut to those legs (tests/python/robot_cut.py). Its kinematics are
the paper robot's for the kept legs (check_result's kinematic checks hold on it); its physics
is no longer a robot's (the removed legs' forces are gone), which is fine for a test of the
layout: the scripts that check physics (check_result --dynamics, paper_statements,
urdf_dynamics) must run to their verdict on it, not pass.

Checked, on both files, against the file's own names:
  - figures.leg_panels: rows = ceil(L / 2), the left legs (L1, L3, ...) in the left column,
    front at the top; for six legs L1 L2 / L3 L4 / L5 L6;
  - plot_grip.draw: one leg panel per leg, at its leg_panels cell, titled by the leg's name;
  - plot_actuators.draw: a grid of (joints per leg) x L panels, one visible panel per joint,
    titled by the joint's name, in its leg's column;
  - plot_kinematics: the gait diagram has one row per leg (its tick labels, L1 on top), the
    foot-path figure one line per leg;
  - plot_paper: Fig. 3a one line per leg (and the sum);
  - the command lines of plot_paper, plot_kinematics, plot_grip, plot_actuators, animate
    (an HTML page at 2 frames per second), robot_summary and check_result (kinematics) exit 0
    and write their files; check_result --dynamics, paper_statements and urdf_dynamics exit 0
    on the paper result and reach a verdict (exit 0 or 1, no traceback) on the four legs.

usage: test_leg_counts.py --hexdyn BUILD/hexdyn --source SOURCE_DIR   (PYTHONPATH=BUILD/python)
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile

failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def cell_of(ax):
    """(row, column) of a panel in its grid."""
    spec = ax.get_subplotspec()
    return spec.rowspan.start, spec.colspan.start


def test_layout():
    from figures import bottom_panels, leg_panels
    rows, cells = leg_panels(6)
    check(rows == 3 and cells == [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1)],
          "leg_panels(6): L1 L2 / L3 L4 / L5 L6", str(cells))
    for n in range(2, 9):
        rows, cells = leg_panels(n)
        left = [k for k in range(n) if k % 2 == 0]  # L1, L3, ...: the odd legs, on the left
        ok = rows == math.ceil(n / 2) and len(set(cells)) == n and \
            all(cells[k] == (k // 2, 0 if k in left else 1) for k in range(n))
        check(ok, f"leg_panels({n}): {rows} rows, left legs left, front at the top", str(cells))
    check(bottom_panels(leg_panels(5)[1]) == {3, 4}, "bottom_panels of five legs: L4, L5")


def test_figures(path, label):
    import matplotlib.pyplot as plt
    from hexdyn import results as hr

    import plot_actuators
    import plot_grip
    import plot_kinematics
    import plot_paper
    from figures import leg_panels

    res = hr.open_result(path)
    legs, joints = hr.leg_names(res), hr.joint_names(res)
    per_leg = hr.leg_joints(res)
    n = len(legs)

    fig, artists, _ = plot_grip.draw(res)
    rows, cells = leg_panels(n)
    panels = [ax for ax in fig.axes if cell_of(ax)[0] > 0]
    check(len(artists["legs"]) == n and len(panels) == n,
          f"{label}: grip figure has {n} leg panels", f"{len(panels)} panels")
    titles = {ax.get_title().split(":")[0]: cell_of(ax) for ax in panels}
    check(titles == {legs[k]: (1 + cells[k][0], cells[k][1]) for k in range(n)},
          f"{label}: grip panels at leg_panels' cells ({rows} rows)", str(titles))
    plt.close(fig)

    fig, artists, _ = plot_actuators.draw(res)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    depth = max(len(j) for j in per_leg)
    grid = fig.axes[0].get_subplotspec().get_gridspec().get_geometry()
    check(len(artists) == len(joints) and len(visible) == len(joints) and grid == (depth, n),
          f"{label}: actuator grid {depth} x {n}, one panel per joint ({len(joints)})",
          f"{len(visible)} panels, grid {grid}")
    where = {ax.get_title().split("\n")[0]: cell_of(ax) for ax in visible}
    check(all(where.get(joints[k]) == (j, leg) for leg, ks in enumerate(per_leg)
              for j, k in enumerate(ks)), f"{label}: each joint in its leg's column", str(where))
    plt.close(fig)

    captured = {}

    def keep(fig, outdir, name, **kw):
        captured[name] = fig
        return name
    for module in (plot_kinematics, plot_paper):
        module.save_atomically = keep
    with tempfile.TemporaryDirectory() as d:
        plot_kinematics.plot_gait_diagram(res, d)
        plot_kinematics.plot_feet_heights(res, d)
        plot_paper.fig3a(res, d)
    ax = captured["gait_diagram.png"].axes[0]
    ticks = [t.get_text() for t in ax.get_yticklabels()]
    check(ticks == list(legs[::-1]), f"{label}: gait diagram rows {', '.join(legs)} (L1 on "
          "top)", str(ticks))
    ax = captured["feet_heights.png"].axes[0]
    drawn = [line.get_label().split()[0] for line in ax.get_lines() if line.get_label() in
             {f"{leg} ({side})" for leg in legs for side in ("left", "right")}]
    check(drawn == list(legs), f"{label}: one foot path per leg", str(drawn))
    ax = captured["fig3a_normal_forces.png"].axes[0]
    drawn = [line.get_label() for line in ax.get_lines() if line.get_label() in legs]
    check(drawn == list(legs), f"{label}: Fig. 3a one force line per leg", str(drawn))
    for fig in captured.values():
        plt.close(fig)


def run(script, *argv, verdict_only=False):
    """Runs analysis/<script> on the arguments; returns its exit status (checked by caller)."""
    r = subprocess.run([sys.executable, os.path.join(ANALYSIS, script), *argv],
                       capture_output=True, text=True)
    ok = r.returncode in (0, 1) and "Traceback" not in r.stderr if verdict_only else \
        r.returncode == 0
    check(ok, f"{script} {' '.join(os.path.basename(a) for a in argv)} exits "
          f"{'with a verdict' if verdict_only else '0'}",
          f"exit {r.returncode}: {(r.stderr or r.stdout).strip().splitlines()[-1:]}")
    return r.returncode


def test_commands(path, label, d, physical):
    out = os.path.join(d, f"{label}_figures")
    for script in ("plot_paper.py", "plot_kinematics.py", "plot_grip.py", "plot_actuators.py"):
        run(script, path, out)
    pngs = sorted(f for f in os.listdir(out) if f.endswith(".png"))
    check(len(pngs) == 9, f"{label}: the four figure scripts wrote 9 figures", str(pngs))
    page = os.path.join(d, f"{label}.html")
    run("animate.py", path, "-o", page, "--fps", "2")
    check(os.path.isfile(page), f"{label}: animate wrote {os.path.basename(page)}")
    run("robot_summary.py", path)
    run("check_result.py", path)
    for argv in (("check_result.py", path, "--dynamics"), ("paper_statements.py", path),
                 ("urdf_dynamics.py", path, "--model-urdf")):
        run(*argv, verdict_only=not physical)


ANALYSIS = ""


def main():
    global ANALYSIS
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    ANALYSIS = os.path.join(args.source, "analysis")
    sys.path[:0] = [ANALYSIS, os.path.join(args.source, "tests", "python")]
    from robot_cut import cut_copy
    import hexdyn

    test_layout()
    with tempfile.TemporaryDirectory() as d:
        paper = os.path.join(d, "paper.h5")
        subprocess.run([args.hexdyn, "run", os.path.join(args.source, "configs", "paper.yaml"),
                        "-o", paper], check=True, capture_output=True)
        four = os.path.join(d, "four_legs.h5")
        cut_copy(paper, four, [0, 1, 2, 3])
        check(hexdyn.leg_names(four) == ("L1", "L2", "L3", "L4") and
              len(hexdyn.joint_names(four)) == 12, "the four-legged copy: 4 legs, 12 joints")
        for path, label, physical in ((paper, "paper", True), (four, "four legs", False)):
            test_figures(path, label)
            test_commands(path, label.replace(" ", "_"), d, physical)
    print(f"leg counts: {'OK' if not failures else f'{len(failures)} failed'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
