#!/usr/bin/python3
"""Size and read time of a `--keep-runs` sweep file, compressed against uncompressed.

    /usr/bin/python3 bench/compression.py --new build/hexdyn --old OLD_HEXDYN [--reps 30]

Runs the sweep bench/compression.yaml (20 stair scenes) with `--keep-runs` three times:
with the `hexdyn` under test (chunked, shuffle + deflate: docs/user/output.md#compression);
with the same `hexdyn` and `output.compression: none`, which writes the same content
contiguous and uncompressed; and with an older `hexdyn` that writes every dataset
contiguous and uncompressed (the hexdyn-sweep/1 writer of commit bbaf71c, which holds
less: no event samples, no coordinate variables). Prints the sizes and their ratios, then
the time to read every dataset of one kept run's group with h5py, the three files in
turn (`--reps` rounds, each read a fresh open), as medians and their ratios, and the time
zlib alone takes to inflate that group's compressed datasets (the floor of any deflate
reader). Targets: size at most 60 % of the uncompressed file of the same
content, read time at most 1.5 times the old file's.
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time
import zlib

import h5py
import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))


def sweep(hexdyn, out, compression=None):
    """The benchmark's sweep into `out`; `compression` sets the base scene's
    output.compression (a copy of the sweep file next to `out`)."""
    sweep_file = os.path.join(HERE, "compression.yaml")
    if compression is not None:
        with open(sweep_file) as f:
            spec = yaml.safe_load(f)
        spec["base"] = os.path.normpath(os.path.join(HERE, spec["base"]))
        spec.setdefault("set", {})["output.compression"] = compression
        sweep_file = out + ".yaml"
        with open(sweep_file, "w") as f:
            yaml.safe_dump(spec, f)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run([hexdyn, "sweep", sweep_file, "-o", out, "--keep-runs"], check=True, env=env,
                   stderr=subprocess.DEVNULL)


def inflate_seconds(path, run, reps=50):
    """Median seconds zlib takes to inflate the compressed datasets of /runs/<run> (their
    bytes shuffled and deflated as HDF5 stores them): what any deflate reader pays."""
    blobs = []
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and obj.compression == "gzip":
                a = np.ascontiguousarray(obj[()])
                shuffled = np.frombuffer(a.tobytes(), np.uint8).reshape(-1, a.itemsize).T
                blobs.append(zlib.compress(shuffled.tobytes(), obj.compression_opts))
        f[f"runs/{run}"].visititems(visit)
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        for b in blobs:
            zlib.decompress(b)
        times.append(time.perf_counter() - start)
    return statistics.median(times), len(blobs)


RENAMED = {"power/per_joint": "power/joint", "energy/per_joint": "energy/joint"}


def read_run(path, run, only=None):
    """Seconds to open the file and read every dataset of /runs/<run> (or those of
    `only`, version-1 names), and the set of version-1 names read."""
    names = set()
    start = time.perf_counter()
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            old = RENAMED.get(name, name)
            if isinstance(obj, h5py.Dataset) and (only is None or old in only):
                obj[()]
                names.add(old)
        f[f"runs/{run}"].visititems(visit)
    return time.perf_counter() - start, names


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--new", required=True, help="hexdyn under test")
    parser.add_argument("--old", required=True, help="hexdyn writing uncompressed files")
    parser.add_argument("--reps", type=int, default=30)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as d:
        old, new, raw = (os.path.join(d, n) for n in ("old.h5", "new.h5", "raw.h5"))
        sweep(args.old, old)
        sweep(args.new, new)
        sweep(args.new, raw, compression="none")
        with h5py.File(new, "r") as f:
            runs = sorted(f["runs"])
        size = {p: os.path.getsize(p) for p in (old, new, raw)}
        print(f"scenarios kept: {len(runs)}")
        print(f"size: new {size[new] / 1e6:.2f} MB; the same content uncompressed "
              f"(output.compression: none) {size[raw] / 1e6:.2f} MB, ratio "
              f"{size[new] / size[raw]:.3f}; old {size[old] / 1e6:.2f} MB, ratio "
              f"{size[new] / size[old]:.3f}")
        t = {k: [] for k in ("old", "new", "raw", "same")}
        for i in range(args.reps):
            run = runs[i % len(runs)]
            dt, names = read_run(old, run)
            t["old"].append(dt)
            t["new"].append(read_run(new, run)[0])
            t["raw"].append(read_run(raw, run)[0])
            t["same"].append(read_run(new, run, only=names)[0])
        m = {k: statistics.median(v) for k, v in t.items()}
        print(f"read one run's group (medians of {args.reps}, in turn): old {m['old'] * 1e3:.2f} ms; "
              f"new {m['new'] * 1e3:.2f} ms, ratio {m['new'] / m['old']:.2f}; the old file's "
              f"datasets only {m['same'] * 1e3:.2f} ms, ratio {m['same'] / m['old']:.2f}; "
              f"uncompressed (output.compression: none) {m['raw'] * 1e3:.2f} ms, ratio "
              f"{m['raw'] / m['old']:.2f}")
        floor, n = inflate_seconds(new, runs[len(runs) // 2])
        print(f"zlib alone inflates that group's {n} compressed datasets in {floor * 1e3:.2f} ms "
              f"({floor / m['old']:.2f} of the old file's whole read)")


if __name__ == "__main__":
    main()
