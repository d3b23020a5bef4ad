"""A second computation of the drive train's datasets (docs/theory/drive-train.md) from a
result file's stored series and its resolved configuration (/meta config_yaml), in numpy,
for tests/python/test_drive_train.py and test_drive_sweep.py.

Each quantity is computed here from the formulas of docs/theory/drive-train.md, with the
sum of the magnitudes of its terms (the scale its rounding error is relative to), and
compared with the file under one rule:

    |file − here| ≤ RTOL · scale,   scale = Σ |terms| ≥ |here|

so 1e-9 relative to the quantity itself when its terms share a sign (energies, losses,
RMS), and relative to its largest terms when they cancel (a drive torque whose link torque
and friction nearly cancel, a power whose copper loss and mechanical power nearly cancel).
The downstream series (current, power, energies) are computed from the file's
/joints/drive_torque, itself checked first, so that a branch chosen on the sign of τ_drive q̇
is the file's branch.
"""

import xml.etree.ElementTree as ET

import h5py
import numpy as np
import yaml

from common import text

RTOL = 1e-9
GRAVITY = 9.81  # m/s², src/hexdyn/core/common.hpp kGravity (docs/theory/drive-train.md#energies)
KEYS = ("gear_ratio", "torque_constant", "resistance", "coulomb_friction", "viscous_friction",
        "gear_efficiency", "voltage", "peak_torque", "continuous_torque", "regeneration",
        "thermal_window", "armature")
OPTIONAL = ("voltage", "peak_torque", "continuous_torque", "thermal_window")  # absent = +inf
# The three-phase and thermal keys (docs/theory/drive-train.md): absent = these defaults.
DEFAULTS = {"voltage_utilization": 0.5, "thermal_resistance_winding": np.nan,
            "thermal_capacity_winding": np.nan, "thermal_resistance_housing": np.nan,
            "thermal_capacity_housing": np.nan, "ambient_temperature": 25.0,
            "winding_temperature_limit": np.inf}
COPPER_FACTOR = {"dc": 1.0, "three_phase_amplitude": 1.5, "three_phase_power": 1.0}
THERMAL_DATASETS = (
    "/thermal/winding_temperature", "/thermal/housing_temperature",
    "/thermal/peak_winding_temperature", "/thermal/time_to_limit", "/thermal/limit_reached",
    "/thermal/peak", "/thermal/first_time_to_limit")
DRIVE_DATASETS = (
    "/joints/drive_torque", "/joints/drive_torque_limit", "/joints/drive_torque_lower_limit",
    "/joints/current",
    "/joints/drive_torque_rms", "/joints/drive_torque_window_rms", "/power/electrical",
    "/power/electrical_total", "/energy/electrical", "/energy/electrical_per_joint",
    "/energy/copper_loss", "/energy/friction_loss", "/energy/regenerated",
    "/energy/cost_of_transport_electrical")
INPUTS = ("/time", "/joints/torque", "/joints/velocity", "/joints/acceleration",
          "/contacts/phase", "/contacts/force", "/solver/status", "/energy/distance",
          "/model/total_mass")


def read_result(group):
    """{dataset: value} of a result (an h5py File or a sweep's /runs/<id> group), with
    "joints" (/model/joint_names) and "config" (/meta config_yaml parsed)."""
    r = {k: group[k.lstrip("/")][()] for k in INPUTS + DRIVE_DATASETS + THERMAL_DATASETS
         if k.lstrip("/") in group}
    r["joints"] = [text(n) for n in group["model/joint_names"][()]]
    r["config"] = yaml.safe_load(text(group["meta"].attrs["config_yaml"]))
    r["urdf"] = text(group["model/urdf"][()])
    return r


def read_file(path):
    with h5py.File(path, "r") as f:
        return read_result(f)


def parameters(r):
    """{key: (J,) array in /model/joint_names order} of /meta actuators.joints; the
    optional keys +inf where absent."""
    joints = r["config"]["actuators"]["joints"]
    assert sorted(joints) == sorted(r["joints"]), (sorted(joints), r["joints"])
    out = {}
    for k in KEYS:
        if k in OPTIONAL:
            out[k] = np.array([float(joints[n].get(k, np.inf)) for n in r["joints"]])
        else:
            out[k] = np.array([float(joints[n][k]) for n in r["joints"]])
    for k, default in DEFAULTS.items():
        out[k] = np.array([float(joints[n].get(k, default)) for n in r["joints"]])
    out["winding"] = np.array([joints[n].get("winding", "dc") for n in r["joints"]])
    out["copper_factor"] = np.array([COPPER_FACTOR[w] for w in out["winding"]])
    return out


