"""output.compression (docs/user/output.md#compression): `deflate` (the default) chunks and
compresses numeric datasets of at least 4 KiB with shuffle + deflate, `none` writes every
dataset contiguous; both hold the same values. Checked on a run, on a sweep's kept runs
and on a bad value, with h5py reading the files' storage properties.

    /usr/bin/python3 tests/python/test_compression.py HEXDYN SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_error, cli_run  # noqa: E402

MIN_BYTES = 4096  # io/h5io.hpp kChunkMinBytes


def storage(path, group="/"):
    """{name: (dataset, compression, shuffle, chunks, nbytes)} under `group`."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                numeric = obj.dtype.kind in "fiu"
                out[name] = (obj[()], obj.compression, obj.shuffle, obj.chunks,
                             obj.size * obj.dtype.itemsize if numeric else 0)
        f[group].visititems(visit)
    return out


def check_layouts(deflated, plain, what, at_least):
    assert deflated.keys() == plain.keys(), f"{what}: the datasets differ"
    compressed = 0
    for name, (value, comp, shuffle, chunks, nbytes) in deflated.items():
        p_value, p_comp, _, p_chunks, _ = plain[name]
        assert p_comp is None and p_chunks is None, f"{what}: {name} compressed under none"
        if nbytes >= MIN_BYTES:
            assert comp == "gzip" and shuffle and chunks is not None, \
                f"{what}: {name} ({nbytes} B) is not shuffled and deflated"
            compressed += 1
        else:
            assert comp is None, f"{what}: {name} ({nbytes} B) compressed below 4 KiB"
        if name.endswith("solver/seconds") or name == "meta":
            continue  # wall-clock times differ from run to run
        if isinstance(value, np.ndarray) and value.dtype.kind in "fiu":
            assert value.shape == p_value.shape and np.array_equal(
                value, p_value, equal_nan=value.dtype.kind == "f"), \
                f"{what}: {name} differs between deflate and none"
    assert compressed >= at_least, f"{what}: only {compressed} compressed datasets"
    return compressed


def main():
    hexdyn, src = args()
    paper = os.path.join(src, "configs", "paper.yaml")
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "a.h5"), os.path.join(d, "b.h5")
        for out, sets in ((a, ()), (b, ("output.compression=none",))):
            rc, err = cli_run(hexdyn, paper, out, sets)
            assert rc == 0, err
        n = check_layouts(storage(a), storage(b), "run", 10)
        assert os.path.getsize(a) < 0.8 * os.path.getsize(b), "deflate saves under 20 %"

        rc, line = cli_error(hexdyn, ["run", paper, "-o", os.path.join(d, "c.h5"),
                                      "--set", "output.compression=gzip"])
        assert rc == 2 and "output.compression" in line and "gzip" in line and \
            "deflate" in line and "none" in line, line
        assert not os.path.exists(os.path.join(d, "c.h5"))

        # A sweep's kept runs follow their scenes; the sweep's own datasets its base scene.
        base = os.path.join(src, "configs", "sweeps", "stairs_base.yaml")
        files = {}
        for mode in ("deflate", "none"):
            spec = os.path.join(d, f"{mode}.yaml")
            with open(spec, "w") as f:
                f.write(f"name: {mode}\nbase: {base}\nset:\n  output.grid: uniform\n"
                        "  motion.cycles: 1\n  motion.posture: null\n"
                        "  motion.initial_position: [0.0, 0.412, 0.235]\n"
                        f"  output.compression: {mode}\n"
                        "axes:\n  - key: terrain.riser_height\n    values: [0.04, 0.08]\n")
            files[mode] = os.path.join(d, f"{mode}.h5")
            p = subprocess.run([hexdyn, "sweep", spec, "-o", files[mode], "--keep-runs"],
                               capture_output=True, text=True)
            assert p.returncode == 0, p.stderr
        with h5py.File(files["deflate"], "r") as f:
            runs = sorted(f["runs"])
        assert len(runs) == 2
        for run in runs:
            check_layouts(storage(files["deflate"], f"/runs/{run}"),
                          storage(files["none"], f"/runs/{run}"), f"kept run {run}", 5)
        for name, (_, comp, _, _, _) in storage(files["none"]).items():
            assert comp is None, f"sweep with output.compression: none: {name} compressed"
    print(f"compression: {n} datasets of a run deflated, the same values uncompressed under "
          "none; kept runs likewise; a bad value refused in one line")


if __name__ == "__main__":
    main()
