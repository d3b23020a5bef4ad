"""Joint torque and velocity limits of a run, and the drawing of torque limits and their
exceedances, shared by the torque figures (plot_paper.py, plot_actuators.py, plot_sweep.py).

Torque limit: `allocation.torque_limit` of the resolved configuration (/meta config_yaml),
the same for every joint, or `effort`: each joint's `<limit effort>` in /model/urdf.
Velocity limit: `<limit velocity>` of /model/urdf, only for a robot read from a URDF file
(the result has /model/leg_mapping); a robot given by parameters has none (its generated
URDF carries a placeholder, src/hexdyn/model/urdf.hpp). The allocation keeps |tau| within
the torque limit on every optimal sample; a sample above it is one where the allocation had
to relax a constraint (/solver/status 1) or failed (2). docs/user/animation.md#figures
"""

import xml.etree.ElementTree as ET

import numpy as np

RELAXED_COLOR, FAILED_COLOR, OPTIMAL_OVER_COLOR = "#d62728", "black", "#9467bd"
LIMIT_COLOR = "0.2"
# |tau| above limit * (1 + REL) + ABS counts as an exceedance (the allocation's tolerance).
EXCEED_REL, EXCEED_ABS = 1e-6, 1e-9


def urdf_joint_limits(urdf_text):
    """{joint name: {"effort": N m, "velocity": rad/s}} of the <limit> elements (missing or
    non-positive values left out)."""
    out = {}
    if not urdf_text:
        return out
    root = ET.fromstring(urdf_text)
    for joint in root.findall("joint"):
        lim = joint.find("limit")
        entry = {}
        if lim is not None:
            for key in ("effort", "velocity"):
                v = lim.get(key)
                if v is not None and float(v) > 0:
                    entry[key] = float(v)
        out[joint.get("name")] = entry
    return out


def torque_limits(config, urdf_text, joint_names):
    """(limits (J,) N m or None, a few words naming the source)."""
    value = (config or {}).get("allocation", {}).get("torque_limit")
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return np.full(len(joint_names), float(value)), "allocation.torque_limit"
    if value == "effort":
        lims = urdf_joint_limits(urdf_text)
        tau = np.array([lims.get(n, {}).get("effort", np.nan) for n in joint_names])
        if np.isfinite(tau).any():
            return tau, "URDF effort limits"
    return None, "no torque limit"


def velocity_limits(urdf_text, joint_names, from_description):
    """(J,) rad/s (NaN where none) or None for a robot given by parameters."""
    if not from_description:
        return None
    lims = urdf_joint_limits(urdf_text)
    vel = np.array([lims.get(n, {}).get("velocity", np.nan) for n in joint_names])
    return vel if np.isfinite(vel).any() else None


def exceeds(values, limit):
    """|values| above `limit` (broadcast) beyond the allocation's tolerance."""
    limit = np.asarray(limit, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.abs(values) > limit * (1 + EXCEED_REL) + EXCEED_ABS


def draw_limit_and_exceedances(ax, x, tau, limit, status, color=LIMIT_COLOR, label=True,
                               xy=None):
    """±limit as horizontal lines and the samples above it as markers: red crosses where
    the allocation relaxed (status 1), black where it failed (2), purple circles on
    optimal samples (not expected). x, tau, status: (T,); xy: the points' x if not x.
    Returns {"limit": [Line2D, Line2D], "relaxed": artist or None, "failed": ...,
    "optimal": ..., "counts": {"relaxed": n, "failed": n, "optimal": n}}."""
    out = {"limit": [], "relaxed": None, "failed": None, "optimal": None,
           "counts": {"relaxed": 0, "failed": 0, "optimal": 0}}
    if limit is None or not np.isfinite(limit):
        return out
    for s in (-1, 1):
        out["limit"].append(ax.axhline(s * limit, color=color, ls=":", lw=0.9,
                                       label=f"torque limit ±{limit:g} N m"
                                       if (label and s == 1) else None))
    over = exceeds(tau, limit)
    status = np.zeros_like(tau, dtype=int) if status is None else np.asarray(status)
    px = x if xy is None else xy
    for key, code, style in (("relaxed", 1, dict(marker="x", color=RELAXED_COLOR, s=22)),
                             ("failed", 2, dict(marker="x", color=FAILED_COLOR, s=22)),
                             ("optimal", 0, dict(marker="o", facecolors="none",
                                                 edgecolors=OPTIMAL_OVER_COLOR, s=22))):
        sel = over & (status == code)
        out["counts"][key] = int(sel.sum())
        if sel.any():
            out[key] = ax.scatter(px[sel], tau[sel], zorder=6, lw=1.0, **style,
                                  label=f"above the limit, {key} sample ({int(sel.sum())})"
                                  if label else None)
    return out


def time_rms(t, values):
    """Time-weighted RMS over t (trapezoid rule of values² dt, over the duration), per column."""
    t = np.asarray(t, dtype=float)
    values = np.asarray(values, dtype=float)
    if t.size < 2 or t[-1] <= t[0]:
        return np.sqrt(np.mean(values ** 2, axis=0))
    sq = values ** 2
    integral = np.sum(0.5 * (sq[1:] + sq[:-1]) * np.diff(t).reshape((-1,) + (1,) * (sq.ndim - 1)),
                      axis=0)
    return np.sqrt(integral / (t[-1] - t[0]))