def trapezoid(t, y):
    """∫ y dt by the trapezoid rule over the samples t (axis 0)."""
    h = np.diff(t)
    if y.ndim == 2:
        h = h[:, None]
    return np.sum(0.5 * h * (y[1:] + y[:-1]), axis=0)


def cumulative(t, s):
    """C(t_i) = ∫_{t_0}^{t_i} s with s linear between the samples."""
    return np.concatenate([[0.0], np.cumsum(0.5 * np.diff(t) * (s[1:] + s[:-1]))])


def integral_to(t, s, c, x):
    """∫_{t_0}^{x} s, s linear between the samples, for an array x in [t_0, t_end]."""
    i = np.clip(np.searchsorted(t, x, side="right") - 1, 0, len(t) - 2)
    h = t[i + 1] - t[i]
    u = x - t[i]
    slope = np.where(h > 0, (s[i + 1] - s[i]) / np.where(h > 0, h, 1.0), 0.0)
    return c[i] + u * s[i] + 0.5 * slope * u * u


def largest_window_rms(t, y, window):
    """The largest sqrt(∫_a^{a+W} y² / W) over a ∈ [t_0, t_end − W], y² linear between the
    samples (the run's RMS when W ≥ t_end − t_0), and whether it lies inside a piece.

    F(a) = ∫_a^{a+W} y² is continuous, and quadratic in a between consecutive breakpoints
    (the starts a where a or a + W meets a sample). On each piece F is fitted by the
    parabola through its two ends and its midpoint; F is evaluated (exactly, through the
    cumulative integral) at every breakpoint and at the parabola's vertex where that is a
    maximum inside the piece."""
    s = y * y
    c = cumulative(t, s)
    t0, t1 = t[0], t[-1]
    if not window < t1 - t0:
        return np.sqrt(c[-1] / (t1 - t0)), False
    last = t1 - window
    a = np.concatenate([t[t <= last], t[t - window >= t0] - window, [t0, last]])
    a = np.unique(np.clip(a, t0, last))

    def F(x):
        return integral_to(t, s, c, x + window) - integral_to(t, s, c, x)

    ends = F(a)
    lo, hi = a[:-1], a[1:]
    mid = 0.5 * (lo + hi)
    f0, fm, f1 = ends[:-1], F(mid), ends[1:]
    # Parabola through (−1, f0), (0, fm), (1, f1) in u = (x − mid) / half width.
    curvature = f0 + f1 - 2.0 * fm
    slope = 0.5 * (f1 - f0)
    inside = curvature < 0
    u = np.where(inside, -slope / np.where(inside, curvature, 1.0), 0.0)
    inside &= np.abs(u) < 1.0
    best = float(np.max(ends))
    interior = False
    if np.any(inside):
        x = mid[inside] + u[inside] * 0.5 * (hi - lo)[inside]
        fx = float(np.max(F(x)))
        if fx > best:
            best, interior = fx, True
    return np.sqrt(max(best, 0.0) / window), interior


def scan_window_rms(t, y, window, starts=4001):
    """The windowed RMS maximum over a dense scan of window starts (a lower bound of the
    exact maximum, close to it): a check of largest_window_rms."""
    s = y * y
    c = cumulative(t, s)
    a = np.linspace(t[0], t[-1] - window, starts)
    F = integral_to(t, s, c, a + window) - integral_to(t, s, c, a)
    return np.sqrt(max(float(np.max(F)), 0.0) / window)


def compare(name, got, want, scale, problems):
    """Appends to problems when |got − want| > RTOL · scale anywhere."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    if got.shape != want.shape:
        problems.append(f"{name}: shape {got.shape}, expected {want.shape}")
        return
    err = np.abs(got - want)
    bound = RTOL * np.broadcast_to(np.asarray(scale, float), want.shape)
    bad = ~(err <= bound)
    if np.any(bad):
        i = np.unravel_index(np.argmax(np.where(bad, err / np.maximum(bound, 1e-300), 0)),
                             want.shape)
        problems.append(f"{name}: {int(np.sum(bad))} values off, worst at {tuple(int(j) for j in i)}: "
                        f"file {got[i]!r}, here {want[i]!r} (scale {np.broadcast_to(scale, want.shape)[i]:.3g})")


def torque_limits(r):
    """allocation.torque_limit per joint: a number, or each joint's URDF effort limit."""
    limit = r["config"]["allocation"]["torque_limit"]
    if limit != "effort":
        return np.full(len(r["joints"]), float(limit))
    root = ET.fromstring(r["urdf"])
    effort = {j.get("name"): float(j.find("limit").get("effort"))
              for j in root.findall("joint") if j.find("limit") is not None}
    return np.array([effort[n] for n in r["joints"]])


