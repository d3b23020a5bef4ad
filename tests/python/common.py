"""Shared by the Python module's tests (tests/install.cmake): the hexdyn binary and the
source tree from the command line, the CLI's output read with h5py."""

import os
import subprocess
import sys

import h5py
import numpy as np
from hexdyn import decode_text


def args():
    """(hexdyn binary, source dir) from argv."""
    if len(sys.argv) != 3:
        sys.exit(f"usage: {sys.argv[0]} HEXDYN_BINARY SOURCE_DIR")
    return sys.argv[1], os.path.realpath(sys.argv[2])


def cli_run(hexdyn, scene, out, sets=()):
    """`hexdyn run scene -o out --set ...`; returns (exit status, stderr)."""
    cmd = [hexdyn, "run", scene, "-o", out]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stderr


def cli_error(hexdyn, argv):
    """The one-line message the CLI prints for a failing command, without its prefix."""
    p = subprocess.run([hexdyn] + argv, capture_output=True, text=True)
    assert p.returncode != 0, f"hexdyn {argv} succeeded"
    line = p.stderr.strip().splitlines()[-1]
    assert line.startswith("hexdyn: error: "), line
    return p.returncode, line[len("hexdyn: error: "):]


def file_datasets(path):
    """{"/path": value} of every dataset of an HDF5 file, as h5py reads it, but the group
    coordinates (copies of a root coordinate in a group, schema.hpp), and the attributes:
    /meta's by name, any other group's as "/group/name" (as hexdyn.Result.attrs)."""
    out, attrs = {}, {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and "/" in name and h5py.h5ds.is_scale(obj.id):
                return  # a group coordinate
            if isinstance(obj, h5py.Dataset):
                out["/" + name] = (obj[()], obj.dtype, obj.attrs.get("units"))
            elif name != "meta":
                for k, v in obj.attrs.items():
                    attrs[f"/{name}/{k}"] = decode_text(v)
        f.visititems(visit)
        attrs.update({k: decode_text(v) for k, v in f["/meta"].attrs.items()})
    return out, attrs


def text(v):
    return str(decode_text(v))


def same_dataset(path, file_value, file_dtype, mine):
    """None when `mine` (hexdyn.Result's value) equals the file's dataset bit for bit: same
    dtype, shape and bytes for numbers; the same strings for text."""
    if file_dtype.kind in "fiu":
        a = np.asarray(mine)
        if a.dtype != file_dtype:
            return f"{path}: dtype {a.dtype}, file {file_dtype}"
        if a.shape != np.shape(file_value):
            return f"{path}: shape {a.shape}, file {np.shape(file_value)}"
        if a.tobytes() != np.asarray(file_value).tobytes():
            return f"{path}: values differ (max |diff| {np.max(np.abs(a - file_value))})"
        return None
    if np.ndim(file_value) == 0:
        return None if isinstance(mine, str) and mine == text(file_value) else f"{path}: text differs"
    want = [text(v) for v in file_value]
    got = list(mine)
    return None if got == want and all(isinstance(g, str) for g in got) else f"{path}: strings differ"


def swing_runs(phase):
    """(first, last) sample of every run of swing samples (phase 0) with a contact sample on
    both sides, in one leg's /contacts/phase column."""
    runs, i, n = [], 0, len(phase)
    while i < n:
        if phase[i] != 0:
            i += 1
            continue
        j = i
        while j + 1 < n and phase[j + 1] == 0:
            j += 1
        if i > 0 and j + 1 < n:
            runs.append((i, j))
        i = j + 1
    return runs


def transfers(feet, phase, exact):
    """(sample, leg) of every transfer sample of /feet/position `feet` (T, L, 3): in a swing, its
    horizontal position more than `exact` from both the lift-off and the touchdown foothold."""
    out = []
    for leg in range(feet.shape[1]):
        for i, j in swing_runs(phase[:, leg]):
            lo, hi = feet[i - 1, leg, :2], feet[j + 1, leg, :2]
            for k in range(i, j + 1):
                p = feet[k, leg, :2]
                if min(np.abs(p - lo).max(), np.abs(p - hi).max()) > exact:
                    out.append((k, leg))
    return out


def segment_distance(py, pz, ty, tz):
    """Distance of points (py, pz) (any shape) to the polyline of vertices (ty, tz)."""
    a = np.stack([ty[:-1], tz[:-1]], axis=-1)
    d = np.stack([ty[1:], tz[1:]], axis=-1) - a
    p = np.stack([py, pz], axis=-1)[..., None, :] - a
    s = np.clip((p * d).sum(-1) / np.maximum((d * d).sum(-1), 1e-300), 0.0, 1.0)
    return np.linalg.norm(p - s[..., None] * d, axis=-1).min(-1)


FAILURES = []


def check(ok, what, detail=""):
    """Prints one line, "ok" or "FAIL", for a check that goes on after a failure; the failed
    ones are counted in FAILURES (exit_status)."""
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail else ''}")
    if not ok:
        FAILURES.append(what)


def exit_status():
    """0, or 1 after a line naming every failed check."""
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed: {'; '.join(FAILURES)}")
        return 1
    return 0
