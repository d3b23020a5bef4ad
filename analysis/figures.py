"""What every figure of analysis/ shares: writing files atomically, the colours, labels with
units, titles that fit their figure, and the joint torque and velocity limits of a run with
the drawing of the limits and of the samples above them.

    import figures                       # analysis/ on sys.path (the scripts run from it)
    figures.save_atomically(fig, outdir, "name.png")
    ax.set_xlabel(figures.with_units("peak speed", "m/s"))      # "peak speed [m/s]"
    figures.fit_suptitle(fig, "a long title ...")          # wrapped to the figure's width

Torque limit: `allocation.torque_limit` of the resolved configuration (/meta config_yaml),
the same for every joint, or `effort`: each joint's `<limit effort>` in /model/urdf.
Velocity limit: `<limit velocity>` of /model/urdf, only for a robot read from a URDF file
(the result has /model/leg_mapping); a robot given by parameters has none (its generated
URDF carries a placeholder, src/hexdyn/model/urdf.hpp). The allocation keeps |tau| within
the torque limit on every optimal sample; a sample above it is one where the allocation had
to relax a constraint (/solver/status 1) or failed (2). docs/user/animation.md#figures

The drive train (a scene with `actuators`, docs/theory/drive-train.md): each joint's drive
from /meta config_yaml actuators.joints, and its torque-speed bound
min(peak, G k_t eta (V - G k_t |omega|) / R) as a polyline that is the bound exactly.
"""

import csv
import os
import textwrap
import xml.etree.ElementTree as ET
from fractions import Fraction

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
import hexdyn  # noqa: E402

# ---------------------------------------------------------------- colours
SUPPORT_COLOR, IMPACT_COLOR = "tab:blue", "tab:red"
# One colour per leg, in leg order (as many as a robot has legs at most: core/sizes.hpp
# kMaxLegs); leg_color(k) for leg k.
LEG_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
              "tab:pink", "tab:olive")
RELAXED_COLOR, FAILED_COLOR, OPTIMAL_OVER_COLOR = "#d62728", "black", "#9467bd"
LIMIT_COLOR = "0.2"
RMS_COLOR = "#2ca02c"
# |tau| above limit * (1 + REL) + ABS counts as an exceedance (the allocation's tolerance).
EXCEED_REL, EXCEED_ABS = 1e-6, 1e-9


# ---------------------------------------------------------------- files
def save_atomically(fig, outdir, name, dpi=150):
    """Saves `fig` as OUTDIR/name via a temporary file and os.replace; closes the figure."""
    final = os.path.join(outdir, name)
    tmp = os.path.join(outdir, f".{name}.tmp.{os.getpid()}")
    try:
        fig.savefig(tmp, format=os.path.splitext(name)[1].lstrip(".") or "png", dpi=dpi)
        os.replace(tmp, final)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    finally:
        plt.close(fig)
    return final


def write_csv_atomically(path, header, rows):
    """Writes `header` and `rows` (lists of cells) as CSV to `path` via a temporary file
    and os.replace; returns `path`."""
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(rows)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


# ---------------------------------------------------------------- legs and their joints
# The legs and joints of a run are the file's: /model/leg_names (L legs) and
# /model/joint_names (J joints, leg-major), never a count written here. A leg's joints are
# the joints whose names start with the leg's name and "_" (L1_coxa, L1_j1:
# docs/theory/conventions.md#legs-and-joints); its side follows the leg order of the same
# page: L1 left front, then right, alternating (the odd legs L1, L3, ... are on the left).
def leg_color(k):
    """The colour of leg k (0-based)."""
    return LEG_COLORS[k % len(LEG_COLORS)]


def leg_side(k):
    """"left" or "right" for leg k (0-based) by the documented leg order."""
    return "left" if k % 2 == 0 else "right"


def joint_role(legs_joints, leg, j):
    """The positional name of joint j (0-based, hip to foot) of leg `leg` (0-based) of the legs'
    joints `legs_joints` (run_legs): coxa, femur, tibia for a leg of three joints, j1 ... jm
    else (hexdyn.results.joint_roles), whatever the description calls them."""
    return hexdyn.results.joint_roles(len(legs_joints[leg]))[j]


def run_legs(res):
    """(leg names, joints of each leg) of a result or replay (hexdyn.results.leg_names and
    leg_joints)."""
    return tuple(hexdyn.results.leg_names(res)), hexdyn.results.leg_joints(res)