def recompute(r):
    """Every drive-train dataset of r computed here: {dataset: (value, scale)}, and the
    branch counts {name: number of (sample, joint) pairs}."""
    p = parameters(r)
    t = r["/time"]
    qd, qdd, tau = r["/joints/velocity"], r["/joints/acceleration"], r["/joints/torque"]
    G, kt, R, eta = p["gear_ratio"], p["torque_constant"], p["resistance"], p["gear_efficiency"]
    Ja, tc, b, reg = p["armature"], p["coulomb_friction"], p["viscous_friction"], p["regeneration"]
    Gk = G * kt
    out = {}
    terms = [tau, Ja * qdd, tc * np.sign(qd), b * qd]
    out["/joints/drive_torque"] = (sum(terms), sum(np.abs(x) for x in terms))

    dc = p["winding"] == "dc"
    voltage = np.where(np.isfinite(p["voltage"]),
                       np.maximum(0.0, Gk * eta * (p["voltage"] - Gk * np.abs(qd)) / R), np.inf)
    bounded = np.isfinite(p["voltage"]) | np.isfinite(p["peak_torque"])
    limit = np.where(bounded, np.minimum(p["peak_torque"], voltage), torque_limits(r))
    voltage_terms = np.where(np.isfinite(voltage),
                             Gk * eta * (p["voltage"] + Gk * np.abs(qd)) / R, 0.0)
    upper, lower, scale3 = three_phase_bounds(p, qd, torque_limits(r))
    out["/joints/drive_torque_limit"] = (np.where(dc, limit, upper),
                                         np.where(dc, np.maximum(limit, voltage_terms), scale3))
    out["/joints/drive_torque_lower_limit"] = (np.where(dc, -limit, lower),
                                               np.where(dc, np.maximum(limit, voltage_terms),
                                                        scale3))

    td = r["/joints/drive_torque"]
    driving = td * qd >= 0
    current = np.where(driving, td / (Gk * eta), td * eta / Gk)
    out["/joints/current"] = (current, np.abs(current))
    copper = p["copper_factor"] * R * current ** 2
    mech = Gk * qd * current
    P = copper + mech
    P_scale = copper + np.abs(mech)
    drawn = np.where(P >= 0, P, reg * P)
    drawn_scale = np.where(P >= 0, P_scale, reg * P_scale)
    out["/power/electrical"] = (drawn, drawn_scale)
    out["/power/electrical_total"] = (drawn.sum(axis=1), drawn_scale.sum(axis=1))
    per_joint, per_joint_scale = trapezoid(t, drawn), trapezoid(t, drawn_scale)
    out["/energy/electrical_per_joint"] = (per_joint, per_joint_scale)
    energy = trapezoid(t, drawn.sum(axis=1))
    energy_scale = trapezoid(t, drawn_scale.sum(axis=1))
    out["/energy/electrical"] = (energy, energy_scale)
    loss = trapezoid(t, copper.sum(axis=1))
    out["/energy/copper_loss"] = (loss, loss)
    friction = trapezoid(t, (tc * np.abs(qd) + b * qd * qd).sum(axis=1))
    out["/energy/friction_loss"] = (friction, friction)
    regen = trapezoid(t, (reg * np.maximum(0.0, -P)).sum(axis=1))
    out["/energy/regenerated"] = (regen, trapezoid(t, (reg * np.where(P < 0, P_scale, 0)).sum(axis=1)))
    mgd = float(r["/model/total_mass"]) * GRAVITY * float(r["/energy/distance"])
    out["/energy/cost_of_transport_electrical"] = (energy / mgd, energy_scale / mgd)

    duration = t[-1] - t[0]
    rms = np.sqrt(trapezoid(t, td * td) / duration)
    out["/joints/drive_torque_rms"] = (rms, rms)
    window = np.zeros(td.shape[1])
    interior = 0
    for k in range(td.shape[1]):
        window[k], inside = largest_window_rms(t, td[:, k], p["thermal_window"][k])
        interior += inside
        if p["thermal_window"][k] < duration:
            scan = scan_window_rms(t, td[:, k], p["thermal_window"][k])
            assert scan <= window[k] * (1 + 1e-12) and scan >= window[k] * (1 - 1e-3), \
                f"joint {k}: windowed RMS {window[k]} against a dense scan {scan}"
    out["/joints/drive_torque_window_rms"] = (window, window)

    counts = {
        "driving (τ_drive q̇ > 0)": int(np.sum(td * qd > 0)),
        "back-driven (τ_drive q̇ < 0)": int(np.sum(td * qd < 0)),
        "back-driven with η < 1": int(np.sum((td * qd < 0) & (eta < 1))),
        "at rest (q̇ = 0)": int(np.sum(qd == 0)),
        "P < 0, regenerated (r > 0)": int(np.sum((P < 0) & (reg > 0))),
        "P < 0, lost (r = 0)": int(np.sum((P < 0) & (reg == 0))),
        "bound: voltage": int(np.sum(bounded & (voltage < p["peak_torque"]) & (voltage > 0))),
        "bound: voltage clipped at 0": int(np.sum(bounded & (voltage == 0))),
        "bound: peak": int(np.sum(bounded & (p["peak_torque"] < voltage))),
        "bound: allocation.torque_limit": int(np.sum(~bounded & np.ones_like(td, bool))),
        "windowed RMS shorter than the run": int(np.sum(p["thermal_window"] < duration)),
        "windowed maximum inside a piece": interior,
    }
    return out, counts


