#!/usr/bin/python3
"""Size and read time of a `--keep-runs` sweep file, compressed against uncompressed.

    /usr/bin/python3 bench/compression.py --new build/hexdyn --old OLD_HEXDYN [--reps 30]

Runs the sweep bench/compression.yaml (20 stair scenes) with `--keep-runs` twice: with
the `hexdyn` under test (chunked, shuffle + deflate: docs/user/output.md#compression) and
with an older `hexdyn` that writes every dataset contiguous and uncompressed (the
hexdyn-sweep/1 writer of commit bbaf71c). Prints both file sizes and their ratio, then
the time to read every dataset of one kept run's group with h5py, old and new files
alternately (`--reps` pairs, each a fresh open), as medians and their ratio. Targets
(issue 21): size at most 60 % of the old file, read time at most 1.5 times.
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import h5py

HERE = os.path.dirname(os.path.abspath(__file__))


def sweep(hexdyn, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run([hexdyn, "sweep", os.path.join(HERE, "compression.yaml"), "-o", out,
                    "--keep-runs"], check=True, env=env, stderr=subprocess.DEVNULL)


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
        old, new = os.path.join(d, "old.h5"), os.path.join(d, "new.h5")
        sweep(args.old, old)
        sweep(args.new, new)
        with h5py.File(new, "r") as f:
            runs = sorted(f["runs"])
        size_old, size_new = os.path.getsize(old), os.path.getsize(new)
        print(f"scenarios kept: {len(runs)}")
        print(f"size old {size_old / 1e6:.2f} MB, new {size_new / 1e6:.2f} MB, "
              f"ratio {size_new / size_old:.3f}")
        t_old, t_new, t_same = [], [], []
        for i in range(args.reps):
            run = runs[i % len(runs)]
            t, names = read_run(old, run)
            t_old.append(t)
            t_new.append(read_run(new, run)[0])
            t_same.append(read_run(new, run, only=names)[0])
        mo, mn, ms = (statistics.median(t) for t in (t_old, t_new, t_same))
        print(f"read one run's group: old {mo * 1e3:.2f} ms, new {mn * 1e3:.2f} ms "
              f"(medians of {args.reps}, alternately), ratio {mn / mo:.2f}; the old file's "
              f"datasets only: new {ms * 1e3:.2f} ms, ratio {ms / mo:.2f}")


if __name__ == "__main__":
    main()
