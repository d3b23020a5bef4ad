#!/usr/bin/python3
"""The comparison half of the pinned regression (tests/regression/regression.py): the units of
the pinned quantities, their JSON form (NaN as null, nested lists), and the comparison of a
run's quantities with the reference, each to its own relative tolerance."""

import json
import math

import numpy as np

UNITS = {
    "total_mass": "kg", "duration": "s", "energy_total": "J", "energy_joint": "J",
    "cost_of_transport": "1", "distance": "m", "impacts_leg": "1", "impacts_t_start": "s",
    "impacts_duration": "s", "impacts_peak_force": "N", "impacts_impulse": "N s",
    "peak_torque": "N m", "rms_torque": "N m", "fz_between_impacts_time": "s",
    "fz_between_impacts_mean": "N", "fz_between_impacts_min": "N",
    "fz_between_impacts_max": "N", "fz_between_impacts_mean_over_weight": "1",
    "energy": "J", "peak_impact_force": "N", "peak_torque_between_impacts": "N m",
    "rms_torque_between_impacts": "N m",
}


def to_json(value):
    """numpy / float -> JSON-able, floats exact (repr round-trips), NaN -> None."""
    if isinstance(value, np.ndarray):
        return [to_json(v) for v in value.tolist()] if value.ndim else to_json(value.item())
    if isinstance(value, list):
        return [to_json(v) for v in value]
    if isinstance(value, (float, np.floating)):
        return None if math.isnan(value) else float(value)
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    return value


def from_json(value):
    """JSON value -> numpy array (floats with NaN for null) or list of strings."""
    if isinstance(value, list) and _leaves_are(value, str):
        return value
    if isinstance(value, str):
        return value
    if _leaves_are(value, (int, bool)) and not _has_null(value):
        return np.asarray(value, dtype=np.int64)
    return np.asarray(_null_to_nan(value), dtype=np.float64)


def _leaves(value):
    if isinstance(value, list):
        for v in value:
            yield from _leaves(v)
    else:
        yield value


def _leaves_are(value, types):
    return all(isinstance(v, types) for v in _leaves(value))


def _has_null(value):
    return any(v is None for v in _leaves(value))


def _null_to_nan(value):
    if isinstance(value, list):
        return [_null_to_nan(v) for v in value]
    return math.nan if value is None else value


def format_json(obj, indent=0):
    """JSON with one quantity per block and numeric lists on one line (matrices: one row
    per line): small, readable diffs."""
    pad = " " * indent
    if isinstance(obj, dict):
        items = [f'{pad}  {json.dumps(k)}: {format_json(v, indent + 2).lstrip()}'
                 for k, v in obj.items()]
        return pad + "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(obj, list) and obj and isinstance(obj[0], list):
        rows = [pad + "  " + json.dumps(r, allow_nan=False) for r in obj]
        return pad + "[\n" + ",\n".join(rows) + "\n" + pad + "]"
    return pad + json.dumps(obj, allow_nan=False)


# ---------------------------------------------------------------- comparison

def describe(value):
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, float):
        return repr(value)
    return json.dumps(to_json(value))


def compare_quantity(name, ref, got, rtol):
    """None if got agrees with ref, else one line: name, reference, got, tolerance."""
    ref_v, got_v = from_json(ref), from_json(to_json(got))
    if isinstance(ref_v, (list, str)) or isinstance(got_v, (list, str)):
        if ref_v == got_v:
            return None
        if isinstance(ref_v, list) and isinstance(got_v, list) and len(ref_v) == len(got_v):
            i = next(k for k in range(len(ref_v)) if ref_v[k] != got_v[k])
            return (f"{name}[{i}]: reference {ref_v[i]!r}, got {got_v[i]!r}, "
                    f"tolerance exact")
        return f"{name}: reference {json.dumps(ref_v)}, got {json.dumps(got_v)}, tolerance exact"
    if ref_v.shape != got_v.shape:
        return (f"{name}: reference shape {ref_v.shape}, got shape {got_v.shape}, "
                f"tolerance exact (reference {describe(ref_v)}, got {describe(got_v)})")
    diff, nan_mismatch, scale = numeric_difference(ref_v, got_v)
    allowed = rtol * scale
    bad = nan_mismatch | (diff > allowed)
    if not bad.any():
        return None
    nb = int(np.sum(bad))
    i = np.unravel_index(np.argmax(np.where(nan_mismatch, np.inf, diff)), ref_v.shape)
    where = f"[{','.join(str(int(k)) for k in i)}]" if ref_v.ndim else ""
    tol = "exact" if rtol == 0 else f"{allowed:.3g} (rtol {rtol:g} x scale {scale:.6g})"
    extra = f"; {nb} of {ref_v.size} elements differ" if ref_v.ndim else ""
    unit = UNITS.get(name.split(".")[-1], "1")
    unit = "" if unit == "1" else f" {unit}"
    rel = "" if nan_mismatch[i] else f", |got - ref| {float(diff[i]):.3g}{unit}"
    return (f"{name}{where}: reference {describe(ref_v[i])}, got {describe(got_v[i])}"
            f"{rel}, tolerance {tol}{extra}")


def numeric_difference(ref_v, got_v):
    """For numeric arrays of one shape: |got - ref| (0 where either is NaN), the mask of
    elements NaN in one only, and the scale max |ref| (NaN ignored; 1 if all are 0)."""
    r, g = ref_v.astype(np.float64), got_v.astype(np.float64)
    nan_r, nan_g = np.isnan(r), np.isnan(g)
    finite = ~(nan_r | nan_g)
    scale = float(np.max(np.abs(r[~nan_r]))) if (~nan_r).any() else 0.0
    diff = np.where(finite, np.abs(g - r), 0.0)
    return diff, nan_r != nan_g, scale if scale > 0 else 1.0


def deviation(ref, got):
    """max |got - ref| / scale over the elements (the quantity rtol is compared with);
    inf for a different shape, NaN pattern or exact value (strings)."""
    ref_v, got_v = from_json(to_json(ref)), from_json(to_json(got))
    if isinstance(ref_v, (list, str)) or isinstance(got_v, (list, str)):
        return 0.0 if ref_v == got_v else math.inf
    if ref_v.shape != got_v.shape:
        return math.inf
    diff, nan_mismatch, scale = numeric_difference(ref_v, got_v)
    if nan_mismatch.any():
        return math.inf
    return float(np.max(diff, initial=0.0)) / scale


def compare_all(reference, results):
    """Lines for every quantity that differs (or is missing) between reference and results."""
    lines = []
    for section in ("paper", "smoke"):
        ref_q = reference.get(section, {}).get("quantities", {})
        got_q = results[section]
        for name in sorted(set(ref_q) - set(got_q)):
            lines.append(f"{section}.{name}: in the reference, not extracted from the run")
        for name in got_q:
            if name not in ref_q:
                lines.append(f"{section}.{name}: extracted from the run, not in the reference "
                             f"(update the reference)")
                continue
            entry = ref_q[name]
            line = compare_quantity(f"{section}.{name}", entry["value"], got_q[name],
                                    float(entry["rtol"]))
            if line:
                lines.append(line)
    return lines