def three_phase_bounds(p, qd, fallback):
    """The bounds lower ≤ τ_drive ≤ upper of three-phase joints (docs/theory/drive-train.md#
    voltage-limit): the q-axis voltage |R I + k_e ω_m| ≤ V_q, k_e = k_t / c, V_q = u V (√(3/2)
    u V power-invariant), through the gearbox (η driving, 1/η back-driven), each side clamped
    to [−peak, peak]; the
    allocation's limit for a joint with neither. Returns (upper, lower, scale)."""
    G, kt, R, eta = p["gear_ratio"], p["torque_constant"], p["resistance"], p["gear_efficiency"]
    ke = kt / p["copper_factor"]
    vq = np.where(p["winding"] == "three_phase_power", np.sqrt(1.5), 1.0) \
        * p["voltage_utilization"] * p["voltage"]
    wm = G * qd

    def joint(tm):
        return np.where(tm * qd >= 0, eta * G * tm, G * tm / eta)

    with np.errstate(all="ignore"):
        up_v = joint(kt * (vq - ke * wm) / R)
        lo_v = joint(kt * (-vq - ke * wm) / R)
        reach = np.abs(G * kt * (vq + np.abs(ke * wm)) / R) / np.minimum(eta, 1.0)
    has_v = np.isfinite(p["voltage"])
    peak = p["peak_torque"]
    # Each side clamped to ±peak (past the speed where both sides pass the peak, the drive
    # holds its current limit, as MIT's ActuatorModel clamps).
    upper = np.clip(np.where(has_v, up_v, np.inf), -peak, peak)
    lower = np.clip(np.where(has_v, lo_v, -np.inf), -peak, peak)
    bounded = has_v | np.isfinite(peak)
    upper = np.where(bounded, upper, fallback)
    lower = np.where(bounded, lower, -fallback)
    scale = np.where(has_v, reach, 0.0)
    scale = np.maximum(np.maximum(np.abs(upper), np.abs(lower)), np.nan_to_num(scale))
    return upper, lower, scale


def thermal_matrices(p, k):
    """The two-node network of joint k: dx/dt = A x + B P, x the rise over the ambient."""
    R1, C1 = p["thermal_resistance_winding"][k], p["thermal_capacity_winding"][k]
    R2, C2 = p["thermal_resistance_housing"][k], p["thermal_capacity_housing"][k]
    A = np.array([[-1 / (R1 * C1), 1 / (R1 * C1)], [1 / (R1 * C2), -1 / (R1 * C2) - 1 / (R2 * C2)]])
    return A, np.array([1 / C1, 0.0])


def thermal_step(A, B, x, p0, slope, h):
    """x after h under P = p0 + slope·s, exactly: the matrix exponential of the system
    augmented by P and its slope (scipy), a method of its own against the program's modal
    closed form."""
    from scipy.linalg import expm
    M = np.zeros((4, 4))
    M[:2, :2] = A
    M[:2, 2] = B
    M[2, 3] = 1.0
    return (expm(M * h) @ np.array([x[0], x[1], p0, slope]))[:2]


