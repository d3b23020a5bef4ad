#!/usr/bin/python3
"""Joint operating points of a run, for sizing the actuators: each joint's torque against
its speed, and for a scene with actuators its drive torque on its servo's torque-speed
envelope with the continuous rating and the windowed RMS.

Without actuators: for each joint (/model/joint_names), the torque tau against the angular velocity
omega over the run (/joints/torque against /joints/velocity), with the torque limit, the
URDF velocity limit where the robot has one and the RMS torque (time-weighted, trapezoid
rule over /time) marked. With actuators (docs/theory/drive-train.md): the drive torque
against the speed, (omega, tau_drive) (/joints/drive_torque against /joints/velocity).

usage: /usr/bin/python3 analysis/plot_actuators.py RESULT.h5 OUTDIR [--name FILE]

Writes OUTDIR/actuators.png (or --name): a grid of joints per leg x legs, one column per
leg (/model/leg_names, L1 first) and one row per joint of a leg, hip to foot (coxa, femur,
tibia for the legs of three joints); a leg with fewer joints than the longest leaves its
lower panels empty. Samples are grey dots; samples above the
torque bound are red crosses where the allocation relaxed a constraint (/solver/status 1),
black crosses where it failed (2) and purple circles on optimal samples (not expected).

Without actuators: dotted, ±torque limit (allocation.torque_limit, or each joint's URDF
effort); dash-dotted vertical, ±URDF velocity limit (a robot read from a URDF only); dashed
green, ±RMS torque.

With actuators: solid, the envelope ±min(peak, G k_t eta (V - G k_t |omega|) / R) of the
joint's values in /meta config_yaml actuators.joints (the per-sample bound
/joints/drive_torque_limit; the bound that samples are marked above), falling to 0 at the
no-load speed ±V / (G k_t) (diamonds); dotted orange, ±continuous_torque where the servo has
a continuous rating; dashed green, ±the largest RMS drive torque over the thermal window
(/joints/drive_torque_window_rms; over the run when no window is set); dash-dotted vertical,
the URDF velocity limit as above. A joint whose drive has neither a peak torque nor a
voltage keeps the torque limit, drawn dotted.

The figure is saved under a temporary name and renamed when complete.
"""

import argparse
import os
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from figures import (CONTINUOUS_COLOR, LIMIT_COLOR, RMS_COLOR,  # first: Agg
                     actuator_specs, draw_limit_and_exceedances, drive_torque_bound,
                     envelope_speeds, fit_suptitle, joint_role, mark_exceedances,
                     no_load_speed, run_legs, save_atomically, time_rms, torque_limits,
                     velocity_limits)
from hexdyn.results import open_result
import matplotlib.pyplot as plt
import numpy as np

# The size of one joint's panel [in] (16 x 8 in for six legs of three joints).
PANEL_SIZE = (8 / 3, 8 / 3)
# The envelope is drawn out to the no-load speed when that is within this many times the
# fastest sample of the row, else to the samples' range (a made-up supply far above need).
NO_LOAD_REACH = 4.0


def operating_points(res):
    """The quantities the figure draws, as arrays: t (T,), tau (T,J), omega (T,J), status
    (T,), names (J,), torque limit (J,) or None, velocity limit (J,) or None, rms (J,), the
    legs' names and joints ("legs", "leg_joints": figures.run_legs); with
    actuators also specs (figures.actuator_specs), tau_drive (T,J), drive_limit (T,J) and
    window_rms (J,); specs None without."""
    names = list(res["/model/joint_names"])
    tau_lim, source = torque_limits(res.config, res.urdf, names)
    vel_lim = velocity_limits(res.urdf, names, "/model/leg_mapping" in res)
    t = np.asarray(res["/time"], dtype=float)
    tau = np.asarray(res["/joints/torque"], dtype=float)
    op = {"t": t, "tau": tau, "omega": np.asarray(res["/joints/velocity"], dtype=float),
          "status": np.asarray(res["/solver/status"]), "names": names, "tau_limit": tau_lim,
          "tau_limit_source": source, "velocity_limit": vel_lim, "rms": time_rms(t, tau),
          "specs": actuator_specs(res.config, names)}
    op["legs"], op["leg_joints"] = run_legs(res)
    if op["specs"] is not None:
        op["tau_drive"] = np.asarray(res["/joints/drive_torque"], dtype=float)
        op["drive_limit"] = np.asarray(res["/joints/drive_torque_limit"], dtype=float)
        op["window_rms"] = np.asarray(res["/joints/drive_torque_window_rms"], dtype=float)
    return op