def leg_panels(n_legs):
    """The panels of a figure with one panel per leg: (rows, cells), rows = ceil(n_legs / 2)
    and cells[k] = (row, column) of leg k, the left legs in the left column (0) and the
    right legs in the right one (1), each side front (row 0) to rear. For six legs: L1 L2 /
    L3 L4 / L5 L6."""
    cells, count = [], {"left": 0, "right": 0}
    for k in range(n_legs):
        side = leg_side(k)
        cells.append((count[side], 0 if side == "left" else 1))
        count[side] += 1
    return -(-n_legs // 2), cells


def bottom_panels(cells):
    """The legs whose panel is the lowest of its column (they carry the x labels)."""
    last = {}
    for k, (row, col) in enumerate(cells):
        if row >= last.get(col, (-1, None))[0]:
            last[col] = (row, k)
    return {k for _, k in last.values()}


# ---------------------------------------------------------------- labels and titles
def with_units(name, units):
    """An axis label with its units: "riser [m]"; dimensionless ("1") as "[-]"; no units
    (None or "": words, cases) the name alone."""
    if units is None or units == "":
        return name
    return f"{name} [{'-' if units == '1' else units}]"


def fraction_text(x, max_denominator=12):
    """A number as the fraction it is ("1/2", "5/6") when one with a small denominator
    equals it to 1e-9, else as %g."""
    q = Fraction(float(x)).limit_denominator(max_denominator)
    if q.denominator > 1 and abs(float(q) - float(x)) < 1e-9:
        return f"{q.numerator}/{q.denominator}"
    return f"{float(x):g}"


def sweep_axis_units(sweep):
    """Units of each axis of a sweep (the `units` attribute of /axes/{i}/values: the unit of
    the swept key, docs/user/output.md; None for words, cases and keys without one), as the
    reader gives them (SweepAxis.units)."""
    return [a.units for a in sweep.axes]


def sweep_axis_label(sweep, i, units=None):
    """The label of axis i of a sweep: its key and the key's unit ("terrain.riser_height [m]")."""
    units = sweep_axis_units(sweep) if units is None else units
    return with_units(sweep.axes[i].key, units[i])


def _chars_per_line(width_inches, fontsize):
    # An average glyph of DejaVu Sans is about 0.6 em wide.
    return max(20, int(width_inches * 72.0 / (0.6 * fontsize)))


def wrap(text, width_inches, fontsize):
    """`text` with each of its lines wrapped to fit `width_inches` at `fontsize` points."""
    n = _chars_per_line(width_inches, fontsize)
    return "\n".join(textwrap.fill(line, n) if line else line for line in text.split("\n"))


def fit_suptitle(fig, text, fontsize=9):
    """The figure title, wrapped to the figure's width (never cut at its edges)."""
    return fig.suptitle(wrap(text, 0.96 * fig.get_figwidth(), fontsize), fontsize=fontsize)


def fit_title(ax, text, fontsize=10):
    """The title of one panel, wrapped to the panel's width."""
    width = ax.get_position().width * ax.figure.get_figwidth()
    return ax.set_title(wrap(text, width, fontsize), fontsize=fontsize)


# ---------------------------------------------------------------- intervals in time
# A shaded interval is at least this fraction of the run's duration wide: a touchdown
# transient or a relaxed sample lasts milliseconds of a run of seconds.
MIN_SPAN = 0.006


def runs_of(mask):
    """(first, last) sample indices of each run of True in a boolean vector."""
    padded = np.concatenate(([False], np.asarray(mask, dtype=bool), [False]))
    edges = np.flatnonzero(np.diff(padded.astype(np.int8)))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2])]


def shade_runs(ax, t, mask, color, label):
    """One span per run of True samples of `mask`, from its first to its last time, widened
    to MIN_SPAN of the run's duration so that it shows; `label` names the spans in a legend
    (once). Returns the spans."""
    t = np.asarray(t, dtype=float)
    width = MIN_SPAN * (t[-1] - t[0]) if len(t) > 1 else 0.0
    spans = []
    for a, b in runs_of(mask):
        spans.append(ax.axvspan(t[a], max(t[b], t[a] + width), color=color, lw=0, zorder=0,
                                label=label if not spans else None))
    return spans


# ---------------------------------------------------------------- limits
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
    if limit is None or not np.isfinite(limit):
        return {"limit": [], **mark_exceedances(ax, x, tau, None, status)}
    lines = [ax.axhline(s * limit, color=color, ls=":", lw=0.9,
                        label=f"torque limit ±{limit:g} N m" if (label and s == 1) else None)
             for s in (-1, 1)]
    return {"limit": lines, **mark_exceedances(ax, x, tau, limit, status, label, xy)}


def mark_exceedances(ax, x, tau, limit, status, label=False, xy=None):
    """The samples with |tau| above `limit` (a number, or one bound per sample) as markers,
    by /solver/status as draw_limit_and_exceedances draws them; no limit (None): none.
    Returns {"relaxed": artist or None, "failed": ..., "optimal": ..., "counts": {...}}."""
    out = {"relaxed": None, "failed": None, "optimal": None,
           "counts": {"relaxed": 0, "failed": 0, "optimal": 0}}
    if limit is None:
        return out
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


# ---------------------------------------------------------------- the drive train
# Keys of /meta config_yaml actuators.joints.NAME and the value when the file leaves one out
# (docs/user/configuration.md#actuators): no voltage, peak or continuous rating is +inf.
DRIVE_KEYS = (("gear_ratio", np.nan), ("torque_constant", np.nan), ("resistance", np.nan),
              ("gear_efficiency", 1.0), ("voltage", np.inf), ("peak_torque", np.inf),
              ("continuous_torque", np.inf))
