#!/usr/bin/python3
"""Plot of a hexdyn-envelope/2 file (`hexdyn envelope`, docs/user/envelope.md):
the largest climbable riser over peak speed, one panel per tread depth, one colour per
duty factor, one line style per criterion (kinematic, torque, friction).

    /usr/bin/python3 analysis/plot_envelope.py ENVELOPE.h5 OUTDIR [--check] [--table]

Writes OUTDIR/envelope.png (saved under a temporary name and renamed when complete).
A criterion that fails already at the lowest riser probed is drawn as a cross at that
riser. --check verifies the file against the layout declared in src/hexdyn/io/schema.hpp
(every dataset present, with its units, shape and element type); --table prints the
envelope as a text table (riser in mm, and what limits it) on stdout.
"""

import argparse
import os
import sys


import h5py  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from hexdyn import results as hr  # noqa: E402
from plot_kinematics import save_atomically  # noqa: E402

S = hr.SCHEMA
STYLES = {"kinematic": "-", "torque": "--", "friction": ":"}
MARKERS = {"kinematic": "o", "torque": "s", "friction": "^"}


def _strings(ds):
    return [hr.decode_text(v) for v in ds.asstr()[()]] if ds.shape else hr.decode_text(ds.asstr()[()])


def read_envelope(path):
    """The envelope file as a dict: axes, criteria, riser_max/fail (W,B,S,C), limit and
    message (W,B,S,C) strings, posture (W,B,S), meta."""
    with h5py.File(path, "r") as f:
        # Version 1 (no coordinates, flattened limit and message) plots too.
        hr.check_filetype_version(f, S["kEnvelopeSchema"], (1, S["kEnvelopeSchemaVersion"]), path)
        d = {"meta": {k: hr.decode_text(v) for k, v in f["meta"].attrs.items()}}
        d["tread"] = f[S["kEnvelopeTreadDepth"].path][()]
        d["duty"] = f[S["kEnvelopeDutyFactor"].path][()]
        d["speed"] = f[S["kEnvelopePeakSpeed"].path][()]
        d["criteria"] = _strings(f[S["kEnvelopeCriteria"].path])
        d["riser_from"] = float(f[S["kEnvelopeRiserFrom"].path][()])
        d["riser_to"] = float(f[S["kEnvelopeRiserTo"].path][()])
        d["riser_max"] = f[S["kEnvelopeRiserMax"].path][()]
        d["riser_fail"] = f[S["kEnvelopeRiserFail"].path][()]
        shape = d["riser_max"].shape
        d["limit"] = np.array(_strings(f[S["kEnvelopeLimit"].path]), dtype=object).reshape(shape)
        d["message"] = np.array(_strings(f[S["kEnvelopeMessage"].path]), dtype=object).reshape(shape)
        d["posture_height"] = f[S["kEnvelopePostureHeight"].path][()]
        d["posture_foot_lateral"] = f[S["kEnvelopePostureFootLateral"].path][()]
        d["probes"] = int(f[S["kProbeRiser"].path].shape[0])
        # With cases (a design each), a leading dimension `case`; without, one unnamed case.
        d["cases"] = _strings(f[S["kCaseCoordinate"].path]) if S["kCaseCoordinate"].path in f else None
    if d["cases"] is None:
        for k in ("riser_max", "riser_fail", "limit", "message", "posture_height",
                  "posture_foot_lateral"):
            d[k] = d[k][np.newaxis]
    return d


def check_layout(path):
    """Every declared dataset of the envelope layout, with its units, shape, element."""
    with h5py.File(path, "r") as f:
        W = f[S["kEnvelopeTreadDepth"].path].shape[0]
        B = f[S["kEnvelopeDutyFactor"].path].shape[0]
        V = f[S["kEnvelopePeakSpeed"].path].shape[0]
        C = f[S["kEnvelopeCriteria"].path].shape[0]
        P = f[S["kProbeRiser"].path].shape[0]
        sizes = {"W": W, "B": B, "S": V, "C": C, "P": P, "G": W * B * V * C}
        specs = list(S["kEnvelopeDatasets"]) + list(S["kEnvelopeCoordinates"])
        if S["kCaseCoordinate"].path in f:  # cases: their declarations replace those of a path
            sizes["D"] = f[S["kCaseCoordinate"].path].shape[0]
            sizes["K"] = f[S["kEnvelopeCaseKeys"].path].shape[0]
            by_case = {c.path: c for c in S["kEnvelopeCaseDatasets"]}
            specs = [by_case.pop(c.path, c) for c in specs] + list(by_case.values())
        declared = set()
        for spec in specs:
            declared.add(spec.path)
            if spec.path not in f:
                raise SystemExit(f"plot_envelope: {path}: {spec.path} missing")
            ds = f[spec.path]
            want = hr.expected_shape(spec.shape, **sizes)
            if ds.shape != want:
                raise SystemExit(f"plot_envelope: {path}: {spec.path} shape {ds.shape}, expected {want}")
            if hr.decode_text(ds.attrs.get("units", "")) != spec.units:
                raise SystemExit(f"plot_envelope: {path}: {spec.path} units {ds.attrs.get('units')!r}, "
                                 f"expected {spec.units!r}")
            kind = "string" if h5py.check_string_dtype(ds.dtype) else str(ds.dtype)
            if kind != spec.element:
                raise SystemExit(f"plot_envelope: {path}: {spec.path} element {kind}, expected {spec.element}")
        # Group coordinates (schema.hpp): a group's copy of a root coordinate, a dimension
        # scale below the root, equal to it.
        found = []
        f.visititems(lambda n, o: found.append("/" + n) if isinstance(o, h5py.Dataset) else None)
        for p in set(found) - declared:
            ds, root = f[p], f.get("/" + p.rsplit("/", 1)[1])
            if ("/" in p[1:] and h5py.h5ds.is_scale(ds.id) and isinstance(root, h5py.Dataset)
                    and root.name in declared and np.array_equal(ds[()], root[()])):
                declared.add(p)
        extra = sorted(set(found) - declared)
        if extra:
            raise SystemExit(f"plot_envelope: {path}: undeclared datasets {extra}")
        for a in S["kEnvelopeMetaAttributes"]:
            if a.name not in f["meta"].attrs:
                raise SystemExit(f"plot_envelope: {path}: /meta attribute {a.name} missing")