def panels(op):
    """(leg, row) of each joint's panel, in joint order: column = the leg, row = the joint's
    place in its leg, hip to foot."""
    where = {}
    for leg, joints in enumerate(op["leg_joints"]):
        for j, k in enumerate(joints):
            where[k] = (leg, j)
    return [where[k] for k in range(len(op["names"]))]


def row_names(op):
    """The name of each row of panels: the joint's place in its leg ("coxa", "j4"), from the
    first leg that has a joint in that row (figures.joint_role)."""
    names = {}
    for leg, joints in enumerate(op["leg_joints"]):
        for j in range(len(joints)):
            names.setdefault(j, joint_role(op["leg_joints"], leg, j))
    return [names[j] for j in range(len(names))]


def joint_grid(op):
    """The figure and its panels axs[row][leg]; the panels below a leg's last joint hidden."""
    legs = op["leg_joints"]
    rows = max(len(joints) for joints in legs)
    fig, axs = plt.subplots(rows, len(legs), figsize=(PANEL_SIZE[0] * len(legs),
                                                      PANEL_SIZE[1] * rows),
                            sharex="row", sharey="row", constrained_layout=True, squeeze=False)
    for leg, joints in enumerate(legs):
        for j in range(len(joints), rows):
            axs[j][leg].set_visible(False)
    return fig, axs


def label_panel(ax, op, leg, j, ylabel):
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    if leg == 0:
        ax.set_ylabel(f"{row_names(op)[j]}: {ylabel} [N m]", fontsize=8)
    if j == len(op["leg_joints"][leg]) - 1:
        ax.set_xlabel("ω [rad/s]", fontsize=8)


def draw_velocity_limit(ax, op, k):
    if op["velocity_limit"] is None or not np.isfinite(op["velocity_limit"][k]):
        return []
    v = float(op["velocity_limit"][k])
    return [ax.axvline(s * v, color="0.2", ls="-.", lw=0.9) for s in (-1, 1)]


def over_text(artists):
    counts = {key: sum(a["counts"][key] for a in artists) for key in ("relaxed", "failed",
                                                                        "optimal")}
    return (f"samples above the {'bound' if 'envelope' in artists[0] else 'limit'}: "
            f"{counts['relaxed']} relaxed (red), {counts['failed']} failed (black), "
            f"{counts['optimal']} optimal (purple)")


def draw(res):
    """The figure and, per joint, the artists drawn: without actuators {"limit", "relaxed",
    "failed", "optimal", "counts", "velocity", "rms"}; with actuators {"envelope",
    "no_load", "limit", "continuous", "window_rms", "relaxed", "failed", "optimal",
    "counts", "velocity"} (lists of Line2D or collections); and the operating points."""
    op = operating_points(res)
    if op["specs"] is not None:
        return draw_drive(op)
    fig, axs = joint_grid(op)
    artists = []
    where = panels(op)
    for k, name in enumerate(op["names"]):
        leg, j = where[k]
        ax = axs[j][leg]
        tau, omega = op["tau"][:, k], op["omega"][:, k]
        ax.scatter(omega, tau, s=3, color="0.55", lw=0, zorder=2)
        limit = None if op["tau_limit"] is None else float(op["tau_limit"][k])
        drawn = draw_limit_and_exceedances(ax, omega, tau, limit, op["status"], label=False)
        drawn["velocity"] = draw_velocity_limit(ax, op, k)
        rms = float(op["rms"][k])
        drawn["rms"] = [ax.axhline(s * rms, color=RMS_COLOR, ls="--", lw=1.0) for s in (-1, 1)]
        peak = float(np.max(np.abs(tau)))
        ax.set_title(f"{name}\nRMS {rms:.2f}, peak {peak:.2f} N m", fontsize=8)
        label_panel(ax, op, leg, j, "τ")
        artists.append(drawn)
    if op["tau_limit"] is None:
        limit_text = "no torque limit in the configuration"
    elif np.allclose(op["tau_limit"], op["tau_limit"][0]):
        limit_text = f"torque limit ±{op['tau_limit'][0]:g} N m ({op['tau_limit_source']})"
    else:
        limit_text = f"torque limits per joint ({op['tau_limit_source']})"
    vel_text = ("velocity limits: URDF (dash-dotted)" if op["velocity_limit"] is not None
                else "no velocity limit given")
    fit_suptitle(fig, f"Joint operating points τ(ω) over the run: {limit_text} (dotted), "
                 f"{vel_text}, RMS torque (dashed green)\n{over_text(artists)}", fontsize=10)
    return fig, artists, op