CONTINUOUS_COLOR = "tab:orange"


def actuator_specs(config, joint_names):
    """Each joint's drive from the resolved configuration (/meta config_yaml,
    actuators.joints.NAME): {key: (J,) array} for the keys of DRIVE_KEYS, and "model": (J,)
    servo names ("" where none); None for a result without actuators."""
    joints = ((config or {}).get("actuators") or {}).get("joints")
    if not joints:
        return None
    out = {key: np.array([float(joints[n].get(key, missing)) for n in joint_names])
           for key, missing in DRIVE_KEYS}
    out["model"] = np.array([str(joints[n].get("model", "")) for n in joint_names])
    return out


def drive_torque_bound(specs, k, omega):
    """The drive's bound on |tau_drive| of joint k at the joint speeds `omega` [rad/s]:
    min(peak, G k_t eta (V - G k_t |omega|) / R), clipped at 0
    (docs/theory/drive-train.md#torque-bound); +inf where the joint has neither bound."""
    gk = specs["gear_ratio"][k] * specs["torque_constant"][k]
    v, peak = specs["voltage"][k], specs["peak_torque"][k]
    w = np.abs(np.asarray(omega, dtype=float))
    line = np.full(w.shape, np.inf) if np.isinf(v) else \
        gk * specs["gear_efficiency"][k] * (v - gk * w) / specs["resistance"][k]
    return np.maximum(0.0, np.minimum(peak, line))


def no_load_speed(specs, k):
    """V / (G k_t) [rad/s], where the bound falls to 0; +inf without a voltage."""
    return specs["voltage"][k] / (specs["gear_ratio"][k] * specs["torque_constant"][k])


def envelope_speeds(specs, k, omega_max):
    """The speeds in [-omega_max, omega_max] where the bound bends (0, the knee where the
    torque-speed line meets the peak rating, the no-load speed) and the ends: the polyline
    through (w, drive_torque_bound(w)) at these speeds is the bound exactly."""
    gk = specs["gear_ratio"][k] * specs["torque_constant"][k]
    w0 = no_load_speed(specs, k)
    bends = [0.0, omega_max, w0]
    if np.isfinite(w0) and np.isfinite(specs["peak_torque"][k]):
        bends.append(w0 - specs["peak_torque"][k] * specs["resistance"][k]
                     / (gk * gk * specs["gear_efficiency"][k]))
    w = sorted({b for b in bends if 0.0 <= b <= omega_max})
    return np.array([-b for b in reversed(w) if b > 0] + w)


# ---------------------------------------------------------------- limits of a sweep
LIMIT_KEY = "allocation.torque_limit"


def nanmax_rows(a):
    """Row maxima ignoring NaN; NaN for a row with no finite value."""
    out = np.full(a.shape[0], np.nan)
    finite = np.isfinite(a).any(axis=1)
    out[finite] = np.nanmax(a[finite], axis=1)
    return out


def scenario_torque_limits(sweep):
    """Torque limits per scenario and joint, (N, J) N m, or None with the reason."""
    joints = list(sweep.joint_names)
    n = sweep.size
    keys = [a.key for a in sweep.axes]
    if LIMIT_KEY in keys and sweep.axes[keys.index(LIMIT_KEY)].numeric:
        axis = sweep.axes[keys.index(LIMIT_KEY)]
        col = np.asarray(sweep.table["axis_index"])[:, keys.index(LIMIT_KEY)]
        return np.repeat(np.asarray(axis.values, dtype=float)[col][:, None], len(joints), 1), \
            f"{LIMIT_KEY} (swept)"
    config = sweep.config
    value = config.get("allocation", {}).get("torque_limit")
    urdf = ""
    if value == "effort":
        if not sweep.has_runs:
            return None, "URDF effort limits: not in a sweep file without kept runs"
        import h5py

        with h5py.File(sweep.path, "r") as f:
            first = sorted(f["runs"].keys())[0]
            urdf = str(hexdyn.decode_text(f["runs"][first]["model"]["urdf"][()]))
    limits, source = torque_limits(config, urdf, joints)
    if limits is None:
        return None, source
    return np.repeat(limits[None, :], n, 0), source


def torque_ratio(sweep, column="peak_torque"):
    """Per scenario, the largest peak |tau_k| / limit_k over the joints of the per-joint
    /scenarios column `column` (peak_torque, peak_torque_gait or peak_torque_transient; NaN
    where the scenario failed or has no such sample), the limits (N, J) or None, and the
    limits' source."""
    limits, source = scenario_torque_limits(sweep)
    if limits is None:
        return None, None, source
    peak = np.asarray(sweep.table[column], dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = nanmax_rows(peak / limits)
    return ratio, limits, source


def limit_text(limits, source):
    """A few words on the limits: one value or "per joint or scenario", with the source."""
    if limits is None:
        return None
    finite = limits[np.isfinite(limits)]
    if finite.size and np.allclose(finite, finite[0]):
        return f"torque limit {finite[0]:g} N m ({source})"
    return f"torque limits per joint or scenario ({source})"