def recompute_thermal(r, copper):
    """/thermal/* recomputed here from the file's copper loss per joint (T×J) and /meta;
    {dataset: (value, scale)} and the list of problems of the peak and the crossing."""
    p = parameters(r)
    t = r["/time"]
    T, J = copper.shape
    Tw, Th = np.full((T, J), np.nan), np.full((T, J), np.nan)
    problems = []
    for k in range(J):
        if np.isnan(p["thermal_capacity_housing"][k]):
            continue
        A, B = thermal_matrices(p, k)
        amb, lim = p["ambient_temperature"][k], p["winding_temperature_limit"][k]
        x = np.zeros(2)
        Tw[0, k] = Th[0, k] = amb
        for i in range(1, T):
            h = t[i] - t[i - 1]
            if h > 0:
                x = thermal_step(A, B, x, copper[i - 1, k], (copper[i, k] - copper[i - 1, k]) / h, h)
            Tw[i, k], Th[i, k] = amb + x[0], amb + x[1]
        peak = r["/thermal/peak_winding_temperature"][k]
        if not peak >= np.max(Tw[:, k]) - 1e-9 * (np.max(Tw[:, k]) - amb):
            problems.append(f"joint {k}: peak {peak} below the samples' largest {np.max(Tw[:, k])}")
        when = r["/thermal/time_to_limit"][k]
        reached = bool(r["/thermal/limit_reached"][k])
        if reached != (peak >= lim):
            problems.append(f"joint {k}: limit_reached {reached}, peak {peak}, limit {lim}")
        if reached:
            # The interval [t_j, t_n] holding the crossing: t_j the last sample before it.
            j = int(np.searchsorted(t, when, side="left")) - 1
            n = j + 1
            x0 = np.array([Tw[j, k] - amb, Th[j, k] - amb])
            slope = (copper[n, k] - copper[j, k]) / (t[n] - t[j])
            at = amb + thermal_step(A, B, x0, copper[j, k], slope, when - t[j])[0]
            before = Tw[:j + 1, k]
            rise = lim - amb
            if abs(at - lim) > 1e-9 * rise or np.any(before > lim + 1e-9 * rise):
                problems.append(f"joint {k}: at the time to the limit {when} the winding is {at}, "
                                f"limit {lim}")
        elif when != np.inf:
            problems.append(f"joint {k}: time to the limit {when}, expected +inf (not reached)")
    scale = np.where(np.isnan(Tw), np.nan, np.maximum(np.abs(Tw), 1.0))
    out = {"/thermal/winding_temperature": (Tw, scale),
           "/thermal/housing_temperature": (Th, np.where(np.isnan(Th), np.nan, np.maximum(np.abs(Th), 1.0)))}
    return out, problems


def compare_nan(name, got, want, scale, problems):
    """compare(), NaN in the file where NaN here."""
    got, want = np.asarray(got, float), np.asarray(want, float)
    if not np.array_equal(np.isnan(got), np.isnan(want)):
        problems.append(f"{name}: NaN where there should be none, or none where there should be")
        return
    keep = ~np.isnan(want)
    compare(name, got[keep], want[keep], np.asarray(scale)[keep], problems)


def check_thermal(r, label):
    """Every /thermal/* dataset of r against a second computation; returns the joints with a
    thermal model and those that reach their limit."""
    missing = [k for k in THERMAL_DATASETS if k not in r]
    assert not missing, f"{label}: no {missing}"
    p = parameters(r)
    td, qd = r["/joints/drive_torque"], r["/joints/velocity"]
    Gk, eta = p["gear_ratio"] * p["torque_constant"], p["gear_efficiency"]
    current = np.where(td * qd >= 0, td / (Gk * eta), td * eta / Gk)
    copper = p["copper_factor"] * p["resistance"] * current ** 2
    out, problems = recompute_thermal(r, copper)
    for name, (want, scale) in out.items():
        compare_nan(name, r[name], want, scale, problems)
    model = ~np.isnan(p["thermal_capacity_housing"])
    peaks = r["/thermal/peak_winding_temperature"]
    if not np.isclose(r["/thermal/peak"], np.max(peaks[model]), rtol=0, atol=0):
        problems.append(f"/thermal/peak {r['/thermal/peak']} is not the largest joint peak")
    if r["/thermal/first_time_to_limit"] != np.min(r["/thermal/time_to_limit"][model]):
        problems.append("/thermal/first_time_to_limit is not the joints' least")
    assert not problems, f"{label}:\n  " + "\n  ".join(problems)
    return int(np.sum(model)), int(np.sum(r["/thermal/limit_reached"]))


def check(r, label):
    """Every drive-train dataset of r against recompute(r); returns the branch counts."""
    missing = [k for k in DRIVE_DATASETS if k not in r]
    assert not missing, f"{label}: no {missing}"
    out, counts = recompute(r)
    problems = []
    # First the drive torque from the link torque and the joint's state; everything after
    # from the file's drive torque.
    for name in DRIVE_DATASETS:
        want, scale = out[name]
        compare(name, r[name], want, scale, problems)
    assert not problems, f"{label}:\n  " + "\n  ".join(problems)
    return counts