def envelope_reach(op, row):
    """The speed the envelopes of a row of panels are drawn to: past the row's no-load
    speeds when they lie within NO_LOAD_REACH times its fastest sample, else past that
    sample's speed."""
    ks = [joints[row] for joints in op["leg_joints"] if len(joints) > row]
    fastest = max(1e-3, float(np.max(np.abs(op["omega"][:, ks]))))
    w0 = max(no_load_speed(op["specs"], k) for k in ks)
    return 1.08 * (max(w0, fastest) if w0 <= NO_LOAD_REACH * fastest else fastest)


def draw_envelope(ax, op, k, reach):
    """±the drive's bound as polylines through its bends; the no-load speed as diamonds."""
    specs = op["specs"]
    w = envelope_speeds(specs, k, reach)
    bound = drive_torque_bound(specs, k, w)
    if not np.isfinite(bound).all():
        return [], []
    lines = [ax.plot(w, s * bound, color=LIMIT_COLOR, lw=1.1, zorder=3)[0] for s in (1, -1)]
    w0 = no_load_speed(specs, k)
    marks = [ax.plot([-w0, w0], [0.0, 0.0], "D", ms=4, color=LIMIT_COLOR, zorder=4)[0]] \
        if w0 <= reach else []
    return lines, marks


def draw_drive_joint(ax, op, k, reach):
    specs = op["specs"]
    tau, omega = op["tau_drive"][:, k], op["omega"][:, k]
    ax.scatter(omega, tau, s=3, color="0.55", lw=0, zorder=2)
    lines, marks = draw_envelope(ax, op, k, reach)
    if lines:
        drawn = {"limit": [], **mark_exceedances(ax, omega, tau, op["drive_limit"][:, k],
                                                 op["status"])}
    else:  # neither peak nor voltage: the allocation's limit, as without actuators
        limit = None if op["tau_limit"] is None else float(op["tau_limit"][k])
        drawn = draw_limit_and_exceedances(ax, omega, tau, limit, op["status"], label=False)
    drawn.update(envelope=lines, no_load=marks, velocity=draw_velocity_limit(ax, op, k))
    rated = float(specs["continuous_torque"][k])
    drawn["continuous"] = [ax.axhline(s * rated, color=CONTINUOUS_COLOR, ls=":", lw=1.2)
                           for s in (-1, 1)] if np.isfinite(rated) else []
    rms = float(op["window_rms"][k])
    drawn["window_rms"] = [ax.axhline(s * rms, color=RMS_COLOR, ls="--", lw=1.0)
                           for s in (-1, 1)]
    model = str(specs["model"][k]).replace("dynamixel_", "")
    rating = f"rated {rated:.2f}" if np.isfinite(rated) else "no rating"
    ax.set_title(f"{op['names'][k]}{' (' + model + ')' if model else ''}\nwindow RMS "
                 f"{rms:.2f}, peak {float(np.max(np.abs(tau))):.2f}, {rating}", fontsize=8)
    return drawn


def draw_drive(op):
    fig, axs = joint_grid(op)
    reach = [envelope_reach(op, j) for j in range(len(axs))]
    artists = []
    for k, (leg, j) in enumerate(panels(op)):
        artists.append(draw_drive_joint(axs[j][leg], op, k, reach[j]))
        label_panel(axs[j][leg], op, leg, j, "τ_drive")
    for j in range(len(axs)):
        axs[j][0].set_xlim(-reach[j], reach[j])
    rated = np.isfinite(op["specs"]["continuous_torque"]).sum()
    rating = ("no joint has a continuous rating" if rated == 0 else
              f"continuous rating (dotted orange) on {rated} of {len(op['names'])} joints")
    fit_suptitle(fig, "Drive operating points (ω, τ_drive) over the run on each servo's "
                 "torque-speed envelope ±min(peak, G k_t η (V − G k_t|ω|)/R) (solid; "
                 "diamonds: the no-load speed V/(G k_t)); largest RMS over the thermal "
                 f"window (dashed green); {rating}\n{over_text(artists)}", fontsize=10)
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
