#!/usr/bin/python3
"""The paper's figures from a hexdyn-result file.

usage: /usr/bin/python3 analysis/plot_paper.py RESULT.h5 OUTDIR

Writes, atomically:
  fig3a_normal_forces.png    normal foot forces F_iz of every leg (paper Fig. 3a)
  fig3b_impacts_legs_3_4.png close view of the first touchdowns of legs 3 and 4 (Fig. 3b)
  fig4a_torques_leg1.png     joint torques of leg 1 (Fig. 4a), with the torque limit and
                             the samples above it marked (relaxed: red crosses)
  fig4b_torques_leg2.png     joint torques of leg 2 (Fig. 4b), the same
  fig5_total_power.png       total instantaneous power P_in = sum |tau omega| (Fig. 5)
"""
import argparse
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (MIN_SPAN, OPTIMAL_OVER_COLOR, RELAXED_COLOR,  # first: Agg
                     draw_limit_and_exceedances, fit_title, fraction_text, joint_role,
                     leg_side, run_legs, save_atomically, shade_runs, torque_limits)
from hexdyn.results import open_result
import matplotlib.pyplot as plt
import numpy as np

G = 9.81
LEG_STYLE = {"left": "-", "right": "--"}  # left solid, right dashed
RELAXED_SPAN_COLOR = "#f2c4c4"  # a light tint of RELAXED_COLOR


def shade_relaxed(ax, t, status):
    """Shaded spans where the allocation had to relax a constraint (status 1) or failed, each
    at least figures.MIN_SPAN of the run wide, named once in the legend."""
    return shade_runs(ax, t, np.asarray(status) != 0, RELAXED_SPAN_COLOR,
                      f"relaxed or failed samples (shaded at least {100 * MIN_SPAN:g} % of the "
                      "run wide)")


def scene_words(res):
    """The scene as its resolved configuration says: "duty factor 1/2, stairs 0.05 m risers,
    0.25 m treads" (terrain words for flat ground and slopes)."""
    config = res.config if isinstance(res.config, dict) else {}
    words = []
    duty = config.get("gait", {}).get("duty_factor")
    if duty is not None:
        words.append(f"duty factor {fraction_text(duty)}")
    terrain = config.get("terrain", {})
    kind = terrain.get("type")
    if kind == "stairs":
        words.append(f"stairs of {float(terrain['riser_height']):g} m risers and "
                     f"{float(terrain['tread_depth']):g} m treads")
    elif kind == "slope":
        words.append(f"slope of {np.degrees(float(terrain.get('angle', 0.0))):.3g}°")
    elif kind:
        words.append(f"{kind} ground")
    return ", ".join(words)


def fig3a(res, outdir):
    t = res["/time"]
    F = res["/contacts/force"]
    fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    for leg, name in enumerate(run_legs(res)[0]):
        ax.plot(t, F[:, leg, 2], LEG_STYLE[leg_side(leg)], lw=1.0, label=name)
    total = F[:, :, 2].sum(axis=1)
    ax.plot(t, total, color="k", lw=0.8, alpha=0.6, label="sum")
    weight = float(res["/model/total_mass"]) * G
    ax.axhline(weight, color="k", ls=":", lw=0.8, label=f"weight {weight:.1f} N")
    shade_relaxed(ax, t, res["/solver/status"])
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("normal foot force $F_{iz}$ [N]")
    fit_title(ax, f"Normal foot forces, {scene_words(res)} (cf. paper Fig. 3a)")
    ax.legend(ncol=4, fontsize=8, loc="upper right")
    ax.grid(alpha=0.3)
    return save_atomically(fig, outdir, "fig3a_normal_forces.png")


def fig3b(res, outdir):
    t = res["/time"]
    F = res["/contacts/force"]
    legs = res["/impacts/leg"].astype(int) + 1  # 0-based in the file (leg dimension)
    starts = res["/impacts/t_start"]
    durations = res["/impacts/duration"]
    step = (res.config.get("output", {}).get("sample_step") if isinstance(res.config, dict)
            else None)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for ax, leg in zip(axes, (3, 4)):
        k = np.flatnonzero(legs == leg)
        if k.size == 0:
            ax.text(0.5, 0.5, f"no impact of L{leg}", transform=ax.transAxes, ha="center")
            continue
        t0, d = starts[k[0]], durations[k[0]]
        window = (t >= t0 - 4 * d) & (t <= t0 + 6 * d)
        ax.plot((t[window] - t0) * 1e3, F[window, leg - 1, 2], "o-", ms=2.5, lw=1.0,
                label=f"L{leg}, touchdown at t = {t0:.3f} s")
        coarse = np.arange(0.0, t[-1] + 1e-9, float(step)) if step else np.array([])
        near = coarse[(coarse >= t0 - 4 * d) & (coarse <= t0 + 6 * d)]
        for c in near:
            ax.axvline((c - t0) * 1e3, color="r", ls=":", lw=0.8)
        ax.set_xlabel("time since touchdown [ms]")
        ax.set_ylabel(f"$F_{{{leg}z}}$ [N]")
        fit_title(ax, f"Impact of L{leg}: peak {res['/impacts/peak_force'][k[0]]:.1f} N, "
                  f"{d * 1e3:.2f} ms")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Touchdown transients" + (f" (red dotted: the output.sample_step {float(step):g} s "
                                           "samples, if any fall here)" if step else ""),
                 fontsize=10)
    return save_atomically(fig, outdir, "fig3b_impacts_legs_3_4.png")


