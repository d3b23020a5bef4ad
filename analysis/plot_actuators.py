#!/usr/bin/python3
"""Joint operating points of a run, for sizing the actuators: for each of the 18 joints, the
torque tau against the angular velocity omega over the run (/joints/torque against
/joints/velocity), with the torque limit, the URDF velocity limit where the robot has one
and the RMS torque (time-weighted, trapezoid rule over /time) marked.

usage: /usr/bin/python3 analysis/plot_actuators.py RESULT.h5 OUTDIR [--name FILE]

Writes OUTDIR/actuators.png (or --name): a 3 x 6 grid, rows coxa, femur, tibia (the joints
of each leg hip to foot), columns legs L1 ... L6. Samples are grey dots; samples above the
torque limit are red crosses where the allocation relaxed a constraint (/solver/status 1),
black crosses where it failed (2) and purple circles on optimal samples (not expected).
Dotted: ±torque limit (allocation.torque_limit, or each joint's URDF effort); dash-dotted
vertical: ±URDF velocity limit (a robot read from a URDF only); dashed green: ±RMS torque.
The figure is saved under a temporary name and renamed when complete.
"""

import argparse
import os
import sys

from figures import (RMS_COLOR, draw_limit_and_exceedances, fit_suptitle,  # first: Agg
                     save_atomically, time_rms, torque_limits, velocity_limits)
from hexdyn.results import open_result
import matplotlib.pyplot as plt
import numpy as np

JOINT_ROWS = ("coxa", "femur", "tibia")


def operating_points(res):
    """The quantities the figure draws, as arrays: t (T,), tau (T,J), omega (T,J), status
    (T,), names (J,), torque limit (J,) or None, velocity limit (J,) or None, rms (J,)."""
    names = list(res["/model/joint_names"])
    tau_lim, source = torque_limits(res.config, res.urdf, names)
    vel_lim = velocity_limits(res.urdf, names, "/model/leg_mapping" in res)
    t = np.asarray(res["/time"], dtype=float)
    tau = np.asarray(res["/joints/torque"], dtype=float)
    return {"t": t, "tau": tau, "omega": np.asarray(res["/joints/velocity"], dtype=float),
            "status": np.asarray(res["/solver/status"]), "names": names, "tau_limit": tau_lim,
            "tau_limit_source": source, "velocity_limit": vel_lim, "rms": time_rms(t, tau)}


def draw(res):
    """The figure and, per joint, the artists drawn: {"limit", "relaxed", "failed",
    "optimal", "counts", "velocity", "rms"} (lists of Line2D or collections)."""
    op = operating_points(res)
    fig, axs = plt.subplots(3, 6, figsize=(16, 8), sharex="row", sharey="row",
                            constrained_layout=True)
    artists = []
    for k, name in enumerate(op["names"]):
        leg, j = divmod(k, 3)
        ax = axs[j][leg]
        tau, omega = op["tau"][:, k], op["omega"][:, k]
        ax.scatter(omega, tau, s=3, color="0.55", lw=0, zorder=2)
        limit = None if op["tau_limit"] is None else float(op["tau_limit"][k])
        drawn = draw_limit_and_exceedances(ax, omega, tau, limit, op["status"], label=False)
        drawn["velocity"] = []
        if op["velocity_limit"] is not None and np.isfinite(op["velocity_limit"][k]):
            v = float(op["velocity_limit"][k])
            drawn["velocity"] = [ax.axvline(s * v, color="0.2", ls="-.", lw=0.9) for s in (-1, 1)]
        rms = float(op["rms"][k])
        drawn["rms"] = [ax.axhline(s * rms, color=RMS_COLOR, ls="--", lw=1.0) for s in (-1, 1)]
        peak = float(np.max(np.abs(tau)))
        ax.set_title(f"{name}\nRMS {rms:.2f}, peak {peak:.2f} N m", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
        if leg == 0:
            ax.set_ylabel(f"{JOINT_ROWS[j]}: τ [N m]", fontsize=8)
        if j == 2:
            ax.set_xlabel("ω [rad/s]", fontsize=8)
        artists.append(drawn)
    counts = {key: sum(a["counts"][key] for a in artists) for key in ("relaxed", "failed",
                                                                        "optimal")}
    if op["tau_limit"] is None:
        limit_text = "no torque limit in the configuration"
    elif np.allclose(op["tau_limit"], op["tau_limit"][0]):
        limit_text = f"torque limit ±{op['tau_limit'][0]:g} N m ({op['tau_limit_source']})"
    else:
        limit_text = f"torque limits per joint ({op['tau_limit_source']})"
    vel_text = ("velocity limits: URDF (dash-dotted)" if op["velocity_limit"] is not None
                else "no velocity limit given")
    over = (f"samples above the limit: {counts['relaxed']} relaxed (red), {counts['failed']} "
            f"failed (black), {counts['optimal']} optimal (purple)")
    fit_suptitle(fig, f"Joint operating points τ(ω) over the run: {limit_text} (dotted), "
                 f"{vel_text}, RMS torque (dashed green)\n{over}", fontsize=10)
    return fig, artists, op


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="plot_actuators.py", description=__doc__.strip().split("\n\n")[0],
        epilog=__doc__.strip().split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", help="a hexdyn result file with dynamics")
    ap.add_argument("outdir")
    ap.add_argument("--name", default="actuators.png", help="file name (default actuators.png)")
    args = ap.parse_args(argv)
    try:
        res = open_result(args.result)
    except (OSError, ValueError) as e:
        print(f"plot_actuators: {args.result}: {e}", file=sys.stderr)
        return 2
    if not res.has_dynamics:
        print(f"plot_actuators: {args.result} has no dynamics datasets", file=sys.stderr)
        return 2
    os.makedirs(args.outdir, exist_ok=True)
    fig, _, _ = draw(res)
    path = save_atomically(fig, args.outdir, args.name, dpi=110)
    print(f"plot_actuators: wrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