def duty_label(beta):
    for q in range(2, 13):
        p = round(beta * q)
        if abs(p / q - beta) < 1e-9:
            return f"{p}/{q}"
    return f"{beta:g}"


def table(d):
    lines = []
    for i, case in enumerate(d["cases"] or [None]):
        lines += case_table(d, i, case)
    return "\n".join(lines)


def case_table(d, i, case):
    lines = []
    for w, tread in enumerate(d["tread"]):
        lines.append(("" if case is None else f"{case}: ") +
                     f"tread {tread:.2f} m: largest climbable riser [mm] per duty factor (rows) "
                     f"and peak speed (columns), criteria {'/'.join(d['criteria'])}")
        lines.append("  beta   " + "".join(f"{v:>22.2f}" for v in d["speed"]))
        for b, beta in enumerate(d["duty"]):
            cells = []
            for v in range(len(d["speed"])):
                vals = ["-" if not np.isfinite(x) else f"{1e3 * x:.0f}"
                        for x in d["riser_max"][i, w, b, v]]
                cells.append("/".join(vals))
            lines.append(f"  {duty_label(beta):>5}  " + "".join(f"{c:>22}" for c in cells))
        limits = {}
        for b in range(len(d["duty"])):
            for v in range(len(d["speed"])):
                for c, name in enumerate(d["criteria"]):
                    lim = d["limit"][i, w, b, v, c]
                    if lim:
                        key = f"{name}: {lim}"
                        limits[key] = limits.get(key, 0) + 1
        for k, n in sorted(limits.items(), key=lambda kv: -kv[1]):
            lines.append(f"    {n:3d} x {k}")
    return lines


def plot(d, outdir):
    W = len(d["tread"])
    cases = d["cases"] or [None]
    fig, grid = plt.subplots(len(cases), W, figsize=(4.2 * W, 4.0 * len(cases)), sharey=True,
                             squeeze=False)
    colors = plt.cm.viridis(np.linspace(0.0, 0.85, len(d["duty"])))
    for (i, case), (w, ax) in ((ic, wa) for ic in enumerate(cases) for wa in enumerate(grid[ic[0]])):
        for b, beta in enumerate(d["duty"]):
            for c, name in enumerate(d["criteria"]):
                y = 1e3 * d["riser_max"][i, w, b, :, c]
                ax.plot(d["speed"], y, STYLES.get(name, "-"), marker=MARKERS.get(name, "o"), ms=4,
                        color=colors[b], label=f"β = {duty_label(beta)}, {name}")
                none = ~np.isfinite(y)
                if none.any():
                    ax.plot(d["speed"][none], np.full(none.sum(), 1e3 * d["riser_from"]), "x",
                            color=colors[b], ms=8)
        ax.set_title(("" if case is None else f"{case}, ") + f"tread {d['tread'][w]:.2f} m")
        ax.set_xlabel("peak speed [m/s]")
        ax.grid(alpha=0.3)
    for row in grid:
        row[0].set_ylabel("largest climbable riser [mm]")
    handles, labels = grid[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(d["duty"]), fontsize=7, frameon=False)
    fig.suptitle(f"climbable envelope '{d['meta'].get('name', '')}' (x: fails at the lowest riser)")
    fig.tight_layout(rect=(0, 0.16 / len(cases), 1, 1 - 0.05 / len(cases)))
    save_atomically(fig, outdir, "envelope.png")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("envelope")
    ap.add_argument("outdir")
    ap.add_argument("--check", action="store_true", help="verify the layout against schema.hpp")
    ap.add_argument("--table", action="store_true", help="print the envelope as a text table")
    a = ap.parse_args()
    if a.check:
        check_layout(a.envelope)
    d = read_envelope(a.envelope)
    os.makedirs(a.outdir, exist_ok=True)
    plot(d, a.outdir)
    if a.table:
        print(table(d))


if __name__ == "__main__":
    main()