def draw_torques(ax, res, leg):
    """The joint torques of leg `leg` (1-based) over time on `ax`, one line per joint of the
    leg (/model/joint_names: "coxa (joint 1)", ...), with each joint's torque
    limit (allocation.torque_limit, or its URDF effort) as dotted lines and the samples above
    it marked (red crosses: relaxed samples; black: failed; purple circles: optimal, not
    expected), analysis/figures.py. Returns one dict of artists per joint
    (figures.draw_limit_and_exceedances)."""
    t = res["/time"]
    tau = res["/joints/torque"]
    names = list(res["/model/joint_names"])
    limits, _ = torque_limits(res.config, res.urdf, names)
    uniform = limits is not None and np.allclose(limits, limits[0])
    joints = run_legs(res)[1]
    drawn = []
    for j, k in enumerate(joints[leg - 1]):
        role = joint_role(joints, leg - 1, j)
        line = ax.plot(t, tau[:, k], lw=1.0, label=f"{role} (joint {j + 1})")[0]
        limit = None if limits is None else float(limits[k])
        drawn.append(draw_limit_and_exceedances(
            ax, t, tau[:, k], limit, res["/solver/status"],
            color="k" if uniform else line.get_color(), label=False))
        if drawn[-1]["limit"] and uniform and j > 0:
            for a in drawn[-1]["limit"]:  # one pair of lines for a common limit
                a.remove()
            drawn[-1]["limit"] = drawn[0]["limit"]
    if limits is not None:
        ax.plot([], [], color="k", ls=":", lw=0.9,
                label=f"torque limit ±{limits[0]:g} N m" if uniform else "torque limits")
    counts = {key: sum(d["counts"][key] for d in drawn) for key in ("relaxed", "failed",
                                                                    "optimal")}
    for key, style in (("relaxed", dict(marker="x", color=RELAXED_COLOR, ls="")),
                       ("failed", dict(marker="x", color="k", ls="")),
                       ("optimal", dict(marker="o", mfc="none", mec=OPTIMAL_OVER_COLOR, ls=""))):
        if counts[key]:
            ax.plot([], [], label=f"above the limit: {key} sample ({counts[key]})", **style)
    return drawn


def fig4(res, outdir, leg, name, panel):
    t = res["/time"]
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    draw_torques(ax, res, leg)
    shade_relaxed(ax, t, res["/solver/status"])
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("joint torque [N m]")
    fit_title(ax, f"Joint torques of L{leg} (cf. paper Fig. 4{panel}); shaded: relaxed "
              "or failed samples", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return save_atomically(fig, outdir, name)


def fig5(res, outdir):
    t = res["/time"]
    P = res["/power/total"]
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    ax.plot(t, P, lw=1.0, color="C3")
    shade_relaxed(ax, t, res["/solver/status"])
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(r"$P_{in} = \sum |\tau_{ij}\,\omega_{ij}|$ [W]")
    fit_title(ax, f"Total instantaneous power (cf. paper Fig. 5); energy "
              f"{float(res['/energy/total']):.2f} J")
    ax.grid(alpha=0.3)
    return save_atomically(fig, outdir, "fig5_total_power.png")


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="plot_paper.py", description=__doc__.strip().split("\n\n")[0],
        epilog=__doc__.strip().split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="a hexdyn-result file with dynamics")
    ap.add_argument("outdir", help="directory for the PNG files (created if missing)")
    args = ap.parse_args(argv)
    try:
        res = open_result(args.result)
    except (OSError, ValueError) as e:
        print(f"plot_paper: {e}", file=sys.stderr)
        return 2
    if not res.has_dynamics:
        print(f"plot_paper: {args.result} has no dynamics datasets", file=sys.stderr)
        return 2
    out = args.outdir
    os.makedirs(out, exist_ok=True)
    written = [fig3a(res, out), fig3b(res, out),
               fig4(res, out, 1, "fig4a_torques_leg1.png", "a"),
               fig4(res, out, 2, "fig4b_torques_leg2.png", "b"),
               fig5(res, out)]
    for w in written:
        print(f"plot_paper: wrote {w}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
